// Unit tests of the module profiles and of the bundled include files: facts from the two
// manuals, consistency of every table, and agreement of the include files with the tables and
// with TMCL-IDE's list of TMCLParam.tmc names.
#include "check.hpp"
#include "data_file.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tmcl/isa.hpp"
#include "tmcl/param_names.hpp"
#include "tmcl/profile.hpp"

namespace {

using tmcl::kAutoStore;
using tmcl::kEeprom;
using tmcl::kRead;
using tmcl::kWrite;
using tmcl::ParamInfo;
using tmcl::Profile;

const Profile& usb() { return *tmcl::find_profile("usb-2-sd"); }
const Profile& eval() { return *tmcl::find_profile("tmc2300-eval"); }
const Profile& generic() { return tmcl::generic_profile(); }

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

struct Def {
  std::string name;
  long long value;
  int line;
};

// Reads a bundled include file. Every line must be empty, a // comment, or `Name = integer`
// with an optional trailing comment; anything else fails the calling test.
std::vector<Def> parse_include(const std::string& file, std::istream& in) {
  std::vector<Def> defs;
  std::string raw;
  int line = 0;
  while (std::getline(in, raw)) {
    ++line;
    if (const auto c = raw.find("//"); c != std::string::npos) raw.erase(c);
    const std::string text = trim(raw);
    if (text.empty()) continue;
    const auto eq = text.find('=');
    const std::string name = eq == std::string::npos ? "" : trim(text.substr(0, eq));
    const std::string value = eq == std::string::npos ? "" : trim(text.substr(eq + 1));
    const bool name_ok = !name.empty() && !std::isdigit(static_cast<unsigned char>(name[0])) &&
                         std::all_of(name.begin(), name.end(), [](char ch) {
                           return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
                         });
    std::size_t used = 0;
    long long v = 0;
    bool value_ok = !value.empty();
    if (value_ok) {
      errno = 0;
      char* end = nullptr;
      v = std::strtoll(value.c_str(), &end, 10);
      used = static_cast<std::size_t>(end - value.c_str());
      value_ok = errno == 0 && used > 0;  // a number, in range
    }
    value_ok = value_ok && used == value.size();
    if (!name_ok || !value_ok) {
      ::tmcl_test::fail(__FILE__, __LINE__, file + ":" + std::to_string(line) + ": not `Name = value`: " + text);
      continue;
    }
    defs.push_back({name, v, line});
  }
  CHECK(!defs.empty());
  return defs;
}

std::vector<Def> read_include(const std::string& file) {
  std::ifstream in(std::string(TMCL_INCLUDE_FILES_DIR) + "/" + file);
  CHECK(in.good());
  return parse_include(file, in);
}

// Upper-cased name -> value; a name defined twice in one file fails the test.
std::map<std::string, long long> as_map(const std::string& file, const std::vector<Def>& defs) {
  std::map<std::string, long long> m;
  for (const auto& d : defs)
    if (!m.emplace(upper(d.name), d.value).second)
      ::tmcl_test::fail(__FILE__, __LINE__, file + ": " + d.name + " defined twice");
  return m;
}

const char* const kIncludeFiles[] = {"TMCLParam.tmc", "Interrupts.inc", "USB-2-SD.inc", "TMC2300-MOTOR-EVAL.inc"};

std::multiset<long long> numbers(std::span<const ParamInfo> table) {
  std::multiset<long long> s;
  for (const auto& p : table) s.insert(p.number);
  return s;
}

// The values of the definitions whose name starts with `prefix` (case-insensitive).
std::multiset<long long> values_with_prefix(const std::vector<Def>& defs, std::string_view prefix) {
  std::multiset<long long> s;
  for (const auto& d : defs)
    if (upper(d.name).rfind(upper(prefix), 0) == 0) s.insert(d.value);
  return s;
}

bool has_write(const ParamInfo* p) { return p != nullptr && (p->access & kWrite) != 0; }

}  // namespace

// ---- The profile registry ------------------------------------------------------------------

// The profile folder's files, generic first, then in name order: what the build bundles
// (vm/isa/embed_files.cmake), so a new file there is a new target with nothing registered by hand.
std::vector<std::string> profile_folder_names() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(TMCL_PROFILES_DIR))
    if (entry.path().extension() == ".profile") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) {
    return (a == "generic") != (b == "generic") ? a == "generic" : a < b;
  });
  return names;
}

