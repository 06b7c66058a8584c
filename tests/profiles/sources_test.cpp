// Every bundled profile (but generic) against its sources, as copied into tests/data/modules/ (each file
// names its source on its first lines): the manuals' tables (number and access), the vendor's ROS
// driver and host library (the numbers newer firmware has). A profile has every parameter its
// sources list, and no parameter no source lists unless it says `unverified=exists`; its access is
// the manual's but for the corrections docs/errata.md explains. Also: every fact of a bundled
// profile names its source or says it is unverified, and docs/profiles.md lists every unverified
// fact of every module.
#include "check.hpp"
#include "data_file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "tmcl/profile.hpp"

namespace {

using tmcl::ParamInfo;
using tmcl::Profile;

struct Row {
  std::string kind;  // axis, global0, global3
  int number = 0;
  std::string access;     // manuals only: as the table prints it ("" where no table has it)
  std::string corrected;  // our access where docs/errata.md corrects the manual, else ""
};

std::vector<Row> rows(const std::string& file) {
  std::vector<Row> out;
  for (const std::string& line : DATA_LINES("modules/" + file)) {
    const auto f = tmcl_test::tsv_fields(line);
    if (f.size() < 2 || f.size() == 4) {
      ::tmcl_test::fail(__FILE__, __LINE__, file + ": a row is KIND NUMBER [ACCESS [OURS ERRATUM [WHERE]]]: " + line);
      continue;
    }
    out.push_back({f[0], std::stoi(f[1]), f.size() > 2 && f[2] != "-" ? f[2] : "", f.size() > 3 ? f[3] : ""});
  }
  return out;
}

const ParamInfo* param(const Profile& p, const Row& r) {
  if (r.kind == "axis") return p.axis_param(r.number);
  if (r.kind == "global0") return p.global_param(0, r.number);
  if (r.kind == "global3") return p.global_param(3, r.number);
  return nullptr;
}

// A bundled profile's source table: the files tests/data/modules/NAME-*.tsv, NAME its name in
// capitals (TMCM-1110-manual.tsv, TMCM-1110-pytrinamic.tsv for tmcm-1110); NAME-manual.tsv is the
// module's own manual. Found by name, so a new profile is checked as soon as its files are there,
// and a profile without them fails (sources_of) instead of passing unchecked.
struct Module {
  std::string name;
  std::vector<std::string> sources;  // files in tests/data/modules/
  std::string manual;                // the one of them that is the module's own manual, or ""
};

std::string capitals(std::string_view name) {
  std::string out(name);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

Module sources_of(const Profile& p) {
  Module m{std::string(p.name), {}, ""};
  const std::string prefix = capitals(p.name) + "-";
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(tmcl_test::data_path("modules"), ec)) {
    const std::string file = entry.path().filename().string();
    if (file.rfind(prefix, 0) != 0 || file.size() < 4 || file.substr(file.size() - 4) != ".tsv") continue;
    m.sources.push_back(file);
    if (file == prefix + "manual.tsv") m.manual = file;
  }
  std::sort(m.sources.begin(), m.sources.end());
  return m;
}

// Every bundled profile but generic (made up by design: it is no module, docs/profiles.md).
std::vector<Module> bundled_modules() {
  std::vector<Module> out;
  for (const Profile* p : tmcl::all_profiles())
    if (p->name != "generic") out.push_back(sources_of(*p));
  return out;
}

// The manuals' access letters in our terms: in a TMCM manual's bank 0 table, E on 64..127 means
// "stored at every SGP" (the text of section 6.1 / 5.1), our A. A row's own correction (a fourth
// field, with its docs/errata.md entry) wins.
std::string expected_access(const Row& r) {
  if (!r.corrected.empty()) return r.corrected;
  std::string a = r.access;
  if (r.kind == "global0" && r.number >= 64 && r.number < 128 && a == "RWE") a = "RWA";
  return a;
}

}  // namespace

