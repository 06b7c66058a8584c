// Unit tests of the profile file reader and writer (vm/isa/profile_file.cpp, profile_write.cpp):
// a good file with every statement, based-on, and every kind of bad file, each reported at its
// line and column with every error of the file; the writer's drafts read back to the same facts.
#include "check.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "tmcl/profile_file.hpp"

namespace {

using tmcl::FileDiag;
using tmcl::Profile;

const char* const kGood = R"P(# a module of our own
tmcl-profile 1
name my-module
alias mine my.module
title "My module (firmware 2.01)"
source MAN "My module's manual, firmware 2.01"
firmware 4242V201 src=MAN:1
motors 2 src=MAN:1
standalone yes
program-memory 1024 eeprom src=MAN:2
user-variables 100 eeprom=20
coordinates 5 unverified
parameters listed
motion linear fallback=ideal
motion-constant clock 16000000 src=MAN:5.5
commands 1-6 SIO GIO 19-28 128-137 255
axis 4 "Maximum speed" 0..2047 RWE default=100 unit=pps src=MAN:5 unverified=default
axis 0 "Target position" -2147483648..2147483647 RW src=MAN:5 not-simulated="never moves"
global 0 77 "Auto start mode" 0..1 RWE
global 3 0 "Timer 0 period" 0..4294967295 RW default=4294967295 unit=ms
vector 0 TI_TIMER0 "Timer 0"
)P";

struct Parsed {
  std::unique_ptr<tmcl::ProfileStore> store;
  std::vector<FileDiag> diags;
  std::string text;  // rendered
};

const Profile* bundled(std::string_view name, std::string&) { return tmcl::find_profile(name); }

Parsed parse(const std::string& text, int limit = 0) {
  Parsed r;
  r.store = tmcl::parse_profile(text, "t.profile", "t.profile", r.diags, bundled);
  r.text = tmcl::render_file_diags(r.diags, limit);
  return r;
}

bool says(const Parsed& r, const std::string& what) {
  if (r.text.find(what) != std::string::npos) return true;
  std::fprintf(stderr, "expected '%s' in:\n%s", what.c_str(), r.text.c_str());
  return false;
}

// kGood with line `n` (1-based, of kGood) replaced by `line`.
std::string with_line(int n, const std::string& line) {
  std::string s = kGood, out;
  int at = 1;
  for (std::size_t pos = 0; pos < s.size();) {
    std::size_t end = s.find('\n', pos);
    out += (at == n ? line : s.substr(pos, end - pos)) + "\n";
    pos = end + 1;
    ++at;
  }
  return out;
}

}  // namespace

TEST(good_file_gives_every_fact) {
  Parsed r = parse(kGood);
  CHECK_EQ(r.text, std::string());
  CHECK(r.store != nullptr);
  if (!r.store) return;
  const Profile& p = r.store->profile;
  CHECK_EQ(p.name, "my-module");
  CHECK_EQ(p.title, "My module (firmware 2.01)");
  CHECK_EQ(p.aliases.size(), std::size_t{2});
  CHECK_EQ(p.firmware, "4242V201");
  CHECK_EQ(p.motors, 2);
  CHECK(p.standalone);
  CHECK_EQ(p.program_memory, 1024);
  CHECK(p.program_store == tmcl::ProgramStore::Eeprom);
  CHECK_EQ(p.user_vars, 100);
  CHECK_EQ(p.eeprom_user_vars, 20);
  CHECK_EQ(p.coords, 5);
  CHECK(!p.any_parameter);
  CHECK_EQ(p.default_motion, "linear");
  CHECK_EQ(p.fallback_motion, "ideal");
  CHECK_EQ(p.motion_constant("clock", 0), 16000000);
  CHECK_EQ(p.motion_constant("nothing", -1), -1);
  for (int op : {1, 6, 14, 15, 19, 28, 128, 137, 255}) CHECK(p.has_command(static_cast<std::uint8_t>(op)));
  for (int op : {7, 13, 29, 138}) CHECK(!p.has_command(static_cast<std::uint8_t>(op)));
  CHECK_EQ(p.axis_params.size(), std::size_t{2});
  CHECK_EQ(p.axis_params[0].number, 0);  // sorted by number
  const tmcl::ParamInfo* a4 = p.axis_param(4);
  CHECK(a4 && a4->max == 2047 && a4->default_value == 100 && a4->unit == "pps" && a4->source == "MAN:5");
  CHECK(a4 && a4->access == (tmcl::kRead | tmcl::kWrite | tmcl::kEeprom));
  CHECK(a4 && a4->unverified == tmcl::kFactDefault);
  CHECK(p.axis_param(0) && p.axis_param(0)->default_value == 0);  // no default=: 0
  CHECK(p.axis_param(0) && p.axis_param(0)->not_simulated == "never moves");
  CHECK(a4 && a4->not_simulated.empty());
  CHECK(p.global_param(0, 77) != nullptr);
  CHECK(p.global_param(3, 0) && p.global_param(3, 0)->default_value == -1);  // 4294967295 as a 32-bit field
  CHECK(p.vector(0) && p.vector(0)->name == "TI_TIMER0");
  // Every unverified fact, one phrase each, in file order.
  std::vector<std::string> facts(p.unverified.begin(), p.unverified.end());
  CHECK(facts == (std::vector<std::string>{"coordinates", "axis 4 default"}));
  CHECK_EQ(p.origin, "t.profile");
  CHECK_EQ(p.text, std::string_view(kGood));
}

