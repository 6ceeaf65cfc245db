// PLY (Greg Turk's polygon file format, 1994): a text header
//   ply / format ascii|binary_little_endian|binary_big_endian 1.0 / comment ... / obj_info ...
//   element NAME COUNT / property TYPE NAME / property list COUNT_TYPE ITEM_TYPE NAME / ...
//   end_header
// then, for each element in header order, COUNT records of its properties in order: in ascii
// as white-space separated numbers, in binary as packed values (a list is its count, then the
// items). Types: char/int8, uchar/uint8, short/int16, ushort/uint16, int/int32, uint/uint32,
// float/float32, double/float64.

#include <bit>
#include <cstring>
#include <limits>
#include <optional>
#include <type_traits>
#include <vector>

#include <fmt/format.h>

#include "files/internal/mesh_readers.h"
#include "files/internal/mesh_text.h"

namespace chasles::internal {
namespace {

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

struct PlyTypeInfo {
  std::string_view name, alias;
  std::size_t size;
  bool integer;
  double min, max;  // the range of an integer type
};

constexpr PlyTypeInfo kTypes[] = {
    {"char", "int8", 1, true, -128.0, 127.0},
    {"uchar", "uint8", 1, true, 0.0, 255.0},
    {"short", "int16", 2, true, -32768.0, 32767.0},
    {"ushort", "uint16", 2, true, 0.0, 65535.0},
    {"int", "int32", 4, true, -2147483648.0, 2147483647.0},
    {"uint", "uint32", 4, true, 0.0, 4294967295.0},
    {"float", "float32", 4, false, 0, 0},
    {"double", "float64", 8, false, 0, 0},
};

const PlyTypeInfo& Info(PlyType t) {
  return kTypes[static_cast<int>(t)];
}

std::optional<PlyType> TypeNamed(std::string_view name) {
  for (int i = 0; i < 8; ++i) {
    if (kTypes[i].name == name || kTypes[i].alias == name) return static_cast<PlyType>(i);
  }
  return std::nullopt;
}

struct PlyProperty {
  std::string_view name;
  bool list = false;
  PlyType count_type = PlyType::kUint8;  // lists only
  PlyType type = PlyType::kFloat32;      // the value, or a list's items
};

struct PlyElement {
  std::string_view name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  std::size_t line = 0;  // in the header, for messages
};

enum class PlyEncoding { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct PlyHeader {
  PlyEncoding encoding = PlyEncoding::kAscii;
  std::vector<PlyElement> elements;
  std::size_t body = 0;  // offset of the first byte after end_header's line
};

// The words of one header line (header lines are short; the header is read once).
std::vector<std::string_view> Words(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
  return words;
}

PlyHeader ReadHeader(std::string_view bytes, const std::string& name) {
  PlyHeader h;
  std::size_t pos = 0, line_no = 0;
  bool have_format = false;
  auto fail = [&](std::string_view what) {
    MeshFail(name, fmt::format("PLY header: {} (line {})", what, line_no));
  };
  for (;;) {
    if (pos >= bytes.size()) {
      if (line_no == 0) line_no = 1;
      fail(line_no == 1 ? "empty file" : "the file ends before 'end_header'");
    }
    const std::size_t nl = bytes.find('\n', pos);
    std::string_view line = bytes.substr(pos, nl == std::string_view::npos ? bytes.npos : nl - pos);
    pos = nl == std::string_view::npos ? bytes.size() : nl + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line_no == 1) {
      if (line != "ply") fail("not a PLY file (the first line is not 'ply')");
      continue;
    }
    const std::vector<std::string_view> w = Words(line);
    if (w.empty()) continue;
    if (w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") {
      if (w.size() != 1) fail("unexpected words after 'end_header'");
      if (!have_format) fail("no 'format' line before 'end_header'");
      h.body = pos;
      return h;
    }
    if (w[0] == "format") {
      if (have_format) fail("a second 'format' line");
      if (w.size() != 3) fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      if (w[1] == "ascii") {
        h.encoding = PlyEncoding::kAscii;
      } else if (w[1] == "binary_little_endian") {
        h.encoding = PlyEncoding::kBinaryLittleEndian;
      } else if (w[1] == "binary_big_endian") {
        h.encoding = PlyEncoding::kBinaryBigEndian;
      } else {
        fail(
            fmt::format("unknown format '{}' (ascii, binary_little_endian or "
                        "binary_big_endian)",
                        TextScanner::Short(w[1])));
      }
      if (w[2] != "1.0")
        fail(fmt::format("unsupported version '{}' (1.0)", TextScanner::Short(w[2])));
      have_format = true;
    } else if (w[0] == "element") {
      if (w.size() != 3) fail("expected 'element NAME COUNT'");
      std::int64_t count = 0;
      if (!ParseInt(w[2], count) || count < 0) {
        fail(fmt::format("element '{}': count '{}' is not a non-negative integer",
                         TextScanner::Short(w[1]), TextScanner::Short(w[2])));
      }
      for (const PlyElement& e : h.elements) {
        if (e.name == w[1]) fail(fmt::format("a second element '{}'", TextScanner::Short(w[1])));
      }
      h.elements.push_back({w[1], static_cast<std::uint64_t>(count), {}, line_no});
    } else if (w[0] == "property") {
      if (h.elements.empty()) fail("'property' before any 'element'");
      PlyProperty p;
      auto type = [&](std::string_view word) {
        const std::optional<PlyType> t = TypeNamed(word);
        if (!t) {
          fail(
              fmt::format("unknown property type '{}' (char, uchar, short, ushort, int, uint, "
                          "float, double, or int8 ... float64)",
                          TextScanner::Short(word)));
        }
        return *t;
      };
      if (w.size() == 5 && w[1] == "list") {
        p.list = true;
        p.count_type = type(w[2]);
        p.type = type(w[3]);
        p.name = w[4];
        if (!Info(p.count_type).integer) {
          fail(fmt::format("list '{}': its count type '{}' is not an integer type",
                           TextScanner::Short(p.name), Info(p.count_type).name));
        }
      } else if (w.size() == 3 && w[1] != "list") {
        p.type = type(w[1]);
        p.name = w[2];
      } else {
        fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE ITEM_TYPE NAME'");
      }
      h.elements.back().properties.push_back(p);
    } else {
      fail(fmt::format("unknown header line '{}'", TextScanner::Short(line)));
    }
  }
}

// Reads binary values, bounds-checked against the end of the bytes.
class BinaryValues {
 public:
  BinaryValues(std::string_view bytes, std::size_t start, bool big_endian, const std::string& name)
      : bytes_(bytes),
        pos_(start),
        swap_(big_endian != (std::endian::native == std::endian::big)),
        name_(name) {}

