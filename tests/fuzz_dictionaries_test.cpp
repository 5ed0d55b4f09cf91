// The fuzzers' dictionaries (tests/fuzz/dict/): every line one entry libFuzzer can parse, and the
// text formats' dictionaries hold every registry key (and enum choice), so that a parameter added
// later cannot be left out of the words the fuzzers splice in.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "app/config/params.h"
#include "sss/bssrdf/material.h"

namespace tallow {
namespace {

const std::filesystem::path kDictionaries = std::filesystem::path(TALLOW_TEST_SOURCE_DIR) / "tests" / "fuzz" / "dict";

/// The entries of a dictionary in libFuzzer's format: `"text"` with \\, \" and \xHH escapes, one a
/// line, `#` comments and blank lines. A line that is none of these fails the test.
std::set<std::string> entries(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::set<std::string> out;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    const auto open = line.find('"');
    EXPECT_TRUE(open != std::string::npos && line.size() >= open + 2 && line.back() == '"')
        << file.filename() << ":" << number << ": " << line;
    if (open == std::string::npos || line.size() < open + 2) continue;
    std::string text;
    for (std::size_t i = open + 1; i + 1 < line.size(); ++i) {
      if (line[i] != '\\') {
        EXPECT_NE(line[i], '"') << file.filename() << ":" << number << ": unescaped quote";
        text += line[i];
        continue;
      }
      ++i;
      if (line[i] == 'x' && i + 2 < line.size()) {
        text += static_cast<char>(std::stoi(line.substr(i + 1, 2), nullptr, 16));
        i += 2;
      } else {
        text += line[i];
      }
    }
    out.insert(text);
  }
  return out;
}

TEST(FuzzDictionaries, EveryTextFormatHasADictionaryInLibFuzzersFormat) {
  for (const std::string name : {"bssrdf_csv", "cli_values", "exr", "exr_attributes", "hdr", "materials", "ply",
                                 "points_csv", "preset", "view_script"}) {
    const auto file = kDictionaries / (name + ".dict");
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    EXPECT_GE(entries(file).size(), 5u) << file;
  }
}

TEST(FuzzDictionaries, TheParameterKeysAreInTheDictionariesOfTheFormatsThatNameThem) {
  const auto materials = sss::MaterialTable::load(std::filesystem::path(TALLOW_TEST_DATA_DIR) / "materials.csv");
  const app::Registry registry = app::parameterRegistry(materials);
  const std::set<std::string> preset = entries(kDictionaries / "preset.dict");
  const std::set<std::string> script = entries(kDictionaries / "view_script.dict");
  const std::set<std::string> cli = entries(kDictionaries / "cli_values.dict");
  for (const auto& p : registry.params()) {
    EXPECT_TRUE(preset.count("\"" + p.key + "\"")) << "preset.dict lacks \"\\\"" << p.key << "\\\"\"";
    EXPECT_TRUE(script.count(p.key)) << "view_script.dict lacks " << p.key;
    EXPECT_TRUE(cli.count(p.key)) << "cli_values.dict lacks " << p.key;
    // Material names are the data's, not the code's; the other choices are the code's words.
    if (p.type != "enum" || p.key == "material") continue;
    for (const std::string& choice : p.choices) {
      EXPECT_TRUE(script.count(choice)) << "view_script.dict lacks " << p.key << " choice " << choice;
      EXPECT_TRUE(cli.count(choice)) << "cli_values.dict lacks " << p.key << " choice " << choice;
    }
  }
}

}  // namespace
}  // namespace tallow
