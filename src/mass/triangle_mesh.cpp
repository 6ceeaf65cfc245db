#include "chasles/mass/triangle_mesh.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/files/mapped_file.h"
#include "mass/internal/mesh_workspace.h"

namespace chasles {
namespace {

using internal::MeshWorkspace;

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

// Finaliser of splitmix64: cheap and mixes every input bit into the low bits that index the
// power-of-two tables below.
inline std::uint64_t Mix(std::uint64_t x) {
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ULL;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return x;
}

std::string FormatPoint(const Vec3& p) {
  return fmt::format("({:.9g}, {:.9g}, {:.9g})", p.x(), p.y(), p.z());
}

// Cell coordinates (offset by one, < 2^21) packed into one 64-bit key.
inline std::uint64_t PackCell(std::int64_t ix, std::int64_t iy, std::int64_t iz) {
  return static_cast<std::uint64_t>(ix + 1) << 42 | static_cast<std::uint64_t>(iy + 1) << 21 |
         static_cast<std::uint64_t>(iz + 1);
}

// The slot of cell `key` in the weld table (open addressing, linear probing; a slot holds the
// index of the cell's most recent kept vertex, whose key is kept_key[index]): holding its
// head, or empty (kNone) where it would go.
inline std::uint32_t& FindCell(std::vector<std::uint32_t>& table,
                               const std::vector<std::uint64_t>& kept_key, std::uint64_t key) {
  const std::size_t mask = table.size() - 1;
  std::size_t slot = Mix(key) & mask;
  while (table[slot] != kNone && kept_key[table[slot]] != key) slot = (slot + 1) & mask;
  return table[slot];
}

// Doubles the weld table, re-inserting every cell's head.
inline void GrowCells(std::vector<std::uint32_t>& table,
                      const std::vector<std::uint64_t>& kept_key) {
  std::vector<std::uint32_t> old(2 * table.size(), kNone);
  old.swap(table);
  for (std::uint32_t head : old) {
    if (head != kNone) FindCell(table, kept_key, kept_key[head]) = head;
  }
}

// Reserves room for `capacity` elements in `v` and makes the pages of the first `present` of
// them present at once (PrefaultForWrite): a fresh process pays a page fault per 4 KB page it
// touches, and one call for the whole array costs less than a fault per page.
template <typename T>
void ReservePresent(std::vector<T>& v, std::size_t capacity, std::size_t present) {
  v.reserve(capacity);
  PrefaultForWrite(v.data(), std::min(present, capacity) * sizeof(T));
}

// The input's coordinates: Packed<T> over an array x0, y0, z0, x1, ...; Records over the
// records of a FloatSoupRecords. Get(i, k) is coordinate k of input vertex i.
template <typename T>
struct Packed {
  using Value = T;
  std::span<const T> xyz;
  std::size_t coordinates() const { return xyz.size(); }
  T Get(std::size_t i, std::size_t k) const { return xyz[3 * i + k]; }
};

struct Records {
  using Value = float;
  FloatSoupRecords r;
  std::size_t coordinates() const { return 9 * r.triangles; }
  float Get(std::size_t i, std::size_t k) const {
    float f;
    std::memcpy(&f, r.data + i / 3 * r.stride + i % 3 * 12 + 4 * k, sizeof f);
    return f;
  }
};

// The bits of input vertex i's coordinates (U: an unsigned integer of the coordinates' size).
template <typename U, typename C>
std::array<U, 3> CoordinateBits(const C& xyz, std::size_t i) {
  return {std::bit_cast<U>(xyz.Get(i, 0)), std::bit_cast<U>(xyz.Get(i, 1)),
          std::bit_cast<U>(xyz.Get(i, 2))};
}

// Empties welding's arrays and makes room in them for n input vertices. The table holds, per
// occupied cell, the index of its most recent kept vertex (the head of the cell's chain, `next`);
// the cell key of a kept vertex sits in `keys`, in insertion order. Four bytes a slot keep the
// table small enough for the caches: with 16-byte slots holding the key the random probes made
// welding 1.4 times slower. It starts at the size an STL needs (about n / 6 kept vertices at a
// load factor below 1/2), so that it is not filled again at every doubling: fresh memory costs
// a page fault per 4 KB. The arrays are made present at once (ReservePresent), the kept
// vertices' at the size an STL needs (n / 6: a closed surface has about half as many vertices
// as triangles).
void PrepareWeld(MeshWorkspace& ws, std::vector<Vec3>* kept, std::size_t n, bool soup) {
  const std::size_t slots = std::bit_ceil(std::max<std::size_t>(16, n / 3));
  const std::size_t expected = soup ? n / 6 : n / 4;
  ReservePresent(ws.table, slots, slots);
  ws.table.assign(slots, kNone);
  ws.keys.clear();
  ws.next.clear();
  kept->clear();
  ReservePresent(ws.keys, n / 4, expected);
  ReservePresent(ws.next, n / 4, expected);
  ReservePresent(*kept, n / 4, expected);
}

// Welding in one pass over the input vertices (an STL repeats each position once per incident
// triangle, so this pass sees about six copies of every vertex). Positions are scaled to
// double and sorted into grid cells of size h >= 2 tol: the tol-ball of a point then reaches
// at most one neighbouring cell along each axis (on the side where the point lies within tol
// of the cell wall), so at most 8 cells are searched, and usually only the point's own,
// because h is made much larger than the default tol (h >= diagonal / 2^20). Exact
// duplicates, at distance 0, are always found in the own cell. Each vertex maps to the
// earliest kept vertex within tol; kept vertices are never merged later, so chains of near
// points cannot drift. Cell coordinates pack into one 64-bit key (PackCell); the hash table
// grows with the number of kept vertices, not of input vertices, which keeps
// it small enough to stay in cache.
// `put(i, k)` receives the kept vertex k of input vertex i.
template <typename C, typename Put>
void Weld(const C& xyz, bool soup, double scale, double tol, const Vec3& lo, double diagonal,
          std::vector<Vec3>* kept, MeshWorkspace& ws, Put put) {
  using T = typename C::Value;
  const std::size_t n = xyz.coordinates() / 3;
  constexpr double kCellsPerDiagonal = 1 << 20;
  const double h = diagonal > 0.0 ? std::max(2.0 * tol, diagonal / kCellsPerDiagonal) : 1.0;
  const double inv_h = 1.0 / h;
  const double tol2 = tol * tol;
  std::vector<std::uint32_t>& table = ws.table;
  std::vector<std::uint64_t>& kept_key = ws.keys;
  std::vector<std::uint32_t>& next = ws.next;  // chain of kept vertices within a cell
  PrepareWeld(ws, kept, n, soup);
  const auto pack = PackCell;
  auto find = [&](std::uint64_t key) -> std::uint32_t& { return FindCell(table, kept_key, key); };
  // A small direct-mapped cache of recently seen exact positions in front of the grid: the
  // triangles of a file usually come in strips, so most repeated vertices were seen a few
  // hundred triangles earlier. A hit gives the same answer as the grid would (the earliest
  // kept vertex within tol of a position cannot change later: later kept vertices have larger
  // indices). It saves about 15 % of the welding time on a tessellated torus.
  using U = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
  struct Recent {
    U x, y, z;
    std::uint32_t id = kNone;
  };
  constexpr std::size_t kRecent = 1 << 14;
  std::vector<Recent> recent(kRecent);
  auto cell_key = [&](std::size_t i) {
    return pack(
        static_cast<std::int64_t>((static_cast<double>(xyz.Get(i, 0)) * scale - lo.x()) * inv_h),
        static_cast<std::int64_t>((static_cast<double>(xyz.Get(i, 1)) * scale - lo.y()) * inv_h),
        static_cast<std::int64_t>((static_cast<double>(xyz.Get(i, 2)) * scale - lo.z()) * inv_h));
  };
  // The table probes are cache misses; requesting the slot of the vertex kPrefetch places
  // ahead lets several misses overlap (measured: welding 1.4 times faster). Only for a vertex
  // the recent-position cache does not hold already (about one in six on an STL): computing
  // the cell key of every vertex ahead cost more than the probes it saved. The cache slot of
  // each vertex is computed once, kPrefetch places ahead, and kept in a ring until its turn.
  constexpr std::size_t kPrefetch = 16;
  const auto bits = [&xyz](std::size_t i) { return CoordinateBits<U>(xyz, i); };
  const auto recent_slot = [](const std::array<U, 3>& u) {
    return Mix(std::uint64_t{u[0]} * 0x9E3779B97F4A7C15ULL +
               std::uint64_t{u[1]} * 0xC2B2AE3D27D4EB4FULL + std::uint64_t{u[2]}) &
           (kRecent - 1);
  };
  std::array<std::size_t, kPrefetch> ring{};
  for (std::size_t j = 0; j < std::min(n, kPrefetch); ++j) ring[j] = recent_slot(bits(j));
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t own_slot = ring[i % kPrefetch];
    if (const std::size_t ahead = i + kPrefetch; ahead < n) {
      const std::array<U, 3> a = bits(ahead);
      const std::size_t slot = recent_slot(a);
      const Recent& ra = recent[slot];
      if (ra.id == kNone || ra.x != a[0] || ra.y != a[1] || ra.z != a[2]) {
        __builtin_prefetch(&table[Mix(cell_key(ahead)) & (table.size() - 1)]);
      }
      ring[i % kPrefetch] = slot;
    }
    const auto [ux, uy, uz] = bits(i);
    Recent& r = recent[own_slot];
    if (r.id != kNone && r.x == ux && r.y == uy && r.z == uz) {
      put(i, r.id);
      continue;
    }
    const Vec3 p(static_cast<double>(xyz.Get(i, 0)) * scale,
                 static_cast<double>(xyz.Get(i, 1)) * scale,
                 static_cast<double>(xyz.Get(i, 2)) * scale);
    const Vec3 q = (p - lo) * inv_h;
    const std::int64_t base[3] = {static_cast<std::int64_t>(q.x()),
                                  static_cast<std::int64_t>(q.y()),
                                  static_cast<std::int64_t>(q.z())};  // q >= 0: truncation floors
    const std::uint64_t own = pack(base[0], base[1], base[2]);
    std::uint32_t best = kNone;
    std::uint32_t& cell = find(own);
    for (std::uint32_t k = cell; k != kNone; k = next[k]) {
      if (((*kept)[k] - p).squaredNorm() <= tol2 && k < best) best = k;
    }
    int side[3];
    bool near_wall = false;
    for (int a = 0; a < 3; ++a) {
      const double f = (q[a] - static_cast<double>(base[a])) * h;  // distance to lower wall
      side[a] = f <= tol ? -1 : (h - f <= tol ? 1 : 0);
      near_wall |= side[a] != 0;
    }
    if (near_wall) {
      for (int m = 1; m < 8; ++m) {
        if (((m & 1) && !side[0]) || ((m & 2) && !side[1]) || ((m & 4) && !side[2])) continue;
        const std::uint32_t c =
            find(pack(base[0] + ((m & 1) ? side[0] : 0), base[1] + ((m & 2) ? side[1] : 0),
                      base[2] + ((m & 4) ? side[2] : 0)));
        for (std::uint32_t k = c; k != kNone; k = next[k]) {
          if (((*kept)[k] - p).squaredNorm() <= tol2 && k < best) best = k;
        }
      }
    }
    r = Recent{ux, uy, uz, best};
    if (best != kNone) {
      put(i, best);
      continue;
    }
    const auto k = static_cast<std::uint32_t>(kept->size());
    r.id = k;
    std::uint32_t* target = &cell;
    kept_key.push_back(own);
    if (cell == kNone && 2 * (k + 1) > table.size()) {  // keep the load factor below 1/2
      GrowCells(table, kept_key);
      target = &find(own);
    }
    next.push_back(*target);
    *target = k;
    kept->push_back(p);
    put(i, k);
  }
}

// The bounding box of the input vertices (lo x, y, z, hi x, y, z, in the input's precision:
// the minimum and maximum of floats are floats, exact in double). Throws InputError naming the
// first non-finite coordinate. One branch-free pass over the coordinates gives both; the loop
// that names the offender runs only when one failed.
template <typename C>
std::array<typename C::Value, 6> BoundingBox(const C& xyz) {
  using T = typename C::Value;
  using U = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
  constexpr U kExponent = static_cast<U>(sizeof(T) == 4 ? 0x7f800000ull : 0x7ff0000000000000ull);
  constexpr T kInf = std::numeric_limits<T>::infinity();
  std::array<T, 6> box = {kInf, kInf, kInf, -kInf, -kInf, -kInf};
  U non_finite = 0;  // all exponent bits set: an infinity or a NaN
  const std::size_t nv = xyz.coordinates() / 3;
  const auto take = [&](const T* p) {  // one vertex
    for (std::size_t k = 0; k < 3; ++k) {
      non_finite |= static_cast<U>((std::bit_cast<U>(p[k]) & kExponent) == kExponent);
      box[k] = std::min(box[k], p[k]);
      box[3 + k] = std::max(box[3 + k], p[k]);
    }
  };
  if constexpr (std::is_same_v<C, Records>) {
    for (std::size_t t = 0; t < xyz.r.triangles; ++t) {  // a record's nine floats at once
      float f[9];
      std::memcpy(f, xyz.r.data + t * xyz.r.stride, sizeof f);
      take(f);
      take(f + 3);
      take(f + 6);
    }
  } else {
    for (std::size_t i = 0; i < nv; ++i) take(xyz.xyz.data() + 3 * i);
  }
  if (non_finite == 0) return box;
  for (std::size_t i = 0; i < nv; ++i) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (!std::isfinite(xyz.Get(i, k))) {
        if constexpr (std::is_same_v<C, Records>) {
          if (xyz.r.non_finite) xyz.r.non_finite(i / 3);  // the caller's own error
        }
        throw InputError(
            fmt::format("mesh: vertex {} has a non-finite coordinate ({}); the file is "
                        "garbled",
                        i, static_cast<double>(xyz.Get(i, k))));
      }
    }
  }
  return box;
}

