// The simulated EEPROM: what STGP/STAP/SCO-255/auto-stored bank-0 parameters keep across runs,
// and its file format (tmclrun --eeprom FILE).
//
// File format, version 1 (text, one record per line, sorted, so it diffs well):
//   tmcl-eeprom 1
//   profile usb-2-sd
//   var <index> <value>
//   global <param> <value>          (bank 0)
//   global3 <param> <value>         (bank 3, the interrupt settings: STGP of a parameter with E)
//   axis <motor> <param> <value>
//   coord <motor> <n> <value>
//   program <address> <op> <type> <motor> <value>   (program memory, on a module that keeps it
//                                   in EEPROM: every word from address 0, without a gap)
//   check <8 hex digits>            FNV-1a 32 of every byte before this line
// global3 and program came after the first files were written; a file without them reads as
// before, and the version stays 1 (an older tmclrun refuses a file with one as an unknown
// record, by name).
// A file that does not match (header, syntax, duplicate record, checksum) is rejected with every
// error in one go, each FILE:LINE:COL: error: ... with the line and a caret, like the assembler. Saving writes FILE.tmp, flushes it, then renames it over FILE, so a
// killed process leaves either the old or the new file, never half of one.
//
// Editing by hand: change, add or delete records in any text editor, then run
// `tmclrun --eeprom-seal FILE` (seal_eeprom_file): it checks every record, sorts them and writes
// a fresh checksum line. Without that a hand-edited file is refused as corrupt.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "tmcl/codec.hpp"
#include "tmcl/diag_text.hpp"

namespace tmcl {

struct EepromImage {
  std::string profile;  // the -t name it was written with
  std::map<int, std::int32_t> vars;                     // bank 2 (STGP)
  std::map<int, std::int32_t> globals;                  // bank 0 (auto-stored or STGP)
  std::map<int, std::int32_t> bank3;                    // bank 3 (STGP of a parameter with E)
  std::map<std::pair<int, int>, std::int32_t> axis;     // (motor, param) (STAP)
  std::map<std::pair<int, int>, std::int32_t> coords;   // (motor, n) (SCO n, 255 / global 84)
  // Program memory, on a module whose profile keeps it in EEPROM (program-memory N eeprom):
  // what a host downloaded (132/133), or the program of a plain run (docs/errata.md E55).
  std::vector<Instruction> program;
  friend bool operator==(const EepromImage&, const EepromImage&) = default;
};

std::string eeprom_to_text(const EepromImage& image);
// Parses `text` (named `file` in messages), checking every line; returns false when any is bad,
// with `diags` holding every error in line order (render_file_diags shows them, capped).
// `check_checksum` false (sealing) ignores the checksum line.
bool eeprom_from_text(const std::string& text, const std::string& file, EepromImage& image, std::vector<FileDiag>& diags,
                      bool check_checksum = true);
// The same, with the errors rendered (at most kDefaultErrorLimit) into `error`.
bool eeprom_from_text(const std::string& text, const std::string& file, EepromImage& image, std::string& error,
                      bool check_checksum = true);

// Loads FILE; a missing file is an empty EEPROM (returns true, `existed` false). A bad file
// returns false with its errors in `diags`; one that cannot be read, with `error` set
// ("FILE: error: cannot read EEPROM file: ...") and `diags` untouched.
bool load_eeprom_file(const std::string& path, EepromImage& image, bool& existed, std::vector<FileDiag>& diags,
                      std::string& error);
// The same, with the errors rendered into `error`.
bool load_eeprom_file(const std::string& path, EepromImage& image, bool& existed, std::string& error);
// Atomic save: temporary file + rename.
bool save_eeprom_file(const std::string& path, const EepromImage& image, std::string& error);
// --eeprom-seal: reads a hand-edited FILE without checking its checksum, checks every record and
// saves it again (sorted, with a fresh checksum line). Errors as load_eeprom_file reports them;
// a file that cannot be written sets `error` to "FILE: error: cannot write EEPROM file: ...".
bool seal_eeprom_file(const std::string& path, std::vector<FileDiag>& diags, std::string& error);
bool seal_eeprom_file(const std::string& path, std::string& error);

}  // namespace tmcl