TEST(registry_lists_every_bundled_profile_generic_first) {
  const auto all = tmcl::all_profiles();
  std::vector<std::string> names;
  for (const Profile* p : all) names.emplace_back(p->name);
  CHECK(names.size() >= 11u);
  CHECK(names == profile_folder_names());
  CHECK_EQ(all[0], &tmcl::generic_profile());
  CHECK(tmcl::find_profile("usb-2-sd") != nullptr);
  CHECK(tmcl::find_profile("tmc2300-eval") != nullptr);
  CHECK(tmcl::find_profile("generic") == &tmcl::generic_profile());
  CHECK(tmcl::find_profile("USB-2-SD") == nullptr);  // -t names are exact
  CHECK(tmcl::find_profile("tmcm-9999") == nullptr);
  CHECK(tmcl::find_profile("pd60-1260") == tmcl::find_profile("tmcm-1260"));  // an alias
  CHECK(tmcl::find_profile("steprocker") == tmcl::find_profile("tmcm-1110"));
  for (const Profile* p : all) CHECK_EQ(p->origin, "bundled");
}

// ---- USB-2-SD --------------------------------------------------------------------------------

TEST(usb2sd_memory_and_limits) {
  CHECK_EQ(usb().program_memory, 577);
  CHECK_EQ(usb().user_vars, 256);
  CHECK_EQ(usb().eeprom_user_vars, 56);
  CHECK_EQ(usb().coords, 21);
  CHECK_EQ(usb().motors, 1);
  CHECK(!usb().any_parameter);
  CHECK_EQ(usb().default_motion, std::string_view("tmc4361"));
  CHECK_EQ(usb().firmware, std::string_view("0015V114"));
}

TEST(usb2sd_commands) {
  const Profile& p = usb();
  CHECK(p.has_command(80));  // CALL
  CHECK(!p.has_command(7));  // STAP
  CHECK(!p.has_command(8));  // RSAP
  for (int op : {1, 2, 3, 4, 5, 6, 9, 10, 11, 12, 14, 15, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 30, 31,
                 32, 33, 34, 35, 36, 37, 38, 39, 40, 41, 42, 43, 44, 45, 46, 48, 49, 50, 51, 55, 56, 57,
                 64, 65, 66, 67, 68, 69, 70, 71, 80, 128, 129, 130, 131, 132, 133, 134, 135, 136, 137,
                 138, 255})
    if (!p.has_command(static_cast<std::uint8_t>(op)))
      ::tmcl_test::fail(__FILE__, __LINE__, "usb-2-sd lacks opcode " + std::to_string(op));
  // Not in the USB-2-SD manual.
  for (int op : {13, 16, 17, 18, 47, 52, 53, 54, 58, 59, 60, 61, 62, 63})
    if (p.has_command(static_cast<std::uint8_t>(op)))
      ::tmcl_test::fail(__FILE__, __LINE__, "usb-2-sd has opcode " + std::to_string(op));
  CHECK_EQ(p.commands.count(), std::size_t{67});
}

