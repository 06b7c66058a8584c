// Reading test files (parse_test_file): every line kind, where the program is found, and every
// mistake reported at once with its place, a caret and a "did you mean", scenario lines through
// the scenario reader itself.
#include "check.hpp"
#include "helpers.hpp"

using namespace tmcl::testrun;

namespace {

TestFile parsed(const std::string& text, const std::string& path = "dir/t.tmctest") {
  TestFile t;
  std::vector<tmcl::FileDiag> diags;
  CHECK(parse_test_file(text, path, "generic", t, diags, true));
  CHECK_EQ(tmcl::render_file_diags(diags, 0), "");
  return t;
}

std::string errors(const std::string& text, const std::string& target = "generic") {
  TestFile t;
  std::vector<tmcl::FileDiag> diags;
  CHECK(!parse_test_file(text, "t.tmctest", target, t, diags, true));
  return tmcl::render_file_diags(diags, 0);
}

}  // namespace

TEST(file_every_line_kind) {
  TestFile t = parsed(
      "# a comment\r\n"
      "program prog.tmc   # relative to the test file\r\n"
      "target usb-2-sd\n"
      "motion linear\n"
      "instr-time 10us\n"
      "max-time 1.5s\n"
      "define SPEED=1000 * 2\n"
      "at 100ms input 0 = 1\n"
      "expect at 1.5s position 0 = 0 \xC2\xB1 10\n"
      "expect at 2.5s v[3] = 7\n"
      "expect at end acc != 0\n"
      "expect at end ap(1, 0) >= 100000   # = != < <= > >=\n"
      "expect at end (acc << 2) < 8\n"
      "expect at end halted max-time\n"
      "expect never fault\n"
      "expect no warnings\n");
  CHECK_EQ(t.program, "dir/prog.tmc");
  CHECK_EQ(t.program_line, 2);
  CHECK_EQ(t.target, "usb-2-sd");
  CHECK_EQ(t.motion, "linear");
  CHECK_EQ(t.instr_time, 10);
  CHECK_EQ(t.max_time, 1'500'000);
  CHECK(t.max_time_given);
  CHECK_EQ(t.defines.size(), 1u);
  CHECK_EQ(t.defines[0].name, "SPEED");
  CHECK_EQ(t.defines[0].value, "1000 * 2");
  CHECK_EQ(t.defines[0].line, 7);
  CHECK_EQ(t.defines[0].col, 14);  // where the value starts: its errors are shown there
  CHECK_EQ(t.inputs.size(), 1u);
  CHECK_EQ(t.inputs[0].at, 100'000);
  CHECK_EQ(t.inputs[0].line, 8);
  CHECK_EQ(t.expects.size(), 8u);
  const Expectation& pos = t.expects[0];
  CHECK(pos.kind == Expectation::At);
  CHECK_EQ(pos.at, 1'500'000);
  CHECK_EQ(pos.when, "1.5s");
  CHECK_EQ(pos.left, "position 0");
  CHECK(pos.op == Compare::Eq);
  CHECK_EQ(pos.right, "0");
  CHECK_EQ(pos.tolerance, "10");
  CHECK_EQ(pos.left_col, 16);
  CHECK_EQ(pos.right_col, 29);
  CHECK(t.expects[2].kind == Expectation::AtEnd);
  CHECK(t.expects[2].op == Compare::Ne);
  CHECK(t.expects[3].op == Compare::Ge);
  CHECK_EQ(t.expects[3].left, "ap(1, 0)");
  CHECK_EQ(t.expects[3].right, "100000");
  CHECK(t.expects[4].op == Compare::Lt);  // << is a shift, not a comparison
  CHECK_EQ(t.expects[4].left, "(acc << 2)");
  CHECK(t.expects[5].kind == Expectation::Halted);
  CHECK(t.expects[5].halted == End::MaxTime);
  CHECK(t.expects[6].kind == Expectation::NeverFault);
  CHECK(t.expects[7].kind == Expectation::NoWarnings);
  CHECK(!t.skipped);
}

TEST(file_tolerance_in_ascii_and_comparisons_in_parentheses) {
  TestFile t = parsed(
      "program p.tmc\n"
      "expect at end x = -5 +/- 2\n"
      "expect at end (v[1] == 2) == 1\n"
      "expect at end halted = 3\n",  // a label named 'halted'
      "t.tmctest");
  CHECK_EQ(t.program, "p.tmc");
  CHECK_EQ(t.expects[0].right, "-5");
  CHECK_EQ(t.expects[0].tolerance, "2");
  CHECK_EQ(t.expects[1].left, "(v[1] == 2)");
  CHECK(t.expects[1].op == Compare::Eq);
  CHECK(t.expects[2].kind == Expectation::AtEnd);
  CHECK_EQ(t.expects[2].left, "halted");
}

TEST(file_program_paths_are_relative_to_the_test_file) {
  CHECK_EQ(parsed("program ../lib/p.tmc\n", "a/b/t.tmctest").program, "a/lib/p.tmc");
  CHECK_EQ(parsed("program ../../p.tmc\n", "a/t.tmctest").program, "../p.tmc");
  CHECK_EQ(parsed("program /abs/p.bin\n", "a/t.tmctest").program, "/abs/p.bin");
  CHECK_EQ(parsed("program my prog.tmc\n", "t.tmctest").program, "my prog.tmc");
}

TEST(file_skip_needs_no_program) {
  TestFile t = parsed("skip waits for the TMCM-1110 profile\n");
  CHECK(t.skipped);
  CHECK_EQ(t.skip, "waits for the TMCM-1110 profile");
  CHECK(parsed("program p.tmc\nskip\n").skipped);
}

TEST(file_every_mistake_at_once) {
  CHECK_EQ(errors("programm p.tmc\n"
                  "target usb2sd\n"
                  "max-tme 10s\n"
                  "max-time 10\n"
                  "instr-time -5us\n"
                  "motion tmc4631\n"
                  "define SPEED\n"
                  "expcet never fault\n"
                  "expect never faults\n"
                  "expect no\n"
                  "expect sometimes v[1] = 2\n"
                  "expect at 2x acc = 3\n"
                  "expect at ned acc = 3\n"
                  "expect at 1s\n"
                  "expect at end acc\n"
                  "expect at end acc => 3\n"
                  "expect at end acc = 1 = 2\n"
                  "expect at end = 3\n"
                  "expect at end acc =\n"
                  "expect at end acc < 3 +/- 1\n"
                  "expect at end acc = 3 +/-\n"
                  "expect at end halted stpo\n"
                  "expect at end halted\n"
                  "expect at end halted stop now\n"
                  "at 1s inptu 0 = 1\n"
                  "at 1s left 3 = 1\n"
                  "target generic\n"
                  "target generic\n",
                  "usb-2-sd"),
           "t.tmctest:1: error: no 'program' line: a test names the program it runs (program FILE)\n"
           "t.tmctest:1:1: error: unknown line 'programm' (program, target, motion, instr-time, max-time, define, skip, at, "
           "switch, hardstop, load, expect); did you mean 'program'?\n programm p.tmc\n ^~~~~~~~\n"
           "t.tmctest:2:8: error: unknown target 'usb2sd'; did you mean 'usb-2-sd'? (see tmclasm --list-targets; or a profile "
           "file, docs/profiles.md)\n"
           " target usb2sd\n        ^~~~~~\n"
           "t.tmctest:3:1: error: unknown line 'max-tme' (program, target, motion, instr-time, max-time, define, skip, at, "
           "switch, hardstop, load, expect); did you mean 'max-time'?\n max-tme 10s\n ^~~~~~~\n"
           "t.tmctest:4:10: error: bad duration: '10' needs a unit: us, ms, s, min or h (only 0 may go without one)\n max-time 10\n          ^~\n"
           "t.tmctest:5:12: error: bad duration: '-5us' is negative; a duration is 0 or more\n instr-time -5us\n            ^~~~\n"
           "t.tmctest:6:8: error: unknown motion core 'tmc4631' (ideal, linear, tmc429, tmc4361, tmc5160, tmc5240); did you mean 'tmc4361'?\n"
           " motion tmc4631\n        ^~~~~~~\n"
           "t.tmctest:7:8: error: expected 'define NAME=VALUE', as tmclasm's -D\n define SPEED\n        ^~~~~\n"
           "t.tmctest:8:1: error: unknown line 'expcet' (program, target, motion, instr-time, max-time, define, skip, at, "
           "switch, hardstop, load, expect); did you mean 'expect'?\n expcet never fault\n ^~~~~~\n"
           "t.tmctest:9:14: error: expected 'never fault', found 'faults'; did you mean 'fault'?\n"
           " expect never faults\n              ^~~~~~\n"
           "t.tmctest:10:10: error: expected 'no warnings' or 'no notes'\n expect no\n          ^\n"
           "t.tmctest:11:8: error: unknown expectation 'sometimes' (at TIME, at end, never fault, no warnings, no notes, stall MOTOR at TIME, never stall MOTOR)\n"
           " expect sometimes v[1] = 2\n        ^~~~~~~~~\n"
           "t.tmctest:12:11: error: bad instant '2x': unknown unit 'x' in '2x'; use us, ms, s, min or h (or 'end')\n"
           " expect at 2x acc = 3\n           ^~\n"
           "t.tmctest:13:11: error: bad instant 'ned': 'ned' has no number before its unit (or 'end'); did you mean 'end'?\n"
           " expect at ned acc = 3\n           ^~~\n"
           "t.tmctest:14:13: error: expected a condition after '1s' (e.g. v[3] = 7)\n expect at 1s\n             ^\n"
           "t.tmctest:15:15: error: expected a comparison: EXPRESSION = VALUE (or !=, <, <=, >, >=)\n"
           " expect at end acc\n               ^~~\n"
           "t.tmctest:16:19: error: '=>' is not a comparison; did you mean '>='?\n expect at end acc => 3\n                   ^~\n"
           "t.tmctest:17:23: error: a second comparison (an expectation compares once; parentheses make a comparison a "
           "value)\n expect at end acc = 1 = 2\n                       ^\n"
           "t.tmctest:18:15: error: nothing before '='\n expect at end = 3\n               ^\n"
           "t.tmctest:19:19: error: no value after '='\n expect at end acc =\n                   ^\n"
           "t.tmctest:20:23: error: a tolerance goes only with '=' (VALUE ± TOLERANCE)\n"
           " expect at end acc < 3 +/- 1\n                       ^~~\n"
           "t.tmctest:21:23: error: a tolerance is missing after '+/-'\n expect at end acc = 3 +/-\n                       ^~~\n"
           "t.tmctest:22:22: error: unknown end 'stpo' (stop, fault, max-time, blocked); did you mean 'stop'?\n"
           " expect at end halted stpo\n                      ^~~~\n"
           "t.tmctest:23:21: error: 'halted' needs how the run ended: stop, fault, max-time or blocked\n"
           " expect at end halted\n                     ^\n"
           "t.tmctest:24:27: error: unexpected 'now' after 'stop'\n expect at end halted stop now\n                           ^~~\n"
           "t.tmctest:25:7: error: unknown input 'inptu' (input, analog, left, right, home, slip, load); did you mean 'input'?\n"
           " at 1s inptu 0 = 1\n       ^~~~~\n"
           "t.tmctest:27:1: error: a second 'target' line (the first is line 2)\n target generic\n ^~~~~~\n"
           "t.tmctest:28:1: error: a second 'target' line (the first is line 2)\n target generic\n ^~~~~~\n");
}

TEST(file_scenario_motors_follow_the_target) {
  // usb-2-sd has one motor: a switch of motor 3 is refused with the module's name.
  CHECK_EQ(errors("program p.tmc\ntarget usb-2-sd\nat 1s left 3 = 1\n"),
           "t.tmctest:3:12: error: usb-2-sd has no motor 3 (0..0)\n at 1s left 3 = 1\n            ^\n");
}

// A slip needs an encoder the test's core models on its module: the file's `motion` line, else
// the module's core (issue 34).
TEST(file_slip_needs_an_encoder) {
  CHECK_EQ(errors("program p.tmc\ntarget tmcm-6110\nat 1s slip 0 = -400\n"),
           "t.tmctest:3:7: error: 'slip' needs an encoder: the motion core 'tmc429' models none on tmcm-6110\n"
           " at 1s slip 0 = -400\n       ^~~~\n");
  CHECK_EQ(errors("program p.tmc\ntarget tmcm-1260\nmotion linear\nat 1s slip 0 = -400\n"),
           "t.tmctest:4:7: error: 'slip' needs an encoder: the motion core 'linear' models none on tmcm-1260\n"
           " at 1s slip 0 = -400\n       ^~~~\n");
  CHECK_EQ(parsed("program p.tmc\ntarget tmcm-1260\nat 1s slip 0 = -400\n").inputs.size(), std::size_t{1});
}

// Switches at positions are scenario lines of a test file too, read by the scenario reader
// (its errors included); they are placed switches, not timed inputs.
TEST(file_switch_lines_are_scenario_lines) {
  const TestFile t = parsed("program p.tmc\ntarget tmcm-1110\nswitch left 0 at -20000\nswitch home 0 from -150 to 150\n");
  CHECK_EQ(t.inputs.size(), std::size_t{2});
  CHECK_EQ(errors("program p.tmc\ntarget tmcm-1110\nswitch left 0 at far\n"),
           "t.tmctest:3:18: error: bad position 'far' (microsteps, a 32-bit integer)\n switch left 0 at far\n"
           "                  ^~~\n");
}

// `target` takes what -t takes: a profile file too, a relative path from the test file's folder.
TEST(file_target_may_be_a_profile_file) {
  const std::string folder = tmcl_test::make_temp_dir("tmcl-testrun");
  CHECK(!folder.empty());
  {
    std::FILE* f = std::fopen((folder + "/mine.profile").c_str(), "w");
    CHECK(f != nullptr);
    std::fputs("tmcl-profile 1\nname mine\ntitle \"mine\"\nbased-on usb-2-sd\n", f);
    std::fclose(f);
  }
  TestFile t = parsed("program p.tmc\ntarget ./mine.profile\n", folder + "/t.tmctest");
  CHECK_EQ(t.module, folder + "/./mine.profile");
  std::string why;
  const tmcl::Profile* p = test_profile(t, &why);
  CHECK(p != nullptr);
  CHECK_EQ(why, "");
  if (p) CHECK_EQ(std::string(p->name), "mine");
  // A file name without a folder is a profile file as for -t (it ends in .profile), found beside
  // the test file too, not in the current folder (the scratch folder, which has none).
  TestFile bare = parsed("program p.tmc\ntarget mine.profile\n", folder + "/t.tmctest");
  CHECK_EQ(bare.module, folder + "/mine.profile");
  CHECK(test_profile(bare, &why) == p);
  CHECK_EQ(why, "");
  std::vector<tmcl::FileDiag> diags;
  CHECK(!parse_test_file("program p.tmc\ntarget ./none.profile\n", folder + "/t.tmctest", "generic", t, diags, true));
  CHECK(test_profile(t, &why) == nullptr);
  CHECK(why.find("none.profile") != std::string::npos);
  CHECK_EQ(diags.size(), std::size_t{1});
  std::error_code ec;
  std::filesystem::remove_all(folder, ec);
}

// Without a `target` line a test runs where a plain `tmclrun PROGRAM` would: on -t when given,
// else on what the program's first line names (`// tmcl-target: NAME`), else on -t's default;
// a module the program names that does not exist is shown at the `program` line.
TEST(file_module_as_for_tmclrun) {
  runtest::put("named/p.tmc", "// tmcl-target: tmcm-1110\n  STOP\n");
  runtest::put("named/bad.tmc", "// tmcl-target: tmcm-9999\n  STOP\n");
  runtest::put("named/plain.tmc", "  STOP\n");
  auto module = [](const std::string& text, bool target_given) {
    TestFile t;
    std::vector<tmcl::FileDiag> diags;
    CHECK(parse_test_file(text, "named/tests/t.tmctest", "usb-2-sd", t, diags, target_given));
    CHECK_EQ(tmcl::render_file_diags(diags, 0), "");
    return t.module;
  };
  CHECK_EQ(module("program ../p.tmc\n", false), "tmcm-1110");
  CHECK_EQ(module("program ../p.tmc\n", true), "usb-2-sd");         // -t wins over the program, as for tmclrun
  CHECK_EQ(module("program ../p.tmc\ntarget tmcm-3110\n", false), "tmcm-3110");  // the test file's own wins over both
  CHECK_EQ(module("program ../plain.tmc\n", false), "usb-2-sd");
  CHECK_EQ(module("program ../none.tmc\n", false), "usb-2-sd");     // not there: the error is the loader's
  // The scenario lines' motors are the named module's: a USB-2-SD has one motor.
  runtest::put("named/one.tmc", "// tmcl-target: usb-2-sd\n  STOP\n");
  TestFile t;
  std::vector<tmcl::FileDiag> diags;
  CHECK(!parse_test_file("program ../one.tmc\nat 1s left 2 = 1\n", "named/tests/t.tmctest", "tmcm-3110", t, diags, false));
  CHECK_EQ(tmcl::render_file_diags(diags, 0),
           "named/tests/t.tmctest:2:12: error: usb-2-sd has no motor 2 (0..0)\n at 1s left 2 = 1\n            ^\n");
  diags.clear();
  CHECK(!parse_test_file("program  ../bad.tmc  # named\n", "named/tests/t.tmctest", "generic", t, diags, false));
  CHECK(runtest::has(tmcl::render_file_diags(diags, 0),
                     "named/tests/t.tmctest:1:10: error: the program's first line names the target 'tmcm-9999': unknown target 'tmcm-9999'"));
  CHECK(runtest::has(tmcl::render_file_diags(diags, 0), " program  ../bad.tmc  # named\n          ^~~~~~~~~~\n"));
}

// Diagnostics quote a line as written when it is valid UTF-8 (a test file's "±"), with the
// caret counted in characters; other bytes, controls and invisible characters that would move
// the caret or turn the text around are '?'.
TEST(file_diagnostics_quote_utf8_as_written) {
  CHECK_EQ(tmcl::caret_lines("x = 0 \xC2\xB1 10 +", 13, 1), " x = 0 \xC2\xB1 10 +\n            ^\n");
  CHECK_EQ(tmcl::caret_lines("\xC3\xA9t\xC3\xA9 = 1", 1, 5), " \xC3\xA9t\xC3\xA9 = 1\n ^~~\n");  // 5 bytes, 3 letters
  CHECK_EQ(tmcl::caret_lines("\tv\xE2\x80\xAE" "1 \xE9 \xC2\x85 x", 13, 1), " \tv?1 ? ? x\n \t        ^\n");
  CHECK_EQ(tmcl::caret_lines("ab", 5, 2), " ab\n     ^\n");  // past the end: no tildes
}
