// The PLY reader (geometry/ply_reader): the two scanned test meshes, the three encodings, and
// every error the reader reports.
#include "geometry/ply_reader.h"

#include <gtest/gtest.h>

#include "support/temp_dir.h"
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace tallow::geometry {
namespace {

namespace fs = std::filesystem;

const fs::path kDataDir = TALLOW_TEST_DATA_DIR;

using test::TempDir;

// ---------------------------------------------------------------------------------------------
// A small PLY writer for the tests: one description, any of the three encodings.

struct PropertySpec {
  std::string name;
  std::string type;       ///< any PLY type name or alias
  std::string countType;  ///< empty for a scalar
};

struct ElementSpec {
  std::string name;
  std::vector<PropertySpec> properties;
  /// One row per item: a scalar takes one value, a list its length then its items.
  std::vector<std::vector<double>> rows;
};

enum class Encoding { Ascii, LittleEndian, BigEndian };

template <class T>
void appendBytes(std::string& out, T value, bool bigEndian) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (bigEndian != (std::endian::native == std::endian::big)) std::reverse(bytes, bytes + sizeof(T));
  out.append(bytes, sizeof(T));
}

void appendValue(std::string& out, const std::string& type, double v, Encoding encoding) {
  if (encoding == Encoding::Ascii) {
    char text[64];
    if (type == "float" || type == "float32") std::snprintf(text, sizeof(text), "%.9g", v);
    else if (type == "double" || type == "float64") std::snprintf(text, sizeof(text), "%.17g", v);
    else std::snprintf(text, sizeof(text), "%lld", static_cast<long long>(v));
    out += text;
    return;
  }
  const bool big = encoding == Encoding::BigEndian;
  if (type == "char" || type == "int8") appendBytes(out, static_cast<std::int8_t>(v), big);
  else if (type == "uchar" || type == "uint8") appendBytes(out, static_cast<std::uint8_t>(v), big);
  else if (type == "short" || type == "int16") appendBytes(out, static_cast<std::int16_t>(v), big);
  else if (type == "ushort" || type == "uint16") appendBytes(out, static_cast<std::uint16_t>(v), big);
  else if (type == "int" || type == "int32") appendBytes(out, static_cast<std::int32_t>(v), big);
  else if (type == "uint" || type == "uint32") appendBytes(out, static_cast<std::uint32_t>(v), big);
  else if (type == "float" || type == "float32") appendBytes(out, static_cast<float>(v), big);
  else appendBytes(out, v, big);
}

std::string plyHeader(const std::vector<ElementSpec>& elements, Encoding encoding) {
  static const char* kFormats[] = {"ascii", "binary_little_endian", "binary_big_endian"};
  std::string out = "ply\nformat " + std::string(kFormats[static_cast<int>(encoding)]) + " 1.0\ncomment test\n";
  for (const ElementSpec& element : elements) {
    out += "element " + element.name + " " + std::to_string(element.rows.size()) + "\n";
    for (const PropertySpec& p : element.properties)
      out += p.countType.empty() ? "property " + p.type + " " + p.name + "\n"
                                 : "property list " + p.countType + " " + p.type + " " + p.name + "\n";
  }
  return out + "end_header\n";
}

std::string makePly(const std::vector<ElementSpec>& elements, Encoding encoding) {
  std::string out = plyHeader(elements, encoding);
  for (const ElementSpec& element : elements) {
    for (const auto& row : element.rows) {
      std::size_t next = 0;
      bool first = true;
      const auto put = [&](const std::string& type) {
        if (encoding == Encoding::Ascii && !first) out += ' ';
        first = false;
        appendValue(out, type, row.at(next++), encoding);
      };
      for (const PropertySpec& p : element.properties) {
        if (p.countType.empty()) {
          put(p.type);
          continue;
        }
        const auto count = static_cast<std::size_t>(row.at(next));
        put(p.countType);
        for (std::size_t i = 0; i < count; ++i) put(p.type);
      }
      if (encoding == Encoding::Ascii) out += '\n';
    }
  }
  return out;
}

/// A tetrahedron-ish mesh with a quad, extra vertex properties (scalar and list), an unknown
/// element before the faces and extra face properties: everything the reader must skip.
std::vector<ElementSpec> richMesh() {
  ElementSpec vertex{"vertex",
                     {{"x", "float", ""},
                      {"red", "uchar", ""},
                      {"y", "float32", ""},
                      {"weights", "double", "ushort"},
                      {"z", "double", ""},
                      {"id", "int", ""},
                      {"nx", "float", ""},
                      {"ny", "float", ""},
                      {"nz", "float", ""}},
                     {}};
  const double positions[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, -1.25}};
  for (int i = 0; i < 5; ++i)
    vertex.rows.push_back({positions[i][0], 200.0 + i, positions[i][1], 2, 0.5, -1e300, positions[i][2], -7.0 - i,
                           0.0, 0.0, 2.0});
  ElementSpec edge{"edge", {{"vertex1", "int", ""}, {"corners", "int16", "uint8"}, {"crease", "float64", ""}},
                   {{0, 2, -1, 30000, 0.25}, {3, 0, 1e-300}}};
  ElementSpec face{"face",
                   {{"flags", "uint16", ""}, {"vertex_indices", "uint", "uchar"}, {"texcoord", "float", "int"}},
                   {{7, 4, 0, 3, 2, 1, 0}, {8, 3, 0, 1, 4, 2, 0.5, 0.5}, {9, 3, 1, 2, 4, 0}, {65535, 3, 2, 3, 4, 0}}};
  return {vertex, edge, face};
}

