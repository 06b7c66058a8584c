// The symbols file (tmclasm -f symbols, docs/tmclasm.md "symbols"): its one reader and the line
// table it carries. Labels give a .bin its names (tmclasm -d, tmclrun --debug, --analyze); the
// line table gives every address of a .bin the file and line it came from, through includes and
// across linked units, so that a debugger and the disassembler can show source positions of an
// image. The writer is format_symbols (output.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace tmcl {

struct AsmResult;

// Source positions of a program: runs of consecutive addresses on consecutive lines of a file.
struct LineTable {
  struct Run {
    std::int64_t address = 0;  // first address of the run
    std::int64_t count = 1;    // instructions: address + k is on line + k
    int file = 0;              // index into files
    int line = 1;              // 1-based
  };
  std::vector<std::string> files;  // paths as tmclasm was given them
  std::vector<Run> runs;           // in address order, not overlapping
  bool empty() const { return runs.empty(); }
  // The file index and line of `address`; {-1, 0} when the table has no position for it.
  std::pair<int, int> at(std::int64_t address) const;
  // The address one past the last run (0 for an empty table).
  std::int64_t end() const { return runs.empty() ? 0 : runs.back().address + runs.back().count; }
};

// What a symbols file gives a .bin: label names and, when the file has one, a line table.
struct LabelNames {
  std::vector<std::pair<std::string, std::int64_t>> labels;  // name, address; in file order
  LineTable lines;
};

// Parses the symbols format; false with the 1-based line of the file and what is wrong there
// (line 0: the file as a whole). Files of symbols version 1 without a line table still read.
bool parse_symbols(const std::string& text, LabelNames& out, int& error_line, std::string& error);

// Reads and parses the symbols file `path`. On failure `message` is one diagnostic without a
// newline: "PATH:LINE: error: WHAT", or "TOOL: error: cannot open 'PATH': ..." when unreadable.
bool load_symbols(const std::string& path, const std::string& tool, LabelNames& out, std::string& message);

// The line table of a linked program as the symbols format writes it (appended by
// format_symbols): "# tmclasm lines 1", then "#file" and "#lines" records.
std::string format_line_table(const AsmResult& result);

}  // namespace tmcl
