#include "chasles/mass/triangle_mesh.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <type_traits>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {
namespace {

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

// The bits of input vertex i's coordinates (U: an unsigned integer of T's size).
template <typename U, typename T>
std::array<U, 3> CoordinateBits(std::span<const T> xyz, std::size_t i) {
  return {std::bit_cast<U>(xyz[3 * i]), std::bit_cast<U>(xyz[3 * i + 1]),
          std::bit_cast<U>(xyz[3 * i + 2])};
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
template <typename T, typename Put>
void Weld(std::span<const T> xyz, double scale, double tol, const Vec3& lo, double diagonal,
          std::vector<Vec3>* kept, Put put) {
  const std::size_t n = xyz.size() / 3;
  constexpr double kCellsPerDiagonal = 1 << 20;
  const double h = diagonal > 0.0 ? std::max(2.0 * tol, diagonal / kCellsPerDiagonal) : 1.0;
  const double inv_h = 1.0 / h;
  const double tol2 = tol * tol;
  // The table holds, per occupied cell, the index of its most recent kept vertex (the head of
  // the cell's chain); the cell key of a kept vertex sits in kept_key, in insertion order.
  // Four bytes a slot keep the table small enough for the caches: with 16-byte slots holding
  // the key the random probes made welding 1.4 times slower. It starts at the size an STL
  // needs (about n / 6 kept vertices at a load factor below 1/2), so that it is not filled
  // again at every doubling: fresh memory costs a page fault per 4 KB.
  std::vector<std::uint32_t> table(std::bit_ceil(std::max<std::size_t>(16, n / 3)), kNone);
  std::vector<std::uint64_t> kept_key;
  std::vector<std::uint32_t> next;  // chain of kept vertices within a cell
  kept_key.reserve(n / 4);
  next.reserve(n / 4);
  kept->clear();
  kept->reserve(n / 4);
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
        static_cast<std::int64_t>((static_cast<double>(xyz[3 * i]) * scale - lo.x()) * inv_h),
        static_cast<std::int64_t>((static_cast<double>(xyz[3 * i + 1]) * scale - lo.y()) * inv_h),
        static_cast<std::int64_t>((static_cast<double>(xyz[3 * i + 2]) * scale - lo.z()) * inv_h));
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
    const Vec3 p(static_cast<double>(xyz[3 * i]) * scale,
                 static_cast<double>(xyz[3 * i + 1]) * scale,
                 static_cast<double>(xyz[3 * i + 2]) * scale);
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

// Throws InputError naming the first non-finite coordinate. The test runs branch-free over the
// whole array (so it vectorises); the loop that names the offender only when one failed.
template <typename T>
void CheckFinite(std::span<const T> xyz) {
  using U = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
  constexpr U kExponent = static_cast<U>(sizeof(T) == 4 ? 0x7f800000ull : 0x7ff0000000000000ull);
  U non_finite = 0;  // all exponent bits set: an infinity or a NaN
  for (const T x : xyz)
    non_finite |= static_cast<U>((std::bit_cast<U>(x) & kExponent) == kExponent);
  if (non_finite == 0) return;
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    if (!std::isfinite(xyz[i])) {
      throw InputError(
          fmt::format("mesh: vertex {} has a non-finite coordinate ({}); the file is "
                      "garbled",
                      i / 3, static_cast<double>(xyz[i])));
    }
  }
}

// `soup`: the input is a triangle soup given without indices (triangle t is vertices 3 t,
// 3 t + 1, 3 t + 2, and `indices` is empty).
template <typename T>
TriangleMesh BuildImpl(std::span<const T> xyz, std::span<const std::uint32_t> indices, bool soup,
                       double scale, double tolerance, MeshRepairReport* report) {
  if (!(std::isfinite(scale) && scale > 0.0)) {
    throw InputError(
        fmt::format("mesh scale is {}; it must be a positive, finite number of "
                    "metres per file unit",
                    scale));
  }
  if (xyz.size() % (soup ? 9 : 3) != 0 || indices.size() % 3 != 0) {
    throw InputError("mesh arrays: coordinates and indices must come in threes");
  }
  const std::size_t nv = xyz.size() / 3;
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
  CheckFinite(xyz);
  MeshRepairReport local;
  MeshRepairReport& rep = report ? *report : local;
  rep.vertices_in = nv;
  rep.triangles_in = soup ? nv / 3 : indices.size() / 3;

  // Bounding box of the scaled input, for the default tolerance and the weld grid (in the
  // input's precision: the minimum and maximum of floats are floats, exact in double).
  T box[6] = {std::numeric_limits<T>::infinity(),  std::numeric_limits<T>::infinity(),
              std::numeric_limits<T>::infinity(),  -std::numeric_limits<T>::infinity(),
              -std::numeric_limits<T>::infinity(), -std::numeric_limits<T>::infinity()};
  for (std::size_t i = 0; i < nv; ++i) {
    for (int k = 0; k < 3; ++k) {
      box[k] = std::min(box[k], xyz[3 * i + k]);
      box[3 + k] = std::max(box[3 + k], xyz[3 * i + k]);
    }
  }
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
    mesh.triangles.resize(nv / 3);
    TriangleIndices* tris = mesh.triangles.data();
    Weld(xyz, scale, tol, lo, diagonal, &mesh.vertices,
         [tris](std::size_t i, std::uint32_t k) { tris[i / 3][i % 3] = k; });
  } else {
    std::vector<std::uint32_t> remap(nv);
    Weld(xyz, scale, tol, lo, diagonal, &mesh.vertices,
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
  return BuildImpl(xyz, indices, false, scale, tolerance, report);
}

TriangleMesh BuildTriangleMesh(std::span<const double> xyz, std::span<const std::uint32_t> indices,
                               double scale, double tolerance, MeshRepairReport* report) {
  return BuildImpl(xyz, indices, false, scale, tolerance, report);
}

TriangleMesh BuildTriangleSoup(std::span<const float> xyz, double scale, double tolerance,
                               MeshRepairReport* report) {
  return BuildImpl(xyz, {}, true, scale, tolerance, report);
}

namespace {

// Calls pair(he0, he1) for the two half-edges of every undirected edge and returns the number
// of edges whose two triangles traverse it in the same direction (inconsistent orientation).
// Throws InputError for a boundary or non-manifold edge.
template <typename Pair>
std::size_t MatchEdges(const TriangleMesh& mesh, Pair pair) {
  const std::vector<TriangleIndices>& tris = mesh.triangles;
  const std::size_t nt = tris.size();
  const std::size_t nv = mesh.vertices.size();
  // Edges bucketed by their lower vertex (compressed rows): each half-edge he is stored at its
  // lower endpoint as (upper endpoint << 32 | he). Sorting a bucket groups the uses of each
  // undirected edge; buckets hold about six entries, so this is linear in practice and needs
  // 8 bytes per half-edge, less than a hash table of edges.
  std::vector<std::uint32_t> offset(nv + 1, 0);
  for (const TriangleIndices& t : tris) {
    for (int k = 0; k < 3; ++k) ++offset[std::min(t[k], t[(k + 1) % 3]) + 1];
  }
  for (std::size_t i = 0; i < nv; ++i) offset[i + 1] += offset[i];
  std::vector<std::uint64_t> entries(3 * nt);
  {
    // offset[v] serves as the fill position of bucket v, and ends as the start of bucket v + 1.
    for (std::uint32_t t = 0; t < nt; ++t) {
      for (std::uint32_t k = 0; k < 3; ++k) {
        const std::uint32_t a = tris[t][k], b = tris[t][(k + 1) % 3];
        entries[offset[std::min(a, b)]++] = (std::uint64_t{std::max(a, b)} << 32) | (3 * t + k);
      }
    }
  }
  std::size_t boundary = 0, nonmanifold = 0, inconsistent = 0;
  std::uint32_t first_bad = kNone;  // a half-edge of the first offending edge
  const char* first_kind = "";
  for (std::size_t v = 0; v < nv; ++v) {
    std::uint64_t* b = entries.data() + (v == 0 ? 0 : offset[v - 1]);
    std::uint64_t* e = entries.data() + offset[v];
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
  if (boundary > 0 || nonmanifold > 0) {
    const Vec3& a = mesh.vertices[From(tris, first_bad)];
    const Vec3& b = mesh.vertices[To(tris, first_bad)];
    throw InputError(fmt::format(
        "mesh is not a closed manifold surface, so it encloses no well-defined solid: {} "
        "boundary edge(s) (used by one triangle) and {} non-manifold edge(s) (used by three or "
        "more); the first is the {} edge from {} to {}. Close the mesh in the CAD tool, or use "
        "mode: shell with a thickness or areal density for sheet parts",
        boundary, nonmanifold, first_kind, FormatPoint(a), FormatPoint(b)));
  }
  return inconsistent;
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
  MeshRepairReport local;
  MeshRepairReport& rep = report ? *report : local;
  const std::size_t nt = mesh.triangles.size();
  if (3 * nt >= kNone) throw InputError("mesh: more than 2^32 / 3 triangles are not supported");
  // First pass: closed and manifold, consistently oriented, and the components by union–find.
  std::vector<std::uint32_t> parent(nt);
  for (std::uint32_t t = 0; t < nt; ++t) parent[t] = t;
  const auto root = [&parent](std::uint32_t t) {
    while (parent[t] != t) t = parent[t] = parent[parent[t]];
    return t;
  };
  const std::size_t inconsistent = MatchEdges(mesh, [&](std::uint32_t he0, std::uint32_t he1) {
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
  edges.inconsistent = MatchEdges(mesh, [&twin](std::uint32_t he0, std::uint32_t he1) {
    twin[he0] = he1;
    twin[he1] = he0;
  });
  const Components components = FindComponents(mesh, edges);
  rep.components = components.count();
  OrientConsistently(mesh, components, rep);
  OrientOutward(mesh, components, rep);
}

}  // namespace chasles
