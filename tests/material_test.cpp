// MaterialTable (materials.csv) and validateMaterial.
#include "sss/bssrdf/material.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace tallow::sss {
namespace {

const std::string kHeader =
    "name,source,sigma_s_r,sigma_s_g,sigma_s_b,sigma_a_r,sigma_a_g,sigma_a_b,g_r,g_g,g_b,eta,unit\n";
const std::string kMarble = "Marble,Jensen et al. 2001,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n";

std::string errorOf(const std::string& text) {
  try {
    MaterialTable::parse(text, "m.csv");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

std::string validationError(const Material& m) {
  try {
    validateMaterial(m);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

Material valid() {
  Material m;
  m.sigma_s = glm::vec3(1.0f);
  m.sigma_a = glm::vec3(0.1f);
  m.g = glm::vec3(0.5f);
  m.eta = 1.3f;
  return m;
}

TEST(MaterialTable, LoadsTheSharedTable) {
  const MaterialTable table = MaterialTable::load(TALLOW_TEST_DATA_DIR "/materials.csv");
  EXPECT_EQ(table.materials().size(), 52u);
  EXPECT_TRUE(table.find("Head & Shoulders Shampoo"));
  EXPECT_TRUE(table.find("Chocolate Milk (Gkioulekas)"));
  EXPECT_FALSE(table.find("marble"));  // case-sensitive

  // Read Marble's row independently, with plain stream parsing, and compare every field.
  std::ifstream in(TALLOW_TEST_DATA_DIR "/materials.csv");
  std::string line, row;
  while (std::getline(in, line))
    if (line.rfind("Marble,", 0) == 0) row = line;
  ASSERT_FALSE(row.empty());
  std::vector<std::string> fields;
  std::stringstream ss(row);
  for (std::string f; std::getline(ss, f, ',');) fields.push_back(f);
  ASSERT_EQ(fields.size(), 13u);
  const auto number = [&](int i) { return std::strtof(fields[static_cast<std::size_t>(i)].c_str(), nullptr); };

  const auto marble = table.find("Marble");
  ASSERT_TRUE(marble);
  EXPECT_EQ(marble->name, "Marble");
  EXPECT_EQ(marble->source, fields[1]);
  EXPECT_EQ(marble->sigma_s, glm::vec3(number(2), number(3), number(4)));
  EXPECT_EQ(marble->sigma_a, glm::vec3(number(5), number(6), number(7)));
  EXPECT_EQ(marble->g, glm::vec3(number(8), number(9), number(10)));
  EXPECT_EQ(marble->eta, number(11));
  EXPECT_FLOAT_EQ(marble->eta, 1.5f);
}

TEST(MaterialTable, AcceptsPurelyAbsorbingBands) {
  // Coke has σ_s = 0 in blue (and g = 0 there): valid, since σ_a > 0.
  const MaterialTable table = MaterialTable::parse(
      kHeader + "Coke,Narasimhan et al. 2006,0.00254,0.00299,0,0.10014,0.16503,0.2468,0.965,0.972,0,1.33,mm^-1\n",
      "m.csv");
  EXPECT_EQ(table.find("Coke")->sigma_s.b, 0.0f);
}

TEST(MaterialTable, AcceptsCrLfAndBlankLines) {
  std::string crlf;
  for (const char c : kHeader + kMarble + "\n") {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  EXPECT_EQ(MaterialTable::parse(crlf, "m.csv").materials().size(), 1u);
}

TEST(MaterialTable, ErrorsNameFileLineAndColumn) {
  EXPECT_EQ(errorOf(""), "m.csv:1: empty file (expected the header)");
  EXPECT_EQ(errorOf("name,source\n"),
            "m.csv:1: expected the header \"" + kHeader.substr(0, kHeader.size() - 1) + "\"");
  EXPECT_EQ(errorOf(kHeader), "m.csv:1: no materials");
  EXPECT_EQ(errorOf(kHeader + kMarble + "Bad,src,1,2,3\n"), "m.csv:3: expected 13 columns, found 5");
  EXPECT_EQ(errorOf(kHeader + kMarble + kMarble.substr(0, kMarble.size() - 1) + ",x\n"),
            "m.csv:3: expected 13 columns, found 14");
  EXPECT_EQ(errorOf(kHeader + "Marble,J,2.19,abc,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n"),
            "m.csv:2: sigma_s_g: \"abc\" is not a number");
  EXPECT_EQ(errorOf(kHeader + "Marble,J,2.19,2.62,3,0.0021,0.0041,,0,0,0,1.5,mm^-1\n"),
            "m.csv:2: sigma_a_b: \"\" is not a number");
  EXPECT_EQ(errorOf(kHeader + "Marble,J,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0, 1.5,mm^-1\n"),
            "m.csv:2: eta: \" 1.5\" is not a number");
  EXPECT_EQ(errorOf(kHeader + "Marble,J,2.19,2.62,3,0.0021,0.0041,0.0071,0,0.5x,0,1.5,mm^-1\n"),
            "m.csv:2: g_g: \"0.5x\" is not a number");
  EXPECT_EQ(errorOf(kHeader + "Marble,J,1e99,2.62,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n"),
            "m.csv:2: sigma_s_r: \"1e99\" is out of range");
  EXPECT_EQ(errorOf(kHeader + "Marble,J,2.19,2.62,3,-0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n"),
            "m.csv:2: Marble: sigma_a_r is negative (-0.0021)");
  EXPECT_EQ(errorOf(kHeader + "Marble,J,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,1,1.5,mm^-1\n"),
            "m.csv:2: Marble: g_b = 1 is not in (-1, 1)");
  EXPECT_EQ(errorOf(kHeader + "Marble,J,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0,0,mm^-1\n"),
            "m.csv:2: Marble: eta must be a positive number (0)");
  EXPECT_EQ(errorOf(kHeader + "Marble,J,2.19,nan,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n"),
            "m.csv:2: Marble: sigma_s_g is not finite (nan)");
  EXPECT_EQ(errorOf(kHeader + "Marble,J,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0,1.5,m^-1\n"),
            "m.csv:2: unit: \"m^-1\" (expected \"mm^-1\")");
  EXPECT_EQ(errorOf(kHeader + ",J,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n"), "m.csv:2: name: empty");
  EXPECT_EQ(errorOf(kHeader + kMarble + "\n" + kMarble), "m.csv:4: duplicate material \"Marble\" (first on line 2)");
  EXPECT_EQ(errorOf(kHeader + "Mar\rble,J,2.19,2.62,3,0.0021,0.0041,0.0071,0,0,0,1.5,mm^-1\n"),
            "m.csv:2: name: contains a control character");
}

TEST(MaterialTable, LoadReportsMissingFile) {
  EXPECT_THROW(MaterialTable::load("/nonexistent/materials.csv"), std::runtime_error);
}

TEST(ValidateMaterial, AcceptsValidAndNamesTheBadCoefficient) {
  EXPECT_EQ(validationError(valid()), "");
  Material m = valid();
  m.sigma_s.g = -1.0f;
  EXPECT_EQ(validationError(m), "sigma_s_g is negative (-1)");
  m = valid();
  m.sigma_a.b = -0.5f;
  EXPECT_EQ(validationError(m), "sigma_a_b is negative (-0.5)");
  m = valid();
  m.g.r = -1.0f;
  EXPECT_EQ(validationError(m), "g_r = -1 is not in (-1, 1)");
  m.g.r = 0.999f;
  EXPECT_EQ(validationError(m), "");
  m = valid();
  m.sigma_a.r = INFINITY;
  EXPECT_EQ(validationError(m), "sigma_a_r is not finite (inf)");
  m = valid();
  m.eta = NAN;
  EXPECT_EQ(validationError(m), "eta must be a positive number (nan)");
  m.eta = -1.3f;
  EXPECT_EQ(validationError(m), "eta must be a positive number (-1.3)");
  m = valid();
  m.sigma_s.g = 0.0f;  // purely absorbing band: fine
  EXPECT_EQ(validationError(m), "");
  m.sigma_a.g = 0.0f;  // σ_t = 0: nothing to scatter
  EXPECT_EQ(validationError(m), "sigma_s_g + sigma_a_g is 0 (nothing scatters or absorbs)");
}

}  // namespace
}  // namespace tallow::sss
