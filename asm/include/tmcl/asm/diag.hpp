// Diagnostics are collected, never thrown: every error and warning of a run is recorded with its
// place (file, line, column, length) and rendered in one go as
//   file:line:col: error: message
//    source line
//        ^~~~
// preceded by "In file included from FILE:LINE:" lines and followed by notes.
#pragma once

#include <cstdint>
#include <deque>
#include <set>
#include <unordered_map>
#include <string>
#include <string_view>
#include <vector>

#include "tmcl/diag_text.hpp"  // closest_match (did-you-mean), shared with the VM's file readers

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

// A machine-readable fix an editor can offer (the language server's code actions): replace the
// text from `begin` up to `end` (same file, 1-based line and byte column, `end` exclusive; equal
// for an insertion) with `text`. Never rendered: tmclasm prints the same with or without fixes.
struct Fix {
  std::string title;  // "replace 'SAPP' with 'SAP'", "add RETI", "remove unreachable code"
  SourceLoc begin;
  SourceLoc end;
  std::string text;
};

struct Diagnostic {
  Severity severity;
  SourceLoc loc;
  std::string message;
  std::vector<Diagnostic> notes;
  // A named warning's name ("call-depth"), rendered after the message as " [-Wcall-depth]", or as
  // " [-Werror=call-depth]" when -Werror made it an error. Empty: an error or an unnamed warning.
  std::string name;
  std::vector<Fix> fixes;
};

// Every named warning: its name (-Wname, -Wno-name, -Werror=name), whether it is on without
// options, and what it is about (shown by docs and --help). One table for every tool.
struct WarningInfo {
  std::string_view name;
  bool on_by_default;
  std::string_view what;
};
const std::vector<WarningInfo>& warning_table();
// The names of warning_table(), in its order (-Wno-NAME's completion).
std::vector<std::string> warning_names();
const WarningInfo* find_warning(std::string_view name);

// The -W options of a run: which named warnings are shown and which are errors.
struct WarningOptions {
  bool all_errors = false;          // -Werror
  std::set<std::string, std::less<>> on;      // -Wname (turns on one that is off by default)
  std::set<std::string, std::less<>> off;     // -Wno-name
  std::set<std::string, std::less<>> errors;  // -Werror=name (also turns it on)
  bool enabled(std::string_view name) const;
  bool is_error(std::string_view name) const;
  // Applies one option: -Werror, -Werror=name, -Wno-name, -Wall or -Wname. Returns false with `error`
  // set when `arg` is such an option with an unknown name; false with `error` empty when `arg`
  // is not a -W option at all.
  bool parse(std::string_view arg, std::string& error);
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
  // A named warning: dropped (the reference is to a scratch diagnostic) when -Wno-name turned it
  // off, an error when -Werror or -Werror=name made it one.
  Diagnostic& warning(SourceLoc loc, std::string message, std::string_view name);
  bool enabled(std::string_view name) const { return flags_.enabled(name); }
  // Warnings of one kind (one name; the unnamed ones are a kind too) beyond `limit` are counted,
  // not kept (0: all are kept): a tool that shows at most --error-limit of each kind sets it, so
  // that 80,000 warnings of one kind cost neither their messages nor their memory.
  void set_kind_limit(int limit) { kind_limit_ = limit; }
  // Whether warning(…, name) at `loc` would keep the next warning of that kind (an error always
  // is): a check that can warn many times asks first, and builds the message only when true.
  // When false the warning has been counted, as warning() would (not at all when -Wno-name or
  // when a comment allows it there).
  bool take(std::string_view name, SourceLoc loc);

  // Per-line suppression in the source: a comment `tmcl: allow NAME` (or `NAME, NAME`; words
  // after the list are the reason) keeps the named warnings from being reported, or counted, on
  // its line, or on the next line when the comment stands alone on its line. Reads `f`, source
  // `file` of a run, for such comments; false when one names no warning (then warned about).
  bool allow_from_comments(const SourceFile& f, int file);
  bool allowed(SourceLoc loc, std::string_view name) const;
  void note(Diagnostic& d, SourceLoc loc, std::string message);
  // Did-you-mean: the note "did you mean 'HINT'?" at `loc`, and the fix replacing the `wrote`
  // there (the `loc.len` bytes at `loc`, or at `replace` when the word is only part of what the
  // note points at) with `hint`. Nothing when `hint` is empty.
  void suggest(Diagnostic& d, SourceLoc loc, std::string_view wrote, const std::string& hint);
  void suggest(Diagnostic& d, SourceLoc loc, SourceLoc replace, std::string_view wrote, const std::string& hint);

  bool has_errors() const { return errors_ > 0; }
  int error_count() const { return errors_; }
  int warning_count() const { return warnings_; }
  const std::vector<Diagnostic>& all() const { return list_; }
  // Diagnostic `index` of all(), to add a note found later (an error is always kept).
  Diagnostic& at(std::size_t index) { return list_[index]; }
  // -Werror: warnings count as errors from now on, and are shown as errors.
  void set_warnings_are_errors(bool on) {
    flags_.all_errors = on;
    refresh_kinds();
  }
  void set_warning_options(const WarningOptions& flags) {
    flags_ = flags;
    refresh_kinds();
  }
  const WarningOptions& warning_options() const { return flags_; }

  // Every diagnostic in source order (location-less ones last), as render() shows them.
  std::vector<const Diagnostic*> sorted(const SourceSet& sources) const;
  // Renders the diagnostics in source order, stopping after `error_limit` errors (0: no limit,
  // --error-limit) with a line saying how many more errors and warnings there were; of each kind
  // of warning at most `error_limit` are shown, and one line per kind says how many more.
  std::string render(const SourceSet& sources, int error_limit = kDefaultErrorLimit) const;

 private:
  std::vector<Diagnostic> list_;
  int errors_ = 0;
  int warnings_ = 0;
  WarningOptions flags_;
  Diagnostic dropped_{Severity::Note, {}, {}, {}, {}, {}};
  // Per kind of warning met: how many were kept and how many only counted, and what the -W
  // options say of it (looked up once: a check may ask 80,000 times in a row).
  struct Kind {
    std::string name;
    bool enabled, error;
    long long kept = 0, skipped = 0;
  };
  std::vector<Kind> kinds_;
  std::size_t last_kind_ = 0;
  int kind_limit_ = 0;
  // (file, line) -> the warnings a comment allows there.
  std::unordered_map<std::uint64_t, std::vector<std::string>> allows_;
  Kind& kind(std::string_view name);
  void refresh_kinds();
};

// Renders one diagnostic (with its notes).
std::string render_diagnostic(const Diagnostic& d, const SourceSet& sources);

}  // namespace tmcl
