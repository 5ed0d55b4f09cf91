#include "geometry/ply_reader.h"

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <new>
#include <optional>
#include <set>
#include <stdexcept>
#include <vector>

#include "gpu/file_bytes.h"

namespace tallow::geometry {
namespace {

// ---------------------------------------------------------------------------------------------
// Types of the PLY format (Turk 1994, "The PLY Polygon File Format")

enum class Scalar : std::uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct ScalarInfo {
  std::string_view name;   ///< the original name
  std::string_view alias;  ///< the sized name used by newer writers
  int bytes;
  bool integer;
  double min, max;  ///< range of the integer types
};

constexpr ScalarInfo kScalars[] = {
    {"char", "int8", 1, true, -128.0, 127.0},
    {"uchar", "uint8", 1, true, 0.0, 255.0},
    {"short", "int16", 2, true, -32768.0, 32767.0},
    {"ushort", "uint16", 2, true, 0.0, 65535.0},
    {"int", "int32", 4, true, -2147483648.0, 2147483647.0},
    {"uint", "uint32", 4, true, 0.0, 4294967295.0},
    {"float", "float32", 4, false, 0.0, 0.0},
    {"double", "float64", 8, false, 0.0, 0.0},
};

const ScalarInfo& info(Scalar type) { return kScalars[static_cast<int>(type)]; }

std::optional<Scalar> parseScalarName(std::string_view name) {
  for (std::size_t i = 0; i < std::size(kScalars); ++i)
    if (name == kScalars[i].name || name == kScalars[i].alias) return static_cast<Scalar>(i);
  return std::nullopt;
}

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Property {
  std::string name;
  Scalar type = Scalar::Float32;  ///< the item type for a list
  bool list = false;
  Scalar countType = Scalar::UInt8;
  int line = 0;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
  int line = 0;
};

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::size_t dataOffset = 0;  ///< first byte after end_header's line
  int endHeaderLine = 0;
};

/// What each vertex property is for.
enum class Role : std::uint8_t { Skip, X, Y, Z, NX, NY, NZ };

struct Layout {
  std::size_t vertexElement = 0;
  std::size_t faceElement = 0;
  std::vector<Role> vertexRoles;
  bool hasNormals = false;
  std::size_t faceList = 0;  ///< index of vertex_indices among the face properties
};

/// Token for an error message: bounded length, control characters escaped.
std::string quote(std::string_view token) {
  constexpr std::size_t kMaxShown = 40;
  std::string out = "\"";
  for (std::size_t i = 0; i < token.size() && i < kMaxShown; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\x%02x", c);
      out += escaped;
    }
  }
  if (token.size() > kMaxShown) out += "…";
  return out + "\"";
}

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::vector<std::string_view> splitTokens(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isSpace(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !isSpace(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

[[noreturn]] void failAtLine(const std::string& name, int line, const std::string& message) {
  throw std::runtime_error(name + ":" + std::to_string(line) + ": " + message);
}

// ---------------------------------------------------------------------------------------------
// Header

Header parseHeader(std::string_view data, const std::string& name) {
  Header header;
  bool haveFormat = false;
  // Names seen so far (views into `data`), for duplicate checks in O(log n) per name.
  std::set<std::string_view> elementNames, propertyNames;
  std::size_t offset = 0;
  int line = 0;
  while (offset < data.size()) {
    const std::size_t newline = data.find('\n', offset);
    const std::size_t end = newline == std::string_view::npos ? data.size() : newline;
    const std::string_view text = data.substr(offset, end - offset);
    offset = newline == std::string_view::npos ? data.size() : newline + 1;
    ++line;
    const std::vector<std::string_view> tokens = splitTokens(text);
    if (line == 1) {
      if (tokens.size() != 1 || tokens[0] != "ply") failAtLine(name, line, "not a PLY file");
      continue;
    }
    if (tokens.empty()) continue;
    const std::string_view keyword = tokens[0];
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      if (haveFormat) failAtLine(name, line, "second format line");
      if (tokens.size() != 3) failAtLine(name, line, "expected \"format TYPE 1.0\"");
      if (tokens[1] == "ascii") header.format = Format::Ascii;
      else if (tokens[1] == "binary_little_endian") header.format = Format::BinaryLittleEndian;
      else if (tokens[1] == "binary_big_endian") header.format = Format::BinaryBigEndian;
      else failAtLine(name, line, "unsupported format " + quote(tokens[1]));
      if (tokens[2] != "1.0" && tokens[2] != "1") failAtLine(name, line, "unsupported PLY version " + quote(tokens[2]));
      haveFormat = true;
    } else if (keyword == "element") {
      if (tokens.size() != 3) failAtLine(name, line, "expected \"element NAME COUNT\"");
      Element element;
      element.name = tokens[1];
      element.line = line;
      const std::string_view count = tokens[2];
      const auto [end, ec] = std::from_chars(count.data(), count.data() + count.size(), element.count);
      if (ec != std::errc() || end != count.data() + count.size())
        failAtLine(name, line, "invalid element count " + quote(count));
      if (!elementNames.insert(tokens[1]).second) failAtLine(name, line, "second element named " + quote(tokens[1]));
      propertyNames.clear();
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) failAtLine(name, line, "property before any element");
      Property property;
      property.line = line;
      if (tokens.size() >= 2 && tokens[1] == "list") {
        if (tokens.size() != 5) failAtLine(name, line, "expected \"property list COUNTTYPE ITEMTYPE NAME\"");
        const auto countType = parseScalarName(tokens[2]);
        const auto itemType = parseScalarName(tokens[3]);
        if (!countType) failAtLine(name, line, "unknown type " + quote(tokens[2]));
        if (!itemType) failAtLine(name, line, "unknown type " + quote(tokens[3]));
        if (!info(*countType).integer) failAtLine(name, line, "list count type must be an integer type");
        property.list = true;
        property.countType = *countType;
        property.type = *itemType;
        property.name = tokens[4];
      } else {
        if (tokens.size() != 3) failAtLine(name, line, "expected \"property TYPE NAME\"");
        const auto type = parseScalarName(tokens[1]);
        if (!type) failAtLine(name, line, "unknown type " + quote(tokens[1]));
        property.type = *type;
        property.name = tokens[2];
      }
      if (!propertyNames.insert(tokens.back()).second)
        failAtLine(name, line, "second property named " + quote(tokens.back()));
      header.elements.back().properties.push_back(std::move(property));
    } else if (keyword == "end_header") {
      if (tokens.size() != 1) failAtLine(name, line, "extra tokens after end_header");
      if (!haveFormat) failAtLine(name, line, "no format line before end_header");
      header.dataOffset = offset;
      header.endHeaderLine = line;
      return header;
    } else {
      failAtLine(name, line, "unknown header keyword " + quote(keyword));
    }
  }
  if (line == 0) failAtLine(name, 1, "not a PLY file (empty)");
  failAtLine(name, line, "no end_header line");
}

const Property* findProperty(const Element& element, std::string_view name) {
  for (const Property& property : element.properties)
    if (property.name == name) return &property;
  return nullptr;
}

Layout findLayout(const Header& header, const std::string& name) {
  Layout layout;
  const auto findElement = [&](std::string_view elementName) -> std::optional<std::size_t> {
    for (std::size_t i = 0; i < header.elements.size(); ++i)
      if (header.elements[i].name == elementName) return i;
    return std::nullopt;
  };
  const auto vertex = findElement("vertex");
  if (!vertex) failAtLine(name, header.endHeaderLine, "no vertex element");
  const auto face = findElement("face");
  if (!face) failAtLine(name, header.endHeaderLine, "no face element");
  layout.vertexElement = *vertex;
  layout.faceElement = *face;

  const Element& vertices = header.elements[*vertex];
  if (vertices.count > std::numeric_limits<std::uint32_t>::max())
    failAtLine(name, vertices.line, "more vertices than 32-bit indices can address");
  constexpr std::string_view kRoleNames[] = {"", "x", "y", "z", "nx", "ny", "nz"};
  int found[std::size(kRoleNames)] = {};
  layout.vertexRoles.assign(vertices.properties.size(), Role::Skip);
  for (std::size_t p = 0; p < vertices.properties.size(); ++p) {
    const Property& property = vertices.properties[p];
    for (std::size_t r = 1; r < std::size(kRoleNames); ++r) {
      if (property.name != kRoleNames[r]) continue;
      if (property.list) failAtLine(name, property.line, "vertex property " + property.name + " must not be a list");
      layout.vertexRoles[p] = static_cast<Role>(r);
      ++found[r];
    }
  }
  const auto has = [&](Role role) { return found[static_cast<int>(role)] > 0; };
  if (!has(Role::X) || !has(Role::Y) || !has(Role::Z))
    failAtLine(name, vertices.line, "vertex element lacks an x, y or z property");
  layout.hasNormals = has(Role::NX) && has(Role::NY) && has(Role::NZ);
  if (!layout.hasNormals)  // a partial normal is no normal
    for (Role& role : layout.vertexRoles)
      if (role == Role::NX || role == Role::NY || role == Role::NZ) role = Role::Skip;

  const Element& faces = header.elements[*face];
  const Property* list = findProperty(faces, "vertex_indices");
  if (!list) list = findProperty(faces, "vertex_index");
  if (!list || !list->list) failAtLine(name, faces.line, "face element lacks a vertex_indices list");
  if (!info(list->type).integer) failAtLine(name, list->line, "vertex indices must have an integer type");
  layout.faceList = static_cast<std::size_t>(list - faces.properties.data());
  if (faces.count == 0) failAtLine(name, faces.line, "the mesh has no faces");
  return layout;
}

/// The fewest bytes one item of `element` can take, so that absurd counts fail before anything is
/// allocated. An ascii value takes at least 2 bytes (a digit and a separator).
std::uint64_t minItemBytes(const Element& element, bool ascii, bool isFace, std::size_t faceList) {
  constexpr std::uint64_t kMinAsciiValueBytes = 2;
  constexpr std::uint64_t kMinFaceCorners = 3;
  std::uint64_t bytes = 0;
  for (std::size_t p = 0; p < element.properties.size(); ++p) {
    const Property& property = element.properties[p];
    const std::uint64_t corners = isFace && p == faceList ? kMinFaceCorners : 0;
    if (ascii) {
      bytes += kMinAsciiValueBytes * (1 + corners);
    } else {
      bytes += property.list ? info(property.countType).bytes + corners * info(property.type).bytes
                             : info(property.type).bytes;
    }
  }
  return bytes;
}

// ---------------------------------------------------------------------------------------------
// Data sources: the same element loop reads ascii lines and binary bytes.

class AsciiSource {
public:
  AsciiSource(std::string_view data, std::size_t offset, int lineBefore, const std::string& name)
      : data_(data), next_(offset), line_(lineBefore), name_(name) {}

  /// Moves to the next non-blank line; one element item per line.
  void beginItem() {
    while (true) {
      if (next_ >= data_.size()) fail("unexpected end of file (more elements expected)");
      const std::size_t newline = data_.find('\n', next_);
      cursor_ = next_;
      end_ = newline == std::string_view::npos ? data_.size() : newline;
      next_ = newline == std::string_view::npos ? data_.size() : newline + 1;
      ++line_;
      skipSpaces();
      if (cursor_ < end_) return;
    }
  }

  double value(Scalar type) {
    skipSpaces();
    if (cursor_ >= end_) fail("too few values on the line");
    const std::size_t start = cursor_;
    while (cursor_ < end_ && !isSpace(data_[cursor_])) ++cursor_;
    return parse(data_.substr(start, cursor_ - start), type);
  }

  /// A list length is a value like any other in ascii; the line bounds the loop.
  void checkListFits(double, Scalar) const {}

  void endItem() {
    skipSpaces();
    if (cursor_ < end_) fail("extra values at the end of the line: " + quote(data_.substr(cursor_, end_ - cursor_)));
  }

  void finish() {
    for (std::size_t i = next_; i < data_.size(); ++i) {
      if (data_[i] == '\n') {
        ++line_;
      } else if (!isSpace(data_[i])) {
        ++line_;
        fail("data after the last element");
      }
    }
  }

  [[noreturn]] void fail(const std::string& message) const { failAtLine(name_, line_, message); }

private:
  void skipSpaces() {
    while (cursor_ < end_ && isSpace(data_[cursor_])) ++cursor_;
  }

  double parse(std::string_view token, Scalar type) const {
    std::string_view digits = token;
    // from_chars rejects a leading '+', which some writers emit.
    if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-' && digits[1] != '+') digits.remove_prefix(1);
    const char* first = digits.data();
    const char* last = first + digits.size();
    const ScalarInfo& scalar = info(type);
    if (scalar.integer) {
      std::int64_t v = 0;
      const auto [end, ec] = std::from_chars(first, last, v);
      if (ec == std::errc() && end == last && v >= scalar.min && v <= scalar.max) return static_cast<double>(v);
      if ((ec == std::errc() && end == last) || ec == std::errc::result_out_of_range)
        fail(quote(token) + " is out of range for " + std::string(scalar.name));
      fail(quote(token) + " is not an integer");
    }
    double v = 0.0;
    std::errc ec;
    const char* end;
    if (type == Scalar::Float32) {
      float f = 0.0f;
      const auto result = std::from_chars(first, last, f);
      ec = result.ec;
      end = result.ptr;
      v = f;
    } else {
      const auto result = std::from_chars(first, last, v);
      ec = result.ec;
      end = result.ptr;
    }
    if (end != last || (ec != std::errc() && ec != std::errc::result_out_of_range))
      fail(quote(token) + " is not a number");
    if (ec == std::errc::result_out_of_range) {
      // Overflow and underflow: let strtod pick ±inf or the nearest tiny value; the caller decides.
      const std::string copy(digits);
      v = std::strtod(copy.c_str(), nullptr);
      if (type == Scalar::Float32) v = static_cast<float>(v);
    }
    return v;
  }

  std::string_view data_;
  std::size_t next_;
  std::size_t cursor_ = 0, end_ = 0;
  int line_;
  const std::string& name_;
};

template <bool kSwap>
class BinarySource {
public:
  BinarySource(std::string_view data, std::size_t offset, const std::string& name)
      : data_(data), position_(offset), name_(name) {}

  void beginItem() {}
  void endItem() {}
  void finish() {}  // trailing bytes (padding by some writers) are ignored

  double value(Scalar type) {
    valueOffset_ = position_;
    switch (type) {
      case Scalar::Int8: return load<std::int8_t>();
      case Scalar::UInt8: return load<std::uint8_t>();
      case Scalar::Int16: return load<std::int16_t>();
      case Scalar::UInt16: return load<std::uint16_t>();
      case Scalar::Int32: return load<std::int32_t>();
      case Scalar::UInt32: return load<std::uint32_t>();
      case Scalar::Float32: return load<float>();
      case Scalar::Float64: return load<double>();
    }
    fail("bad type");
  }

  /// Fails fast when a list claims more items than the file holds.
  void checkListFits(double count, Scalar itemType) const {
    if (count * info(itemType).bytes > static_cast<double>(data_.size() - position_))
      fail("list of " + std::to_string(static_cast<std::uint64_t>(count)) + " items runs past the end of the file");
  }

  [[noreturn]] void fail(const std::string& message) const {
    throw std::runtime_error(name_ + ": byte " + std::to_string(valueOffset_) + ": " + message);
  }

private:
  template <typename T>
  double load() {
    if (sizeof(T) > data_.size() - position_) fail("unexpected end of file (more elements expected)");
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, data_.data() + position_, sizeof(T));
    if constexpr (kSwap) std::reverse(bytes, bytes + sizeof(T));
    T v;
    std::memcpy(&v, bytes, sizeof(T));
    position_ += sizeof(T);
    return static_cast<double>(v);
  }

  std::string_view data_;
  std::size_t position_;
  std::size_t valueOffset_ = 0;
  const std::string& name_;
};