// `soup`: the input is a triangle soup given without indices (triangle t is vertices 3 t,
// 3 t + 1, 3 t + 2, and `indices` is empty).
template <typename C>
TriangleMesh BuildImpl(const C& xyz, std::span<const std::uint32_t> indices, bool soup,
                       double scale, double tolerance, MeshRepairReport* report,
                       MeshWorkspace& ws) {
  if (!(std::isfinite(scale) && scale > 0.0)) {
    throw InputError(
        fmt::format("mesh scale is {}; it must be a positive, finite number of "
                    "metres per file unit",
                    scale));
  }
  if (xyz.coordinates() % (soup ? 9 : 3) != 0 || indices.size() % 3 != 0) {
    throw InputError("mesh arrays: coordinates and indices must come in threes");
  }
  const std::size_t nv = xyz.coordinates() / 3;
  if (nv >= kNone) throw InputError("mesh: more than 2^32 - 1 vertices are not supported");
  // The checks are done branch-free over whole arrays (so they vectorise) and the loops that
  // name the first offender run only when one failed. A triangle soup (an STL: triangle t uses
  // vertices 3t, 3t + 1, 3t + 2) is recognised in the same pass as the range check.
  std::uint32_t max_index = 0;
  std::uint32_t not_identity = indices.size() == nv ? 0 : 1;
  for (std::size_t i = 0; i < indices.size(); ++i) {
    max_index = std::max(max_index, indices[i]);
    not_identity |= indices[i] ^ static_cast<std::uint32_t>(i);
  }
  soup = soup || not_identity == 0;
  if (!indices.empty() && max_index >= nv) {
    for (std::size_t i = 0; i < indices.size(); ++i) {
      if (indices[i] >= nv) {
        throw InputError(
            fmt::format("mesh: triangle {} refers to vertex {}, but there are only {} "
                        "vertices",
                        i / 3, indices[i], nv));
      }
    }
  }
  const auto box = BoundingBox(xyz);
  MeshRepairReport local;
  MeshRepairReport& rep = report ? *report : local;
  rep.vertices_in = nv;
  rep.triangles_in = soup ? nv / 3 : indices.size() / 3;

  // The bounding box of the scaled input, for the default tolerance and the weld grid.
  Vec3 lo(static_cast<double>(box[0]), static_cast<double>(box[1]), static_cast<double>(box[2]));
  Vec3 hi(static_cast<double>(box[3]), static_cast<double>(box[4]), static_cast<double>(box[5]));
  lo *= scale;
  hi *= scale;
  const double diagonal = nv == 0 ? 0.0 : (hi - lo).norm();
  if (diagonal > 0.0 && diagonal < kMinMeshExtent) {
    throw InputError(
        fmt::format("mesh: its bounding box is only {:.3g} across (in its own unit), less than "
                    "the {:g} a mesh may measure; check the unit of the file",
                    diagonal, kMinMeshExtent));
  }
  const double tol = std::isnan(tolerance) ? kDefaultWeldRelativeTolerance * diagonal : tolerance;
  if (!(tol >= 0.0) || !std::isfinite(tol)) {
    throw InputError(fmt::format("mesh weld tolerance is {} m; it must be zero or positive", tol));
  }
  rep.weld_tolerance = tol;
  TriangleMesh mesh;
  // A triangle soup is welded straight into the triangle array, without a separate vertex
  // map: 12 bytes a triangle less memory.
  if (soup) {
    ReservePresent(mesh.triangles, nv / 3, nv / 3);
    mesh.triangles.resize(nv / 3);
    TriangleIndices* tris = mesh.triangles.data();
    Weld(xyz, true, scale, tol, lo, diagonal, &mesh.vertices, ws,
         [tris](std::size_t i, std::uint32_t k) { tris[i / 3][i % 3] = k; });
  } else {
    std::vector<std::uint32_t> remap(nv);
    Weld(xyz, false, scale, tol, lo, diagonal, &mesh.vertices, ws,
         [&remap](std::size_t i, std::uint32_t k) { remap[i] = k; });
    mesh.triangles.resize(indices.size() / 3);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      mesh.triangles[t] = {remap[indices[3 * t]], remap[indices[3 * t + 1]],
                           remap[indices[3 * t + 2]]};
    }
  }
  rep.vertices_out = mesh.vertices.size();

  // Drop degenerate triangles, compacting in place.
  const Vec3* v = mesh.vertices.data();
  std::size_t kept_triangles = 0;
  for (const TriangleIndices& tri : mesh.triangles) {
    const bool repeated = tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2];
    if (repeated || (v[tri[1]] - v[tri[0]]).cross(v[tri[2]] - v[tri[0]]).isZero(0.0)) {
      ++rep.degenerate_dropped;
      continue;
    }
    mesh.triangles[kept_triangles++] = tri;
  }
  mesh.triangles.resize(kept_triangles);
  mesh.triangles.shrink_to_fit();
  if (rep.degenerate_dropped > 0) {
    rep.warnings.push_back(fmt::format(
        "{} degenerate triangle(s) (zero area or a repeated vertex after welding) dropped",
        rep.degenerate_dropped));
  }
  if (mesh.triangles.empty()) {
    throw InputError(
        fmt::format("mesh: empty mesh ({} triangles read, all degenerate)", rep.triangles_in));
  }
  return mesh;
}

