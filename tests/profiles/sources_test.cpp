// Every bundled TMCM profile against its sources, as copied into tests/data/modules/ (each file
// names its source on its first lines): the manuals' tables (number and access), the vendor's ROS
// driver and host library (the numbers newer firmware has). A profile has every parameter its
// sources list, and no parameter no source lists unless it says `unverified=exists`; its access is
// the manual's but for the corrections docs/errata.md explains. Also: every fact of a bundled
// profile names its source or says it is unverified, and docs/profiles.md lists every unverified
// fact of every module.
#include "check.hpp"
#include "data_file.hpp"

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
  std::string access;  // manuals only
};

std::vector<Row> rows(const std::string& file) {
  std::vector<Row> out;
  for (const std::string& line : DATA_LINES("modules/" + file)) {
    const auto f = tmcl_test::tsv_fields(line);
    if (f.size() < 2) {
      ::tmcl_test::fail(__FILE__, __LINE__, file + ": a row is KIND NUMBER [ACCESS]: " + line);
      continue;
    }
    out.push_back({f[0], std::stoi(f[1]), f.size() > 2 ? f[2] : ""});
  }
  return out;
}

const ParamInfo* param(const Profile& p, const Row& r) {
  if (r.kind == "axis") return p.axis_param(r.number);
  if (r.kind == "global0") return p.global_param(0, r.number);
  if (r.kind == "global3") return p.global_param(3, r.number);
  return nullptr;
}

struct Module {
  const char* name;
  std::vector<std::string> sources;  // files in tests/data/modules/
  const char* manual;                // the one of them that is the module's own manual, or nullptr
};

const Module kModules[] = {
    {"tmcm-1110", {"TMCM-1110-manual.tsv", "TMCM-1110-pytrinamic.tsv"}, "TMCM-1110-manual.tsv"},
    {"tmcm-3110", {"TMCM-3110-ros.tsv", "TMCM-3110-pytrinamic.tsv"}, nullptr},
    {"tmcm-6110", {"TMCM-6110-ros.tsv", "TMCM-6110-pytrinamic.tsv"}, nullptr},
    {"tmcm-1140", {"TMCM-1140-ros.tsv", "TMCM-1140-pytrinamic.tsv"}, nullptr},
    {"tmcm-1160", {"TMCM-1160-ros.tsv", "TMCM-1160-pytrinamic.tsv"}, nullptr},
    {"tmcm-1161", {"TMCM-1161-pytrinamic.tsv"}, nullptr},
    {"tmcm-1260", {"PD57-60-1260-manual.tsv", "TMCM-1260-ros.tsv", "TMCM-1260-pytrinamic.tsv"}, "PD57-60-1260-manual.tsv"},
    {"tmcm-351", {"TMCM-351-manual.tsv", "TMCM-351-ros.tsv"}, "TMCM-351-manual.tsv"},
};

// The manuals' access letters in our terms: in a TMCM manual's bank 0 table, E on 64..127 means
// "stored at every SGP" (the text of section 6.1 / 5.1), our A. And the corrections of the manual
// (docs/errata.md): a measurement the table calls RW is R.
std::string expected_access(const char* module, const Row& r) {
  std::string a = r.access;
  if (r.kind == "global0" && r.number >= 64 && r.number < 128 && a == "RWE") a = "RWA";
  const std::string m = module;
  if (r.kind == "axis" && r.number == 3 && (m == "tmcm-1110" || m == "tmcm-351")) a = "R";
  if (r.kind == "axis" && r.number == 180 && m == "tmcm-1110") a = "R";
  return a;
}

}  // namespace

TEST(every_parameter_of_the_sources_is_in_the_profile) {
  for (const Module& m : kModules) {
    const Profile* p = tmcl::find_profile(m.name);
    CHECK(p != nullptr);
    if (!p) continue;
    std::set<std::pair<std::string, int>> listed;
    for (const std::string& file : m.sources) {
      for (const Row& r : rows(file)) {
        listed.insert({r.kind, r.number});
        const ParamInfo* info = param(*p, r);
        if (!info) {
          ::tmcl_test::fail(__FILE__, __LINE__, std::string(m.name) + " lacks " + r.kind + " " + std::to_string(r.number) + " of " + file);
          continue;
        }
        if (m.manual && file == m.manual && tmcl::access_letters(info->access) != expected_access(m.name, r))
          ::tmcl_test::fail(__FILE__, __LINE__, std::string(m.name) + " " + r.kind + " " + std::to_string(r.number) + ": access " +
                                                    tmcl::access_letters(info->access) + ", the manual " + r.access);
        if (m.manual && file == m.manual && (info->unverified & (tmcl::kFactAccess | tmcl::kFactExists)))
          ::tmcl_test::fail(__FILE__, __LINE__, std::string(m.name) + " " + r.kind + " " + std::to_string(r.number) +
                                                    ": the manual gives it, yet it is marked unverified");
      }
    }
    // Conversely: what no source lists is marked so.
    auto check_table = [&](const char* kind, std::span<const ParamInfo> table) {
      for (const ParamInfo& info : table)
        if (!listed.count({kind, info.number}) && !(info.unverified & tmcl::kFactExists))
          ::tmcl_test::fail(__FILE__, __LINE__, std::string(m.name) + " " + kind + " " + std::to_string(info.number) +
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

bool cites(const ParamInfo& info, const std::string& id, const std::string& section) {
  const std::string src = "," + std::string(info.source) + ",";
  return src.find("," + id + ":" + section + ",") != std::string::npos;
}

}  // namespace

TEST(the_tmcl_reference_confirms_or_leaves_unverified) {
  const std::vector<RefRow> ref = reference_rows();
  CHECK(ref.size() > 100u);
  for (const char* name : {"tmcm-3110", "tmcm-6110", "tmcm-1140", "tmcm-1160", "tmcm-1161"}) {
    const Profile* p = tmcl::find_profile(name);
    CHECK(p != nullptr);
    if (!p) continue;
    CHECK_EQ(reference_id(*p), "R");
    int confirmed = 0;
    for (const RefRow& r : ref) {
      if (r.scope != "all") continue;
      const ParamInfo* info = param(*p, Row{r.kind, r.number, ""});
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
    CHECK(confirmed >= 25);  // the basic and advanced parameters and the interface settings
  }
  // Every TMCM profile: a fact sourced from the reference, and not marked unverified, is its row's.
  for (const Module& m : kModules) {
    const Profile* p = tmcl::find_profile(m.name);
    if (!p) continue;
    const std::string id = reference_id(*p);
    if (id.empty()) continue;
    for (const RefRow& r : ref) {
      const ParamInfo* info = param(*p, Row{r.kind, r.number, ""});
      if (!info || std::string(info->source).find(id + ":") == std::string::npos) continue;
      const std::string what = std::string(m.name) + " " + r.kind + " " + std::to_string(r.number);
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
    if (it == documented.end()) {
      ::tmcl_test::fail(__FILE__, __LINE__, "docs/profiles.md has no ```unverified " + std::string(p->name) + " block");
      continue;
    }
    if (it->second != facts) {
      std::string want;
      for (const auto& f : facts) want += f + "\n";
      ::tmcl_test::fail(__FILE__, __LINE__, "docs/profiles.md: the unverified facts of " + std::string(p->name) + " are:\n" + want);
    }
  }
  for (const auto& [name, facts] : documented)
    if (!tmcl::find_profile(name)) ::tmcl_test::fail(__FILE__, __LINE__, "docs/profiles.md lists unverified facts of an unknown module " + name);
}
