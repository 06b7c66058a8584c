// Diagnostics are collected, never thrown: every error and warning of a run is recorded with its
// place (file, line, column, length) and rendered in one go as
//   file:line:col: error: message
//    source line
//        ^~~~
// preceded by "In file included from FILE:LINE:" lines and followed by notes.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <string_view>
#include <vector>

namespace tmcl {

// A loaded source buffer. `includer` is the file and line that included it (-1: a root file).
struct SourceFile {
  std::string name;   // as shown in messages
  std::string path;   // as opened (canonical where possible)
  std::string text;
  int includer = -1;
  int include_line = 0;
  std::vector<std::uint32_t> line_starts;  // byte offset of each line
  std::string_view line(int number) const;  // 1-based, without the line break
};

struct SourceLoc {
  int file = -1;  // index into SourceSet::files; -1: no place (command line)
  int line = 0;   // 1-based
  int col = 0;    // 1-based byte column
  int len = 1;    // bytes to underline
};

enum class Severity : std::uint8_t { Note, Warning, Error };

struct Diagnostic {
  Severity severity;
  SourceLoc loc;
  std::string message;
  std::vector<Diagnostic> notes;
};

// All source buffers of one run, so a location can be rendered with its line and include chain.
struct SourceSet {
  std::deque<SourceFile> files;  // a deque: tokens point into the texts, which must not move
  int add(SourceFile f);
};

class Diagnostics {
 public:
  Diagnostic& error(SourceLoc loc, std::string message);
  Diagnostic& warning(SourceLoc loc, std::string message);
  void note(Diagnostic& d, SourceLoc loc, std::string message);

  bool has_errors() const { return errors_ > 0; }
  int error_count() const { return errors_; }
  int warning_count() const { return warnings_; }
  const std::vector<Diagnostic>& all() const { return list_; }
  // -Werror: warnings count as errors from now on, and are shown as errors.
  void set_warnings_are_errors(bool on) { werror_ = on; }

  // Renders every diagnostic in the order reported.
  std::string render(const SourceSet& sources) const;

 private:
  std::vector<Diagnostic> list_;
  int errors_ = 0;
  int warnings_ = 0;
  bool werror_ = false;
};

// Renders one diagnostic (with its notes).
std::string render_diagnostic(const Diagnostic& d, const SourceSet& sources);

// The closest candidate by edit distance, if close enough to suggest ("did you mean ...?").
std::string closest_match(std::string_view word, const std::vector<std::string_view>& candidates);

}  // namespace tmcl
