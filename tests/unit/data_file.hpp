// Reading the fact tables in tests/data/ (copies of the manuals' examples and TMCL-IDE's names,
// each starting with a comment line saying where its facts come from). A test that needs a table
// must fail loudly when it is missing or holds no rows, naming the file: a silent "0 rows" would
// let every check over the rows pass vacuously.
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include "check.hpp"

namespace tmcl_test {

// The path of tests/data/NAME; TMCL_TEST_DATA_DIR is set by tests/CMakeLists.txt.
inline std::string data_path(const std::string& name) { return std::string(TMCL_TEST_DATA_DIR) + "/" + name; }

// The non-empty lines of tests/data/NAME that are not comments ('#'), in order. A missing,
// unreadable or row-less file is a test failure whose message names the file; the caller gets
// an empty vector and should stop.
inline std::vector<std::string> data_lines(const char* file, int line, const std::string& name) {
  const std::string path = data_path(name);
  std::ifstream in(path);
  std::vector<std::string> rows;
  if (!in) {
    fail(file, line, "cannot read test data file " + path + " (tests/data/ must ship with the tree)");
    return rows;
  }
  std::string text;
  while (std::getline(in, text)) {
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.empty() || text[0] == '#') continue;
    rows.push_back(text);
  }
  if (rows.empty()) fail(file, line, "test data file " + path + " holds no rows");
  return rows;
}

// Splits one TSV line at tabs (empty fields kept).
inline std::vector<std::string> tsv_fields(const std::string& line) {
  std::vector<std::string> cols;
  std::size_t start = 0;
  for (;;) {
    const std::size_t tab = line.find('\t', start);
    cols.push_back(line.substr(start, tab == std::string::npos ? std::string::npos : tab - start));
    if (tab == std::string::npos) break;
    start = tab + 1;
  }
  return cols;
}

}  // namespace tmcl_test

#define DATA_LINES(name) ::tmcl_test::data_lines(__FILE__, __LINE__, (name))
