// What the audit does with a mesh that bounds no solid (analysis/internal/audit_steps.h): cap
// its holes, else take its convex hull. Visual meshes are often open (a logo's faces left
// loose, a seam never closed); both keep the volume integrals exact for a closed polyhedron
// near the part, and the report says which was used.

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <vector>

#include "analysis/internal/audit_steps.h"

namespace chasles::internal {

namespace {

std::uint64_t EdgeKey(std::uint32_t a, std::uint32_t b) {
  return static_cast<std::uint64_t>(a) << 32 | b;
}

}  // namespace

bool CapHoles(TriangleMesh& mesh) {
  // Directed edges as the triangles traverse them; an edge whose reverse is absent is on a
  // hole. The cap's triangles traverse it the other way.
  std::unordered_map<std::uint64_t, int> count;
  for (const TriangleIndices& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) ++count[EdgeKey(t[k], t[(k + 1) % 3])];
  }
  std::unordered_map<std::uint32_t, std::uint32_t> next;  // along the boundary, reversed
  for (const auto& [key, n] : count) {
    const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key);
    if (n > 1) return false;  // two triangles the same way round: non-manifold or misoriented
    if (count.count(EdgeKey(b, a))) continue;
    if (!next.emplace(b, a).second) return false;  // a vertex on two holes
  }
  if (next.empty()) return true;
  std::vector<TriangleIndices> caps;
  while (!next.empty()) {
    std::vector<std::uint32_t> loop{next.begin()->first};
    for (std::size_t guard = 0; guard <= mesh.vertices.size(); ++guard) {
      const auto it = next.find(loop.back());
      if (it == next.end()) return false;
      const std::uint32_t v = it->second;
      next.erase(it);
      if (v == loop.front()) break;
      loop.push_back(v);
    }
    if (loop.size() < 3) return false;
    Vec3 c = Vec3::Zero();
    for (const std::uint32_t v : loop) c += mesh.vertices[v];
    const auto centre = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.push_back(c / static_cast<double>(loop.size()));
    for (std::size_t k = 0; k < loop.size(); ++k) {
      caps.push_back({loop[k], loop[(k + 1) % loop.size()], centre});
    }
  }
  mesh.triangles.insert(mesh.triangles.end(), caps.begin(), caps.end());
  return true;
}

namespace {

/// Quickhull (Barber, Dobkin & Huhdanpaa 1996): every point not yet on the hull waits in the
/// outside set of one face it sees; the farthest point of a face's set is added, the faces it
/// sees (found by walking from that face across edges) are replaced by a cone over their
/// horizon, and their waiting points go to the new faces they see.
class Hull {
 public:
  explicit Hull(const std::vector<Vec3>& p) : p_(p) {}

  TriangleMesh Build();

 private:
  struct Face {
    std::uint32_t v[3];
    Vec3 n;
    double d;
    bool alive = true;
    std::vector<std::uint32_t> outside;
  };
  double Height(std::uint32_t f, std::uint32_t i) const {
    return faces_[f].n.dot(p_[i]) - faces_[f].d;
  }
  std::uint32_t AddFace(std::uint32_t a, std::uint32_t b, std::uint32_t c);
  bool Seed(std::vector<std::uint32_t>& order);
  void AddPoint(std::uint32_t face, std::uint32_t i);
  void Assign(const std::vector<std::uint32_t>& points, const std::vector<std::uint32_t>& faces);