TEST(usb2sd_parameters) {
  const Profile& p = usb();
  CHECK_EQ(p.axis_params.size(), std::size_t{37});
  CHECK_EQ(p.axis_param(4)->max, std::int64_t{16777215});
  CHECK_EQ(p.axis_param(2)->min, std::int64_t{-16777215});
  CHECK_EQ(p.axis_param(18)->max, std::int64_t{16777215});
  CHECK_EQ(p.axis_param(4)->default_value, 51200);
  CHECK_EQ(p.axis_param(5)->default_value, 51200);
  CHECK_EQ(p.axis_param(35)->default_value, 1);
  CHECK_EQ(p.axis_param(35)->min, std::int64_t{1});
  CHECK_EQ(p.axis_param(127)->max, std::int64_t{2});
  CHECK_EQ(p.axis_param(140)->default_value, 8);
  CHECK_EQ(p.axis_param(202)->default_value, 200);
  CHECK_EQ(p.axis_param(255)->default_value, 1);
  CHECK(p.axis_param(201) != nullptr);
  CHECK(p.axis_param(6) == nullptr);  // no current setting on a step/direction generator
  CHECK(p.axis_param(7) == nullptr);
  CHECK(has_write(p.axis_param(29)));
  // Read only.
  for (int n : {3, 8, 131, 132, 207}) CHECK(!has_write(p.axis_param(n)));
  for (int n : {128, 129, 130}) CHECK(!has_write(p.global_param(0, n)));
  // Bank 0 settings from 64 to 127 are stored in EEPROM by SGP itself.
  for (int n : {66, 76, 77, 84, 85, 86}) CHECK((p.global_param(0, n)->access & kAutoStore) != 0);
  CHECK_EQ(p.global_param(0, 66)->default_value, 1);
  CHECK_EQ(p.global_param(0, 76)->default_value, 2);
  CHECK_EQ(p.global_param(0, 85)->default_value, 0);  // user variables are restored
  CHECK_EQ(p.global_param(0, 130)->max, std::int64_t{p.program_memory - 1});
  CHECK((p.global_param(0, 255)->access & kAutoStore) == 0);
  // Bank 3.
  CHECK_EQ(p.bank3.size(), std::size_t{5});
  CHECK_EQ(p.global_param(3, 0)->max, std::int64_t{4294967295LL});
  CHECK_EQ(p.global_param(3, 28)->max, std::int64_t{3});
  CHECK(p.global_param(3, 3) == nullptr);
  CHECK(p.global_param(2, 0) == nullptr);  // user variables are not a table
  CHECK(p.global_param(1, 0) == nullptr);
}

TEST(usb2sd_vectors) {
  const Profile& p = usb();
  const std::pair<int, std::string_view> expect[] = {
      {0, "TI_TIMER0"},      {1, "TI_TIMER1"},  {2, "TI_TIMER2"},  {3, "TI_TARGET0"}, {15, "TI_STALL0"},
      {21, "TI_DEVIATION0"}, {27, "TI_STOPL0"}, {28, "TI_STOPR0"}, {255, "TI_GLOBAL"}};
  CHECK_EQ(p.vectors.size(), std::size(expect));
  for (const auto& [n, name] : expect) {
    const auto* v = p.vector(n);
    CHECK(v != nullptr);
    if (v) CHECK_EQ(v->name, name);
  }
  CHECK(p.vector(4) == nullptr);
}

// ---- TMC2300-MOTOR-EVAL ----------------------------------------------------------------------

TEST(tmc2300_memory_and_limits) {
  const Profile& p = eval();
  CHECK_EQ(p.user_vars, 256);
  CHECK_EQ(p.eeprom_user_vars, 8);
  CHECK_EQ(p.coords, 0);
  CHECK_EQ(p.motors, 1);
  CHECK_EQ(p.program_memory, 2048);
  CHECK(p.vectors.empty());
  CHECK(p.bank3.empty());
  CHECK_EQ(p.default_motion, std::string_view("linear"));
  CHECK_EQ(p.firmware, std::string_view("2300V100"));
}

TEST(tmc2300_commands) {
  const Profile& p = eval();
  CHECK(p.has_command(7));    // STAP
  CHECK(p.has_command(8));    // RSAP
  CHECK(!p.has_command(37));  // VECT
  for (int op : {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 14, 15, 19, 20, 21, 22, 23, 24, 27, 28, 33, 34,
                 35, 36, 64, 65, 66, 67, 68, 69, 70, 71, 128, 129, 130, 131, 132, 133, 134, 135, 136,
                 137, 255})
    if (!p.has_command(static_cast<std::uint8_t>(op)))
      ::tmcl_test::fail(__FILE__, __LINE__, "tmc2300-eval lacks opcode " + std::to_string(op));
  // No interrupts, no coordinates, no newer commands, no 138.
  for (int op : {13, 16, 17, 18, 25, 26, 30, 31, 32, 37, 38, 39, 40, 41, 42, 43, 44, 45, 46, 47, 48, 49,
                 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60, 61, 62, 63, 80, 138})
    if (p.has_command(static_cast<std::uint8_t>(op)))
      ::tmcl_test::fail(__FILE__, __LINE__, "tmc2300-eval has opcode " + std::to_string(op));
  CHECK_EQ(p.commands.count(), std::size_t{45});
}