  std::size_t Remaining() const { return bytes_.size() - pos_; }
  [[noreturn]] void Fail(std::string_view what) const { FailAt(pos_, what); }
  [[noreturn]] void FailAt(std::size_t at, std::string_view what) const {
    MeshFail(name_, fmt::format("{} (byte offset {})", what, at));
  }
  std::size_t pos() const { return pos_; }

  double Value(PlyType t, std::string_view what) {
    const std::size_t size = Info(t).size;
    if (Remaining() < size) {
      Fail(fmt::format("truncated: the file ends inside {}", what));
    }
    unsigned char b[8];
    std::memcpy(b, bytes_.data() + pos_, size);
    if (swap_) {
      for (std::size_t i = 0; i < size / 2; ++i) std::swap(b[i], b[size - 1 - i]);
    }
    pos_ += size;
    switch (t) {
      case PlyType::kInt8:
        return static_cast<double>(static_cast<std::int8_t>(b[0]));
      case PlyType::kUint8:
        return static_cast<double>(b[0]);
      case PlyType::kInt16:
        return static_cast<double>(Load<std::int16_t>(b));
      case PlyType::kUint16:
        return static_cast<double>(Load<std::uint16_t>(b));
      case PlyType::kInt32:
        return static_cast<double>(Load<std::int32_t>(b));
      case PlyType::kUint32:
        return static_cast<double>(Load<std::uint32_t>(b));
      case PlyType::kFloat32:
        return static_cast<double>(Load<float>(b));
      case PlyType::kFloat64:
        return Load<double>(b);
    }
    return 0;
  }
  /// Checks that `n` values of type `t` fit in what is left (before reading or skipping them).
  void CheckFits(std::uint64_t n, PlyType t, std::string_view what) const {
    if (n > Remaining() / Info(t).size) {
      Fail(fmt::format("{} declares {} values of {} bytes but only {} bytes are left", what, n,
                       Info(t).size, Remaining()));
    }
  }
  void SkipValues(std::uint64_t n, PlyType t, std::string_view what) {
    CheckFits(n, t, what);
    pos_ += static_cast<std::size_t>(n * Info(t).size);
  }
  void SkipBytes(std::uint64_t n) { pos_ += static_cast<std::size_t>(n); }  // checked before
  void Finish() const {
    if (Remaining() != 0) {
      Fail(
          fmt::format("{} bytes follow the last element: the header's counts or types do not "
                      "match the data",
                      Remaining()));
    }
  }

