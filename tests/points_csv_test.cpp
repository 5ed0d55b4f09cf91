// The points CSV of `tallow field` (app/points_csv) and the tokeniser it shares with the BSSRDF
// probe (app/csv_reader): accepted layouts, exact `file:line:col:` errors, limits, output format.
#include "app/commands/points_csv.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "app/commands/csv_reader.h"
#include "app/config/input_error.h"
#include "support/error_of.h"

namespace tallow::app {
namespace {

std::string errorOf(const std::string& text) {
  return test::errorOf<InputError>([&] { parsePoints(text, "p.csv"); });
}

TEST(PointsCsv, ReadsRowsWithBlanksCrlfAndBlankLines) {
  const auto points = parsePoints("x,y,z\r\n1,2,3\r\n\n  -0.5 ,\t1e-3, 7 \n4.25,0,-0\n", "p.csv");
  ASSERT_EQ(points.size(), 3u);
  EXPECT_EQ(points[0], glm::dvec3(1, 2, 3));
  EXPECT_EQ(points[1], glm::dvec3(-0.5, 1e-3, 7));
  EXPECT_EQ(points[2], glm::dvec3(4.25, 0, 0));
  EXPECT_TRUE(parsePoints(" x , y , z \n", "p.csv").empty());  // a header and no rows is fine
}

TEST(PointsCsv, HeaderErrorsPointAtTheFirstWrongCell) {
  EXPECT_EQ(errorOf(""), "p.csv:1:1: empty file; expected the header x,y,z");
  EXPECT_EQ(errorOf("\n  \n"), "p.csv:1:1: empty file; expected the header x,y,z");
  EXPECT_EQ(errorOf("x,y,w\n1,2,3\n"), "p.csv:1:5: expected the header x,y,z");
  EXPECT_EQ(errorOf("\nx,y\n"), "p.csv:2:4: expected the header x,y,z");
  EXPECT_EQ(errorOf("x,y,z,value\n"), "p.csv:1:7: expected the header x,y,z");
  EXPECT_EQ(errorOf("X,Y,Z\n"), "p.csv:1:1: expected the header x,y,z");  // case matters
  EXPECT_EQ(errorOf("\xEF\xBB\xBFx,y,z\n"), "p.csv:1:1: expected the header x,y,z");  // no BOM
}

TEST(PointsCsv, RowErrorsNameLineColumnAndCell) {
  EXPECT_EQ(errorOf("x,y,z\n1,2\n"), "p.csv:2:4: expected 3 columns, found 2");
  EXPECT_EQ(errorOf("x,y,z\n1,2,3,4\n"), "p.csv:2:7: expected 3 columns, found 4");
  EXPECT_EQ(errorOf("x,y,z\n\n1, abc ,3\n"), "p.csv:3:4: y: \"abc\" is not a finite number");
  EXPECT_EQ(errorOf("x,y,z\n1,2,\n"), "p.csv:2:5: z: \"\" is not a finite number");
  EXPECT_EQ(errorOf("x,y,z\nnan,0,0\n"), "p.csv:2:1: x: \"nan\" is not a finite number");
  EXPECT_EQ(errorOf("x,y,z\n0,inf,0\n"), "p.csv:2:3: y: \"inf\" is not a finite number");
  EXPECT_EQ(errorOf("x,y,z\n0,0,1e999\n"), "p.csv:2:5: z: \"1e999\" is not a finite number");
  EXPECT_EQ(errorOf("x,y,z\n+1,0,0\n"), "p.csv:2:1: x: \"+1\" is not a finite number");
  EXPECT_EQ(errorOf("x,y,z\n0x10,0,0\n"), "p.csv:2:1: x: \"0x10\" is not a finite number");
  EXPECT_EQ(errorOf("x,y,z\n1.5m,0,0\n"), "p.csv:2:1: x: \"1.5m\" is not a finite number");
  EXPECT_EQ(errorOf("x,y,z\n\"1\",0,0\n"), "p.csv:2:1: x: \"\\\"1\\\"\" is not a finite number");
  EXPECT_EQ(errorOf("x,y,z\n0,0,2e6\n"), "p.csv:2:5: z: \"2e6\" is out of range (|z| <= 1e6 m)");
  EXPECT_EQ(errorOf(std::string("x,y,z\n0,\0,0\n", 12)), "p.csv:2:3: y: \"\\u0000\" is not a finite number");
}

TEST(PointsCsv, RejectsMoreThanTheRowLimit) {
  std::string text = "x,y,z\n";
  text.reserve(text.size() + (kMaxPoints + 1) * 6);
  for (std::size_t i = 0; i < kMaxPoints; ++i) text += "0,0,0\n";
  EXPECT_EQ(parsePoints(text, "p.csv").size(), kMaxPoints);
  text += "1,2,3\n";
  EXPECT_EQ(errorOf(text), "p.csv:" + std::to_string(kMaxPoints + 2) + ":1: more than 10000000 points (the limit per file)");
}

TEST(PointsCsv, OutputHasTheHeaderAndReadsBackExactly) {
  const std::vector<glm::dvec3> points{{0.1, -2.0 / 3.0, 1e-300}};
  const std::vector<FieldSample> samples{{-std::numeric_limits<double>::min(), {1.0 / 3.0, 0.0, -7.5}}};
  EXPECT_EQ(formatFieldValues(points, samples),
            "x,y,z,value,grad_x,grad_y,grad_z\n"
            "0.10000000000000001,-0.66666666666666663,1e-300,-2.2250738585072014e-308,"
            "0.33333333333333331,0,-7.5\n");
  EXPECT_THROW(formatFieldValues(points, {}), std::invalid_argument);
}

TEST(PointsCsv, TokeniserColumnsAreOneBasedBytesOfTheRawLine) {
  CsvLines lines("\n\n  a , b,,c\t\r\n", "t.csv");
  EXPECT_EQ(lines.where(), "t.csv: ");
  ASSERT_TRUE(lines.next());
  EXPECT_EQ(lines.lineNumber(), 3);
  EXPECT_EQ(lines.line(), "a , b,,c");
  ASSERT_EQ(lines.cells().size(), 4u);
  const int columns[] = {3, 7, 9, 10};
  const char* texts[] = {"a", "b", "", "c"};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(lines.cells()[i].text, texts[i]);
    EXPECT_EQ(lines.cells()[i].column, columns[i]) << i;
  }
  EXPECT_EQ(lines.endColumn(), 11);
  EXPECT_EQ(lines.where(lines.cells()[1]), "t.csv:3:7: ");
  EXPECT_EQ(lines.where(), "t.csv:3: ");
  EXPECT_FALSE(lines.next());
  EXPECT_EQ(parseFiniteNumber("-1.25e-2"), -1.25e-2);
  EXPECT_FALSE(parseFiniteNumber(" 1"));
  EXPECT_FALSE(parseFiniteNumber(""));
  EXPECT_FALSE(parseFiniteNumber("-nan"));
}

}  // namespace
}  // namespace tallow::app
