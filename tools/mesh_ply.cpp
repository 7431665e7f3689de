// Strict PLY reader (ascii, binary_little_endian, binary_big_endian).
//
// Steps:
//  1. Header: "ply", a "format" line, "element NAME COUNT" lines each followed by its
//     "property TYPE NAME" / "property list COUNT_TYPE ITEM_TYPE NAME" lines, "comment" and
//     "obj_info" lines ignored, up to "end_header". The vertex element must have scalar x, y,
//     z; the face element (optional) a list vertex_indices (or vertex_index) of integers.
//  2. Before reading an element, its declared count is checked against the bytes left (each
//     instance takes at least its scalar sizes and list counts in binary, two bytes per
//     property in ascii), so no count can make the reader allocate or loop beyond the file.
//  3. Every property of every instance is read by its declared type (ascii: one token,
//     integers range-checked against their type; binary: the type's size in the file's byte
//     order); x, y, z make a vertex, face lists are fanned after their indices are checked
//     against the vertex count; everything else is skipped.
//  4. The data must end exactly after the last declared element.
// Source: G. Turk, "The PLY Polygon File Format" (1994), as documented by Paul Bourke.
#include <array>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "mesh_reader_util.hpp"
#include "mesh_readers.hpp"

namespace proxima::tool {

namespace {

using mesh_read::file_error;

enum class Type { I8, U8, I16, U16, I32, U32, F32, F64 };
enum class Format { Ascii, Little, Big };

struct Property {
  std::string name;
  bool list = false;
  Type count_type = Type::U8;
  Type type = Type::F32;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::size_t data_start = 0;
};

std::optional<Type> type_named(std::string_view name) {
  static constexpr std::array<std::pair<std::string_view, Type>, 16> kTypes{{
      {"char", Type::I8},
      {"int8", Type::I8},
      {"uchar", Type::U8},
      {"uint8", Type::U8},
      {"short", Type::I16},
      {"int16", Type::I16},
      {"ushort", Type::U16},
      {"uint16", Type::U16},
      {"int", Type::I32},
      {"int32", Type::I32},
      {"uint", Type::U32},
      {"uint32", Type::U32},
      {"float", Type::F32},
      {"float32", Type::F32},
      {"double", Type::F64},
      {"float64", Type::F64},
  }};
  for (const auto& [n, t] : kTypes) {
    if (n == name) return t;
  }
  return std::nullopt;
}

std::size_t size_of(Type t) {
  switch (t) {
    case Type::I8:
    case Type::U8: return 1;
    case Type::I16:
    case Type::U16: return 2;
    case Type::I32:
    case Type::U32:
    case Type::F32: return 4;
    case Type::F64: return 8;
  }
  return 8;
}

bool is_integer(Type t) { return t != Type::F32 && t != Type::F64; }

std::string header_line(std::size_t line) { return "PLY header line " + std::to_string(line); }

// One header line's tokens (split on spaces and tabs).
std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> out;
  mesh_read::Tokens tokens(line);
  for (std::string_view t = tokens.next(); !t.empty(); t = tokens.next()) out.push_back(t);
  return out;
}

std::optional<Error> read_property(const std::vector<std::string_view>& w, std::size_t line, Header& header) {
  if (header.elements.empty())
    return file_error(ErrorCode::InvalidArgument, header_line(line) + ": property before any element");
  Property p;
  const bool list = w.size() >= 2 && w[1] == "list";
  if (w.size() != (list ? 5u : 3u)) {
    return file_error(ErrorCode::InvalidArgument, header_line(line) + ": malformed property line");
  }
  p.list = list;
  const auto type = type_named(w[list ? 3 : 1]);
  const auto count_type = list ? type_named(w[2]) : std::optional<Type>(Type::U8);
  if (!type || !count_type)
    return file_error(ErrorCode::InvalidArgument, header_line(line) + ": unknown property type");
  if (!is_integer(*count_type)) {
    return file_error(ErrorCode::InvalidArgument, header_line(line) + ": a list count must have an integer type");
  }
  p.type = *type;
  p.count_type = *count_type;
  p.name = std::string(w.back());
  header.elements.back().properties.push_back(std::move(p));
  return std::nullopt;
}

std::optional<Error> read_header_line(const std::vector<std::string_view>& w, std::size_t line, Header& header,
                                      bool& have_format) {
  if (w.empty() || w[0] == "comment" || w[0] == "obj_info") return std::nullopt;
  if (w[0] == "format") {
    if (w.size() != 3 || w[2] != "1.0")
      return file_error(ErrorCode::InvalidArgument, header_line(line) + ": malformed format line");
    if (w[1] == "ascii") {
      header.format = Format::Ascii;
    } else if (w[1] == "binary_little_endian") {
      header.format = Format::Little;
    } else if (w[1] == "binary_big_endian") {
      header.format = Format::Big;
    } else {
      return file_error(ErrorCode::InvalidArgument, header_line(line) + ": unknown format " + mesh_read::quoted(w[1]));
    }
    have_format = true;
    return std::nullopt;
  }
  if (w[0] == "element") {
    const auto count = w.size() == 3 ? mesh_read::parse_integer(w[2]) : std::nullopt;
    if (!count || *count < 0) {
      return file_error(ErrorCode::InvalidArgument,
                        header_line(line) + ": malformed element line (name and count >= 0)");
    }
    header.elements.push_back(Element{std::string(w[1]), std::uint64_t(*count), {}});
    return std::nullopt;
  }
  if (w[0] == "property") return read_property(w, line, header);
  return file_error(ErrorCode::InvalidArgument, header_line(line) + ": unknown keyword " + mesh_read::quoted(w[0]));
}

Result<Header> read_header(std::string_view bytes) {
  Header header;
  bool have_format = false;
  std::size_t pos = 0;
  for (std::size_t line = 1;; ++line) {
    const std::size_t end = bytes.find('\n', pos);
    if (end == std::string_view::npos) {
      return file_error(ErrorCode::InvalidArgument, "PLY: the header is truncated (no end_header line)");
    }
    std::string_view text = bytes.substr(pos, end - pos);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    pos = end + 1;
    if (line == 1) {
      if (text != "ply") return file_error(ErrorCode::InvalidArgument, "PLY: the file does not start with \"ply\"");
      continue;
    }
    if (text == "end_header") break;
    if (auto e = read_header_line(split(text), line, header, have_format)) return *e;
  }
  if (!have_format) return file_error(ErrorCode::InvalidArgument, "PLY: the header has no format line");
  header.data_start = pos;
  return header;
}

// The values of the data section, read by type (ascii tokens or binary in either order).
class Values {
 public:
  Values(std::string_view data, Format format) : data_(data), format_(format), tokens_(data) {}