// Start vertex of half-edge he = 3 t + k (the edge from corner k to corner k + 1).
inline std::uint32_t From(const std::vector<TriangleIndices>& tris, std::uint32_t he) {
  return tris[he / 3][he % 3];
}
inline std::uint32_t To(const std::vector<TriangleIndices>& tris, std::uint32_t he) {
  return tris[he / 3][(he % 3 + 1) % 3];
}

}  // namespace

TriangleMesh BuildTriangleMesh(std::span<const float> xyz, std::span<const std::uint32_t> indices,
                               double scale, double tolerance, MeshRepairReport* report) {
  MeshWorkspace ws;
  return BuildImpl(Packed<float>{xyz}, indices, false, scale, tolerance, report, ws);
}

TriangleMesh BuildTriangleMesh(std::span<const double> xyz, std::span<const std::uint32_t> indices,
                               double scale, double tolerance, MeshRepairReport* report) {
  MeshWorkspace ws;
  return internal::BuildTriangleMesh(xyz, indices, scale, tolerance, report, ws);
}

TriangleMesh BuildTriangleSoup(std::span<const float> xyz, double scale, double tolerance,
                               MeshRepairReport* report) {
  MeshWorkspace ws;
  return internal::BuildTriangleSoup(xyz, scale, tolerance, report, ws);
}

