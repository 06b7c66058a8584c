// The conformance tables (docs/conformance/MODULE.md) against the module profiles: each bundled
// module has its table; every command, axis parameter, global parameter of banks 0 and 3 and
// interrupt vector of the profile has its row, and no row names something the profile lacks (a
// command row marked `refused` names a command the profile lacks, as the module refuses it); a
// row says simulated, partial, stored, not simulated or refused; a simulated or partial row names
// the tests that pin it, and every test a row names exists in this repository: a golden case
// (`golden/SUITE/CASE`), a unit case (`TEST(CASE)` in a test source) or a CTest test registered in
// a tests/ CMakeLists.txt. The row format is docs/conformance/README.md's.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "check.hpp"
#include "conformance_table.hpp"
#include "text_file.hpp"
#include "tmcl/interrupts.hpp"
#include "tmcl/isa.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/profile.hpp"

namespace fs = std::filesystem;
using tmcl_test::read_text;

namespace {

using conformance::kRoot;
using conformance::modules;
using conformance::read_table;
using conformance::Row;
using conformance::Section;
using conformance::Table;

// Every test name the repository defines: golden cases, unit cases, CTest tests.
const std::set<std::string>& known_tests() {
  static const std::set<std::string> names = [] {
    std::set<std::string> out;
    static const std::regex unit_case(R"(^\s*TEST\(([A-Za-z0-9_]+)\))");
    static const std::regex ctest(R"(^\s*(?:add_test\(NAME|tmcl_unit_test\(|tmcl_motion_test\(|tmcl_script_test\()\s*([A-Za-z0-9_./-]+))");
    static const std::regex run_line(R"((//|;).*RUN:)");
    static const std::regex macro_head(R"(^#define ([A-Z_]+)\(name\))");
    static const std::regex macro_case(R"(TEST\(([A-Za-z0-9_]*)##name\))");
    static const std::regex macro_use(R"(^([A-Z_]+)\(([a-z0-9_]+)\)\s*$)");
    for (const auto& e : fs::recursive_directory_iterator(kRoot / "tests")) {
      if (!e.is_regular_file()) continue;
      const fs::path& p = e.path();
      const std::string ext = p.extension().string();
      if (ext == ".cpp" || ext == ".hpp" || p.filename() == "CMakeLists.txt") {
        // A macro that defines cases (`#define ON_ALL(name) TEST(tcp_##name) ...`) names one
        // case per prefix at each use (`ON_ALL(addresses)`: tcp_addresses, ...).
        std::map<std::string, std::vector<std::string>> case_macros;
        std::string defining;
        std::istringstream in(read_text(p.string()));
        for (std::string line; std::getline(in, line);) {
          std::smatch m;
          if (std::regex_search(line, m, macro_head)) defining = m[1];
          if (!defining.empty()) {
            for (std::sregex_iterator it(line.begin(), line.end(), macro_case), end; it != end; ++it)
              case_macros[defining].push_back((*it)[1]);
            if (line.empty() || line.back() != '\\') defining.clear();
            continue;
          }
          if (std::regex_search(line, m, macro_use) && case_macros.count(m[1]))
            for (const std::string& prefix : case_macros[m[1]]) out.insert(prefix + std::string(m[2]));
          if (std::regex_search(line, m, unit_case)) out.insert(m[1]);
          if (p.filename() == "CMakeLists.txt" && std::regex_search(line, m, ctest)) out.insert(m[1]);
        }
      } else if (ext == ".tmc" || ext == ".run") {
        // A golden case: tests/golden/SUITE/CASE, with a RUN: line. Compared as a relative path,
        // not by a '/' prefix, so that Windows' backslash separators name the same case.
        const std::string text = read_text(p.string());
        if (!std::regex_search(text, run_line)) continue;
        const fs::path rel_path = p.lexically_relative(kRoot / "tests" / "golden");
        const std::string rel = rel_path.empty() || *rel_path.begin() == ".." ? std::string()
                                                                            : fs::path(rel_path).replace_extension().generic_string();
        if (!rel.empty()) out.insert("golden/" + rel);
      }
    }
    return out;
  }();
  return names;
}

using Errors = std::vector<std::string>;

const std::set<std::string> kStatuses = {"simulated", "partial", "stored", "not simulated", "refused"};

// The checks every row makes whatever it names. `where` prefixes the messages.
void check_row(Errors& errs, const std::string& where, const Row& r, bool command) {
  if (!kStatuses.count(r.status)) {
    errs.push_back(where + ": unknown status '" + r.status + "'");
    return;
  }
  if (r.status == "refused" && !command)
    errs.push_back(where + ": only a command is refused");
  if ((r.status == "simulated" || r.status == "partial") && r.tests.empty())
    errs.push_back(where + ": a " + r.status + " row names the tests that pin it");
  if (r.status != "simulated" && r.text.empty())
    errs.push_back(where + ": a " + r.status + " row says what and why");
  for (const std::string& t : r.tests)
    if (!known_tests().count(t)) errs.push_back(where + ": no test '" + t + "' in tests/");
}

std::string where(const fs::path& file, const Row& r) {
  return (r.from.empty() ? file.filename().string() : r.from + " (by " + file.filename().string() + ")") + ":" + std::to_string(r.line);
}

void check_commands(Errors& errs, const fs::path& file, const tmcl::Profile& p, const std::vector<Row>& rows) {
  std::set<int> executed;
  std::set<std::string> keys;
  for (const Row& r : rows) {
    check_row(errs, where(file, r), r, true);
    static const std::regex key(R"(^(\d+)(?:/(\d+))?$)");
    std::smatch m;
    if (!std::regex_match(r.key, m, key) || std::stoi(m[1]) > 255) {
      errs.push_back(where(file, r) + ": a command row's key is OPCODE or OPCODE/TYPE, not '" + r.key + "'");
      continue;
    }
    if (!keys.insert(r.key).second) errs.push_back(where(file, r) + ": a second row " + r.key);
    const int op = std::stoi(m[1]);
    const tmcl::OpInfo* info = tmcl::op_info(static_cast<std::uint8_t>(op));
    if (!info) {
      errs.push_back(where(file, r) + ": " + std::to_string(op) + " is no TMCL command");
      continue;
    }
    if (!info->control && r.name.rfind(std::string(info->mnemonic), 0) != 0)
      errs.push_back(where(file, r) + ": command " + std::to_string(op) + " is " +
                                              std::string(info->mnemonic) + ", the row says '" + r.name + "'");
    const bool has = p.has_command(static_cast<std::uint8_t>(op));
    if (r.status == "refused" && has)
      errs.push_back(where(file, r) + ": the profile executes " + std::to_string(op) + ", the row says refused");
    if (r.status != "refused" && !has)
      errs.push_back(where(file, r) + ": the profile lacks command " + std::to_string(op));
    if (r.status != "refused") executed.insert(op);
  }
  for (int op = 0; op < 256; ++op)
    if (p.has_command(static_cast<std::uint8_t>(op)) && !executed.count(op))
      errs.push_back(file.filename().string() + ": no row for command " + std::to_string(op));
}

void check_params(Errors& errs, const fs::path& file, std::string_view what, std::span<const tmcl::ParamInfo> params,
                  const std::vector<Row>& rows) {
  std::map<int, const tmcl::ParamInfo*> want;
  for (const tmcl::ParamInfo& pi : params) want[pi.number] = &pi;
  std::set<int> seen;
  for (const Row& r : rows) {
    check_row(errs, where(file, r), r, false);
    static const std::regex key(R"(^\d+$)");
    if (!std::regex_match(r.key, key)) {
      errs.push_back(where(file, r) + ": a parameter row's key is its number, not '" + r.key + "'");
      continue;
    }
    const int n = std::stoi(r.key);
    if (!seen.insert(n).second) errs.push_back(where(file, r) + ": a second row " + r.key);
    auto it = want.find(n);
    if (it == want.end()) {
      errs.push_back(where(file, r) + ": the profile has no " + std::string(what) + " " + r.key);
      continue;
    }
    if (r.name != it->second->name)
      errs.push_back(where(file, r) + ": " + std::string(what) + " " + r.key + " is '" +
                                              std::string(it->second->name) + "' in the profile, '" + r.name + "' here");
    // The profile's not-simulated= is the one source (a run's note quotes it); the row agrees.
    const std::string why(it->second->not_simulated);
    if (why.empty() && r.status == "not simulated")
      errs.push_back(where(file, r) + ": a not simulated row, but the profile's " + std::string(what) + " " + r.key +
                     " has no not-simulated=\"REASON\" (the run's note comes from it)");
    if (!why.empty() && r.status != "not simulated")
      errs.push_back(where(file, r) + ": the profile marks " + std::string(what) + " " + r.key + " not-simulated, the row says '" +
                     r.status + "' (drop not-simulated= from its line in vm/isa/profiles/" + file.stem().string() +
                     ".profile, or the row is wrong)");
    if (!why.empty() && r.text.find(why) == std::string::npos)
      errs.push_back(where(file, r) + ": the row does not say the profile's reason '" + why + "'");
  }
  for (const auto& [n, pi] : want)
    if (!seen.count(n))
      errs.push_back(file.filename().string() + ": no row for " + std::string(what) + " " +
                                              std::to_string(n) + " (" + std::string(pi->name) + ")");
}

void check_vectors(Errors& errs, const fs::path& file, const tmcl::Profile& p, const std::vector<Row>& rows) {
  std::set<int> seen;
  for (const Row& r : rows) {
    check_row(errs, where(file, r), r, false);
    static const std::regex key(R"(^\d+$)");
    if (!std::regex_match(r.key, key)) {
      errs.push_back(where(file, r) + ": a vector row's key is its number, not '" + r.key + "'");
      continue;
    }
    const int n = std::stoi(r.key);
    if (!seen.insert(n).second) errs.push_back(where(file, r) + ": a second row " + r.key);
    const tmcl::InterruptVector* v = n < 256 ? p.vector(n) : nullptr;
    if (!v) {
      errs.push_back(where(file, r) + ": the profile has no vector " + r.key);
      continue;
    }
    if (r.name != v->name)
      errs.push_back(where(file, r) + ": vector " + r.key + " is " + std::string(v->name) + ", the row says '" + r.name + "'");
    // vm/interrupts.cpp's table is the one source of the vectors a run never raises (E52).
    const bool never = !tmcl::not_simulated_reason(p, tmcl::make_profile_motion_core(p)->name(), n).empty();
    if (n != tmcl::kVectorGlobal && never != (r.status == "not simulated"))
      errs.push_back(where(file, r) + ": vector " + r.key + (never ? " is never raised (not_simulated_reason), the row says '"
                                                                   : " is raised, the row says '") + r.status + "'");
  }
  for (const tmcl::InterruptVector& v : p.vectors)
    if (!seen.count(v.number))
      errs.push_back(file.filename().string() + ": no row for vector " + std::to_string(v.number));
}

// Each message a failed check of the test.
void report(const Errors& errs) {
  for (const std::string& e : errs) tmcl_test::fail(__FILE__, __LINE__, e);
}

// The messages of one table against its profile.
Errors check_table(const fs::path& file, const tmcl::Profile& p) {
  Errors errs;
  const Table t = conformance::table_of(p, file);
  for (const std::string& e : t.errors) errs.push_back(e);
  auto rows = [&](Section s) {
    auto it = t.rows.find(s);
    return it == t.rows.end() ? std::vector<Row>{} : it->second;
  };
  check_commands(errs, file, p, rows(Section::Commands));
  check_params(errs, file, "axis parameter", p.axis_params, rows(Section::Axis));
  check_params(errs, file, "global parameter (bank 0)", p.bank0, rows(Section::Bank0));
  check_params(errs, file, "global parameter (bank 3)", p.bank3, rows(Section::Bank3));
  check_vectors(errs, file, p, rows(Section::Vectors));
  return errs;
}

}  // namespace

