// What the test runner's tests share: a scratch folder of their own, files written into it, and
// running a test file's text against a program's text through the library (tmcl/testrun.hpp).
#pragma once


#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "os_test.hpp"
#include "tmcl/testrun.hpp"

namespace runtest {

// The scratch folder, made the current folder on first use so that paths in messages are short.
inline std::string scratch() {
  static const std::string dir = [] {
    std::string d = tmcl_test::make_temp_dir("tmcl-testrun");
    std::error_code ec;
    std::filesystem::current_path(d, ec);
    if (d.empty() || ec) return std::string();
    return d;
  }();
  return dir;
}

// Writes `text` to NAME in the scratch folder (subfolders are made) and returns its path there.
inline std::string put(const std::string& name, const std::string& text) {
  scratch();
  const std::string path = name;
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ec);
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

inline bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Runs the test `test` (the text of NAME.tmctest) in the scratch folder, beside whatever
// programs were put there.
inline tmcl::testrun::TestResult run(const std::string& name, const std::string& test,
                                     tmcl::testrun::RunOptions options = {}) {
  tmcl::testrun::ProgramCache cache;
  return tmcl::testrun::run_test_file(put(name + ".tmctest", test), options, cache);
}

// The failures' messages, one a line, for comparing all at once.
inline std::string messages(const tmcl::testrun::TestResult& r) {
  std::string s;
  for (const auto& f : r.failures) s += std::to_string(f.line) + ": " + f.message + "\n";
  return s;
}

}  // namespace runtest
