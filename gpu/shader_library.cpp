#include "gpu/shader_library.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <regex>
#include <sstream>

#include "gpu/embedded_files.h"
#include "gpu/file_bytes.h"

namespace tallow::gpu {

ShaderLibrary::ShaderLibrary(std::optional<std::filesystem::path> overrideDir)
    : overrideDir_(std::move(overrideDir)) {}

std::string ShaderLibrary::read(std::string_view path) const {
  auto embedded = [&]() -> const EmbeddedFile* {
    for (const EmbeddedFile& f : embeddedShaderFiles())
      if (f.path == path) return &f;
    return nullptr;
  };
  if (overrideDir_) {
    const std::filesystem::path file = *overrideDir_ / std::filesystem::path(path);
    // A system header the build embedded (nanovdb/PNanoVDB.h) is not among the shaders to edit:
    // an override folder without it still includes the embedded copy.
    if (path.starts_with("nanovdb/") && !std::filesystem::exists(file))
      if (const EmbeddedFile* f = embedded()) return std::string(f->contents);
    try {
      checkInputFile(file, kMaxTextFileBytes, "a shader file");
    } catch (const std::runtime_error& e) {
      throw ShaderError(e.what(), "");
    }
    std::ifstream in(file, std::ios::binary);
    if (!in) throw ShaderError(file.string() + ": cannot read shader file", "");
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }
  if (const EmbeddedFile* f = embedded()) return std::string(f->contents);
  throw ShaderError("shaders/" + std::string(path) + ": no such shader file", "");
}

namespace {
// Each file's lines are numbered from index × kLineStride in `#line` directives, so that the
// file can be recovered from the line number alone: Mesa sometimes reports an error in an
// included file with source-string number 0 but the right line.
constexpr int kLineStride = 100000;

std::string lineDirective(int line, int fileIndex) {
  return "#line " + std::to_string(fileIndex * kLineStride + line) + " " + std::to_string(fileIndex) + "\n";
}

std::string_view trimLeft(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  return s;
}

/// `#include "x"` → x; `#include NAME` → the path NAME is defined as (`NAME "x"` among the defines:
/// a variant of a shader that includes the file its define names); otherwise empty. An undefined
/// NAME, or one not defined as a quoted path, is an error at `file`:`lineNo`.
std::optional<std::string> includeTarget(std::string_view line, const std::vector<std::string>& defines,
                                         const std::string& file, int lineNo) {
  line = trimLeft(line);
  if (!line.starts_with('#')) return std::nullopt;
  line = trimLeft(line.substr(1));
  if (!line.starts_with("include")) return std::nullopt;
  line = trimLeft(line.substr(7));
  if (!line.empty() && (std::isalpha(static_cast<unsigned char>(line.front())) || line.front() == '_')) {
    std::size_t end = 0;
    while (end < line.size() && (std::isalnum(static_cast<unsigned char>(line[end])) || line[end] == '_')) ++end;
    const std::string name(line.substr(0, end));
    for (const std::string& d : defines) {
      if (d.rfind(name + " ", 0) != 0) continue;
      const std::string value(trimLeft(std::string_view(d).substr(name.size() + 1)));
      if (value.size() >= 2 && value.front() == '"' && value.back() == '"') return value.substr(1, value.size() - 2);
    }
    throw ShaderError(file + ":" + std::to_string(lineNo) + ": error: #include " + name +
                          ": no define gives it a quoted path",
                      "");
  }
  if (line.size() < 2 || line.front() != '"') return std::nullopt;
  const auto close = line.find('"', 1);
  if (close == std::string_view::npos) return std::nullopt;
  return std::string(line.substr(1, close - 1));
}
}  // namespace

void ShaderLibrary::expandInto(std::string_view path, ExpandedSource& out, std::vector<std::string>& stack,
                               std::vector<std::string>& seen, const std::vector<std::string>& defines) const {
  const std::string name(path);
  if (std::find(stack.begin(), stack.end(), name) != stack.end())
    throw ShaderError(name + ":1: error: #include cycle", "");
  if (std::find(seen.begin(), seen.end(), name) != seen.end()) return;  // once per stage
  seen.push_back(name);
  stack.push_back(name);
  const std::string text = read(path);
  const int index = static_cast<int>(out.files.size());
  out.files.push_back(name);

  std::istringstream lines(text);
  std::string line;
  int lineNo = 0;
  bool wroteLine = false;
  while (std::getline(lines, line)) {
    ++lineNo;
    if (auto target = includeTarget(line, defines, name, lineNo)) {
      try {
        expandInto(*target, out, stack, seen, defines);
      } catch (const ShaderError& e) {
        if (std::string(e.what()).find("no such shader file") != std::string::npos ||
            std::string(e.what()).find("cannot read") != std::string::npos)
          throw ShaderError(name + ":" + std::to_string(lineNo) + ": error: cannot include \"" + *target + "\"", "");
        throw;
      }
      out.text += lineDirective(lineNo + 1, index);
      continue;
    }
    if (!wroteLine && index != 0) {
      out.text += lineDirective(lineNo, index);
      wroteLine = true;
    }
    out.text += line;
    out.text += '\n';
  }
  stack.pop_back();
}

ExpandedSource ShaderLibrary::expand(std::string_view path, const std::vector<std::string>& defines) const {
  ExpandedSource body;
  std::vector<std::string> stack, seen;
  expandInto(path, body, stack, seen, defines);

  // `#version` must come first: keep it, then the defines, then resume at line 2 of the file.
  const auto firstNewline = body.text.find('\n');
  const std::string first = body.text.substr(0, firstNewline);
  if (trimLeft(first).rfind("#version", 0) != 0)
    throw ShaderError(std::string(path) + ":1: error: the first line must be #version", "");
  ExpandedSource out;
  out.files = std::move(body.files);
  out.text = first + "\n";
  out.text += "#define TALLOW_GLSL 1\n";
  // A define whose value is a quoted path names a file for `#include NAME` only (GLSL has no strings).
  for (const std::string& d : defines)
    if (d.empty() || d.back() != '"') out.text += "#define " + d + "\n";
  out.text += "#line 2 0\n";
  out.text += body.text.substr(firstNewline + 1);
  return out;
}

std::string mapShaderLog(const std::string& log, const ExpandedSource& source) {
  static const std::regex mesa(R"(^\s*(\d+):(\d+)\((\d+)\):\s*(.*)$)");
  static const std::regex nvidia(R"(^\s*(\d+)\((\d+)\)\s*:\s*(.*)$)");
  std::istringstream lines(log);
  std::string line, out;
  while (std::getline(lines, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::smatch m;
    std::string mapped = line;
    // The file comes from the line number (see kLineStride), not from the source-string number.
    auto place = [&](const std::string& index, const std::string& lineText) {
      const unsigned long encoded = std::stoul(lineText.substr(0, 9));
      const std::size_t file = encoded / kLineStride;
      const std::string name = file < source.files.size() ? "shaders/" + source.files[file] : "shader string " + index;
      return name + ":" + std::to_string(encoded % kLineStride);
    };
    if (std::regex_match(line, m, mesa)) mapped = place(m[1], m[2]) + ": " + m[4].str();
    else if (std::regex_match(line, m, nvidia)) mapped = place(m[1], m[2]) + ": " + m[3].str();
    out += mapped + "\n";
  }
  return out;
}

}  // namespace tallow::gpu
