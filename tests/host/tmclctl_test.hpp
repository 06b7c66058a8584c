// What the tmclctl tests share: the two tools' paths, a scratch folder, files in and out, and
// running tmclctl with pipes for its output (process.hpp).
#pragma once

#include <sys/stat.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "process.hpp"

namespace hosttest {

inline const std::string kCtl = TMCL_TMCLCTL;
inline const std::string kRun = TMCL_TMCLRUN;

inline std::string temp_dir() {
  static std::string dir = [] {
    char t[] = "/tmp/tmclctl-test-XXXXXX";
    return std::string(::mkdtemp(t));
  }();
  return dir;
}

inline std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = temp_dir() + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

inline std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

inline bool exists(const std::string& path) {
  struct stat st{};
  return ::stat(path.c_str(), &st) == 0;
}

inline bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

inline Output ctl(const std::vector<std::string>& args, int timeout_ms = 30000) {
  std::vector<std::string> argv{kCtl};
  argv.insert(argv.end(), args.begin(), args.end());
  return hosttest::run(argv, timeout_ms);
}

inline void show(const Output& o) {
  if (o.status != 0) std::fprintf(stderr, "  status %d\n  stdout: %s\n  stderr: %s\n", o.status, o.out.c_str(), o.err.c_str());
}

}  // namespace hosttest
