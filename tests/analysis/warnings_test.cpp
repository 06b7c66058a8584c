// Every named warning (warning_table(), asm/diag.cpp) is documented and pinned: a row of the table
// in docs/analysis.md ("| `NAME` | example | fix |"), and a golden pair NAME.tmc / NAME-ok.tmc in
// one suite of tests/golden/, the first drawing [-WNAME] and its twin not; and the table has no
// row of a warning that is none. A new warning is a row of warning_table(), its check, a row of
// that table and the pair (docs/architecture.md, "A new warning").
#include "check.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <string>

#include "tmcl/asm/diag.hpp"

namespace {

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The names in the first column of docs/analysis.md's warning table.
std::set<std::string> documented_warnings() {
  std::istringstream in(read_text(std::filesystem::path(TMCL_DOCS_DIR) / "analysis.md"));
  std::set<std::string> names;
  std::string line;
  bool table = false;
  while (std::getline(in, line)) {
    if (line.rfind("| warning |", 0) == 0) table = true;
    else if (table && line.rfind("| `", 0) == 0) names.insert(line.substr(3, line.find('`', 3) - 3));
    else if (table && line.rfind("|", 0) != 0) table = false;
  }
  return names;
}

}  // namespace

TEST(every_warning_has_its_row_in_docs_analysis) {
  const std::set<std::string> rows = documented_warnings();
  CHECK(rows.size() >= 10u);
  for (const auto& w : tmcl::warning_table())
    if (!rows.count(std::string(w.name)))
      ::tmcl_test::fail(__FILE__, __LINE__, "docs/analysis.md: the warning table has no row | `" + std::string(w.name) +
                                                "` | example | fix |");
  for (const auto& name : rows)
    if (!tmcl::find_warning(name))
      ::tmcl_test::fail(__FILE__, __LINE__, "docs/analysis.md: a row of the warning table for '" + name + "', which is no warning");
}

TEST(every_warning_has_a_golden_pair_that_fires_and_one_that_stays_silent) {
  for (const auto& w : tmcl::warning_table()) {
    const std::string name(w.name), tag = "[-W" + name + "]";
    int pairs = 0;
    for (const auto& suite : std::filesystem::directory_iterator(TMCL_GOLDEN_DIR)) {
      const auto fires = suite.path() / (name + ".golden"), silent = suite.path() / (name + "-ok.golden");
      if (!std::filesystem::exists(suite.path() / (name + ".tmc")) || !std::filesystem::exists(suite.path() / (name + "-ok.tmc")))
        continue;
      ++pairs;
      if (read_text(fires).find(tag) == std::string::npos)
        ::tmcl_test::fail(__FILE__, __LINE__, fires.string() + " does not show " + tag);
      if (read_text(silent).find(tag) != std::string::npos)
        ::tmcl_test::fail(__FILE__, __LINE__, silent.string() + " shows " + tag + ": the twin must stay silent");
    }
    if (pairs == 0)
      ::tmcl_test::fail(__FILE__, __LINE__, "no golden pair " + name + ".tmc and " + name + "-ok.tmc in a suite of tests/golden/");
  }
}
