// The Collada reader (chasles/files/collada_reader.h), after the COLLADA 1.4.1 and 1.5
// specifications: <float_array> with <accessor>, <vertices>, <triangles>/<polylist>/<polygons>
// with their interleaved <p> indices, and the node transforms of <visual_scene>.

#include "chasles/files/collada_reader.h"

#include <charconv>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "chasles/math/rotation.h"
#include "chasles/math/types.h"
#include "files/internal/xml_file.h"

namespace chasles {

namespace {

using internal::XmlFile;
using Transform = Eigen::Matrix4d;

/// The positions of one <geometry>'s mesh and its triangles (local indices).
struct ColladaMesh {
  std::vector<double> xyz;
  std::vector<std::uint32_t> indices;
};

/// Reads the indices of a <p> (or <vcount>) element: non-negative integers.
std::vector<std::int64_t> Integers(const XmlFile& xml, pugi::xml_node e) {
  std::vector<std::int64_t> out;
  const std::string_view text = e.text().get();
  std::size_t i = 0;
  while (true) {
    while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
    if (i >= text.size()) break;
    std::size_t j = i;
    while (j < text.size() && !std::isspace(static_cast<unsigned char>(text[j]))) ++j;
    std::int64_t v = 0;
    const auto [end, ec] = std::from_chars(text.data() + i, text.data() + j, v);
    if (ec != std::errc() || end != text.data() + j || v < 0) {
      xml.Fail(e, fmt::format("<{}>: '{}' is not a non-negative integer", e.name(),
                              text.substr(i, std::min<std::size_t>(j - i, 24))));
    }
    out.push_back(v);
    i = j;
  }
  return out;
}

std::string Fragment(const XmlFile& xml, pugi::xml_node e, const char* attribute) {
  const std::string url = e.attribute(attribute).value();
  if (url.size() < 2 || url[0] != '#') {
    xml.Fail(e, fmt::format("<{} {}=\"{}\">: expected a reference '#id' within the file", e.name(),
                            attribute, url));
  }
  return url.substr(1);
}

class ColladaReader {
 public:
  explicit ColladaReader(const XmlFile& xml) : xml_(xml) {
    const pugi::xml_node root = xml.root();
    if (std::string(root.name()) != "COLLADA") {
      xml.Fail(root,
               fmt::format("root element <{}>: a Collada file starts with <COLLADA>", root.name()));
    }
    // Every element with an id, for references (#id).
    std::vector<pugi::xml_node> stack{root};
    while (!stack.empty()) {
      const pugi::xml_node n = stack.back();
      stack.pop_back();
      if (const char* id = n.attribute("id").value(); *id) ids_.emplace(id, n);
      for (pugi::xml_node c = n.first_child(); c; c = c.next_sibling()) {
        if (c.type() == pugi::node_element) stack.push_back(c);
      }
    }
  }

  TriangleSoup Read();

 private:
  pugi::xml_node Find(const std::string& id, pugi::xml_node from, const char* what) const {
    const auto it = ids_.find(id);
    if (it == ids_.end())
      xml_.Fail(from, fmt::format("{} '#{}': no element with this id", what, id));
    return it->second;
  }
  const ColladaMesh& Mesh(pugi::xml_node geometry);
  std::vector<double> Positions(pugi::xml_node source);
  void Primitive(pugi::xml_node prim, ColladaMesh& mesh);
  void Node(pugi::xml_node node, const Transform& X, int depth);
  void Emit(const ColladaMesh& mesh, const Transform& X, pugi::xml_node at);
  Transform NodeTransform(pugi::xml_node node) const;