// ---------------------------------------------------------------------------------------------
// Element loop

template <class Source>
std::uint64_t readListCount(Source& source, const Property& property) {
  const double count = source.value(property.countType);
  if (count < 0) source.fail("negative list length");
  source.checkListFits(count, property.type);
  return static_cast<std::uint64_t>(count);
}

template <class Source>
void skipProperty(Source& source, const Property& property) {
  if (!property.list) {
    source.value(property.type);
    return;
  }
  const std::uint64_t count = readListCount(source, property);
  for (std::uint64_t i = 0; i < count; ++i) source.value(property.type);
}

template <class Source>
void readVertices(Source& source, const Element& element, const Layout& layout, TriangleMesh& mesh) {
  for (std::uint64_t v = 0; v < element.count; ++v) {
    source.beginItem();
    glm::vec3 position(0.0f), normal(0.0f);
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      const Role role = layout.vertexRoles[p];
      if (role == Role::Skip) {
        skipProperty(source, element.properties[p]);
        continue;
      }
      const float value = static_cast<float>(source.value(element.properties[p].type));
      switch (role) {
        case Role::X:
        case Role::Y:
        case Role::Z:
          if (!std::isfinite(value))
            source.fail("vertex " + std::to_string(v) + " has a non-finite " + element.properties[p].name);
          position[static_cast<int>(role) - static_cast<int>(Role::X)] = value;
          break;
        case Role::NX:
        case Role::NY:
        case Role::NZ:
          normal[static_cast<int>(role) - static_cast<int>(Role::NX)] = value;
          break;
        case Role::Skip: break;
      }
    }
    source.endItem();
    mesh.positions.push_back(position);
    if (layout.hasNormals) mesh.normals.push_back(normal);
  }
}

