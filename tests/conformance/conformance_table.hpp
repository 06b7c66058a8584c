// Reading a conformance table (docs/conformance/MODULE.md, format in docs/conformance/README.md):
// its sections and their five-cell rows. Shared by the test of the tables against the profiles
// (conformance_tables_test.cpp) and the test of their rows against the VM (conformance_rows_test.cpp).
#pragma once

#include <cctype>
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
  std::string from;                // the base table's file name for a row it inherits, else ""
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

// A table may start from another's rows: a line `Based on [NAME.md](NAME.md)` (a module whose
// profile is `based-on` that one) takes every row of NAME.md, and a row of its own replaces the
// base's row of the same section and key. An inherited row whose command, parameter or vector
// the module lacks is dropped (is_inherited_and_absent); one it has is checked as its own.
inline Table read_table(const fs::path& file, int depth = 0) {
  Table t;
  Section sec = Section::None;
  static const std::regex based(R"(^Based on \[[^\]]+\]\(([A-Za-z0-9_.+-]+\.md)\))");
  auto own = [&](Section s, Row r) {
    auto& rows = t.rows[s];
    for (Row& old : rows)
      if (!old.from.empty() && old.key == r.key) {
        old = std::move(r);
        return;
      }
    rows.push_back(std::move(r));
  };
  std::istringstream in(tmcl_test::read_text(file.string()));
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();  // a checkout with CRLF line ends
    std::smatch m;
    if (sec == Section::None && std::regex_search(line, m, based)) {
      const fs::path base = file.parent_path() / m[1].str();
      if (depth > 4 || !fs::exists(base)) {
        t.errors.push_back(file.filename().string() + ":" + std::to_string(n) + ": no table " + m[1].str() + " to be based on");
        continue;
      }
      Table b = read_table(base, depth + 1);
      for (auto& [s, rows] : b.rows)
        for (Row& r : rows) {
          if (r.from.empty()) r.from = base.filename().string();
          t.rows[s].push_back(std::move(r));
        }
      for (std::string& e : b.errors) t.errors.push_back(std::move(e));
      continue;
    }
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
    own(sec, Row{n, c[0], c[1], c[2], c[3], test_names(c[4]), ""});
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

// The table of a module as its checks read it: an inherited row (Row::from) of a command,
// parameter or vector the module lacks is the base module's only, and dropped.
inline Table table_of(const tmcl::Profile& p, const fs::path& file) {
  Table t = read_table(file);
  for (auto& [sec, rows] : t.rows)
    std::erase_if(rows, [&, sec = sec](const Row& r) {
      if (r.from.empty() || r.key.empty() || !std::isdigit(static_cast<unsigned char>(r.key[0]))) return false;
      const int n = std::stoi(r.key);
      switch (sec) {
        case Section::Commands: return n > 255 || (!p.has_command(static_cast<std::uint8_t>(n)) && r.status != "refused");
        case Section::Axis: return !p.axis_param(n);
        case Section::Bank0: return !p.global_param(0, n);
        case Section::Bank3: return !p.global_param(3, n);
        case Section::Vectors: return n > 255 || !p.vector(n);
        default: return false;
      }
    });
  return t;
}
inline Table table_of(const tmcl::Profile& p) { return table_of(p, table_file(p)); }

}  // namespace conformance