  const XmlFile& xml_;
  std::map<std::string, pugi::xml_node> ids_;
  std::map<std::string, ColladaMesh> meshes_;
  std::set<std::string> instancing_;  // nodes being expanded (a cycle check)
  TriangleSoup out_;
};

std::vector<double> ColladaReader::Positions(pugi::xml_node source) {
  const pugi::xml_node array = source.child("float_array");
  if (!array) xml_.Fail(source, "a position <source> needs a <float_array>");
  const std::vector<double> values = xml_.TextNumbers(array, 0);
  if (array.attribute("count") &&
      static_cast<std::size_t>(array.attribute("count").as_ullong()) != values.size()) {
    xml_.Fail(array, fmt::format("<float_array count=\"{}\"> holds {} numbers",
                                 array.attribute("count").value(), values.size()));
  }
  const pugi::xml_node accessor = source.child("technique_common").child("accessor");
  std::size_t stride = 3, offset = 0, count = values.size() / 3;
  if (accessor) {
    stride = accessor.attribute("stride") ? accessor.attribute("stride").as_ullong() : 1;
    offset = accessor.attribute("offset").as_ullong();
    count = accessor.attribute("count").as_ullong();
    if (stride < 3 || stride > 64)
      xml_.Fail(accessor, "a position accessor's stride must be 3 to 64");
    if (count > 0 && offset + (count - 1) * stride + 3 > values.size()) {
      xml_.Fail(accessor, fmt::format("<accessor count=\"{}\" stride=\"{}\"> needs more than the "
                                      "{} numbers of its array",
                                      count, stride, values.size()));
    }
  }
  std::vector<double> xyz;
  xyz.reserve(3 * count);
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t k = 0; k < 3; ++k) xyz.push_back(values[offset + i * stride + k]);
  }
  return xyz;
}

void ColladaReader::Primitive(pugi::xml_node prim, ColladaMesh& mesh) {
  const std::string tag = prim.name();
  std::size_t stride = 0, vertex_offset = SIZE_MAX;
  for (pugi::xml_node in = prim.child("input"); in; in = in.next_sibling("input")) {
    const std::size_t offset = in.attribute("offset").as_ullong();
    if (offset > 64) xml_.Fail(in, "an input offset beyond 64");
    stride = std::max(stride, offset + 1);
    const std::string semantic = in.attribute("semantic").value();
    if (semantic == "VERTEX" || semantic == "POSITION") vertex_offset = offset;
  }
  if (vertex_offset == SIZE_MAX) xml_.Fail(prim, fmt::format("<{}> has no VERTEX input", tag));
  const std::size_t nv = mesh.xyz.size() / 3;
  // Each polygon's corners (their vertex indices) are fanned into triangles: (0, k, k+1).
  auto fan = [&](pugi::xml_node at, const std::vector<std::int64_t>& p, std::size_t first,
                 std::size_t n) {
    for (std::size_t k = 0; k < n; ++k) {
      const std::int64_t v = p[(first + k) * stride + vertex_offset];
      if (static_cast<std::size_t>(v) >= nv) {
        xml_.Fail(at, fmt::format("vertex index {} out of range: the mesh has {} vertices", v, nv));
      }
    }
    auto corner = [&](std::size_t k) {
      return static_cast<std::uint32_t>(p[(first + k) * stride + vertex_offset]);
    };
    for (std::size_t k = 1; k + 1 < n; ++k) {
      mesh.indices.insert(mesh.indices.end(), {corner(0), corner(k), corner(k + 1)});
    }
  };
  if (tag == "polygons") {  // one <p> per polygon
    for (pugi::xml_node pe = prim.child("p"); pe; pe = pe.next_sibling("p")) {
      const std::vector<std::int64_t> p = Integers(xml_, pe);
      if (p.size() % stride != 0 || p.size() / stride < 3) {
        xml_.Fail(pe, "a polygon needs at least three corners of every input");
      }
      fan(pe, p, 0, p.size() / stride);
    }
    return;
  }
  const std::size_t count = prim.attribute("count").as_ullong();
  const std::vector<std::int64_t> p =
      prim.child("p") ? Integers(xml_, prim.child("p")) : std::vector<std::int64_t>{};
  std::vector<std::int64_t> vcount;
  if (tag == "polylist") {
    vcount = Integers(xml_, prim.child("vcount"));
    if (vcount.size() != count) {
      xml_.Fail(prim, fmt::format("<polylist count=\"{}\"> has {} entries in <vcount>", count,
                                  vcount.size()));
    }
  } else if (count > p.size()) {
    xml_.Fail(prim,
              fmt::format("<triangles count=\"{}\">: <p> holds only {} indices", count, p.size()));
  }
  std::size_t at = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const std::int64_t n = vcount.empty() ? 3 : vcount[i];
    if (n < 3 || n > (1 << 20)) xml_.Fail(prim, fmt::format("a polygon of {} corners", n));
    if ((at + static_cast<std::size_t>(n)) * stride > p.size()) {
      xml_.Fail(prim,
                fmt::format("<{} count=\"{}\">: <p> holds only {} indices", tag, count, p.size()));
    }
    fan(prim, p, at, static_cast<std::size_t>(n));
    at += static_cast<std::size_t>(n);
  }
  if (at * stride != p.size()) {
    xml_.Fail(prim, fmt::format("<{} count=\"{}\">: <p> holds {} indices, not {}", tag, count,
                                p.size(), at * stride));
  }
}