TriangleMesh BuildTriangleSoup(const FloatSoupRecords& records, double scale, double tolerance,
                               MeshRepairReport* report) {
  MeshWorkspace ws;
  return internal::BuildTriangleSoup(records, scale, tolerance, report, ws);
}

TriangleMesh internal::BuildTriangleMesh(std::span<const double> xyz,
                                         std::span<const std::uint32_t> indices, double scale,
                                         double tolerance, MeshRepairReport* report,
                                         MeshWorkspace& workspace) {
  return BuildImpl(Packed<double>{xyz}, indices, false, scale, tolerance, report, workspace);
}

TriangleMesh internal::BuildTriangleSoup(std::span<const float> xyz, double scale, double tolerance,
                                         MeshRepairReport* report, MeshWorkspace& workspace) {
  return BuildImpl(Packed<float>{xyz}, {}, true, scale, tolerance, report, workspace);
}

TriangleMesh internal::BuildTriangleSoup(const FloatSoupRecords& records, double scale,
                                         double tolerance, MeshRepairReport* report,
                                         MeshWorkspace& workspace) {
  return BuildImpl(Records{records}, {}, true, scale, tolerance, report, workspace);
}

namespace {

// What MatchEdges finds in the buckets: the counts of bad edges and a half-edge of the first.
struct EdgeTally {
  std::size_t boundary = 0, nonmanifold = 0, inconsistent = 0;
  std::uint32_t first_bad = kNone;
  const char* first_kind = "";

