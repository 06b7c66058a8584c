// Reading a conformance table (docs/conformance/MODULE.md, format in docs/conformance/README.md):
// its sections and their five-cell rows. Shared by the test of the tables against the profiles
// (conformance_tables_test.cpp) and the test of their rows against the VM (conformance_rows_test.cpp).
#pragma once

#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "text_file.hpp"
#include "tmcl/profile.hpp"

namespace conformance {

namespace fs = std::filesystem;

inline const fs::path kRoot = TMCL_SOURCE_DIR;

struct Row {
  int line;
  std::string key, name, status, text;
  std::vector<std::string> tests;  // the backticked names of the last cell
};

enum class Section { None, Commands, Axis, Bank0, Bank3, Vectors, Other };

struct Table {
  std::map<Section, std::vector<Row>> rows;
  std::vector<std::string> errors;  // malformed lines
};

inline std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// The cells of a table line `| a | b |`; `\|` is a bar inside a cell.
inline std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (std::size_t i = 1; i < line.size(); ++i) {  // after the leading '|'
    if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
      cur += '|';
      ++i;
    } else if (line[i] == '|') {
      out.push_back(trim(cur));
      cur.clear();
    } else {
      cur += line[i];
    }
  }
  return out;
}

inline Section section_of(const std::string& heading) {
  if (heading == "Commands") return Section::Commands;
  if (heading == "Axis parameters") return Section::Axis;
  if (heading == "Global parameters, bank 0") return Section::Bank0;
  if (heading == "Global parameters, bank 3") return Section::Bank3;
  if (heading == "Interrupt vectors") return Section::Vectors;
  return Section::Other;
}

inline std::vector<std::string> test_names(const std::string& cell) {
  std::vector<std::string> out;
  static const std::regex tick("`([^`]+)`");
  for (std::sregex_iterator it(cell.begin(), cell.end(), tick), end; it != end; ++it) out.push_back((*it)[1]);
  return out;
}

inline Table read_table(const fs::path& file) {
  Table t;
  Section sec = Section::None;
  std::istringstream in(tmcl_test::read_text(file.string()));
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();  // a checkout with CRLF line ends
    if (line.rfind("## ", 0) == 0) {
      sec = section_of(trim(line.substr(3)));
      continue;
    }
    if (sec == Section::None || sec == Section::Other || line.empty() || line[0] != '|') continue;
    std::vector<std::string> c = cells(line);
    if (c.empty() || c[0] == "#" || c[0].find("---") != std::string::npos) continue;  // header, rule
    if (c.size() != 5) {
      t.errors.push_back(file.filename().string() + ":" + std::to_string(n) + ": a row has 5 cells, this one " +
                         std::to_string(c.size()));
      continue;
    }
    t.rows[sec].push_back(Row{n, c[0], c[1], c[2], c[3], test_names(c[4])});
  }
  return t;
}

// The modules a table is kept for: every bundled profile but generic, which is no module.
inline std::vector<const tmcl::Profile*> modules() {
  std::vector<const tmcl::Profile*> out;
  for (const tmcl::Profile* p : tmcl::all_profiles())
    if (!p->any_parameter) out.push_back(p);
  return out;
}

inline fs::path table_file(const tmcl::Profile& p) { return kRoot / "docs" / "conformance" / (std::string(p.name) + ".md"); }

}  // namespace conformance