TEST(every_bundled_module_has_a_table_and_every_table_a_module) {
  Errors errs;
  const fs::path dir = kRoot / "docs" / "conformance";
  CHECK(fs::exists(dir / "README.md"));
  for (const tmcl::Profile* p : modules())
    if (!fs::exists(dir / (std::string(p->name) + ".md")))
      errs.push_back("no docs/conformance/" + std::string(p->name) + ".md for the bundled profile " + std::string(p->name) +
                     " (docs/conformance/README.md)");
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string f = e.path().filename().string();
    if (f == "README.md") continue;
    const tmcl::Profile* p = tmcl::find_profile(e.path().stem().string());
    if (e.path().extension() != ".md" || !p || p->any_parameter || p->name != e.path().stem().string())
      errs.push_back("docs/conformance/" + f + " is no bundled module's table");
  }
  report(errs);
}

TEST(every_table_matches_its_profile_row_by_row) {
  for (const tmcl::Profile* p : modules()) {
    const fs::path file = conformance::table_file(*p);
    if (fs::exists(file)) report(check_table(file, *p));  // a missing one: the test above
  }
}

// The checker itself: a table with one mistake of each kind gets a message for each.
TEST(the_checker_finds_each_kind_of_mistake) {
  const tmcl::Profile* p = tmcl::find_profile("tmc2300-eval");
  CHECK(p != nullptr);
  if (!p) return;
  const fs::path tmp = fs::temp_directory_path() / "tmcl_conformance_selftest.md";
  {
    std::ofstream out(tmp, std::ios::binary);  // "\n", also on Windows
    out << "## Commands\n| # | Command | Status | At run time | Tests |\n|---|---|---|---|---|\n"
        << "| 1 | ROR | simulated | turns | |\n"
        << "| 2 | ROR | simulated | turns | `no_such_test_anywhere` |\n"
        << "| 37 | VECT | simulated | x | `calc_every_operation` |\n"
        << "| 3 | MST | bogus | x | |\n"
        << "| 4 | MVP | stored | x |\n"
        << "## Axis parameters\n| 9999 | Nothing | stored | x | |\n"
        << "| 4 | Top speed | stored | x | |\n"
        << "| 5 | Maximum acceleration | not simulated | | |\n"
        << "| 29 | Measured speed | stored | reads what was written | |\n"
        << "## Interrupt vectors\n| 0 | TI_TIMER0 | simulated | x | `calc_every_operation` |\n";
  }
  const Errors errs = check_table(tmp, *p);
  fs::remove(tmp);
  auto says = [&](const std::string& text) {
    const bool found = std::any_of(errs.begin(), errs.end(), [&](const std::string& e) { return e.find(text) != std::string::npos; });
    if (!found) tmcl_test::fail(__FILE__, __LINE__, "no message saying '" + text + "'");
  };
  says(":4: a simulated row names the tests that pin it");
  says(":5: command 2 is ROL, the row says 'ROR'");
  says(":5: no test 'no_such_test_anywhere' in tests/");
  says(":6: the profile lacks command 37");
  says(":7: unknown status 'bogus'");
  says(":8: a row has 5 cells, this one 4");
  says("no row for command 5");
  says(":10: the profile has no axis parameter 9999");
  says(":11: axis parameter 4 is 'Maximum positioning speed' in the profile, 'Top speed' here");
  says(":12: a not simulated row says what and why");
  says(":12: a not simulated row, but the profile's axis parameter 5 has no not-simulated=\"REASON\"");
  says(":13: the profile marks axis parameter 29 not-simulated, the row says 'stored'");
  says(":13: the row does not say the profile's reason 'reads 0 while the motor turns");
  says("no row for axis parameter 0 (Target position)");
  says(":15: the profile has no vector 0");
  // A real table passes.
  CHECK(check_table(kRoot / "docs" / "conformance" / "tmc2300-eval.md", *p).empty());
}