TEST(tmc2300_parameters) {
  const Profile& p = eval();
  const std::multiset<long long> axis = {0,   1,   2,   3,   4,   5,   6,   7,   8,   29,  100, 140, 141, 162, 168,
                                         169, 170, 171, 172, 174, 180, 181, 182, 187, 191, 192, 204, 206, 220};
  CHECK(numbers(p.axis_params) == axis);
  CHECK(numbers(p.bank0) == (std::multiset<long long>{65, 66, 77, 85, 128, 130, 132}));
  CHECK_EQ(p.axis_param(4)->max, std::int64_t{32767});
  CHECK_EQ(p.axis_param(2)->min, std::int64_t{-32768});
  CHECK_EQ(p.axis_param(6)->max, std::int64_t{31});
  CHECK_EQ(p.axis_param(140)->default_value, 8);
  CHECK_EQ(p.axis_param(140)->max, std::int64_t{8});
  CHECK_EQ(p.global_param(0, 65)->default_value, 0);  // 9600 baud
  for (int n : {3, 8, 29, 180, 206, 220}) CHECK(!has_write(p.axis_param(n)));
  for (int n : {128, 130}) CHECK(!has_write(p.global_param(0, n)));
  // STAP/RSAP exist here: settings can be stored, state cannot.
  for (int n : {4, 5, 6, 7, 140, 174, 204}) CHECK((p.axis_param(n)->access & kEeprom) != 0);
  for (int n : {0, 1, 2, 3, 8, 29, 100, 206}) CHECK((p.axis_param(n)->access & kEeprom) == 0);
  CHECK(p.global_param(3, 0) == nullptr);
}

// ---- generic ---------------------------------------------------------------------------------

TEST(generic_accepts_everything) {
  const Profile& p = generic();
  CHECK(p.any_parameter);
  for (const auto& op : tmcl::all_ops()) CHECK(p.has_command(op.code));
  CHECK_EQ(p.commands.count(), tmcl::all_ops().size());
  CHECK_EQ(p.program_memory, 0);
  CHECK_EQ(p.motors, 6);
  CHECK_EQ(p.coords, 21);
  CHECK_EQ(p.user_vars, 256);
  CHECK_EQ(p.default_motion, std::string_view("tmc4361"));
  // It borrows the USB-2-SD tables for names and defaults.
  CHECK_EQ(p.axis_params.size(), usb().axis_params.size());
  for (std::size_t i = 0; i < p.axis_params.size() && i < usb().axis_params.size(); ++i)
    CHECK_EQ(p.axis_params[i].name, usb().axis_params[i].name);
  CHECK_EQ(p.vectors.size(), usb().vectors.size());
  CHECK_EQ(p.axis_param(4)->default_value, 51200);
  CHECK(p.vector(255) != nullptr);
}

// ---- Invariants of every profile -------------------------------------------------------------

TEST(units_of_the_manuals_tables) {
  for (const Profile* p : {tmcl::find_profile("usb-2-sd"), tmcl::find_profile("tmc2300-eval")}) {
    CHECK_EQ(p->axis_param(0)->unit, "\u03bcsteps");  // Range [Units] column: positions
    CHECK_EQ(p->axis_param(4)->unit, "pps");
    CHECK_EQ(p->axis_param(5)->unit, "pps\u00b2");
    CHECK_EQ(p->axis_param(8)->unit, "");  // a flag: none
  }
  const Profile& usb = *tmcl::find_profile("usb-2-sd");
  CHECK_EQ(usb.axis_param(18)->unit, "pps");  // errata: the table says pps² for a velocity
  CHECK_EQ(usb.axis_param(22)->unit, "pps\u00b3");
  CHECK_EQ(usb.global_param(3, 0)->unit, "ms");
  CHECK_EQ(tmcl::find_profile("tmc2300-eval")->axis_param(220)->unit, "0.1 V");
}