const ColladaMesh& ColladaReader::Mesh(pugi::xml_node geometry) {
  const std::string id = geometry.attribute("id").value();
  if (const auto it = meshes_.find(id); it != meshes_.end()) return it->second;
  ColladaMesh& mesh = meshes_[id];
  const pugi::xml_node m = geometry.child("mesh");
  if (!m) return mesh;  // a spline or another non-mesh geometry has no triangles
  const pugi::xml_node vertices = m.child("vertices");
  if (!vertices) xml_.Fail(m, "a <mesh> without <vertices>");
  pugi::xml_node position;
  for (pugi::xml_node in = vertices.child("input"); in; in = in.next_sibling("input")) {
    if (std::string(in.attribute("semantic").value()) == "POSITION") position = in;
  }
  if (!position) xml_.Fail(vertices, "<vertices> without a POSITION input");
  const std::string source_id = Fragment(xml_, position, "source");
  mesh.xyz = Positions(Find(source_id, position, "source"));
  for (pugi::xml_node prim = m.first_child(); prim; prim = prim.next_sibling()) {
    const std::string tag = prim.name();
    if (tag == "triangles" || tag == "polylist" || tag == "polygons") {
      Primitive(prim, mesh);
    } else if (tag == "trifans" || tag == "tristrips") {
      xml_.Fail(prim, fmt::format("<{}> is not read (triangles, polylist and polygons are)", tag));
    }
  }
  return mesh;
}

Transform ColladaReader::NodeTransform(pugi::xml_node node) const {
  Transform X = Transform::Identity();
  for (pugi::xml_node t = node.first_child(); t; t = t.next_sibling()) {
    const std::string tag = t.name();
    Transform T = Transform::Identity();
    if (tag == "matrix") {
      const std::vector<double> v = xml_.TextNumbers(t, 16);
      for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) T(r, c) = v[4 * r + c];
      }
    } else if (tag == "translate") {
      const std::vector<double> v = xml_.TextNumbers(t, 3);
      T.block<3, 1>(0, 3) = Vec3(v[0], v[1], v[2]);
    } else if (tag == "rotate") {
      const std::vector<double> v = xml_.TextNumbers(t, 4);
      if (Vec3(v[0], v[1], v[2]).norm() == 0.0) continue;
      T.block<3, 3>(0, 0) = RotationFromAxisAngle(Vec3(v[0], v[1], v[2]), v[3] * M_PI / 180.0);
    } else if (tag == "scale") {
      const std::vector<double> v = xml_.TextNumbers(t, 3);
      T.block<3, 3>(0, 0) = Vec3(v[0], v[1], v[2]).asDiagonal();
    } else if (tag == "lookat" || tag == "skew") {
      xml_.Fail(t, fmt::format("<{}> transforms are not read", tag));
    } else {
      continue;
    }
    X = X * T;
  }
  return X;
}