template <class Source>
void readFaces(Source& source, const Element& element, const Layout& layout, std::uint64_t vertexCount,
               TriangleMesh& mesh) {
  std::vector<std::uint32_t> corners;
  for (std::uint64_t f = 0; f < element.count; ++f) {
    source.beginItem();
    for (std::size_t p = 0; p < element.properties.size(); ++p) {
      const Property& property = element.properties[p];
      if (p != layout.faceList) {
        skipProperty(source, property);
        continue;
      }
      const std::uint64_t count = readListCount(source, property);
      if (count < 3) source.fail("face " + std::to_string(f) + " has " + std::to_string(count) + " corners (at least 3 needed)");
      corners.clear();
      for (std::uint64_t i = 0; i < count; ++i) {
        const double index = source.value(property.type);
        if (index < 0 || index >= static_cast<double>(vertexCount))
          source.fail("face " + std::to_string(f) + " uses vertex " + std::to_string(static_cast<std::int64_t>(index)) +
                      ", outside 0.." + std::to_string(static_cast<std::int64_t>(vertexCount) - 1));
        corners.push_back(static_cast<std::uint32_t>(index));
      }
      // A fan from the first corner: exact for convex polygons, which is what scanners write.
      for (std::size_t i = 1; i + 1 < corners.size(); ++i) mesh.triangles.push_back({corners[0], corners[i], corners[i + 1]});
    }
    source.endItem();
  }
}