TEST(every_bundled_module_has_a_source_table) {
  CHECK(bundled_modules().size() + 1 == tmcl::all_profiles().size());
  for (const Module& m : bundled_modules())
    if (m.sources.empty())
      ::tmcl_test::fail(__FILE__, __LINE__, m.name + ": no source table: tests/data/modules/" + capitals(m.name) +
                                                "-*.tsv (its manual's parameter tables, KIND NUMBER ACCESS, as " +
                                                "TMCM-1110-manual.tsv)");
}

TEST(every_parameter_of_the_sources_is_in_the_profile) {
  for (const Module& m : bundled_modules()) {
    const Profile* p = tmcl::find_profile(m.name);
    CHECK(p != nullptr);
    if (!p || m.sources.empty()) continue;
    std::set<std::pair<std::string, int>> listed;
    for (const std::string& file : m.sources) {
      for (const Row& r : rows(file)) {
        listed.insert({r.kind, r.number});
        const ParamInfo* info = param(*p, r);
        if (!info) {
          ::tmcl_test::fail(__FILE__, __LINE__, m.name + " lacks " + r.kind + " " + std::to_string(r.number) + " of " + file);
          continue;
        }
        if (file == m.manual && !expected_access(r).empty() && tmcl::access_letters(info->access) != expected_access(r))
          ::tmcl_test::fail(__FILE__, __LINE__, m.name + " " + r.kind + " " + std::to_string(r.number) + ": access " +
                                                    tmcl::access_letters(info->access) + ", the manual " + r.access);
        if (file == m.manual && (info->unverified & (tmcl::kFactAccess | tmcl::kFactExists)))
          ::tmcl_test::fail(__FILE__, __LINE__, m.name + " " + r.kind + " " + std::to_string(r.number) +
                                                    ": the manual gives it, yet it is marked unverified");
      }
    }
    // Conversely: what no source lists is marked so.
    auto check_table = [&](const char* kind, std::span<const ParamInfo> table) {
      for (const ParamInfo& info : table)
        if (!listed.count({kind, info.number}) && !(info.unverified & tmcl::kFactExists))
          ::tmcl_test::fail(__FILE__, __LINE__, m.name + " " + kind + " " + std::to_string(info.number) +
                                                    ": in no source and not marked unverified=exists");
    };
    check_table("axis", p->axis_params);
    check_table("global0", p->bank0);
    check_table("global3", p->bank3);
  }
}

TEST(the_manuals_own_facts_of_each_module) {
  const Profile* a = tmcl::find_profile("tmcm-1110");
  const Profile* b = tmcl::find_profile("tmcm-351");
  const Profile* c = tmcl::find_profile("tmcm-1260");
  CHECK(a && b && c);
  if (!a || !b || !c) return;
  // Program memory and where it is kept, user variables, coordinates, motors, firmware.
  CHECK_EQ(a->program_memory, 2048);
  CHECK(a->program_store == tmcl::ProgramStore::Eeprom);
  CHECK_EQ(a->eeprom_user_vars, 56);
  CHECK_EQ(a->coords, 21);
  CHECK_EQ(a->motors, 3);
  CHECK_EQ(a->firmware, "1110V103");
  CHECK_EQ(b->motors, 3);
  CHECK_EQ(c->motors, 1);
  CHECK(!c->has_command(7) && !c->has_command(8));  // no STAP/RSAP on the PD-1260
  CHECK(a->has_command(13) && b->has_command(13) && c->has_command(13));  // RFS
  // The TMC429's units: ±2047, divisors 0..13, and the clock of section 5.5.
  CHECK_EQ(a->axis_param(4)->max, 2047);
  CHECK_EQ(a->axis_param(154)->max, 13);
  CHECK_EQ(a->motion_constant("clock", 0), 16000000);
  CHECK_EQ(a->default_motion, "tmc429");
  CHECK_EQ(c->axis_param(4)->max, 7999774);  // pps
  CHECK_EQ(c->axis_param(4)->unit, "pps");
  // Reference search parameters with their ranges (the motion issue's RFS needs them).
  for (const Profile* p : {a, b, c})
    for (int n : {193, 194, 195, 196}) CHECK(p->axis_param(n) != nullptr);
  CHECK_EQ(a->axis_param(193)->min, 1);
  CHECK_EQ(b->axis_param(193)->max, 3);
  // Interrupt vectors of the manuals' tables.
  for (int v : {0, 1, 2, 3, 4, 5, 15, 21, 27, 28, 29, 30, 31, 32, 39, 40, 41, 42, 255}) CHECK(a->vector(v) != nullptr);
  for (int v : {16, 17, 22, 23, 43, 44, 45, 46}) CHECK(b->vector(v) != nullptr);
  for (int v : {0, 1, 2, 3, 15, 21, 27, 28, 39, 40, 41, 255}) CHECK(c->vector(v) != nullptr);
  CHECK(c->vector(4) == nullptr);
}