  std::size_t remaining() const { return format_ == Format::Ascii ? tokens_.remaining() : data_.size() - pos_; }

  /// Reads one value; `problem` says why not.
  bool read(Type type, double& out, std::string& problem) {
    return format_ == Format::Ascii ? read_ascii(type, out, problem) : read_binary(type, out, problem);
  }

  /// What follows the last element, if anything ("" when the data ended).
  std::string trailing() {
    if (format_ != Format::Ascii) {
      return pos_ == data_.size() ? "" : std::to_string(data_.size() - pos_) + " bytes";
    }
    const std::string_view t = tokens_.next();
    return t.empty() ? "" : mesh_read::quoted(t) + " on data line " + std::to_string(tokens_.line());
  }

 private:
  bool read_ascii(Type type, double& out, std::string& problem) {
    const std::string_view token = tokens_.next();
    if (token.empty()) {
      problem = "the data ends early";
      return false;
    }
    if (!is_integer(type)) {
      const auto v = mesh_read::parse_double(token);
      if (!v) problem = "malformed number " + mesh_read::quoted(token);
      out = v.value_or(0.0);
      return v.has_value();
    }
    const auto v = mesh_read::parse_integer(token);
    const std::size_t bits = 8 * size_of(type);
    const bool is_signed = type == Type::I8 || type == Type::I16 || type == Type::I32;
    const std::int64_t lo = is_signed ? -(std::int64_t(1) << (bits - 1)) : 0;
    const std::int64_t hi = is_signed ? (std::int64_t(1) << (bits - 1)) - 1 : (std::int64_t(1) << bits) - 1;
    if (!v || *v < lo || *v > hi) {
      problem = mesh_read::quoted(token) + " is not an integer of the declared type";
      return false;
    }
    out = double(*v);
    return true;
  }