  // Sorts the bucket [b, e) of one vertex, calls pair(he0, he1) for each edge used twice and
  // counts the others.
  template <typename Pair>
  void Match(std::uint64_t* b, std::uint64_t* e, const std::vector<TriangleIndices>& tris,
             Pair& pair) {
    if (e - b <= 16) {
      for (std::uint64_t* i = b + 1; i < e; ++i) {  // insertion sort: buckets are tiny
        const std::uint64_t x = *i;
        std::uint64_t* j = i;
        for (; j > b && *(j - 1) > x; --j) *j = *(j - 1);
        *j = x;
      }
    } else {
      std::sort(b, e);
    }
    for (std::uint64_t* g = b; g < e;) {
      std::uint64_t* h = g + 1;
      while (h < e && (*h >> 32) == (*g >> 32)) ++h;
      const auto he0 = static_cast<std::uint32_t>(*g);
      if (h - g == 2) {
        const auto he1 = static_cast<std::uint32_t>(*(g + 1));
        pair(he0, he1);
        if (From(tris, he0) == From(tris, he1)) ++inconsistent;
      } else {
        if (h - g == 1) {
          ++boundary;
        } else {
          ++nonmanifold;
        }
        if (first_bad == kNone) {
          first_bad = he0;
          first_kind = h - g == 1 ? "boundary" : "non-manifold";
        }
      }
      g = h;
    }
  }
};

// Calls pair(he0, he1) for the two half-edges of every undirected edge and returns the number
// of edges whose two triangles traverse it in the same direction (inconsistent orientation).
// Throws InputError for a boundary or non-manifold edge.
//
// Edges bucketed by their lower vertex (compressed rows): each half-edge he is stored at its
// lower endpoint as (upper endpoint << 32 | he). Sorting a bucket groups the uses of each
// undirected edge; buckets hold about six entries, so this is linear in practice and needs
// 8 bytes per half-edge, less than a hash table of edges. The buckets are filled and matched a
// range of vertices at a time, in `ws.keys` (room for 3/8 of all the half-edges, or more when
// welding left it larger), the pairs coming in the same order as from all the buckets at once:
// fresh memory costs a page fault a page. The triangles scanned for a range are only those
// from the first to the last with a half-edge there, usually a narrow band (vertices are
// numbered in the order the triangles first use them).
template <typename Pair>
std::size_t MatchEdges(const TriangleMesh& mesh, MeshWorkspace& ws, Pair pair) {
  const std::vector<TriangleIndices>& tris = mesh.triangles;
  const auto nt = static_cast<std::uint32_t>(tris.size());
  const std::size_t nv = mesh.vertices.size();
  // offset[v]: the start of bucket v. first[b] to last[b]: the triangles with a half-edge in
  // block b of vertices (2^kBlockBits of them).
  constexpr unsigned kBlockBits = 12;
  const std::size_t nb = (nv >> kBlockBits) + 1;
  std::vector<std::uint32_t> first(nb, kNone), last(nb, 0);
  std::vector<std::uint32_t>& offset = ws.next;
  ReservePresent(offset, nv + 1, nv + 1);
  offset.assign(nv + 1, 0);
  for (std::uint32_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t low = std::min(tris[t][k], tris[t][(k + 1) % 3]);
      ++offset[low + 1];
      first[low >> kBlockBits] = std::min(first[low >> kBlockBits], t);
      last[low >> kBlockBits] = t;
    }
  }
  for (std::size_t i = 0; i < nv; ++i) offset[i + 1] += offset[i];
  std::vector<std::uint64_t>& entries = ws.keys;
  const std::size_t room = std::max<std::size_t>(entries.capacity(), (3 * std::size_t{nt} + 7) / 8);
  ReservePresent(entries, room, room);
  const auto block_end = [nv](std::size_t b) { return std::min(nv, (b + 1) << kBlockBits); };
  EdgeTally tally;
  for (std::size_t b0 = 0, b1 = 1; b0 < nb; b0 = b1++) {
    // The blocks [b0, b1), as many as there is room for (at least one): vertices [v0, v1).
    const std::size_t v0 = b0 << kBlockBits;
    while (b1 < nb && offset[block_end(b1)] - offset[v0] <= room) ++b1;
    const std::size_t v1 = block_end(b1 - 1);
    const std::uint32_t base = offset[v0];
    entries.resize(std::max<std::size_t>(entries.size(), offset[v1] - base));
    std::uint32_t t0 = kNone, t1 = 0;
    for (std::size_t b = b0; b < b1; ++b) {
      if (first[b] == kNone) continue;
      t0 = std::min(t0, first[b]);
      t1 = std::max(t1, last[b]);
    }
    // offset[v] serves as the fill position of bucket v, and ends as the start of bucket v + 1.
    for (std::uint32_t t = t0; t0 != kNone && t <= t1; ++t) {
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t a = tris[t][k], b = tris[t][(k + 1) % 3];
        const std::uint32_t low = std::min(a, b);
        if (low - v0 >= v1 - v0) continue;  // outside [v0, v1)
        entries[offset[low]++ - base] = (std::uint64_t{std::max(a, b)} << 32) | (3 * t + k);
      }
    }
    for (std::size_t v = v0; v < v1; ++v) {
      tally.Match(entries.data() + ((v == 0 ? 0 : offset[v - 1]) - base),
                  entries.data() + (offset[v] - base), tris, pair);
    }
  }
  if (tally.boundary > 0 || tally.nonmanifold > 0) {
    const Vec3& a = mesh.vertices[From(tris, tally.first_bad)];
    const Vec3& b = mesh.vertices[To(tris, tally.first_bad)];
    throw InputError(fmt::format(
        "mesh is not a closed manifold surface, so it encloses no well-defined solid: {} "
        "boundary edge(s) (used by one triangle) and {} non-manifold edge(s) (used by three or "
        "more); the first is the {} edge from {} to {}. Close the mesh in the CAD tool, or use "
        "mode: shell with a thickness or areal density for sheet parts",
        tally.boundary, tally.nonmanifold, tally.first_kind, FormatPoint(a), FormatPoint(b)));
  }
  return tally.inconsistent;
}

