// Reading a whole file into a string, for tests and the golden runner: one definition instead of
// a copy in every test that compares texts. A missing file reads as empty; callers that must
// tell the two apart check existence first.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

namespace tmcl_test {

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace tmcl_test