  bool read_binary(Type type, double& out, std::string& problem) {
    const std::size_t n = size_of(type);
    if (data_.size() - pos_ < n) {
      problem = "the data ends early";
      return false;
    }
    unsigned char b[8];
    for (std::size_t i = 0; i < n; ++i) {
      b[i] = static_cast<unsigned char>(data_[pos_ + (format_ == Format::Little ? i : n - 1 - i)]);
    }
    pos_ += n;
    out = decode(type, b);
    return true;
  }

  static double decode(Type type, const unsigned char* b) {
    std::uint64_t u = 0;
    for (std::size_t i = size_of(type); i-- > 0;) u = (u << 8) | b[i];
    switch (type) {
      case Type::I8: return double(static_cast<std::int8_t>(u));
      case Type::U8: return double(static_cast<std::uint8_t>(u));
      case Type::I16: return double(static_cast<std::int16_t>(u));
      case Type::U16: return double(static_cast<std::uint16_t>(u));
      case Type::I32: return double(static_cast<std::int32_t>(u));
      case Type::U32: return double(static_cast<std::uint32_t>(u));
      case Type::F32: {
        float f = 0.0f;
        const auto bits = mesh_read::quiet_nan_bits(static_cast<std::uint32_t>(u));
        std::memcpy(&f, &bits, sizeof f);
        return double(f);
      }
      case Type::F64: {
        double d = 0.0;
        const std::uint64_t bits = mesh_read::quiet_nan_bits(u);
        std::memcpy(&d, &bits, sizeof d);
        return d;
      }
    }
    return 0.0;
  }