TEST(tables_are_consistent) {
  for (const Profile* p : tmcl::all_profiles()) {
    const std::string who(p->name);
    for (auto table : {p->axis_params, p->bank0, p->bank3}) {
      for (std::size_t i = 0; i < table.size(); ++i) {
        const ParamInfo& a = table[i];
        const std::string what = who + " parameter " + std::to_string(a.number);
        if (i > 0 && table[i - 1].number >= a.number)
          ::tmcl_test::fail(__FILE__, __LINE__, what + ": duplicate or out of order");
        if (!(a.min <= a.default_value && a.default_value <= a.max))
          ::tmcl_test::fail(__FILE__, __LINE__, what + ": default outside its range");
        if (a.name.empty()) ::tmcl_test::fail(__FILE__, __LINE__, what + ": no name");
        if ((a.access & kRead) == 0) ::tmcl_test::fail(__FILE__, __LINE__, what + ": not readable");
        if ((a.access & kAutoStore) && !(a.access & kWrite))
          ::tmcl_test::fail(__FILE__, __LINE__, what + ": stored on write but not writable");
        if (a.number > 255) ::tmcl_test::fail(__FILE__, __LINE__, what + ": not a byte");
        if (a.min < -2147483648LL || a.max > 4294967295LL)
          ::tmcl_test::fail(__FILE__, __LINE__, what + ": range wider than 32 bits");
        // Units: the manuals' spellings (docs/profiles.md), so a typo cannot reach a hover.
        static const std::set<std::string_view> kUnits = {"",   "pps", "pps\u00b2", "pps\u00b3", "\u03bcsteps", "ms", "fullsteps/round",
                                                          "encoder steps", "1/16 \u00b5s", "0.1 V", "10 ms", "32 \u00b5s", "0.16384 s"};
        if (!kUnits.count(a.unit)) ::tmcl_test::fail(__FILE__, __LINE__, what + ": unknown unit '" + std::string(a.unit) + "'");
      }
    }
    // E on an axis parameter only where STAP exists.
    if (!p->has_command(7))
      for (const auto& a : p->axis_params)
        if (a.access & kEeprom) ::tmcl_test::fail(__FILE__, __LINE__, who + ": E without STAP");
    // Vectors: unique, and the interrupt commands exist exactly when there are vectors.
    std::set<int> seen;
    for (const auto& v : p->vectors) {
      CHECK(seen.insert(v.number).second);
      CHECK(v.name.rfind("TI_", 0) == 0);
      CHECK(!v.meaning.empty());
    }
    CHECK_EQ(p->has_command(37), !p->vectors.empty());
    CHECK_EQ(p->has_command(25), !p->vectors.empty());
    if (!p->vectors.empty()) CHECK(p->vector(255) != nullptr);
    // Coordinates exist exactly when SCO does.
    CHECK_EQ(p->has_command(30), p->coords > 0);
    CHECK(p->eeprom_user_vars <= p->user_vars);
    // Control commands every module has.
    for (int op : {128, 129, 130, 131, 132, 133, 134, 135, 136, 137, 255}) CHECK(p->has_command(static_cast<std::uint8_t>(op)));
    // Every command is a real opcode.
    for (int op = 0; op < 256; ++op)
      if (p->has_command(static_cast<std::uint8_t>(op)) && tmcl::op_info(static_cast<std::uint8_t>(op)) == nullptr)
        ::tmcl_test::fail(__FILE__, __LINE__, who + ": unknown opcode " + std::to_string(op));
    // Firmware string: 4-digit module number, 'V', major, 2-digit minor; the TMCM-351 has the
    // older form of its manual (351V.445).
    const std::string_view fw = p->firmware;
    CHECK_EQ(fw.size(), std::size_t{8});
    bool fw_ok = fw.size() == 8 && fw[4] == 'V';
    for (std::size_t i = 0; i < fw.size(); ++i)
      if (i != 4 && !std::isdigit(static_cast<unsigned char>(fw[i]))) fw_ok = false;
    CHECK(fw_ok || (p->name == "tmcm-351" && fw == "351V.445"));
    CHECK(!p->title.empty());
    CHECK(p->motors >= 1);
  }
}

TEST(firmware_versions_match_the_manuals) {
  CHECK_EQ(usb().firmware.substr(4), std::string_view("V114"));
  CHECK_EQ(eval().firmware.substr(4), std::string_view("V100"));
}

// ---- Include files ---------------------------------------------------------------------------

TEST(tmclparam_matches_tmcl_ide_names) {
  std::map<std::string, long long> expect;
  const auto lines = DATA_LINES("tmcl-ide-TMCLParam-names.tsv");
  if (lines.empty()) return;  // already failed, naming the file
  for (const std::string& line : lines) {
    std::istringstream fields(line);
    std::string name;
    long long value = 0;
    std::getline(fields, name, '\t');
    fields >> value;
    CHECK(!fields.fail());
    expect.emplace(upper(name), value);
  }
  CHECK(expect.size() > 50);
  const auto have = as_map("TMCLParam.tmc", read_include("TMCLParam.tmc"));
  for (const auto& [name, value] : expect) {
    const auto it = have.find(name);
    if (it == have.end())
      ::tmcl_test::fail(__FILE__, __LINE__, "TMCLParam.tmc lacks " + name);
    else
      CHECK_EQ(it->second, value);
  }
  CHECK_EQ(have.size(), expect.size());
}

