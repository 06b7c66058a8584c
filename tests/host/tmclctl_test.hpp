// What the tmclctl tests share: the two tools' paths, a scratch folder, files in and out, and
// running tmclctl with pipes for its output (process.hpp) and a generous reply timeout.
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

// Runs tmclctl with `args`. Without a --timeout among them it gets --timeout 5s: where a reply
// is to come, a loaded machine (load average 15 on 2 cores) must not turn a slow one into a
// failure. Tests of silence pass their own short timeout.
inline Output ctl(const std::vector<std::string>& args, int timeout_ms = 30000) {
  std::vector<std::string> argv{kCtl};
  bool timeout = false;
  for (const auto& a : args) timeout = timeout || a == "--timeout";
  if (!timeout) argv.insert(argv.end(), {"--timeout", "5s"});
  argv.insert(argv.end(), args.begin(), args.end());
  return hosttest::run(argv, timeout_ms);
}

inline void show(const Output& o) {
  if (o.status != 0) std::fprintf(stderr, "  status %d\n  stdout: %s\n  stderr: %s\n", o.status, o.out.c_str(), o.err.c_str());
}

}  // namespace hosttest