template <class Source>
void readBody(Source& source, const Header& header, const Layout& layout, TriangleMesh& mesh) {
  const std::uint64_t vertexCount = header.elements[layout.vertexElement].count;
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const Element& element = header.elements[e];
    if (element.properties.empty()) continue;  // items without properties occupy no data
    if (e == layout.vertexElement) {
      readVertices(source, element, layout, mesh);
    } else if (e == layout.faceElement) {
      readFaces(source, element, layout, vertexCount, mesh);
    } else {
      for (std::uint64_t i = 0; i < element.count; ++i) {
        source.beginItem();
        for (const Property& property : element.properties) skipProperty(source, property);
        source.endItem();
      }
    }
  }
  source.finish();
}

/// Keeps stored normals if every one can be normalised; otherwise computes them all from the faces
/// (a zero normal says the writer did not know it, and mixing the two kinds would show seams).
void finishNormals(TriangleMesh& mesh) {
  bool usable = !mesh.normals.empty();
  for (glm::vec3& n : mesh.normals) {
    const float length = glm::length(n);
    if (!(length > 0.0f) || !std::isfinite(length)) {
      usable = false;
      break;
    }
    n /= length;
  }
  if (!usable) computeVertexNormals(mesh);
}

}  // namespace

TriangleMesh parsePly(std::string_view data, const std::string& nameForErrors) {
  const Header header = parseHeader(data, nameForErrors);
  const Layout layout = findLayout(header, nameForErrors);
  const bool ascii = header.format == Format::Ascii;

  // Check every count against the bytes that follow before reserving anything.
  const std::uint64_t dataBytes = data.size() - header.dataOffset;
  // The last ascii item may lack its final newline: one byte of grace.
  std::uint64_t available = dataBytes + (ascii ? 1 : 0);
  for (std::size_t e = 0; e < header.elements.size(); ++e) {
    const Element& element = header.elements[e];
    const std::uint64_t bytes = minItemBytes(element, ascii, e == layout.faceElement, layout.faceList);
    if (bytes == 0) continue;
    if (element.count > available / bytes) {
      const std::string message = "element " + element.name + " claims " + std::to_string(element.count) +
                                  " items, but only " + std::to_string(dataBytes) + " bytes of data follow the header";
      if (ascii) failAtLine(nameForErrors, element.line, message);
      throw std::runtime_error(nameForErrors + ": byte " + std::to_string(header.dataOffset) + ": " + message);
    }
    available -= element.count * bytes;
  }

  TriangleMesh mesh;
  const Element& vertices = header.elements[layout.vertexElement];
  const Element& faces = header.elements[layout.faceElement];
  mesh.positions.reserve(static_cast<std::size_t>(vertices.count));
  if (layout.hasNormals) mesh.normals.reserve(static_cast<std::size_t>(vertices.count));
  mesh.triangles.reserve(static_cast<std::size_t>(faces.count));

  constexpr bool kLittleEndianHost = std::endian::native == std::endian::little;
  switch (header.format) {
    case Format::Ascii: {
      AsciiSource source(data, header.dataOffset, header.endHeaderLine, nameForErrors);
      readBody(source, header, layout, mesh);
      break;
    }
    case Format::BinaryLittleEndian: {
      BinarySource<!kLittleEndianHost> source(data, header.dataOffset, nameForErrors);
      readBody(source, header, layout, mesh);
      break;
    }
    case Format::BinaryBigEndian: {
      BinarySource<kLittleEndianHost> source(data, header.dataOffset, nameForErrors);
      readBody(source, header, layout, mesh);
      break;
    }
  }
  finishNormals(mesh);
  return mesh;
}

TriangleMesh readPly(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw std::runtime_error(name + ": is a directory");
  gpu::checkInputFile(path, gpu::kMaxMeshFileBytes, "a PLY mesh");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(name + ": " + std::strerror(errno));
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw std::runtime_error(name + ": cannot determine the file size");
  in.seekg(0, std::ios::beg);
  try {
    std::string contents(static_cast<std::size_t>(size), '\0');
    if (!in.read(contents.data(), size)) throw std::runtime_error(name + ": read error");
    return parsePly(contents, name);
  } catch (const std::bad_alloc&) {
    gpu::throwOutOfMemoryReading(path);
  }
}

}  // namespace tallow::geometry