// A vector row disagreeing with vm/interrupts.cpp's table either way gets a message.
TEST(the_checker_holds_vector_rows_to_the_not_simulated_table) {
  const tmcl::Profile* p = tmcl::find_profile("tmcm-1110");
  CHECK(p != nullptr);
  if (!p) return;
  std::string text = tmcl_test::read_text((kRoot / "docs" / "conformance" / "tmcm-1110.md").string());
  auto swap = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    CHECK(at != std::string::npos);
    if (at != std::string::npos) text.replace(at, from.size(), to);
  };
  swap("| 0 | TI_TIMER0 | simulated |", "| 0 | TI_TIMER0 | not simulated |");
  swap("| 43 | TI_INPUT4 | not simulated |", "| 43 | TI_INPUT4 | simulated |");
  const fs::path tmp = fs::temp_directory_path() / "tmcl_conformance_vectors_selftest.md";
  std::ofstream(tmp, std::ios::binary) << text;
  const Errors errs = check_table(tmp, *p);
  fs::remove(tmp);
  auto says = [&](const std::string& what) {
    if (std::none_of(errs.begin(), errs.end(), [&](const std::string& e) { return e.find(what) != std::string::npos; }))
      tmcl_test::fail(__FILE__, __LINE__, "no message saying '" + what + "'");
  };
  says("vector 0 is raised, the row says 'not simulated'");
  says("vector 43 is never raised (not_simulated_reason), the row says 'simulated'");
}