// The TMCL reference's tables (tests/data/modules/TMCL-reference-2.22.tsv: sections 4.1, 4.2 and
// 5.1, for every TMCL stepper module) against the five profiles without a manual of their own,
// fact by fact. A row for every module (scope `all`) that gives the profile's access or range
// confirms it: the profile names the reference's section and does not mark the fact unverified. A
// row that gives another access or range (older firmware) leaves the fact unverified (docs/errata.md
// M15). And in every TMCM profile a fact that names the reference as its source is the reference's,
// and unverified where the row is for other modules only.
namespace {

struct RefRow {
  std::string kind;  // axis, global0
  int number = 0;
  std::string access;  // "" where the table gives none
  bool has_range = false;
  std::int64_t min = 0, max = 0;
  std::string scope, section;  // all/only/reserved; 4.1, 4.2, 5.1
};

std::vector<RefRow> reference_rows() {
  std::vector<RefRow> out;
  for (const std::string& line : DATA_LINES("modules/TMCL-reference-2.22.tsv")) {
    const auto f = tmcl_test::tsv_fields(line);
    if (f.size() < 7) {
      ::tmcl_test::fail(__FILE__, __LINE__, "TMCL-reference-2.22.tsv: a row is KIND NUMBER ACCESS MIN MAX SCOPE SECTION [NOTE]: " + line);
      continue;
    }
    RefRow r{f[0], std::stoi(f[1]), f[2] == "-" ? "" : f[2], f[3] != "-", 0, 0, f[5], f[6]};
    if (r.has_range) r.min = std::stoll(f[3]), r.max = std::stoll(f[4]);
    // In our letters: E on 64 ... 127 of bank 0 is "stored at every SGP" (section 5.1; errata M1).
    if (r.kind == "global0" && r.number >= 64 && r.number < 128 && r.access == "RWE") r.access = "RWA";
    out.push_back(r);
  }
  return out;
}

// The source ID a profile gives the TMCL reference ("R"), or "" when it names it not.
std::string reference_id(const Profile& p) {
  std::istringstream in{std::string(p.text)};
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string key, id, rest;
    if (words >> key >> id && key == "source" && std::getline(words, rest) && rest.find("\"TMCL reference") != std::string::npos) return id;
  }
  return "";
}

// The profile a module's is `based-on`, when that one has a manual of its own: the module then
// rests on its family's manual (TMCM-3216 on the TMCM-1290's), not on the TMCL reference.
bool rests_on_family_manual(const Profile& p) {
  std::istringstream in{std::string(p.text)};
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line.substr(0, line.find('#')));
    std::string key, base;
    if (words >> key >> base && key == "based-on") {
      const Profile* b = tmcl::find_profile(base);
      return b && !sources_of(*b).manual.empty();
    }
  }
  return false;
}

bool cites(const ParamInfo& info, const std::string& id, const std::string& section) {
  const std::string src = "," + std::string(info.source) + ",";
  return src.find("," + id + ":" + section + ",") != std::string::npos;
}

}  // namespace

