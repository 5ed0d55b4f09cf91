#pragma once
// The small CSV tokeniser of the files users hand to `tallow probe bssrdf` and `tallow field`:
// lines split at '\n' (trailing '\r's dropped), blank lines skipped, cells split at commas and
// trimmed of spaces and tabs (no quoting: every column is a number or a plain name). Positions for
// error messages are 1-based: the line in the file and the byte column in that line.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tallow::app {

/// One cell of a line: its text (trimmed) and the 1-based byte column where that text starts.
struct CsvCell {
  std::string_view text;
  int column = 1;
};

class CsvLines {
 public:
  /// `name` stands for the file in error messages (`name:line:col: …`). `text` must outlive this.
  CsvLines(std::string_view text, std::string name);

  /// Moves to the next line that is not blank; false at the end of the text.
  bool next();
  int lineNumber() const { return lineNumber_; }
  /// The current line, trimmed of blanks at both ends and of trailing '\r's.
  std::string_view line() const { return trimmed_; }
  /// The current line's cells, split at every comma.
  const std::vector<CsvCell>& cells() const { return cells_; }
  /// 1-based column just past the last character of the current line (for "missing column").
  int endColumn() const { return endColumn_; }

  /// `name:line: ` of the current line, or `name: ` before the first.
  std::string where() const;
  /// `name:line:col: ` of a cell of the current line.
  std::string where(const CsvCell& cell) const;
  /// `name:line:col: ` at a column of the current line.
  std::string where(int column) const;
  const std::string& name() const { return name_; }

 private:
  std::string_view text_;
  std::string name_;
  std::size_t pos_ = 0;
  int lineNumber_ = 0;
  std::string_view trimmed_;
  int endColumn_ = 1;
  std::vector<CsvCell> cells_;
};

/// `text` split at every comma (not trimmed): "a,,b" gives "a", "", "b".
std::vector<std::string_view> splitCsvColumns(std::string_view text);

/// The whole of `text` as a finite double (std::from_chars: no leading '+', no blanks, no hex),
/// or nothing for anything else ("", "1e999", "nan", "inf", "1.5x").
std::optional<double> parseFiniteNumber(std::string_view text);

}  // namespace tallow::app