TEST(interrupts_inc_matches_vectors) {
  const auto defs = read_include("Interrupts.inc");
  const auto have = as_map("Interrupts.inc", defs);
  CHECK_EQ(have.size(), std::size_t{3 + 6 * 5 + 3 + 8 + 1});  // timers, 5 per axis, position compare of 3 axes, inputs, global
  for (const Profile* p : tmcl::all_profiles())
    for (const auto& v : p->vectors) {
      const auto it = have.find(upper(v.name));
      if (it == have.end())
        ::tmcl_test::fail(__FILE__, __LINE__, "Interrupts.inc lacks " + std::string(v.name));
      else
        CHECK_EQ(it->second, static_cast<long long>(v.number));
    }
}

TEST(module_include_files_match_their_profiles) {
  const std::pair<const char*, const Profile*> files[] = {{"USB-2-SD.inc", &usb()},
                                                          {"TMC2300-MOTOR-EVAL.inc", &eval()}};
  for (const auto& [file, p] : files) {
    const auto defs = read_include(file);
    as_map(file, defs);  // no name twice
    // One AP_ name per axis parameter, one GP_ name per bank 0 parameter, one GP3_ per bank 3.
    CHECK(values_with_prefix(defs, "AP_") == numbers(p->axis_params));
    CHECK(values_with_prefix(defs, "GP_") == numbers(p->bank0));
    CHECK(values_with_prefix(defs, "GP3_") == numbers(p->bank3));
    for (const auto& d : defs) {
      const std::string u = upper(d.name);
      if (u.rfind("AP_", 0) != 0 && u.rfind("GP_", 0) != 0 && u.rfind("GP3_", 0) != 0)
        ::tmcl_test::fail(__FILE__, __LINE__, std::string(file) + ": unexpected name " + d.name);
    }
  }
}

TEST(include_files_do_not_clash) {
  // Names are case-insensitive; a name in two files must mean the same value in both.
  std::map<std::string, std::pair<long long, std::string>> all;
  for (const char* file : kIncludeFiles)
    for (const auto& d : read_include(file)) {
      const auto [it, fresh] = all.emplace(upper(d.name), std::make_pair(d.value, std::string(file)));
      if (!fresh && it->second.first != d.value)
        ::tmcl_test::fail(__FILE__, __LINE__,
                          d.name + " is " + std::to_string(it->second.first) + " in " + it->second.second +
                              " but " + std::to_string(d.value) + " in " + file);
    }
  // The module files add names of their own, never TMCLParam.tmc's.
  const auto tmclparam = as_map("TMCLParam.tmc", read_include("TMCLParam.tmc"));
  for (const char* file : {"USB-2-SD.inc", "TMC2300-MOTOR-EVAL.inc", "Interrupts.inc"})
    for (const auto& d : read_include(file))
      if (tmclparam.count(upper(d.name)))
        ::tmcl_test::fail(__FILE__, __LINE__, std::string(file) + " redefines " + d.name);
}