TEST(the_tmcl_reference_confirms_or_leaves_unverified) {
  const std::vector<RefRow> ref = reference_rows();
  CHECK(ref.size() > 100u);
  int without_manual = 0;
  for (const Module& m : bundled_modules()) {
    if (!m.manual.empty()) continue;  // a module without a manual of its own rests on the reference
    if (rests_on_family_manual(*tmcl::find_profile(m.name))) continue;
    ++without_manual;
    const std::string& name = m.name;
    const Profile* p = tmcl::find_profile(name);
    CHECK(p != nullptr);
    if (!p) continue;
    if (reference_id(*p) != "R") ::tmcl_test::fail(__FILE__, __LINE__, name + ": no manual of its own in its source table, and it names not the TMCL reference as source R");
    int confirmed = 0;
    for (const RefRow& r : ref) {
      if (r.scope != "all") continue;
      const ParamInfo* info = param(*p, Row{r.kind, r.number, "", ""});
      if (!info) continue;  // the reference lists parameters of other modules and older firmware too
      const std::string what = std::string(name) + " " + r.kind + " " + std::to_string(r.number);
      bool any = false;
      if (!r.access.empty()) {
        const bool same = tmcl::access_letters(info->access) == r.access;
        const bool marked = (info->unverified & tmcl::kFactAccess) != 0;
        if (same && marked) ::tmcl_test::fail(__FILE__, __LINE__, what + ": the reference (" + r.section + ") confirms access " + r.access + ", yet it is marked unverified");
        if (!same && !marked) ::tmcl_test::fail(__FILE__, __LINE__, what + ": access " + tmcl::access_letters(info->access) + ", the reference " + r.access + ", and it is not marked unverified");
        any = any || same;
      }
      if (r.has_range) {
        const bool same = info->min == r.min && info->max == r.max;
        const bool marked = (info->unverified & tmcl::kFactRange) != 0;
        const std::string range = std::to_string(r.min) + ".." + std::to_string(r.max);
        if (same && marked) ::tmcl_test::fail(__FILE__, __LINE__, what + ": the reference (" + r.section + ") confirms range " + range + ", yet it is marked unverified");
        if (!same && !marked) ::tmcl_test::fail(__FILE__, __LINE__, what + ": range " + std::to_string(info->min) + ".." + std::to_string(info->max) + ", the reference " + range + ", and it is not marked unverified");
        any = any || same;
      }
      if (any && !cites(*info, "R", r.section)) ::tmcl_test::fail(__FILE__, __LINE__, what + ": the reference confirms it, but src= does not name R:" + r.section);
      confirmed += any;
    }
    // The basic and advanced parameters and the interface settings; fewer on a module in pps (the
    // TMC5160 family: its speeds and accelerations are not the reference's TMC429 units) and fewer
    // again on one without RS485 (the TMCM-1276 family: 20).
    if (confirmed < 20) ::tmcl_test::fail(__FILE__, __LINE__, name + ": only " + std::to_string(confirmed) + " facts confirmed by the reference");
  }
  CHECK(without_manual >= 5);  // tmcm-3110, -6110, -1140, -1160, -1161
  // Every TMCM profile: a fact sourced from the reference, and not marked unverified, is its row's.
  for (const Module& m : bundled_modules()) {
    const Profile* p = tmcl::find_profile(m.name);
    if (!p) continue;
    const std::string id = reference_id(*p);
    if (id.empty()) continue;
    for (const RefRow& r : ref) {
      const ParamInfo* info = param(*p, Row{r.kind, r.number, "", ""});
      if (!info || std::string(info->source).find(id + ":") == std::string::npos) continue;
      const std::string what = m.name + " " + r.kind + " " + std::to_string(r.number);
      const bool any_section = std::string("," + std::string(info->source)).find("," + id + ":4.") != std::string::npos ||
                               std::string("," + std::string(info->source)).find("," + id + ":5.") != std::string::npos;
      if (any_section && !cites(*info, id, r.section)) ::tmcl_test::fail(__FILE__, __LINE__, what + ": the reference has it in section " + r.section + ", not where src= says: " + std::string(info->source));
      if (!(info->unverified & tmcl::kFactAccess) && !r.access.empty() && tmcl::access_letters(info->access) != r.access)
        ::tmcl_test::fail(__FILE__, __LINE__, what + ": access " + tmcl::access_letters(info->access) + " from the reference, which says " + r.access);
      if (!(info->unverified & tmcl::kFactRange) && r.has_range && (info->min != r.min || info->max != r.max))
        ::tmcl_test::fail(__FILE__, __LINE__, what + ": a range from the reference, which says " + std::to_string(r.min) + ".." + std::to_string(r.max));
      // A row that names the only modules it is for confirms nothing for these (M15: 213).
      if (r.scope == "only" && ((!r.access.empty() && !(info->unverified & tmcl::kFactAccess)) ||
                                (r.has_range && !(info->unverified & tmcl::kFactRange))))
        ::tmcl_test::fail(__FILE__, __LINE__, what + ": the reference's row is for other modules only, so what it gives is unverified here");
    }
  }
}