// Twin of each half-edge, and the number of inconsistently oriented edges (see MatchEdges).
struct EdgeMatch {
  std::vector<std::uint32_t> twin;
  std::size_t inconsistent = 0;
};

// Connected components over shared edges: component[t] of each triangle, the triangles in
// breadth-first order per component (queue, component c at [start[c], start[c + 1])), and
// parity[t], whether t must be reversed to agree with its component's first triangle.
struct Components {
  std::vector<std::uint32_t> component;
  std::vector<std::uint8_t> parity;
  std::vector<std::uint32_t> queue;
  std::vector<std::uint32_t> start;
  std::size_t count() const { return start.size() - 1; }
};

Components FindComponents(const TriangleMesh& mesh, const EdgeMatch& edges) {
  const std::vector<TriangleIndices>& tris = mesh.triangles;
  const std::size_t nt = tris.size();
  const std::vector<std::uint32_t>& twin = edges.twin;
  const std::size_t inconsistent = edges.inconsistent;
  // Connected components by breadth-first search over shared edges. parity[t] says whether t
  // must be reversed to agree with the component's first triangle: crossing an edge that both
  // triangles traverse in the same direction toggles it.
  Components k;
  std::vector<std::uint32_t>& component = k.component;
  std::vector<std::uint8_t>& parity = k.parity;
  std::vector<std::uint32_t>& queue = k.queue;
  std::vector<std::uint32_t>& component_start = k.start;
  component.assign(nt, kNone);
  parity.assign(nt, 0);
  queue.reserve(nt);
  for (std::uint32_t seed = 0; seed < nt; ++seed) {
    if (component[seed] != kNone) continue;
    const auto c = static_cast<std::uint32_t>(component_start.size());
    component_start.push_back(static_cast<std::uint32_t>(queue.size()));
    component[seed] = c;
    queue.push_back(seed);
    for (std::size_t q = component_start.back(); q < queue.size(); ++q) {
      const std::uint32_t t = queue[q];
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t he = 3 * t + k;
        const std::uint32_t tw = twin[he];
        const std::uint32_t u = tw / 3;
        const std::uint8_t p = parity[t] ^ (From(tris, he) == From(tris, tw) ? 1 : 0);
        if (component[u] == kNone) {
          component[u] = c;
          parity[u] = p;
          queue.push_back(u);
        } else if (inconsistent > 0 && parity[u] != p) {
          throw InputError(fmt::format(
              "mesh is not orientable (like a Moebius strip): no choice of triangle orientations "
              "makes the edge from {} to {} consistent; it cannot bound a solid",
              FormatPoint(mesh.vertices[From(tris, he)]),
              FormatPoint(mesh.vertices[To(tris, he)])));
        }
      }
    }
  }
  component_start.push_back(static_cast<std::uint32_t>(nt));
  return k;
}