 private:
  template <class T>
  static T Load(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof v);
    return v;
  }

  std::string_view bytes_;
  std::size_t pos_;
  bool swap_;
  const std::string& name_;
};

// Reads ascii values: one token each, integers for the integer types.
class AsciiValues {
 public:
  AsciiValues(std::string_view bytes, std::size_t start, const std::string& name)
      : s_(bytes, name) {
    s_.Seek(start);
  }
  [[noreturn]] void Fail(std::string_view what) const { s_.Fail(what); }
  [[noreturn]] void FailAt(std::size_t at, std::string_view what) const { s_.FailAt(at, what); }
  std::size_t pos() {
    s_.SkipSpace();
    return s_.pos();
  }

  double Value(PlyType t, std::string_view what) {
    s_.SkipSpace();
    const std::size_t at = s_.pos();
    const std::string_view tok = s_.Token();
    if (tok.empty()) Fail(fmt::format("truncated: the file ends inside {}", what));
    const PlyTypeInfo& info = Info(t);
    if (info.integer) {
      std::int64_t i = 0;
      if (!ParseInt(tok, i)) {
        FailAt(at, fmt::format("{}: '{}' is not an integer (its type is {})", what,
                               TextScanner::Short(tok), info.name));
      }
      const auto v = static_cast<double>(i);
      if (v < info.min || v > info.max) {
        FailAt(at, fmt::format("{}: {} does not fit its type {}", what, i, info.name));
      }
      return v;
    }
    double v = 0;
    if (!ParseDouble(tok, v)) {
      FailAt(at, fmt::format("{}: '{}' is not a number", what, TextScanner::Short(tok)));
    }
    return v;
  }
  // Each value takes at least two bytes ("0 "); the last of the file may lack its separator.
  void CheckFits(std::uint64_t n, PlyType, std::string_view what) const {
    if (n > (s_.Remaining() + 1) / 2) {
      Fail(
          fmt::format("{} declares {} values but only {} bytes are left", what, n, s_.Remaining()));
    }
  }
  void SkipValues(std::uint64_t n, PlyType t, std::string_view what) {
    CheckFits(n, t, what);
    for (std::uint64_t i = 0; i < n; ++i) Value(t, what);
  }
  void Finish() {
    s_.SkipSpace();
    if (!s_.AtEnd()) Fail("unexpected data after the last element");
  }

