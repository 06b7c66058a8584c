// What every diagnostic of every text format shares, whichever library reports it (the
// assembler, scenario and EEPROM files): the "did you mean" guess, the quoted source line with
// a caret under the column, and for the small line-based files (scenarios, EEPROM files) a
// collected diagnostic rendered and capped like the assembler's. Kept in the base layer so that
// the VM's file readers give the same messages as the assembler without depending on it.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace tmcl {

// The closest candidate by edit distance (case-insensitive, a swap of two letters is one edit),
// if close enough to suggest ("did you mean ...?"): at most a third of the word wrong.
std::string closest_match(std::string_view word, const std::vector<std::string_view>& candidates);

// " LINE\n   ^~~~\n": the line (valid UTF-8 shown as it is, control and invisible characters and
// other bytes as '?', tabs kept so the caret lines up) and a caret under byte column `col`
// (1-based) with a tilde for each further character of the `len` bytes, clipped to the line.
// The caret line counts characters, not bytes, so it lines up under non-ASCII text too.
std::string caret_lines(std::string_view line, int col, int len);

// The length of the valid UTF-8 sequence of a non-ASCII character at `s[i]` (2..4), or 0 when it
// is none (overlong forms, encoded surrogates and code points above U+10FFFF are invalid).
std::size_t utf8_length(std::string_view s, std::size_t i);

// A word of a line of a line-based text file and its 1-based column, for carets under it.
struct LineWord {
  std::string text;
  int col;
};
// The words of `line`, split at blanks and tabs.
std::vector<LineWord> split_words(std::string_view line);

// One error in a line-based text file: FILE:LINE:COL: error: MESSAGE, then the line and a caret
// (col 0: FILE:LINE: only, no caret).
struct FileDiag {
  std::string file;
  int line = 0, col = 0, len = 1;
  std::string message;
  std::string source;  // the line's text
};

// Every diagnostic in order, at most `limit` (0 = all) followed by "FILE: note: N more errors
// not shown (--error-limit N changes the limit, 0 shows all)".
std::string render_file_diags(const std::vector<FileDiag>& diags, int limit);

// The last line of a capped list: "WHERE: note: N more errors [and M warnings] not shown (...)"
// ("note: ..." when `where` is empty).
std::string more_errors_note(const std::string& where, long long errors, long long warnings = 0);

// The default of --error-limit for every tool.
inline constexpr int kDefaultErrorLimit = 20;

}  // namespace tmcl