TEST(include_files_are_ascii) {
  for (const char* file : kIncludeFiles) {
    std::ifstream in(std::string(TMCL_INCLUDE_FILES_DIR) + "/" + file, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK(!text.empty());
    const bool ascii = std::all_of(text.begin(), text.end(), [](char c) {
      const auto u = static_cast<unsigned char>(c);
      return u == '\n' || u == '\t' || (u >= 0x20 && u < 0x7f);
    });
    if (!ascii) ::tmcl_test::fail(__FILE__, __LINE__, std::string(file) + " is not plain ASCII");
  }
}

// ---- The docs that list the bundled modules list them all --------------------------------------

namespace {

// The paragraph of docs/NAME that contains `marker`, from the blank line before it to the next.
std::string doc_paragraph(const std::string& doc, const std::string& marker) {
  std::ifstream in(std::string(TMCL_DOCS_DIR) + "/" + doc, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t at = text.find(marker);
  if (at == std::string::npos) return {};
  std::size_t begin = text.rfind("\n\n", at), end = text.find("\n\n", at);
  begin = begin == std::string::npos ? 0 : begin;
  return text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

}  // namespace

TEST(docs_about_the_bundled_modules_point_to_the_list_instead_of_keeping_one) {
  // tmclrun.md's opening and debugger.md's DAP `target` argument say where the bundled modules
  // are listed (--list-targets) and name a few as examples, not all: a list kept by hand there
  // would be one more file each new profile has to edit (docs/profiles.md, "A new bundled
  // profile"; tests/profiles/new_profile.sh checks every document so).
  const std::pair<const char*, const char*> lists[] = {{"tmclrun.md", "runs a TMCL program on a virtual module"},
                                                       {"debugger.md", "`launch` arguments"}};
  for (const auto& [doc, marker] : lists) {
    const std::string paragraph = doc_paragraph(doc, marker);
    CHECK(!paragraph.empty());
    CHECK(paragraph.find("--list-targets") != std::string::npos);
    int named = 0;
    for (const Profile* p : tmcl::all_profiles()) named += paragraph.find("`" + std::string(p->name) + "`") != std::string::npos;
    if (named > 4) ::tmcl_test::fail(__FILE__, __LINE__, std::string(doc) + " names " + std::to_string(named) + " bundled modules: a list kept by hand");
  }
}

// ---- The include files generated from the profiles (tmcl/param_names.hpp) ------------------------

TEST(generated_module_include_files_name_every_parameter_once_and_clash_with_no_other_file) {
  // Every bundled module without a file of its own in include_files/ gets NAME.inc from its
  // profile: one AP_/GP_/GP3_ name per parameter, no name twice, and, with the hand-written files,
  // a name means the same number in every file (so any of them can be included together) and
  // none redefines a TMCLParam.tmc name.
  std::map<std::string, std::pair<long long, std::string>> all;
  auto add = [&all](const std::string& file, const std::vector<Def>& defs) {
    for (const auto& d : defs) {
      const auto [it, fresh] = all.emplace(upper(d.name), std::make_pair(d.value, file));
      if (!fresh && it->second.first != d.value)
        ::tmcl_test::fail(__FILE__, __LINE__, d.name + " is " + std::to_string(it->second.first) + " in " + it->second.second +
                                                  " but " + std::to_string(d.value) + " in " + file);
    }
  };
  for (const char* file : {"USB-2-SD.inc", "TMC2300-MOTOR-EVAL.inc", "Interrupts.inc"}) add(file, read_include(file));
  const auto tmclparam = as_map("TMCLParam.tmc", read_include("TMCLParam.tmc"));
  int generated = 0;
  for (const Profile* p : tmcl::all_profiles()) {
    if (p->any_parameter || !p->include_file.empty()) continue;
    ++generated;
    const std::string file = tmcl::parameter_include_name(*p);
    CHECK_EQ(file, upper(std::string(p->name)) + ".inc");
    std::istringstream text(tmcl::parameter_include_text(*p));
    const auto defs = parse_include(file, text);
    as_map(file, defs);  // no name twice
    CHECK(values_with_prefix(defs, "AP_") == numbers(p->axis_params));
    CHECK(values_with_prefix(defs, "GP_") == numbers(p->bank0));
    CHECK(values_with_prefix(defs, "GP3_") == numbers(p->bank3));
    for (const auto& d : defs)
      if (tmclparam.count(upper(d.name))) ::tmcl_test::fail(__FILE__, __LINE__, file + " redefines " + d.name);
    add(file, defs);
  }
  CHECK(generated >= 8);  // the TMCM modules (not counted by hand: a new profile changes nothing here)
}

TEST(parameter_constants_follow_the_naming_scheme) {
  auto constant = [](std::string_view name) {
    return tmcl::parameter_constant(tmcl::ParamInfo{0, name, 0, 0, 0, 0, {}});
  };
  CHECK_EQ(constant("Maximum positioning speed"), std::string("MaxPositioningSpeed"));
  CHECK_EQ(constant("SmartEnergy current minimum (SEIMIN)"), std::string("SmartEnergyCurrentMin"));
  CHECK_EQ(constant("TMCL tick timer"), std::string("TickTimer"));
  CHECK_EQ(constant("Chopper hysteresis end / fast decay time"), std::string("ChopperHysteresisEndFastDecayTime"));
  CHECK_EQ(constant("PWM gradient"), std::string("PWMGradient"));
}