// Reverses triangles so that each component is consistently oriented.
void OrientConsistently(TriangleMesh& mesh, const Components& k, MeshRepairReport& rep) {
  std::vector<TriangleIndices>& tris = mesh.triangles;
  const std::size_t nt = tris.size();
  const std::size_t nc = k.count();
  const std::vector<std::uint8_t>& parity = k.parity;
  const std::vector<std::uint32_t>& queue = k.queue;
  const std::vector<std::uint32_t>& component_start = k.start;
  // Keep the majority orientation of each component: fewest triangles reversed.
  std::size_t flipped = 0;
  for (std::size_t c = 0; c < nc; ++c) {
    std::size_t ones = 0;
    for (std::uint32_t q = component_start[c]; q < component_start[c + 1]; ++q) {
      ones += parity[queue[q]];
    }
    const std::size_t size = component_start[c + 1] - component_start[c];
    const std::uint8_t reverse = 2 * ones > size ? 0 : 1;
    for (std::uint32_t q = component_start[c]; q < component_start[c + 1]; ++q) {
      const std::uint32_t t = queue[q];
      if (parity[t] == reverse) {
        std::swap(tris[t][1], tris[t][2]);
        ++flipped;
      }
    }
  }
  rep.triangles_flipped += flipped;
  rep.warnings.push_back(fmt::format(
      "inconsistent triangle orientation: {} of {} triangles reversed to agree with their "
      "neighbours (flood fill per connected component)",
      flipped, nt));
}