 private:
  TextScanner s_;
};

// What the mesh needs from the header: which element and properties hold it.
struct PlyLayout {
  std::size_t vertex = 0, face = 0;              // element indices
  std::size_t x = 0, y = 0, z = 0, indices = 0;  // property indices
  bool has_face = false;
};

PlyLayout FindLayout(const PlyHeader& h, const std::string& name) {
  PlyLayout l;
  bool has_vertex = false;
  for (std::size_t e = 0; e < h.elements.size(); ++e) {
    if (h.elements[e].name == "vertex") {
      l.vertex = e;
      has_vertex = true;
    } else if (h.elements[e].name == "face") {
      l.face = e;
      l.has_face = true;
    }
  }
  if (!has_vertex) MeshFail(name, "PLY header declares no 'vertex' element");
  const PlyElement& v = h.elements[l.vertex];
  std::size_t* axes[3] = {&l.x, &l.y, &l.z};
  const char* axis_names[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    bool found = false;
    for (std::size_t p = 0; p < v.properties.size() && !found; ++p) {
      if (v.properties[p].name != axis_names[k]) continue;
      if (v.properties[p].list) {
        MeshFail(name, fmt::format("PLY header: vertex property '{}' is a list; it must be a "
                                   "number (line {})",
                                   axis_names[k], v.line));
      }
      *axes[k] = p;
      found = true;
    }
    if (!found) {
      MeshFail(name, fmt::format("PLY header: element 'vertex' has no property '{}' (line {})",
                                 axis_names[k], v.line));
    }
  }
  if (!l.has_face) {
    MeshFail(name,
             "empty mesh (the PLY declares no 'face' element: a point cloud has no "
             "surface)");
  }
  const PlyElement& f = h.elements[l.face];
  for (std::size_t p = 0; p < f.properties.size(); ++p) {
    const PlyProperty& prop = f.properties[p];
    if (prop.name != "vertex_indices" && prop.name != "vertex_index") continue;
    if (!prop.list) {
      MeshFail(name, fmt::format("PLY header: face property '{}' must be a list (line {})",
                                 prop.name, f.line));
    }
    if (!Info(prop.type).integer) {
      MeshFail(name, fmt::format("PLY header: face property '{}' has items of type {}; vertex "
                                 "indices must be integers (line {})",
                                 prop.name, Info(prop.type).name, f.line));
    }
    l.indices = p;
    return l;
  }
  MeshFail(name, fmt::format("PLY header: element 'face' has no list property 'vertex_indices' "
                             "(or 'vertex_index') (line {})",
                             f.line));
}

// The counts in the header against the bytes after it, before anything is allocated: each
// record takes at least its fixed-size values and its lists' counts (binary), or two bytes a
// value (ascii).
void CheckCountsFit(const PlyHeader& h, std::uint64_t left, const std::string& name) {
  const bool ascii = h.encoding == PlyEncoding::kAscii;
  if (ascii) ++left;  // the last value may lack its separator
  std::uint64_t need = 0;
  for (const PlyElement& e : h.elements) {
    std::uint64_t record = 0;
    for (const PlyProperty& p : e.properties) {
      record += ascii ? 2 : Info(p.list ? p.count_type : p.type).size;
    }
    if (record == 0) continue;  // an element without properties takes no bytes
    if (e.count > (left - need) / record) {
      MeshFail(name, fmt::format("PLY header declares {} '{}' records of at least {} bytes each, "
                                 "but only {} bytes follow the header: the file is truncated or "
                                 "the count is wrong (line {})",
                                 e.count, TextScanner::Short(e.name), record,
                                 ascii ? left - 1 : left, e.line));
    }
    need += e.count * record;
  }
}

template <class Values>
void ReadBody(Values& in, const PlyHeader& h, const PlyLayout& l, MeshFileData& data) {
  const std::uint64_t nv = h.elements[l.vertex].count;
  FanBuilder fan(data.indices);
  for (std::size_t e = 0; e < h.elements.size(); ++e) {
    const PlyElement& el = h.elements[e];
    if (el.properties.empty()) continue;
    const bool is_vertex = e == l.vertex, is_face = e == l.face;
    if constexpr (std::is_same_v<Values, BinaryValues>) {
      if (!is_vertex && !is_face) {
        bool fixed = true;
        std::uint64_t record = 0;
        for (const PlyProperty& p : el.properties) {
          fixed = fixed && !p.list;
          record += Info(p.type).size;
        }
        if (fixed) {  // CheckCountsFit showed count * record bytes are there
          in.SkipBytes(el.count * record);
          continue;
        }
      }
    }
    for (std::uint64_t r = 0; r < el.count; ++r) {
      if (is_face) fan.Start();
      double xyz[3] = {0, 0, 0};
      for (std::size_t p = 0; p < el.properties.size(); ++p) {
        const PlyProperty& prop = el.properties[p];
        if (!prop.list) {
          const std::size_t at = in.pos();
          const double v = in.Value(prop.type, "a record");
          if (is_vertex && (p == l.x || p == l.y || p == l.z)) {
            const int k = p == l.x ? 0 : p == l.y ? 1 : 2;
            if (!IsMeshCoordinate(v)) {
              in.FailAt(at, fmt::format("vertex {}: coordinate {} is {}, {}", r, "xyz"[k], v,
                                        kCoordinateRule));
            }
            xyz[k] = v;
          }
          continue;
        }
        const std::size_t at = in.pos();
        const double count = in.Value(prop.count_type, "a list's count");
        if (count < 0) in.FailAt(at, fmt::format("a list's count is negative ({})", count));
        const auto n = static_cast<std::uint64_t>(count);
        if (!(is_face && p == l.indices)) {
          in.SkipValues(n, prop.type, "a list");
          continue;
        }
        if (n < 3) {
          in.FailAt(at, fmt::format("face {} has {} vertices; a face needs at least 3", r, n));
        }
        in.CheckFits(n, prop.type, "a face");
        for (std::uint64_t c = 0; c < n; ++c) {
          const std::size_t i_at = in.pos();
          const double i = in.Value(prop.type, "a face's vertex indices");
          if (i < 0 || i >= static_cast<double>(nv)) {
            in.FailAt(i_at, fmt::format("face {}: vertex index {} is out of range (0 to {})", r, i,
                                        static_cast<double>(nv) - 1));
          }
          fan.Add(static_cast<std::uint32_t>(i));
        }
      }
      if (is_vertex) std::memcpy(data.xyz.data() + 3 * r, xyz, sizeof xyz);
    }
  }
  in.Finish();
}

}  // namespace