// Every statement of a bundled profile that states a fact names its source (src=) or says it is
// unverified.
TEST(every_fact_names_its_source) {
  // include-file names a file of ours, not a fact of the module.
  static const std::set<std::string> kNoFact = {"tmcl-profile", "name",       "alias",       "title",
                                                "source",       "based-on",   "parameters",  "include-file"};
  for (const Profile* p : tmcl::all_profiles()) {
    if (p->name == "generic") continue;  // made up by design: it is no module (docs/profiles.md)
    std::istringstream in{std::string(p->text)};
    std::string line;
    int n = 0;
    while (std::getline(in, line)) {
      ++n;
      const std::string code = line.substr(0, line.find('#'));
      std::istringstream words(code);
      std::string key;
      if (!(words >> key) || kNoFact.count(key)) continue;
      if (code.find(" src=") == std::string::npos && code.find(" unverified") == std::string::npos)
        ::tmcl_test::fail(__FILE__, __LINE__, std::string(p->name) + ".profile:" + std::to_string(n) + ": no source: " + line);
    }
  }
}

// docs/profiles.md lists every unverified fact, per module, in a block
//   ```unverified NAME
//   one fact a line (as Profile::unverified words them)
//   ```
// and no other.
TEST(docs_list_every_unverified_fact) {
  std::ifstream in(std::string(TMCL_DOCS_DIR) + "/profiles.md");
  CHECK(in.good());
  std::map<std::string, std::vector<std::string>> documented;
  std::string line, module;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!inside && line.rfind("```unverified ", 0) == 0) {
      module = line.substr(14);
      inside = true;
      documented[module];
    } else if (inside && line == "```") {
      inside = false;
    } else if (inside) {
      documented[module].push_back(line);
    }
  }
  for (const Profile* p : tmcl::all_profiles()) {
    const std::vector<std::string> facts(p->unverified.begin(), p->unverified.end());
    const auto it = documented.find(std::string(p->name));
    if (facts.empty()) {
      if (it != documented.end()) ::tmcl_test::fail(__FILE__, __LINE__, "docs/profiles.md lists unverified facts of " + std::string(p->name) + ", which has none");
      continue;
    }
    std::string want;  // the block to paste
    for (const auto& f : facts) want += f + "\n";
    if (it == documented.end()) {
      ::tmcl_test::fail(__FILE__, __LINE__, "docs/profiles.md has no ```unverified " + std::string(p->name) + " block; it is:\n```unverified " +
                                                std::string(p->name) + "\n" + want + "```");
      continue;
    }
    if (it->second != facts)
      ::tmcl_test::fail(__FILE__, __LINE__, "docs/profiles.md: the unverified facts of " + std::string(p->name) + " are:\n" + want);
  }
  for (const auto& [name, facts] : documented)
    if (!tmcl::find_profile(name)) ::tmcl_test::fail(__FILE__, __LINE__, "docs/profiles.md lists unverified facts of an unknown module " + name);
}