// Turns an inside-out mesh outward; warns about components that enclose a negative volume.
void OrientOutward(TriangleMesh& mesh, const Components& k, MeshRepairReport& rep) {
  std::vector<TriangleIndices>& tris = mesh.triangles;
  const std::size_t nt = tris.size();
  const std::size_t nc = k.count();
  const std::vector<std::uint32_t>& component = k.component;
  const std::vector<std::uint32_t>& component_start = k.start;
  // Enclosed volume per component (divergence theorem, signed tetrahedra from the bounding-box
  // centre; see mesh_mass.cpp), to detect an inside-out mesh.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (const Vec3& p : mesh.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const Vec3 r = 0.5 * (lo + hi);
  std::vector<double> volume(nc, 0.0);
  for (std::size_t t = 0; t < nt; ++t) {
    const Vec3 a = mesh.vertices[tris[t][0]] - r;
    const Vec3 b = mesh.vertices[tris[t][1]] - r;
    const Vec3 c = mesh.vertices[tris[t][2]] - r;
    volume[component[t]] += a.dot(b.cross(c));
  }
  double total = 0.0;
  for (double& vol : volume) {
    vol /= 6.0;
    total += vol;
  }
  const double scale3 = std::pow((hi - lo).norm(), 3);
  if (!(std::abs(total) > 1e-12 * scale3)) {
    throw InputError(fmt::format(
        "mesh encloses no volume ({:.6g} for a bounding-box diagonal of {:.6g}): a flat or "
        "self-cancelling surface cannot be a solid; use mode: shell with a thickness or areal "
        "density for sheet parts",
        total, (hi - lo).norm()));
  }
  if (total < 0.0) {
    for (TriangleIndices& t : tris) std::swap(t[1], t[2]);
    for (double& vol : volume) vol = -vol;
    rep.inside_out_flipped = true;
    rep.warnings.push_back(fmt::format(
        "mesh was inside out (enclosed volume {:.6g} < 0, normals pointing in); all triangles "
        "reversed",
        total));
  }
  for (std::size_t c = 0; c < nc; ++c) {
    if (volume[c] < 0.0) {
      rep.warnings.push_back(fmt::format(
          "component {} ({} triangles) encloses a negative volume ({:.6g}) and is treated as a "
          "cavity; reverse it if it is a separate part",
          c, component_start[c + 1] - component_start[c], volume[c]));
    }
  }
}

// Connected components of a consistently oriented mesh by union–find over the edge pairs
// MatchEdges visits (Tarjan: union by linking the larger root under the smaller, path
// halving), without twins or a search: each root is the smallest triangle of its component,
// every parent index is smaller than its child's, so one ascending pass turns the parents
// into component numbers in the order of each component's first triangle (the numbering of
// FindComponents). `parent` holds the union–find forest and is turned into the numbers.
Components LabelComponents(std::vector<std::uint32_t>&& parent) {
  Components k;
  const std::size_t nt = parent.size();
  std::vector<std::uint32_t> size;
  for (std::uint32_t t = 0; t < nt; ++t) {
    if (parent[t] == t) {
      parent[t] = static_cast<std::uint32_t>(size.size());
      size.push_back(0);
    } else {
      parent[t] = parent[parent[t]];  // parent[t] < t already holds its component's number
    }
    ++size[parent[t]];
  }
  k.component = std::move(parent);
  k.start.assign(1, 0);
  for (std::uint32_t n : size) k.start.push_back(k.start.back() + n);
  return k;
}

}  // namespace

void ValidateSolid(TriangleMesh& mesh, MeshRepairReport* report) {
  MeshWorkspace ws;
  internal::ValidateSolid(mesh, report, ws);
}

void internal::ValidateSolid(TriangleMesh& mesh, MeshRepairReport* report,
                             MeshWorkspace& workspace) {
  MeshRepairReport local;
  MeshRepairReport& rep = report ? *report : local;
  const std::size_t nt = mesh.triangles.size();
  if (3 * nt >= kNone) throw InputError("mesh: more than 2^32 / 3 triangles are not supported");
  // First pass: closed and manifold, consistently oriented, and the components by union–find
  // (in welding's hash table, which has a slot per triangle at least).
  std::vector<std::uint32_t> parent = std::move(workspace.table);
  ReservePresent(parent, nt, nt);
  parent.resize(nt);
  for (std::uint32_t t = 0; t < nt; ++t) parent[t] = t;
  const auto root = [&parent](std::uint32_t t) {
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
  };
  const std::size_t inconsistent =
      MatchEdges(mesh, workspace, [&](std::uint32_t he0, std::uint32_t he1) {
        const std::uint32_t a = root(he0 / 3), b = root(he1 / 3);
        if (a < b) {
          parent[b] = a;
        } else if (b < a) {
          parent[a] = b;
        }
      });
  if (inconsistent == 0) {
    const Components components = LabelComponents(std::move(parent));
    rep.components = components.count();
    OrientOutward(mesh, components, rep);
    return;
  }
  // Orientation to repair: twins, and a breadth-first search that finds each triangle's parity.
  std::vector<std::uint32_t>().swap(parent);
  EdgeMatch edges;
  edges.twin.assign(3 * nt, kNone);
  std::vector<std::uint32_t>& twin = edges.twin;
  edges.inconsistent = MatchEdges(mesh, workspace, [&twin](std::uint32_t he0, std::uint32_t he1) {
    twin[he0] = he1;
    twin[he1] = he0;
  });
  const Components components = FindComponents(mesh, edges);
  rep.components = components.count();
  OrientConsistently(mesh, components, rep);
  OrientOutward(mesh, components, rep);
}

}  // namespace chasles
