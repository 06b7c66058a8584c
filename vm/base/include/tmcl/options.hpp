// The one command-line parser of every tool (tmclasm, tmclrun, tmclctl, tmcl-lsp), driven by a
// table: each tool declares each option once (its spellings, the kind of value it takes, its
// help text, what completes its value, and the handler that applies it), and everything else
// follows from the table:
// - the forms `--opt=value`, `--opt value`, `-oVALUE`, `-o VALUE`, prefixes such as `-Wno-NAME`,
//   options and operands in any order, `--` before operands that start with a dash;
// - the errors: an unknown option with a did-you-mean, a missing value, a value given to a flag;
// - `--help` (the tool's text around the option lines generated here) and `--version`;
// - two hidden options for the shell and the tests: `--list-options` (one line per option:
//   spellings and value) and `--complete WORD...` (what completes the last WORD; the bash
//   completion cli/completion/tmcl asks the tool itself).
// A new option is one entry in its tool's table with its handler.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace tmcl::cli {

// What completes an option's value or an operand in the shell.
struct Values {
  enum class Kind { None, Words, Files, Dirs };
  Kind kind = Kind::None;
  // Words: the candidates. Files: the file extensions offered, without the dot (none: any file).
  std::vector<std::string> items;

  // Words worked out only when the shell asks (the targets found on the search path, which a
  // run need not read).
  std::function<std::vector<std::string>()> later = {};
  // Words whose value may also be a file: a value with a '/' completes files with these
  // extensions (-t NAME or -t PATH/TO/FILE.profile).
  std::vector<std::string> or_files = {};

  static Values words(std::vector<std::string> w) { return {Kind::Words, std::move(w)}; }
  static Values words(std::function<std::vector<std::string>()> f, std::vector<std::string> or_files = {}) {
    return {Kind::Words, {}, std::move(f), std::move(or_files)};
  }
  static Values files(std::vector<std::string> extensions = {}) { return {Kind::Files, std::move(extensions)}; }
  static Values dirs() { return {Kind::Dirs, {}}; }
};

// An option's handler: applies the value, returns the usage error or "".
using Handler = std::function<std::string(const std::string& value)>;
// The handlers most options need: the value into a field, a flag set, a value added to a list.
Handler set(std::string& field);
Handler flag(bool& field);
Handler append(std::vector<std::string>& list);

struct Option {
  // The spellings as --help shows them, separated by ", ": "-t, --target", "--trace", "-I".
  // A spelling that ends in '=' or '-' ("-Werror=", "-Wno-") is a prefix: the value follows it
  // in the same argument. A spelling of two characters ("-o") takes its value attached ("-oFILE")
  // or as the next argument; a longer one ("--map") as the next argument or after '='.
  std::string names;
  // The value's placeholder ("FILE", "NAME", "DURATION"); empty for an option that takes none.
  std::string value;
  // --help's text, its lines separated by '\n' (continuation lines are indented to the column).
  // Empty: the option shares the line of the next one ("-Werror, -Werror=NAME  ...").
  std::string help;
  // Applies the option (value: "" for a flag). Returns the usage error, or "" when it was fine.
  Handler set;
  // What completes the value in the shell.
  Values complete = {};
  // The missing-value error is "SPELLING needs " + needs; empty: derived from the placeholder
  // ("a file" for FILE..., "a folder" for DIR, "a number" for N, "a duration" for DURATION).
  std::string needs = {};
  // Not in --help, nor offered by completion (an alias, or a form kept for old command lines).
  bool hidden = false;
  // The options of one command ("download:"): --help shows the label before the first of a run
  // of options with the same group, and the others aligned under it.
  std::string group = {};

  // The last spelling ("--target" of "-t, --target"): how results and checks name the option.
  std::string name() const;
};

struct Tool {
  std::string name;           // "tmclasm": error messages, --version
  std::string usage;          // --help's text before the option lines (ending in "options:\n")
  std::string epilogue;       // --help's text after them
  int column = 25;            // where the help text of an option starts
  std::vector<Option> options;
  // What completes the operand after `before` (the operands already given), with `given` the
  // options given (by name()); null: any file.
  std::function<Values(const std::vector<std::string>& before, const std::vector<std::string>& given)> operands;
};

struct Result {
  enum class Status { Run, Done, Error };
  // Run: go on with `operands`. Done: --help, --version or a hidden option printed what was
  // asked (exit 0). Error: `error` says what was wrong (the tool reports it, a usage error).
  Status status = Status::Run;
  std::string error;
  std::vector<std::string> operands;  // in order
  std::vector<std::string> given;     // the options given, by name(), in order (with repeats)

  bool has(const std::string& name) const;
};

// Parses argv[1..argc) against the tool's table, calling each option's handler in order; stops at
// the first error. --help, --version, --list-options and --complete print to standard output.
Result parse(const Tool& tool, int argc, char** argv);
Result parse(const Tool& tool, const std::vector<std::string>& args);

// --help's text: usage, the option lines, epilogue.
std::string help_text(const Tool& tool);
// --list-options: a line per visible option, "SPELLING[, SPELLING...]<TAB>VALUE", --help and
// --version included.
std::string option_list(const Tool& tool);
// --complete: what completes the last of `words` (the arguments typed so far, the last possibly
// empty). The first line is "words", "files [EXT...]" or "dirs"; after "words" a candidate a
// line, each the whole word ("--target=usb-2-sd", "-Wno-unreachable").
std::string completion(const Tool& tool, const std::vector<std::string>& words);

}  // namespace tmcl::cli