void ColladaReader::Emit(const ColladaMesh& mesh, const Transform& X, pugi::xml_node at) {
  if (out_.indices.size() / 3 + mesh.indices.size() / 3 > kMaxColladaTriangles ||
      out_.xyz.size() / 3 + mesh.xyz.size() / 3 > 3 * kMaxColladaTriangles) {
    xml_.Fail(at, fmt::format("the scene places more than {} triangles (or three times as many "
                              "vertices)",
                              kMaxColladaTriangles));
  }
  const std::size_t base = out_.xyz.size() / 3;
  if (base + mesh.xyz.size() / 3 > UINT32_MAX) xml_.Fail(at, "more than 2^32 vertices");
  for (std::size_t i = 0; i + 2 < mesh.xyz.size(); i += 3) {
    const Eigen::Vector4d p = X * Eigen::Vector4d(mesh.xyz[i], mesh.xyz[i + 1], mesh.xyz[i + 2], 1);
    out_.xyz.insert(out_.xyz.end(), {p[0], p[1], p[2]});
  }
  for (const std::uint32_t i : mesh.indices)
    out_.indices.push_back(static_cast<std::uint32_t>(base + i));
}

void ColladaReader::Node(pugi::xml_node node, const Transform& parent, int depth) {
  if (depth > internal::kMaxXmlDepth) xml_.Fail(node, "nodes instanced deeper than the limit");
  const Transform X = parent * NodeTransform(node);
  for (pugi::xml_node c = node.first_child(); c; c = c.next_sibling()) {
    const std::string tag = c.name();
    if (tag == "instance_geometry") {
      const pugi::xml_node g = Find(Fragment(xml_, c, "url"), c, "instance_geometry");
      Emit(Mesh(g), X, c);
    } else if (tag == "node") {
      Node(c, X, depth + 1);
    } else if (tag == "instance_node") {
      const std::string id = Fragment(xml_, c, "url");
      if (!instancing_.insert(id).second)
        xml_.Fail(c, fmt::format("node '#{}' instances itself", id));
      Node(Find(id, c, "instance_node"), X, depth + 1);
      instancing_.erase(id);
    }
  }
}

TriangleSoup ColladaReader::Read() {
  const pugi::xml_node root = xml_.root();
  const pugi::xml_node asset = root.child("asset");
  double meter = 1.0;
  if (const pugi::xml_node unit = asset.child("unit"); unit && unit.attribute("meter")) {
    meter = xml_.Number(unit, "meter", 1.0);
    if (!(meter > 0.0)) xml_.Fail(unit, "<unit meter> must be positive");
  }
  const std::string up = asset.child("up_axis") ? asset.child("up_axis").text().get() : "Y_UP";
  Mat3 U = Mat3::Identity();  // into z up, keeping the handedness (COLLADA 1.4.1, 5-16)
  if (up == "Y_UP") {
    U << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  } else if (up == "X_UP") {
    U << 0, -1, 0, 0, 0, -1, 1, 0, 0;
  } else if (up != "Z_UP") {
    xml_.Fail(asset.child("up_axis"), fmt::format("up_axis '{}': expected X_UP, Y_UP or Z_UP", up));
  }
  Transform X0 = Transform::Identity();
  X0.block<3, 3>(0, 0) = meter * U;
  pugi::xml_node scene;
  if (const pugi::xml_node inst = root.child("scene").child("instance_visual_scene")) {
    scene = Find(Fragment(xml_, inst, "url"), inst, "instance_visual_scene");
  } else {
    scene = root.child("library_visual_scenes").child("visual_scene");
  }
  if (scene) {
    for (pugi::xml_node n = scene.child("node"); n; n = n.next_sibling("node")) Node(n, X0, 1);
  } else {
    for (pugi::xml_node g = root.child("library_geometries").child("geometry"); g;
         g = g.next_sibling("geometry")) {
      Emit(Mesh(g), X0, g);
    }
  }
  if (out_.indices.empty()) xml_.Fail(root, "empty mesh: the file places no triangle");
  for (const double v : out_.xyz) {
    if (!std::isfinite(v)) xml_.Fail(root, "a vertex is not finite once transformed and scaled");
  }
  out_.format = "Collada";
  return std::move(out_);
}

}  // namespace

TriangleSoup ReadColladaBytes(std::string bytes, const std::string& name) {
  const XmlFile xml(std::move(bytes), name);
  return ColladaReader(xml).Read();
}

TriangleSoup ReadColladaFile(const std::string& path) {
  return ReadColladaBytes(internal::ReadFileBytes(path, "mesh file", internal::kMaxXmlBytes), path);
}

}  // namespace chasles