TEST(based_on_takes_everything_and_changes_some) {
  Parsed r = parse(
      "tmcl-profile 1\nname usb-variant\nbased-on usb-2-sd\nmotors 2\n"
      "axis 4 \"Maximum positioning speed\" 0..1000 RW default=500\n");
  CHECK_EQ(r.text, std::string());
  if (!r.store) return;
  const Profile& p = r.store->profile;
  const Profile& usb = *tmcl::find_profile("usb-2-sd");
  CHECK_EQ(p.motors, 2);
  CHECK_EQ(p.title, "usb-variant");  // a title is never inherited
  CHECK_EQ(p.firmware, usb.firmware);
  CHECK_EQ(p.program_memory, usb.program_memory);
  CHECK(p.commands == usb.commands);
  CHECK_EQ(p.axis_params.size(), usb.axis_params.size());
  CHECK_EQ(p.axis_param(4)->max, 1000);
  CHECK_EQ(p.axis_param(5)->default_value, usb.axis_param(5)->default_value);
  CHECK_EQ(p.vectors.size(), usb.vectors.size());
}

// `based-on NAME unverified`: the base's parameter facts, none confirmed for this module; `without`
// takes away what the base has and this module lacks, and nothing else.
TEST(based_on_unverified_and_without) {
  Parsed r = parse(
      "tmcl-profile 1\nname usb-kin\nbased-on usb-2-sd unverified\nwithout axis 4 5\nwithout global 0 77\nwithout vector 0\n"
      "axis 8 \"Position reached flag\" 0..1 R\n");
  CHECK_EQ(r.text, std::string());
  if (!r.store) return;
  const Profile& p = r.store->profile;
  const Profile& usb = *tmcl::find_profile("usb-2-sd");
  CHECK(!p.axis_param(4) && !p.axis_param(5) && usb.axis_param(4));
  CHECK_EQ(p.axis_params.size(), usb.axis_params.size() - 2);
  CHECK(!p.global_param(0, 77) && p.global_param(0, 66));
  CHECK(!p.vector(0) && p.vector(1));
  const auto all = tmcl::kFactRange | tmcl::kFactAccess | tmcl::kFactDefault | tmcl::kFactUnit;
  CHECK(p.axis_param(0) && (p.axis_param(0)->unverified & all) == all);
  CHECK(p.global_param(0, 66) && (p.global_param(0, 66)->unverified & all) == all);
  CHECK(p.axis_param(8) && p.axis_param(8)->unverified == 0);  // a line of its own is its own
  std::vector<std::string> facts(p.unverified.begin(), p.unverified.end());
  CHECK(!facts.empty() && facts.front() == "based-on");
  CHECK(says(parse("tmcl-profile 1\nname x\nbased-on usb-2-sd\nwithout axis 4 250\n"),
             "4:16: error: the base has no axis parameter 250 to take away"));
  CHECK(says(parse("tmcl-profile 1\nname x\nbased-on usb-2-sd\nwithout motor 4\n"),
             "4:9: error: without takes 'axis', 'global BANK' or 'vector', not 'motor'"));
  CHECK(says(parse("tmcl-profile 1\nname x\nfirmware 0001V100\nmotors 1\nprogram-memory 10\ncommands 1-6\nwithout axis 4\n"),
             "7:1: error: 'without' takes parameters or vectors away from a profile's base: it needs a based-on line"));
}

TEST(not_a_profile) {
  CHECK(says(parse(""), "t.profile:1: error: not a tmcl profile: the file is empty"));
  CHECK(says(parse("SAP 4, 0, 100\nSTOP\n"), "t.profile:1:1: error: not a tmcl profile: the first line must be 'tmcl-profile 1'"));
  CHECK(says(parse("tmcl-profile 2\n"), "not a tmcl profile"));
  CHECK(says(parse(std::string("tmcl-profile 1\n\0\1\2", 17)), "holds NUL bytes"));
  // A file that is not a profile gives one error, not one per line.
  CHECK_EQ(parse("a\nb\nc\nd\n").diags.size(), std::size_t{1});
}