  std::string_view data_;
  Format format_;
  std::size_t pos_ = 0;
  mesh_read::Tokens tokens_;
};

// What the reader does with an element's properties.
struct Roles {
  int x = -1, y = -1, z = -1;  // vertex element: the coordinates' property indices
  int indices = -1;            // face element: the index list's property index
};

std::optional<Error> check_roles(const Element& e, Roles& roles) {
  for (std::size_t i = 0; i < e.properties.size(); ++i) {
    const Property& p = e.properties[i];
    if (e.name == "vertex" && (p.name == "x" || p.name == "y" || p.name == "z")) {
      if (p.list) return file_error(ErrorCode::InvalidArgument, "PLY: vertex property \"" + p.name + "\" is a list");
      (p.name == "x" ? roles.x : p.name == "y" ? roles.y : roles.z) = int(i);
    }
    if (e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index")) {
      if (!p.list || !is_integer(p.type)) {
        return file_error(ErrorCode::InvalidArgument,
                          "PLY: face property \"" + p.name + "\" must be a list of integers");
      }
      roles.indices = int(i);
    }
  }
  if (e.name == "vertex" && (roles.x < 0 || roles.y < 0 || roles.z < 0)) {
    return file_error(ErrorCode::InvalidArgument, "PLY: the vertex element lacks one of the properties x, y, z");
  }
  if (e.name == "face" && roles.indices < 0) {
    return file_error(ErrorCode::InvalidArgument, "PLY: the face element has no vertex_indices list");
  }
  return std::nullopt;
}

// Step 2: the declared count against the bytes left.
std::optional<Error> check_count(const Element& e, Format format, std::size_t remaining) {
  std::uint64_t least = 0;
  for (const Property& p : e.properties) least += format == Format::Ascii ? 2 : size_of(p.list ? p.count_type : p.type);
  if (least == 0) {
    if (e.count == 0) return std::nullopt;
    return file_error(ErrorCode::InvalidArgument, "PLY: element \"" + e.name + "\" declares no property");
  }
  if (e.count > remaining / least) {
    return file_error(ErrorCode::InvalidArgument, "PLY: element \"" + e.name + "\" declares " +
                                                      std::to_string(e.count) + " instances, but the " +
                                                      std::to_string(remaining) + " bytes left can hold at most " +
                                                      std::to_string(remaining / least));
  }
  return std::nullopt;
}

struct Reading {
  Values values;
  IndexedMesh mesh;
  std::uint64_t vertex_count = 0;
  std::vector<std::uint32_t> corners;
};

std::string where(const Element& e, std::uint64_t i, const Property& p) {
  return "PLY element \"" + e.name + "\" [" + std::to_string(i) + "], property \"" + p.name + "\"";
}

// One list property: its count, then its items (indices collected when `collect`).
std::optional<Error> read_list(Reading& r, const Element& e, std::uint64_t i, const Property& p, bool collect,
                               Format format) {
  double count = 0.0;
  std::string problem;
  if (!r.values.read(p.count_type, count, problem))
    return file_error(ErrorCode::InvalidArgument, where(e, i, p) + ": " + problem);
  const std::size_t least = format == Format::Ascii ? 2 : size_of(p.type);
  if (count < 0 || count > double(r.values.remaining() / least)) {
    return file_error(
        ErrorCode::InvalidArgument,
        where(e, i, p) + ": list count " + std::to_string(std::int64_t(count)) + " does not fit the data left");
  }
  if (collect) r.corners.clear();
  for (std::uint64_t k = 0; k < std::uint64_t(count); ++k) {
    double v = 0.0;
    if (!r.values.read(p.type, v, problem))
      return file_error(ErrorCode::InvalidArgument, where(e, i, p) + ": " + problem);
    if (!collect) continue;
    if (v < 0)
      return file_error(ErrorCode::OutOfRange,
                        where(e, i, p) + ": negative vertex index " + std::to_string(std::int64_t(v)));
    if (v >= double(r.vertex_count)) {
      return file_error(ErrorCode::OutOfRange, where(e, i, p) + ": vertex index " + std::to_string(std::int64_t(v)) +
                                                   " is beyond the " + std::to_string(r.vertex_count) + " vertices");
    }
    r.corners.push_back(static_cast<std::uint32_t>(v));
  }
  if (collect && r.corners.size() >= 3) mesh_read::push_fan(r.mesh, r.corners.data(), r.corners.size());
  return std::nullopt;
}

std::optional<Error> read_element(Reading& r, const Element& e, const Roles& roles, Format format) {
  if (auto error = check_count(e, format, r.values.remaining())) return error;
  if (e.name == "vertex") r.mesh.vertices.reserve(e.count);
  double xyz[3] = {0.0, 0.0, 0.0};
  std::string problem;
  for (std::uint64_t i = 0; i < e.count; ++i) {
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const Property& p = e.properties[k];
      if (p.list) {
        if (auto error = read_list(r, e, i, p, int(k) == roles.indices, format)) return error;
        continue;
      }
      double v = 0.0;
      if (!r.values.read(p.type, v, problem))
        return file_error(ErrorCode::InvalidArgument, where(e, i, p) + ": " + problem);
      if (int(k) == roles.x) xyz[0] = v;
      if (int(k) == roles.y) xyz[1] = v;
      if (int(k) == roles.z) xyz[2] = v;
    }
    if (roles.x >= 0) {
      const std::string at = "PLY element \"vertex\" [" + std::to_string(i) + "]";
      if (auto error = mesh_read::push_vertex(r.mesh, xyz[0], xyz[1], xyz[2], at)) return error;
    }
  }
  return std::nullopt;
}

}  // namespace

Result<IndexedMesh> read_ply(std::string_view bytes) {
  auto header = read_header(bytes);
  if (!header.ok()) return header.error();
  const Header& h = *header;
  std::vector<Roles> roles(h.elements.size());
  std::uint64_t vertex_count = 0;
  int vertex_elements = 0;
  for (std::size_t i = 0; i < h.elements.size(); ++i) {
    if (auto e = check_roles(h.elements[i], roles[i])) return *e;
    if (h.elements[i].name == "vertex") {
      vertex_count = h.elements[i].count;
      ++vertex_elements;
    }
  }
  if (vertex_elements != 1)
    return file_error(ErrorCode::InvalidArgument, "PLY: the header must declare one vertex element");
  if (vertex_count > std::numeric_limits<std::uint32_t>::max()) {
    return file_error(ErrorCode::OutOfRange, "PLY: too many vertices");
  }
  Reading r{Values(bytes.substr(h.data_start), h.format), {}, vertex_count, {}};
  for (std::size_t i = 0; i < h.elements.size(); ++i) {
    if (auto e = read_element(r, h.elements[i], roles[i], h.format)) return *e;
  }
  const std::string rest = r.values.trailing();
  if (!rest.empty()) {
    return file_error(ErrorCode::InvalidArgument, "PLY: data continues past the declared elements (" + rest + ")");
  }
  return std::move(r.mesh);
}

}  // namespace proxima::tool