  const std::vector<Vec3>& p_;
  std::vector<Face> faces_;
  std::unordered_map<std::uint64_t, std::uint32_t> edges_;  // directed edge -> its face
  double eps_ = 0.0;
};

std::uint32_t Hull::AddFace(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  Face f{{a, b, c}, (p_[b] - p_[a]).cross(p_[c] - p_[a]), 0.0, true, {}};
  f.n.normalize();
  f.d = f.n.dot(p_[a]);
  const auto index = static_cast<std::uint32_t>(faces_.size());
  for (int k = 0; k < 3; ++k) edges_[EdgeKey(f.v[k], f.v[(k + 1) % 3])] = index;
  faces_.push_back(std::move(f));
  return index;
}

void Hull::Assign(const std::vector<std::uint32_t>& points,
                  const std::vector<std::uint32_t>& faces) {
  for (const auto i : points) {
    for (const auto f : faces) {
      if (Height(f, i) > eps_) {
        faces_[f].outside.push_back(i);
        break;
      }
    }
  }
}

bool Hull::Seed(std::vector<std::uint32_t>& order) {
  // Four points far apart: the extremes in x, the farthest from their line, the farthest from
  // their plane.
  const auto by_x = std::minmax_element(order.begin(), order.end(),
                                        [&](auto a, auto b) { return p_[a].x() < p_[b].x(); });
  const std::uint32_t a = *by_x.first, b = *by_x.second;
  const Vec3 ab = p_[b] - p_[a];
  std::uint32_t c = a, d = a;
  double best = 0.0;
  for (const auto i : order) {
    const double dist = ab.cross(p_[i] - p_[a]).norm();
    if (dist > best) best = dist, c = i;
  }
  const Vec3 n = ab.cross(p_[c] - p_[a]);
  if (!(best > eps_ * ab.norm()) || n.norm() == 0.0) return false;
  best = 0.0;
  for (const auto i : order) {
    const double dist = std::abs(n.normalized().dot(p_[i] - p_[a]));
    if (dist > best) best = dist, d = i;
  }
  if (!(best > eps_)) return false;
  // Oriented so that every face's normal points away from the fourth point.
  if (n.dot(p_[d] - p_[a]) > 0) {
    AddFace(a, c, b), AddFace(a, b, d), AddFace(b, c, d), AddFace(c, a, d);
  } else {
    AddFace(a, b, c), AddFace(a, d, b), AddFace(b, d, c), AddFace(c, d, a);
  }
  Assign(order, {0, 1, 2, 3});
  return true;
}

void Hull::AddPoint(std::uint32_t start, std::uint32_t i) {
  // The faces i sees, connected to `start`, and their horizon.
  std::vector<std::uint32_t> visible{start}, waiting;
  faces_[start].alive = false;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> horizon;
  for (std::size_t at = 0; at < visible.size(); ++at) {
    const std::uint32_t f = visible[at];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t u = faces_[f].v[k], w = faces_[f].v[(k + 1) % 3];
      const auto it = edges_.find(EdgeKey(w, u));
      if (it == edges_.end()) continue;
      const std::uint32_t g = it->second;
      if (!faces_[g].alive) continue;
      if (Height(g, i) > eps_) {
        faces_[g].alive = false;
        visible.push_back(g);
      } else {
        horizon.emplace_back(u, w);
      }
    }
  }
  for (const auto f : visible) {
    for (int k = 0; k < 3; ++k) {
      const auto it = edges_.find(EdgeKey(faces_[f].v[k], faces_[f].v[(k + 1) % 3]));
      if (it != edges_.end() && it->second == f) edges_.erase(it);
    }
    for (const auto q : faces_[f].outside) {
      if (q != i) waiting.push_back(q);
    }
    std::vector<std::uint32_t>().swap(faces_[f].outside);
  }
  std::vector<std::uint32_t> added;
  for (const auto& [u, w] : horizon) added.push_back(AddFace(u, w, i));
  Assign(waiting, added);
}

TriangleMesh Hull::Build() {
  TriangleMesh out;
  if (p_.size() < 4) return out;
  Vec3 lo = p_[0], hi = p_[0];
  for (const Vec3& q : p_) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  eps_ = 1e-10 * (hi - lo).norm();
  std::vector<std::uint32_t> order(p_.size());
  std::iota(order.begin(), order.end(), 0u);
  if (!Seed(order)) return out;
  for (std::uint32_t f = 0; f < faces_.size(); ++f) {
    while (faces_[f].alive && !faces_[f].outside.empty()) {
      const auto& o = faces_[f].outside;
      const auto far = *std::max_element(
          o.begin(), o.end(), [&](auto a, auto b) { return Height(f, a) < Height(f, b); });
      AddPoint(f, far);
    }
  }
  // Keep the hull's vertices only, renumbered.
  std::vector<std::uint32_t> index(p_.size(), UINT32_MAX);
  for (const Face& f : faces_) {
    if (!f.alive) continue;
    TriangleIndices t;
    for (int k = 0; k < 3; ++k) {
      if (index[f.v[k]] == UINT32_MAX) {
        index[f.v[k]] = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(p_[f.v[k]]);
      }
      t[k] = index[f.v[k]];
    }
    out.triangles.push_back(t);
  }
  return out;
}

}  // namespace

TriangleMesh ConvexHull(const std::vector<Vec3>& points) {
  return Hull(points).Build();
}

}  // namespace chasles::internal