TEST(misspelt_key_and_attribute_get_a_guess) {
  Parsed r = parse(with_line(8, "moters 2"));
  CHECK(says(r, "t.profile:8:1: error: unknown key 'moters'; did you mean 'motors'?\n moters 2\n ^~~~~~\n"));
  r = parse(with_line(17, "axis 4 \"Maximum speed\" 0..2047 RWE defualt=100"));
  CHECK(says(r, "t.profile:17:36: error: unknown attribute 'defualt'; did you mean 'default'?"));
  r = parse(with_line(16, "commands 1-6 SOI"));
  CHECK(says(r, "'SOI' is not a TMCL command (an opcode, FIRST-LAST, a mnemonic or all); did you mean 'SIO'?"));
  r = parse(with_line(17, "axis 4 \"Maximum speed\" 0..2047 RWE src=MNA:5"));
  CHECK(says(r, "17:40: error: unknown source 'MNA' (declare it first: source MNA \"TEXT\"); did you mean 'MAN'?"));
}

TEST(bad_values_are_errors_at_their_column) {
  struct Case {
    int line;
    std::string text, expect;
  };
  const Case cases[] = {
      {7, "firmware 1110-103", "7:10: error: the firmware reply to command 136 is 8 characters"},
      {8, "motors 0", "8:8: error: a motor count 0 is out of range (1 to 255)"},
      {8, "motors two", "8:8: error: expected a motor count (a decimal number from 1 to 255), found 'two'"},
      {8, "motors 1 2", "8:10: error: too many values for 'motors' (expected: motors N)"},
      {8, "motors", "8:1: error: too few values for 'motors'"},
      {10, "program-memory 1024 flash", "10:21: error: where the program is kept: 'eeprom'"},
      {11, "user-variables 10 eeprom=20", "11:26: error: a number of EEPROM-backed user variables 20 is out of range (0 to 10)"},
      {9, "standalone maybe", "9:12: error: standalone takes yes or no"},
      {13, "parameters some", "13:12: error: parameters takes 'listed'"},
      {17, "axis 4 \"Maximum speed\" 2047..0 RWE", "17:24: error: the range's minimum 2047 is above its maximum 0"},
      {17, "axis 4 \"Maximum speed\" 0-2047 RWE", "17:24: error: expected a range MIN..MAX"},
      {17, "axis 4 \"Maximum speed\" 0..2047 RWX", "17:32: error: expected access letters (R, W, E, A; e.g. RWE), found 'RWX'"},
      {17, "axis 4 \"Maximum speed\" 0..2047 W", "17:32: error: access 'W' lacks R"},
      {17, "axis 4 \"Maximum speed\" 0..2047 RA", "17:32: error: access A (stored on every write) needs W"},
      {17, "axis 4 \"Maximum speed\" 0..2047 RW default=5000", "17:43: error: a default within the parameter's range 5000 is out of range (0 to 2047)"},
      {17, "axis 256 \"Maximum speed\" 0..2047 RW", "17:6: error: a parameter number 256 is out of range (0 to 255)"},
      {17, "axis 4 \"Maximum speed 0..2047 RW", "17:8: error: unterminated \"quoted text\""},
      {17, "axis 4 \"Maximum speed\" 0..2047 RW unit=", ""},  // an empty unit is no unit
      {17, "axis 4 \"Maximum speed\" 0..2047 RW unverified=color", "17:46: error: unknown fact 'color' for unverified="},
      {17, "axis 4 \"Maximum speed\" 0..2047 RW default=1 default=2", "17:45: error: a second default on one line"},
      {18, "axis 4 \"Again\" 0..1 RW", "18:6: error: axis parameter 4 is already defined at line 17"},
      {19, "global 2 7 \"Var\" 0..1 RW", "19:8: error: bank 2 holds the user variables"},
      {19, "global 1 7 \"X\" 0..1 RW", "19:8: error: bank 1 is not used"},
      {19, "global 0 77 \"Auto start mode\" 0..1 RWE eeprom=3", "19:40: error: 'global' takes no eeprom= (expected:"},
      {12, "coordinates 5 unverified=name", "12:15: error: 'unverified' on a 'coordinates' line takes no value"},
      {3, "name my/module", "3:6: error: a profile name is letters, digits"},
      {5, "title \"A\"\"B\"", "5:10: error: too many values for 'title'"},
      {6, "source MAN \"again\"", "7:8: error: source MAN is already declared at line 6"},
      {16, "commands 75", "16:10: error: opcode 75 is not a TMCL command"},
      {22, "vector 0 TI_TIMER0 \"again\"", "22:8: error: vector 0 is already defined at line 21"},
      {22, "name other", "22:1: error: a second 'name' line (the first is line 3)"},
      {22, "default=1", "22:1: error: a line starts with a key, not an attribute"},
      {22, "based-on usb-2-sd", "22:1: error: 'based-on' must come before the facts"},
      {22, "motion-constant clock 1", "22:17: error: motion constant clock is given twice"},
      {17, "axis 4 \"Maximum speed\" 0..2047 RW not-simulated=\"\"", "17:35: error: not-simulated= needs the reason"},
      {21, "vector 0 TI_TIMER0 \"Timer 0\" not-simulated=x", "21:30: error: 'vector' takes no not-simulated= (expected:"},
      {17, "axis 4 \"Maximum speed\" 0..2047 RW not-simulatd=x", "17:35: error: unknown attribute 'not-simulatd'; did you mean 'not-simulated'?"},
  };
  for (const auto& c : cases) {
    std::string text = kGood;
    if (c.line == 6) text = with_line(6, "source MAN \"x\"\n" + c.text);
    else if (c.line == 22) text = std::string(kGood) + c.text + "\n";
    else text = with_line(c.line, c.text);
    Parsed r = parse(text);
    if (c.expect.empty()) {
      CHECK_EQ(r.text, std::string());
      continue;
    }
    CHECK(says(r, "t.profile:" + c.expect));
    CHECK(r.store == nullptr);
  }
}