MeshFileData ReadPly(std::string_view bytes, const std::string& name) {
  const PlyHeader h = ReadHeader(bytes, name);
  const PlyLayout l = FindLayout(h, name);
  CheckCountsFit(h, bytes.size() - h.body, name);
  const std::uint64_t nv = h.elements[l.vertex].count;
  if (nv > UINT32_MAX) MeshFail(name, "more than 2^32 - 1 vertices");
  MeshFileData data;
  data.format = "PLY";
  // Binary values are the declared type's (a float widened exactly); ascii ones are the double
  // nearest to their text, whatever the declared type.
  const std::vector<PlyProperty>& vertex = h.elements[l.vertex].properties;
  data.single_precision =
      h.encoding != PlyEncoding::kAscii &&
      (vertex[l.x].type == PlyType::kFloat32 || vertex[l.y].type == PlyType::kFloat32 ||
       vertex[l.z].type == PlyType::kFloat32);
  data.xyz.resize(3 * static_cast<std::size_t>(nv));
  if (h.encoding == PlyEncoding::kAscii) {
    AsciiValues in(bytes, h.body, name);
    ReadBody(in, h, l, data);
  } else {
    BinaryValues in(bytes, h.body, h.encoding == PlyEncoding::kBinaryBigEndian, name);
    ReadBody(in, h, l, data);
  }
  if (data.indices.empty()) MeshFail(name, "empty mesh (the PLY holds no face)");
  return data;
}

}  // namespace chasles::internal
