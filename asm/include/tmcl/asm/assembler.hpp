// The assembler's public interface: TMCL sources, objects and libraries in; a program
// (instructions with their source lines, labels and constants) or one object, and diagnostics out.
//
// Pipeline (assembler.cpp): read -> lex -> parse (one unit per root file, includes inlined; an
//   object is a unit already encoded) -> choose library members -> place -> resolve (constants,
//   labels, expressions, imports) -> encode and relocate -> append STOP -> check the target.
// A single source that assembles without any diagnostic is first tried on the fast path
//   (fast_path.cpp: two passes over the text, no tokens or trees), which gives the same result
//   or gives up; then the pipeline above runs and reports.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tmcl/asm/diag.hpp"
#include "tmcl/asm/object.hpp"
#include "tmcl/isa.hpp"
#include "tmcl/profile.hpp"

namespace tmcl {

// Files are read through this interface so that tests and fuzzers can serve them from memory.
class FileReader {
 public:
  virtual ~FileReader() = default;
  // Reads `path` into `out`; false when it does not exist or cannot be read.
  virtual bool read(const std::string& path, std::string& out) = 0;
  // Why the last read failed ("No such file or directory"), for messages.
  virtual std::string last_error() const { return "cannot be read"; }
  // Why `path` cannot be searched as an -I folder ("does not exist", "is not a folder"); empty
  // when it can, or when the reader cannot tell.
  virtual std::string folder_problem(const std::string& path) {
    (void)path;
    return {};
  }
};

// Reads from the file system; "-" is standard input.
class DiskReader final : public FileReader {
 public:
  bool read(const std::string& path, std::string& out) override;
  std::string last_error() const override { return error_; }
  std::string folder_problem(const std::string& path) override;

 private:
  std::string error_;
};

// Serves some files itself (standard input read already, an editor's unsaved text, one line of
// a console) and every other from the reader below it, the disk unless one is given. What a
// reader says besides the bytes (why a read failed, why an -I folder cannot be searched) is the
// reader's below: a wrapper that forgot to forward it hid the -I warning (issue 28).
class FileOverlay : public FileReader {
 public:
  FileOverlay() : below_(&disk_) {}
  explicit FileOverlay(FileReader& below) : below_(&below) {}
  FileOverlay(const FileOverlay&) = delete;
  FileOverlay& operator=(const FileOverlay&) = delete;
  bool read(const std::string& path, std::string& out) final { return serve(path, out) || below_->read(path, out); }
  std::string last_error() const final { return below_->last_error(); }
  std::string folder_problem(const std::string& path) override { return below_->folder_problem(path); }

 protected:
  // True, with `out` filled, when `path` is one of the overlay's own; false to read it below.
  virtual bool serve(const std::string& path, std::string& out) = 0;

 private:
  DiskReader disk_;
  FileReader* below_;
};

// Serves files from memory (tests, fuzzers, embedders); paths are compared as given.
class MemoryReader final : public FileReader {
 public:
  std::map<std::string, std::string> files;
  bool read(const std::string& path, std::string& out) override;
  std::string last_error() const override { return "No such file or directory"; }
  // A folder exists when some file is in it ("dir/name").
  std::string folder_problem(const std::string& path) override;
};

// A valid name for a label or constant: a letter or '_', then letters, digits and '_'; at most
// 255 bytes (the longest an object file stores).
bool is_valid_name(std::string_view name);

// The include files bundled with tmcl (include_files/), compiled into the library, and NAME.inc
// generated from each bundled module's profile that has none there.
const std::map<std::string, std::string_view>& bundled_includes();
// Those of include_files/ alone: a list of them does not grow with the bundled modules.
const std::map<std::string, std::string_view>& include_file_texts();

struct AsmOptions {
  const Profile* profile = nullptr;             // nullptr: generic
  std::vector<std::string> include_dirs;        // -I, searched after the including file's folder
  std::vector<std::pair<std::string, std::string>> defines;  // -D NAME=VALUE (VALUE an expression)
  bool warnings_are_errors = false;             // -Werror
  WarningOptions warnings;                      // -Wno-name, -Werror=name (diag.hpp)
  bool append_stop = true;                      // append STOP unless the program ends in one
  int error_limit = kDefaultErrorLimit;         // --error-limit: errors a tool shows (0 = all)
  bool relocatable = false;                     // -c: one source file into an object (AsmResult::object)
  bool symbols = true;     // fill AsmResult::symbols (a tool that prints none skips the work)
  bool fast_path = true;  // try the fast path first (same result; tests turn it off to compare)
};

// Where an instruction came from.
struct LineInfo {
  int file = -1;  // index into AsmResult::sources.files
  int line = 0;
};

enum class SymbolKind : std::uint8_t { Label, Constant };

struct Symbol {
  std::string name;     // as spelt at its definition
  SymbolKind kind;
  std::int64_t value;   // address for labels
  SourceLoc defined_at;
  bool exported = false;
};

// One input of a link and where it landed (for the link map).
struct LinkedInput {
  std::string name;     // "main.tmc", "homing.o", "libmotion.a(homing.o)"
  int first = 0;        // address of its first instruction
  int count = 0;        // instructions
  std::string reason;   // library members: the symbol it was linked for
};

struct AsmResult {
  std::vector<Instruction> program;
  std::vector<LineInfo> lines;      // one per instruction; file -1 for the appended STOP
  std::vector<Symbol> symbols;      // labels and constants of every unit, in definition order
                                    // (empty unless AsmOptions::symbols)
  std::vector<LinkedInput> inputs;  // in address order
  std::vector<std::string> unused_members;  // library members not linked
  const Profile* profile = nullptr; // the target: -t, else the one the objects were built for
  bool appended_stop = false;
  std::optional<ObjectFile> object; // relocatable: the object
  SourceSet sources;
  Diagnostics diags;
  bool ok() const { return !diags.has_errors(); }
};

// Assembles the inputs — sources (each its own unit: labels and constants are local to it),
// objects and libraries, told apart by their first bytes — and links them in order from address
// 0. With options.relocatable, `files` is one source, assembled into AsmResult::object.
AsmResult assemble(const std::vector<std::string>& files, const AsmOptions& options, FileReader& reader);

// A library (tmclasm -f lib) of the inputs: objects and library members as they are, sources
// assembled into objects first. Member names are the file names with the extension .o.
struct LibraryResult {
  Library library;
  std::string messages;  // rendered diagnostics of every input
  int errors = 0;
  int warnings = 0;
  bool ok() const { return errors == 0; }
};
LibraryResult make_library(const std::vector<std::string>& files, const AsmOptions& options, FileReader& reader);

}  // namespace tmcl