TEST(missing_facts_are_named) {
  Parsed r = parse("tmcl-profile 1\ntitle \"x\"\n");
  CHECK(says(r, "t.profile:1: error: the profile has no 'name' line (name NAME)"));
  CHECK(says(r, "no 'firmware' line"));
  CHECK(says(r, "no 'motors' line"));
  CHECK(says(r, "no 'commands' line"));
  CHECK(says(r, "no 'program-memory' line"));
  // A module that runs no programs needs no program memory.
  r = parse("tmcl-profile 1\nname x\nfirmware 0001V100\nmotors 1\ncommands 1-6\nstandalone no\n");
  CHECK_EQ(r.text, std::string());
  CHECK(r.store && !r.store->profile.standalone && r.store->profile.program_memory == 0);
  CHECK(says(parse("tmcl-profile 1\nname x\nbased-on nothing\n"), "3:10: error: unknown profile 'nothing' for based-on"));
}

TEST(every_error_of_a_file_is_reported_and_capped) {
  std::string text = "tmcl-profile 1\nname x\nfirmware 0001V100\nmotors 1\nprogram-memory 10\ncommands 1-6\n";
  for (int i = 0; i < 30; ++i) text += "axis " + std::to_string(i) + " \"p\" 0..1 RX\n";
  Parsed r = parse(text, 20);
  CHECK_EQ(r.diags.size(), std::size_t{30});
  CHECK(says(r, "t.profile: note: 10 more errors not shown (--error-limit N changes the limit, 0 shows all)"));
  CHECK(says(r, "t.profile:7:17: error:"));
}

TEST(written_drafts_read_back_to_the_same_facts) {
  for (const Profile* p : tmcl::all_profiles()) {
    const std::string text = tmcl::format_profile(*p, "a draft\nof two lines");
    Parsed r = parse(text);
    CHECK_EQ(r.text, std::string());
    if (!r.store) continue;
    const Profile& q = r.store->profile;
    CHECK_EQ(q.name, p->name);
    CHECK_EQ(q.title, p->title);
    CHECK_EQ(q.firmware, p->firmware);
    CHECK(q.commands == p->commands);
    CHECK_EQ(q.any_parameter, p->any_parameter);
    CHECK_EQ(q.motors, p->motors);
    CHECK_EQ(q.program_memory, p->program_memory);
    CHECK(q.program_store == p->program_store);
    CHECK_EQ(q.user_vars, p->user_vars);
    CHECK_EQ(q.eeprom_user_vars, p->eeprom_user_vars);
    CHECK_EQ(q.coords, p->coords);
    CHECK_EQ(q.default_motion, p->default_motion);
    CHECK_EQ(q.motion_constants.size(), p->motion_constants.size());
    CHECK_EQ(q.vectors.size(), p->vectors.size());
    for (auto [a, b] : {std::pair{q.axis_params, p->axis_params}, std::pair{q.bank0, p->bank0}, std::pair{q.bank3, p->bank3}}) {
      CHECK_EQ(a.size(), b.size());
      for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        CHECK_EQ(a[i].number, b[i].number);
        CHECK_EQ(a[i].min, b[i].min);
        CHECK_EQ(a[i].max, b[i].max);
        CHECK_EQ(a[i].access, b[i].access);
        CHECK_EQ(a[i].default_value, b[i].default_value);
        CHECK_EQ(a[i].unit, b[i].unit);
        CHECK_EQ(a[i].unverified, b[i].unverified);
        CHECK_EQ(a[i].not_simulated, b[i].not_simulated);
      }
    }
    CHECK(text.rfind("# a draft\n# of two lines\ntmcl-profile 1\n", 0) == 0);
  }
}
