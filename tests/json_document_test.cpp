// JsonDocument: DOM equal to nlohmann's, 1-based line:col of every value and key, errors located.
#include "app/config/json_document.h"

#include <gtest/gtest.h>

#include "support/error_of.h"

#include <filesystem>
#include <fstream>
#include <string>

#include "app/config/input_error.h"

namespace tallow::app {
namespace {

using json = nlohmann::json;
using Ptr = json::json_pointer;

template <typename F>
std::string errorOf(F&& f) {
  return test::errorOf<InputError>(std::forward<F>(f));
}

std::string at(const JsonDocument& doc, const char* ptr) { return doc.locate(Ptr(ptr)).str(); }
std::string keyAt(const JsonDocument& doc, const char* ptr) { return doc.locateKey(Ptr(ptr)).str(); }

// Columns:            1234567890123456789012345
const char* kText =
    "{\n"                                   // line 1
    "  \"name\": \"bunny\",\n"              // line 2: key col 3, value col 11
    "  \"objects\": [\n"                    // line 3: key col 3, '[' col 14
    "    {\"material\": \"Marble\",\n"      // line 4: '{' col 5, key col 6, value col 18
    "     \"scale\": 0.1, \"n\": -2},\n"    // line 5: key col 6, 0.1 col 15, "n" col 20, -2 col 25
    "    [true, false, null, 12]\n"         // line 6: '[' col 5, true 6, false 12, null 19, 12 25
    "  ],\n"
    "  \"a/b~c\": {\"\": 1e3}\n"            // line 8: key col 3, '{' col 12, "" col 13, 1e3 col 17
    "}\n";

TEST(JsonDocument, BuildsTheSameDomAsNlohmann) {
  const JsonDocument doc = JsonDocument::parse(kText, "t.json");
  EXPECT_EQ(doc.root(), json::parse(kText));
  EXPECT_EQ(doc.fileName(), "t.json");
}

TEST(JsonDocument, LocatesValues) {
  const JsonDocument doc = JsonDocument::parse(kText, "t.json");
  EXPECT_EQ(at(doc, ""), "t.json:1:1");
  EXPECT_EQ(at(doc, "/name"), "t.json:2:11");
  EXPECT_EQ(at(doc, "/objects"), "t.json:3:14");
  EXPECT_EQ(at(doc, "/objects/0"), "t.json:4:5");
  EXPECT_EQ(at(doc, "/objects/0/material"), "t.json:4:18");
  EXPECT_EQ(at(doc, "/objects/0/scale"), "t.json:5:15");
  EXPECT_EQ(at(doc, "/objects/0/n"), "t.json:5:25");
  EXPECT_EQ(at(doc, "/objects/1"), "t.json:6:5");
  EXPECT_EQ(at(doc, "/objects/1/0"), "t.json:6:6");
  EXPECT_EQ(at(doc, "/objects/1/1"), "t.json:6:12");
  EXPECT_EQ(at(doc, "/objects/1/2"), "t.json:6:19");
  EXPECT_EQ(at(doc, "/objects/1/3"), "t.json:6:25");
  EXPECT_EQ(at(doc, "/a~1b~0c"), "t.json:8:12");  // escaped pointer tokens
  EXPECT_EQ(at(doc, "/a~1b~0c/"), "t.json:8:17");  // the empty key
}

TEST(JsonDocument, LocatesKeys) {
  const JsonDocument doc = JsonDocument::parse(kText, "t.json");
  EXPECT_EQ(keyAt(doc, "/name"), "t.json:2:3");
  EXPECT_EQ(keyAt(doc, "/objects"), "t.json:3:3");
  EXPECT_EQ(keyAt(doc, "/objects/0/material"), "t.json:4:6");
  EXPECT_EQ(keyAt(doc, "/objects/0/n"), "t.json:5:20");
  EXPECT_EQ(keyAt(doc, "/a~1b~0c/"), "t.json:8:13");
  // Array elements and the root have no key: their value's location.
  EXPECT_EQ(keyAt(doc, "/objects/1"), "t.json:6:5");
  EXPECT_EQ(keyAt(doc, ""), "t.json:1:1");
}

TEST(JsonDocument, KeysInDocumentOrder) {
  const JsonDocument doc = JsonDocument::parse("{\"z\": 1, \"a\": {\"y\": 2, \"b\": 3}, \"m\": [4]}", "k.json");
  EXPECT_EQ(doc.keysInOrder(Ptr("")), (std::vector<std::string>{"z", "a", "m"}));
  EXPECT_EQ(doc.keysInOrder(Ptr("/a")), (std::vector<std::string>{"y", "b"}));
  EXPECT_TRUE(doc.keysInOrder(Ptr("/m")).empty());
  EXPECT_TRUE(doc.keysInOrder(Ptr("/nothing")).empty());
}

TEST(JsonDocument, MissingPointersFallBackToTheNearestAncestor) {
  const JsonDocument doc = JsonDocument::parse(kText, "t.json");
  EXPECT_EQ(at(doc, "/objects/0/albedo"), "t.json:4:5");
  EXPECT_EQ(at(doc, "/objects/7/scale"), "t.json:3:14");
  EXPECT_EQ(at(doc, "/objects/1/x"), "t.json:6:5");    // not an index
  EXPECT_EQ(at(doc, "/name/deeper"), "t.json:2:11");   // a string has no members
  EXPECT_EQ(at(doc, "/nothing"), "t.json:1:1");
  EXPECT_EQ(keyAt(doc, "/objects/0/albedo"), "t.json:4:5");
}

TEST(JsonDocument, ColumnsCountUtf8CharactersAndSkipTheBom) {
  // "σ—" is 2 characters but 5 bytes; the BOM takes no column.
  const JsonDocument doc = JsonDocument::parse("\xEF\xBB\xBF{\"d\": \"\xCF\x83\xE2\x80\x94\", \"x\": 1}", "u.json");
  EXPECT_EQ(at(doc, ""), "u.json:1:1");
  EXPECT_EQ(at(doc, "/d"), "u.json:1:7");
  EXPECT_EQ(keyAt(doc, "/x"), "u.json:1:13");
  EXPECT_EQ(at(doc, "/x"), "u.json:1:18");
}

TEST(JsonDocument, HandlesCrLfAndEscapedQuotes) {
  const JsonDocument doc = JsonDocument::parse("{\r\n \"a\\\"b\": \"x\\\\\",\r\n \"c\": [1, 2]}", "w.json");
  EXPECT_EQ(keyAt(doc, "/a\"b"), "w.json:2:2");
  EXPECT_EQ(keyAt(doc, "/c"), "w.json:3:2");
  EXPECT_EQ(at(doc, "/c/1"), "w.json:3:11");
}

TEST(JsonDocument, FailThrowsLocatedInputError) {
  const JsonDocument doc = JsonDocument::parse(kText, "t.json");
  EXPECT_EQ(errorOf([&] { doc.fail(Ptr("/objects/0/scale"), "too small"); }), "t.json:5:15: too small");
  EXPECT_EQ(errorOf([&] { doc.failAtKey(Ptr("/objects/0/scale"), "unknown key \"scale\""); }),
            "t.json:5:6: unknown key \"scale\"");
}

TEST(JsonDocument, SyntaxErrorsNameLineAndColumn) {
  // Unquoted key: the lexer fails on 'b' at line 3, column 3.
  EXPECT_EQ(errorOf([] { JsonDocument::parse("{\n  \"a\": 1,\n  b: 2\n}", "s.json"); }),
            "s.json:3:3: syntax error while parsing object key - invalid literal; expected string literal");
  // Missing comma: the second string starts at line 2, column 3.
  const std::string missingComma = errorOf([] { JsonDocument::parse("[\"a\"\n  \"b\"]", "s.json"); });
  EXPECT_EQ(missingComma.rfind("s.json:2:3: syntax error while parsing array", 0), 0u) << missingComma;
  // Trailing comma before '}'.
  const std::string trailing = errorOf([] { JsonDocument::parse("{\"a\": 1,}", "s.json"); });
  EXPECT_EQ(trailing.rfind("s.json:1:9: ", 0), 0u) << trailing;
  // Truncated input: the error is just past the end.
  const std::string truncated = errorOf([] { JsonDocument::parse("{\"a\": [1,", "s.json"); });
  EXPECT_EQ(truncated.rfind("s.json:1:10: syntax error", 0), 0u) << truncated;
  EXPECT_NE(truncated.find("unexpected end of input"), std::string::npos) << truncated;
  // Empty input and trailing garbage.
  EXPECT_EQ(errorOf([] { JsonDocument::parse("", "s.json"); }).rfind("s.json:1:1: ", 0), 0u);
  EXPECT_EQ(errorOf([] { JsonDocument::parse("{} x", "s.json"); }).rfind("s.json:1:4: ", 0), 0u);
  // Messages stay on one line even when the token spans lines.
  const std::string multiline = errorOf([] { JsonDocument::parse("[\"abc\n\"]", "s.json"); });
  EXPECT_EQ(multiline.find('\n'), std::string::npos) << multiline;
  EXPECT_EQ(multiline.rfind("s.json:1:6: ", 0), 0u) << multiline;
}

TEST(JsonDocument, RejectsNumberOverflow) {
  // Located at the start of the number.
  EXPECT_EQ(errorOf([] { JsonDocument::parse("{\"x\": 1e999}", "n.json"); }),
            "n.json:1:7: number overflow parsing '1e999'");
}

TEST(JsonDocument, RejectsDuplicateKeysAtTheSecondOccurrence) {
  EXPECT_EQ(errorOf([] { JsonDocument::parse("{\"a\": 1,\n \"b\": {\"c\": 1, \"c\": 2}}", "d.json"); }),
            "d.json:2:16: duplicate key \"c\"");
  // Escaped control characters in a key stay escaped in the one-line message.
  EXPECT_EQ(errorOf([] { JsonDocument::parse("{\"a\\nb\": 1, \"a\\nb\": 2}", "d.json"); }),
            "d.json:1:13: duplicate key \"a\\u000ab\"");
  // The same key in different objects is fine.
  EXPECT_NO_THROW(JsonDocument::parse("[{\"c\": 1}, {\"c\": 2}]", "d.json"));
}

TEST(JsonDocument, LimitsNestingDepth) {
  const std::size_t max = JsonDocument::kMaxDepth;
  const std::string ok = std::string(max, '[') + std::string(max, ']');
  EXPECT_NO_THROW(JsonDocument::parse(ok, "deep.json"));
  const std::string tooDeep = std::string(max + 1, '[') + std::string(max + 1, ']');
  EXPECT_EQ(errorOf([&] { JsonDocument::parse(tooDeep, "deep.json"); }),
            "deep.json:1:" + std::to_string(max + 1) + ": nesting deeper than 64 levels");
  // Far deeper input is refused just as quickly, without recursion.
  const std::string huge = std::string(1000000, '[');
  EXPECT_NE(errorOf([&] { JsonDocument::parse(huge, "deep.json"); }).find("nesting deeper"), std::string::npos);
}

TEST(JsonDocument, LoadsFilesAndNamesThemAsGiven) {
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "tallow_json_document_test.json";
  {
    std::ofstream out(file);
    out << "{\n  \"k\": [1, 2,]\n}\n";
  }
  const std::string e = errorOf([&] { JsonDocument::load(file); });
  EXPECT_EQ(e.rfind(file.string() + ":2:14: ", 0), 0u) << e;
  std::filesystem::remove(file);
  EXPECT_EQ(errorOf([&] { JsonDocument::load(file); }), file.string() + ": cannot open");
  const std::filesystem::path folder = std::filesystem::temp_directory_path();
  EXPECT_EQ(errorOf([&] { JsonDocument::load(folder); }), folder.string() + ": is a folder, not a file");
}

}  // namespace
}  // namespace tallow::app