// `Based on [NAME.md](NAME.md)`: a table takes the base's rows, its own replace the base's of the
// same key, and an inherited row of a parameter the module lacks is dropped (the base module's).
TEST(a_table_based_on_another_takes_its_rows_and_replaces_its_own) {
  const tmcl::Profile* p = tmcl::find_profile("tmc2300-eval");
  CHECK(p != nullptr);
  if (!p) return;
  const fs::path dir = fs::temp_directory_path() / "tmcl_conformance_based_on";
  fs::create_directories(dir);
  std::string base = tmcl_test::read_text((kRoot / "docs" / "conformance" / "tmc2300-eval.md").string());
  const auto axis = base.find("## Axis parameters");
  CHECK(axis != std::string::npos);
  const auto rule = base.find("|---", axis);
  base.insert(base.find('\n', rule) + 1, "| 9999 | Not on this module | stored | x | |\n");
  std::ofstream(dir / "base.md", std::ios::binary) << base;
  std::ofstream(dir / "derived.md", std::ios::binary)
      << "# Derived\n\nBased on [base.md](base.md), but for the rows below.\n\n## Axis parameters\n\n"
      << "| # | Name | Status | At run time | Tests |\n|---|---|---|---|---|\n| 4 | Top speed | stored | x | |\n";
  std::ofstream(dir / "orphan.md", std::ios::binary) << "Based on [none.md](none.md)\n";
  const Errors errs = check_table(dir / "derived.md", *p);
  const Errors orphan = check_table(dir / "orphan.md", *p);
  const Table t = conformance::table_of(*p, dir / "derived.md");
  fs::remove_all(dir);
  CHECK(errs.size() == 1);
  for (const std::string& e : errs) CHECK(e.find("derived.md:9: axis parameter 4 is") != std::string::npos);
  std::size_t inherited = 0;
  for (const auto& [sec, rows] : t.rows)
    for (const Row& r : rows) inherited += r.from == "base.md";
  CHECK(inherited > 20);
  CHECK(!orphan.empty() && orphan.front().find("orphan.md:1: no table none.md to be based on") != std::string::npos);
}
