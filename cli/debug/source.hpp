// Source positions of an image for the debugger: the labels and line table of a symbols file
// (tmclasm -f symbols) applied to a .bin's ProgramInfo, and the sources' text found on disk.
#pragma once

#include <string>
#include <vector>

#include "tmcl/debugger.hpp"

namespace tmcl::debug {

// Reads the symbols file `symbols` into `info`: its labels, and from its line table every
// address's file and line, with each file's text when it is found (relative paths: beside the
// symbols file, in the current folder, then in each of `source_dirs`). A malformed file is an
// error ("prog.sym:7: error: ...") and false; a missing source or a table longer than the
// program a warning in `messages`.
bool apply_symbols(const std::string& symbols, const std::vector<std::string>& source_dirs, ProgramInfo& info,
                   std::string& messages);

}  // namespace tmcl::debug