void expectSameMesh(const TriangleMesh& a, const TriangleMesh& b) {
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.triangles, b.triangles);
}

/// Expects parsing to throw std::runtime_error whose single-line message contains `fragment`.
void expectError(const std::string& text, const std::string& fragment, const std::string& name = "t.ply") {
  try {
    parsePly(text, name);
    ADD_FAILURE() << "no exception; expected \"" << fragment << "\" for:\n" << text.substr(0, 400);
  } catch (const std::runtime_error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(fragment), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

const std::string kAsciiHeader =
    "ply\n"
    "format ascii 1.0\n"
    "element vertex 3\n"
    "property float x\n"
    "property float y\n"
    "property float z\n"
    "element face 1\n"
    "property list uchar int vertex_indices\n"
    "end_header\n";  // 9 lines: data starts on line 10

// ---------------------------------------------------------------------------------------------
// The scanned meshes (numbers from shared/data/MODELS.md)

void expectBox(const Aabb& box, glm::vec3 min, glm::vec3 max) {
  constexpr float kTolerance = 1e-6f;  // MODELS.md quotes 6 decimals
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(box.min[i], min[i], kTolerance) << i;
    EXPECT_NEAR(box.max[i], max[i], kTolerance) << i;
  }
}

void expectUnitNormals(const TriangleMesh& mesh) {
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  for (const glm::vec3& n : mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f);
}

TEST(PlyReader, ReadsTheStanfordBunny) {
  const auto start = std::chrono::steady_clock::now();
  const TriangleMesh mesh = readPly(kDataDir / "bunny.ply");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("read_seconds", std::to_string(seconds));
  EXPECT_EQ(mesh.positions.size(), 35947u);
  EXPECT_EQ(mesh.triangles.size(), 69451u);
  expectBox(mesh.bounds(), {-0.094690f, 0.032987f, -0.061874f}, {0.061009f, 0.187321f, 0.058800f});
  expectUnitNormals(mesh);  // computed: the file has none
}

TEST(PlyReader, ReadsTheStanfordDragonAndRecomputesItsBrokenNormals) {
  const TriangleMesh mesh = readPly(kDataDir / "dragon.ply");
  EXPECT_EQ(mesh.positions.size(), 22998u);
  EXPECT_EQ(mesh.triangles.size(), 47794u);
  expectBox(mesh.bounds(), {-0.107673f, 0.052774f, -0.050051f}, {0.095983f, 0.196644f, 0.040826f});
  // 206 stored normals are zero, so all are computed from the faces.
  expectUnitNormals(mesh);
  TriangleMesh recomputed = mesh;
  computeVertexNormals(recomputed);
  EXPECT_EQ(mesh.normals, recomputed.normals);
}

// ---------------------------------------------------------------------------------------------
// Encodings

TEST(PlyReader, ThreeEncodingsGiveTheSameMesh) {
  TempDir dir;
  const auto elements = richMesh();
  std::vector<TriangleMesh> meshes;
  for (Encoding encoding : {Encoding::Ascii, Encoding::LittleEndian, Encoding::BigEndian}) {
    const fs::path file = dir.path() / ("mesh" + std::to_string(static_cast<int>(encoding)) + ".ply");
    std::ofstream(file, std::ios::binary) << makePly(elements, encoding);
    meshes.push_back(readPly(file));
  }
  const TriangleMesh& mesh = meshes[0];
  ASSERT_EQ(mesh.positions.size(), 5u);
  EXPECT_EQ(mesh.positions[4], glm::vec3(0.5f, 0.5f, -1.25f));
  // Stored normals (0, 0, 2) are normalised.
  ASSERT_EQ(mesh.normals.size(), 5u);
  for (const glm::vec3& n : mesh.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
  // The quad is fanned from its first corner; the triangles follow.
  const std::vector<std::array<std::uint32_t, 3>> expected = {{0, 3, 2}, {0, 2, 1}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}};
  EXPECT_EQ(mesh.triangles, expected);
  expectSameMesh(meshes[1], mesh);
  expectSameMesh(meshes[2], mesh);
}

TEST(PlyReader, AllScalarTypesAndAliases) {
  const char* types[] = {"char", "int8",   "uchar", "uint8",   "short",  "int16",  "ushort", "uint16",
                         "int",  "int32",  "uint",  "uint32",  "float",  "float32", "double", "float64"};
  const double values[] = {-128, 127, 255, 0, -32768, 32767, 65535, 1, -2147483648.0, 2147483647.0, 4294967295.0, 2,
                           0.125, -3.5, 1e-300, 1e300};
  ElementSpec vertex{"vertex", {{"x", "int8", ""}, {"y", "uint16", ""}, {"z", "float64", ""}}, {}};
  std::vector<double> row = {-5, 60000, 0.25};
  for (int i = 0; i < 16; ++i) {
    char name[8];  // not "p" + std::to_string(i): GCC 12 warns falsely there (-Wrestrict, bug 105329)
    std::snprintf(name, sizeof(name), "p%d", i);
    vertex.properties.push_back({name, types[i], ""});
    row.push_back(values[i]);
  }
  for (int i = 0; i < 3; ++i) vertex.rows.push_back(row);
  vertex.rows[1][0] = 9;
  vertex.rows[2][1] = 7;
  std::vector<ElementSpec> elements = {vertex, {"face", {{"vertex_index", "uint8", "int8"}}, {{3, 0, 1, 2}}}};
  for (const char* countType : {"uchar", "ushort", "uint", "char", "short", "int"}) {
    elements[1].properties[0].countType = countType;
    const TriangleMesh ascii = parsePly(makePly(elements, Encoding::Ascii), "a.ply");
    ASSERT_EQ(ascii.positions.size(), 3u);
    EXPECT_EQ(ascii.positions[0], glm::vec3(-5.0f, 60000.0f, 0.25f));
    EXPECT_EQ(ascii.positions[1], glm::vec3(9.0f, 60000.0f, 0.25f));
    expectSameMesh(parsePly(makePly(elements, Encoding::LittleEndian), "le.ply"), ascii);
    expectSameMesh(parsePly(makePly(elements, Encoding::BigEndian), "be.ply"), ascii);
  }
}

TEST(PlyReader, FanTriangulatesPolygons) {
  const std::string text =
      "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n1 1 0\n0 1 0\n-1 0.5 0\n"
      "4 0 1 2 3\n5 0 1 2 3 4\n";
  const TriangleMesh mesh = parsePly(text, "fan.ply");
  const std::vector<std::array<std::uint32_t, 3>> expected = {{0, 1, 2}, {0, 2, 3}, {0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
  EXPECT_EQ(mesh.triangles, expected);
  for (const glm::vec3& n : mesh.normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);  // computed: no normals stored
}

TEST(PlyReader, ToleratesCrLfBlankLinesAndSignsInAscii) {
  const std::string text =
      "ply\r\nformat ascii 1.0\r\nobj_info made by hand\r\nelement vertex 3\r\nproperty float x\r\n"
      "property float y\r\nproperty float z\r\nelement face 1\r\nproperty list uchar int vertex_indices\r\n"
      "end_header\r\n+1 0 0\r\n\r\n  0\t+1.5e0 0 \r\n0 0 1e-50\r\n3 0 1 +2\r\n\r\n";
  const TriangleMesh mesh = parsePly(text, "crlf.ply");
  EXPECT_EQ(mesh.positions[1], glm::vec3(0.0f, 1.5f, 0.0f));
  EXPECT_EQ(mesh.positions[2], glm::vec3(0.0f));  // underflows to 0 in float
  EXPECT_EQ(mesh.triangles.size(), 1u);
}

TEST(PlyReader, ZeroOrNonFiniteNormalsAreRecomputed) {
  ElementSpec vertex{"vertex",
                     {{"x", "float", ""}, {"y", "float", ""}, {"z", "float", ""},
                      {"nx", "float", ""}, {"ny", "float", ""}, {"nz", "float", ""}},
                     {{0, 0, 0, 0, 3, 0}, {1, 0, 0, 0, 0, 0}, {0, 1, 0, 0, 0.5, 0}}};
  ElementSpec face{"face", {{"vertex_indices", "int", "uchar"}}, {{3, 0, 1, 2}}};
  const TriangleMesh zero = parsePly(makePly({vertex, face}, Encoding::LittleEndian), "z.ply");
  for (const glm::vec3& n : zero.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));  // from the face, not (0, 1, 0)
  vertex.rows[1] = {1, 0, 0, 0, INFINITY, 0};
  const TriangleMesh infinite = parsePly(makePly({vertex, face}, Encoding::BigEndian), "i.ply");
  for (const glm::vec3& n : infinite.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
  vertex.rows[1] = {1, 0, 0, 0, 2, 0};
  const TriangleMesh stored = parsePly(makePly({vertex, face}, Encoding::LittleEndian), "s.ply");
  for (const glm::vec3& n : stored.normals) EXPECT_EQ(n, glm::vec3(0, 1, 0));  // normalised, kept
}

// ---------------------------------------------------------------------------------------------
// Errors

TEST(PlyReader, HeaderErrorsNameTheLine) {
  expectError("", "t.ply:1: not a PLY file");
  expectError("OFF\n3 1 0\n", "t.ply:1: not a PLY file");
  expectError("ply\nformat binary_middle_endian 1.0\nend_header\n", "t.ply:2: unsupported format");
  expectError("ply\nformat ascii 2.0\nend_header\n", "t.ply:2: unsupported PLY version");
  expectError("ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n", "t.ply:4: unknown type");
  expectError("ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n",
              "t.ply:4: list count type");
  expectError("ply\nformat ascii 1.0\nproperty float x\nend_header\n", "t.ply:3: property before any element");
  expectError("ply\nformat ascii 1.0\nelement vertex -1\nend_header\n", "t.ply:3: invalid element count");
  expectError("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "t.ply:4: no end_header");
  expectError("ply\nformat ascii 1.0\nmaterial red\nend_header\n", "t.ply:3: unknown header keyword");
  expectError("ply\nelement vertex 0\nend_header\n", "t.ply:3: no format line");
  // x, y and z are required; so is the face list.
  expectError("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nelement face 1\n"
              "property list uchar int vertex_indices\nend_header\n0 0\n3 0 0 0\n",
              "t.ply:3: vertex element lacks an x, y or z property");
  expectError("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 1\nproperty list uchar int corners\nend_header\n0 0 0\n3 0 0 0\n",
              "t.ply:7: face element lacks a vertex_indices list");
  expectError("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
              "end_header\n0 0 0\n",
              "t.ply:7: no face element");
  expectError("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
              "element face 0\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n",
              "t.ply:7: the mesh has no faces");
}

TEST(PlyReader, AsciiDataErrorsNameTheLine) {
  // kAsciiHeader has 9 lines: vertices on lines 10-12, the face on 13. Numbers are written long
  // enough that the up-front size check passes and the line-level checks are reached.
  const auto body = [](const std::string& v0, const std::string& v1, const std::string& v2, const std::string& f) {
    return kAsciiHeader + v0 + "\n" + v1 + "\n" + v2 + "\n" + f;
  };
  const std::string v0 = "0.0 0.0 0.0", v1 = "1.0 0.0 0.0", v2 = "0.0 1.0 0.0";
  const std::string ok = body(v0, v1, v2, "3 0 1 2\n");
  ASSERT_NO_THROW(parsePly(ok, "t.ply"));
  expectError(body(v0, v1, v2, ""), "t.ply:12: unexpected end of file");
  expectError(body(v0, v1, v2, "3 0 1"), "t.ply:13: too few values");
  expectError(body(v0, "1.0 abc 0.0", v2, "3 0 1 2\n"), "t.ply:11: \"abc\" is not a number");
  expectError(body(v0, v1, v2, "3 0 x 2\n"), "t.ply:13: \"x\" is not an integer");
  expectError(body(v0, v1, v2, "3 0 1.0 2\n"), "t.ply:13: \"1.0\" is not an integer");
  expectError(body(v0, "1.0 0.0 0.0 7", v2, "3 0 1 2\n"), "t.ply:11: extra values");
  expectError(body(v0, v1, v2, "3 0 1 2 5\n"), "t.ply:13: extra values");
  expectError(body(v0, "1.0 0.0", v2, "3 0 1 2\n"), "t.ply:11: too few values");
  expectError(body(v0, v1, v2, "3 0 1 3\n"), "t.ply:13: face 0 uses vertex 3, outside 0..2");
  expectError(body(v0, v1, v2, "3 0 -1 2\n"), "t.ply:13: face 0 uses vertex -1");
  expectError(body(v0, v1, v2, "2 0 1\n"), "t.ply:13: face 0 has 2 corners");
  expectError(body(v0, v1, v2, "256 0 1 2\n"), "t.ply:13: \"256\" is out of range for uchar");
  expectError(body(v0, v1, v2, "-3 0 1 2\n"), "t.ply:13: \"-3\" is out of range for uchar");
  expectError(body(v0, "nan 0.0 0.0", v2, "3 0 1 2\n"), "t.ply:11: vertex 1 has a non-finite x");
  expectError(body(v0, v1, "0.0 inf 0.0", "3 0 1 2\n"), "t.ply:12: vertex 2 has a non-finite y");
  expectError(body(v0, v1, "0.0 1.0 1e39", "3 0 1 2\n"), "t.ply:12: vertex 2 has a non-finite z");
  expectError(ok + "3 0 1 2\n", "t.ply:14: data after the last element");
  // Too little data for the counts at all: reported at the element's header line.
  expectError(kAsciiHeader + "0 0 0\n", "t.ply:3: element vertex claims 3 items");
}

std::vector<ElementSpec> triangle() {
  return {{"vertex", {{"x", "float", ""}, {"y", "float", ""}, {"z", "float", ""}}, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}},
          {"face", {{"vertex_indices", "int", "uchar"}}, {{3, 0, 1, 2}}}};
}

TEST(PlyReader, BinaryDataErrorsNameTheByte) {
  for (Encoding encoding : {Encoding::LittleEndian, Encoding::BigEndian}) {
    auto elements = triangle();
    const std::size_t dataStart = plyHeader(elements, encoding).size();
    const std::string ok = makePly(elements, encoding);
    ASSERT_NO_THROW(parsePly(ok, "b.ply"));
    // Vertices take 36 bytes; the face's count is at +36, its indices at +37, +41, +45.
    elements[1].rows[0] = {3, 0, 5, 2};
    expectError(makePly(elements, encoding), "b.ply: byte " + std::to_string(dataStart + 41) + ": face 0 uses vertex 5", "b.ply");
    elements[1].rows[0] = {3, 0, 1, -2};
    expectError(makePly(elements, encoding), "b.ply: byte " + std::to_string(dataStart + 45) + ": face 0 uses vertex -2", "b.ply");
    elements = triangle();
    elements[0].rows[1][1] = NAN;
    expectError(makePly(elements, encoding), "b.ply: byte " + std::to_string(dataStart + 16) + ": vertex 1 has a non-finite y", "b.ply");
    // Truncation anywhere in the data.
    for (std::size_t size = dataStart; size < ok.size(); ++size) expectError(ok.substr(0, size), "b.ply: byte ", "b.ply");
    // A face list claiming 200 corners in a 49-byte body (count type uchar).
    std::string longList = ok;
    longList[dataStart + 36] = static_cast<char>(200);
    expectError(longList, "b.ply: byte " + std::to_string(dataStart + 36) + ": list of 200 items", "b.ply");
  }
}

TEST(PlyReader, AbsurdCountsFailFastWithoutAllocating) {
  for (Encoding encoding : {Encoding::Ascii, Encoding::LittleEndian, Encoding::BigEndian}) {
    auto elements = triangle();
    std::string text = makePly(elements, encoding);
    const std::string claim = "element vertex 3\n";
    text.replace(text.find(claim), claim.size(), "element vertex 2147483648\n");
    text.resize(1024, '\n');
    const auto start = std::chrono::steady_clock::now();
    expectError(text, encoding == Encoding::Ascii ? "t.ply:4: element vertex claims 2147483648 items" : "t.ply: byte ");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.1);
  }
  // Faces too: 2^32 - 1 faces of at least 13 bytes cannot fit.
  std::string text = makePly(triangle(), Encoding::LittleEndian);
  text.replace(text.find("element face 1"), 14, "element face 4294967295");
  expectError(text, "element face claims 4294967295 items");
}

TEST(PlyReader, MissingFileIsAnError) {
  TempDir dir;
  try {
    readPly(dir.path() / "none.ply");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), (dir.path() / "none.ply").string() + ": No such file or directory");
  }
  EXPECT_THROW(readPly(dir.path()), std::runtime_error);
}

}  // namespace
}  // namespace tallow::geometry
