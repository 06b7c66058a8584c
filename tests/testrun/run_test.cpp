// Running tests (run_test_file): every kind of expectation passing and failing, instants after
// the end of the run, how the run ended, evaluation errors, and tests that cannot run (a bad
// program, a missing one, an unknown name with its "did you mean").
#include "check.hpp"
#include "helpers.hpp"
#include "tmcl/duration.hpp"
#include "tmcl/image.hpp"

using namespace runtest;
using tmcl::testrun::TestResult;

namespace {

// 20 us an instruction: the loop ends at 140 us with acc 3; motor 0 turns at 1000 pps from
// 180 us for one second; then input 0 decides between two STOPs.
const char* kCounter =
    "        SGP 0, 2, 3         // v0 = 3\n"
    "loop:   CALC ADD, 1\n"
    "        DJNZ 0, loop\n"
    "        SGP 3, 2, 7         // v3 = 7\n"
    "        ROR 0, 1000\n"
    "        WAIT TICKS, 0, 100  // 1 s\n"
    "        MST 0\n"
    "        GIO 0, 0\n"
    "        COMP 1\n"
    "        JC EQ, high\n"
    "        STOP\n"
    "high:   SGP 4, 2, 1\n"
    "        STOP\n";

const TestResult& run_counter(const std::string& name, const std::string& body) {
  static TestResult r;
  put("counter.tmc", kCounter);
  r = run(name, "program counter.tmc\n" + body);
  return r;
}

}  // namespace

TEST(run_every_kind_of_expectation_passes) {
  const TestResult& r = run_counter("pass",
                                    "max-time 5s\n"
                                    "at 0.5s input 0 = 1\n"
                                    "expect at 100us acc = 2\n"
                                    "expect at 140us v[0] = 0\n"
                                    "expect at 0.5s velocity 0 = 1000\n"
                                    "expect at 0.5s position 0 = 500 \xC2\xB1 10\n"
                                    "expect at 0.5s in(0) = 1\n"
                                    "expect at 1.01s position 0 > 990\n"
                                    "expect at 1.01s velocity 0 < 1000\n"
                                    "expect at end v[4] = 1\n"
                                    "expect at end v[3] != 0\n"
                                    "expect at end acc <= 1\n"
                                    "expect at end acc >= 1\n"
                                    "expect at end acc < 2\n"
                                    "expect at end v[3] == 7\n"
                                    "expect at end time < 2s\n"
                                    "expect at end high = 11\n"
                                    "expect at end halted stop\n"
                                    "expect never fault\n"
                                    "expect no warnings\n");
  CHECK_EQ(r.error, "");
  CHECK_EQ(messages(r), "");
  CHECK(r.status == TestResult::Pass);
  CHECK(r.ended_at > 1'000'000 && r.ended_at < 1'100'000);
}

TEST(run_every_kind_of_expectation_fails_with_expected_actual_instant_and_place) {
  const TestResult& r = run_counter("fail",
                                    "max-time 5s\n"
                                    "expect at 100us acc = 3\n"
                                    "expect at 0.5s position 0 = 400 \xC2\xB1 10\n"
                                    "expect at 0.5s velocity 0 != 1000\n"
                                    "expect at end v[4] = 1\n"
                                    "expect at end acc > v[3]\n"
                                    "expect at end acc < 0\n"
                                    "expect at end acc <= -1\n"
                                    "expect at end acc >= 10\n"
                                    "expect at end halted fault\n");
  CHECK(r.status == TestResult::Fail);
  CHECK_EQ(messages(r),
           "3: expected acc = 3 at 100us, got 2\n"
           "4: expected position 0 = 400 \xC2\xB1 10 at 0.5s, got 490\n"
           "5: expected velocity 0 != 1000 at 0.5s, got 1000\n"
           "6: expected v[4] = 1 at the end, got 0\n"
           "7: expected acc > v[3] at the end, got 0 (v[3] is 7)\n"
           "8: expected acc < 0 at the end, got 0\n"
           "9: expected acc <= -1 at the end, got 0\n"
           "10: expected acc >= 10 at the end, got 0\n"
           "11: expected the run to end with fault, but the run ended at 1.019732s (STOP at counter.tmc:11)\n");
  // Where the program was: the instruction's place, the label it is under, its source line.
  CHECK_EQ(r.failures[0].where, "the program was at counter.tmc:2 (loop): loop:   CALC ADD, 1");
  CHECK_EQ(r.failures[1].where, "the program was at counter.tmc:6 (loop+4): WAIT TICKS, 0, 100  // 1 s");
  CHECK_EQ(r.failures[3].where, "the program was at counter.tmc:11 (loop+9): STOP");
}

TEST(run_an_instant_after_the_end_fails_saying_so) {
  const TestResult& r = run_counter("after", "max-time 5s\nexpect at 3s acc = 0\nexpect at 6s acc = 0\n");
  CHECK_EQ(messages(r),
           "3: expected acc = 0 at 3s, but the run ended at 1.019732s (STOP at counter.tmc:11)\n"
           "4: expected acc = 0 at 6s, but the run ended at 1.019732s (STOP at counter.tmc:11)\n");
  const TestResult& cut = run_counter("cut", "max-time 0.5s\nexpect at 0.5s velocity 0 = 1000\nexpect at 0.6s acc = 0\n"
                                             "expect at end halted max-time\n");
  CHECK_EQ(messages(cut), "4: expected acc = 0 at 0.6s, but the run ended at 0.500000s (max-time 0.500000s)\n");
}

TEST(run_max_time_and_instr_time_lines_and_a_default_max_time) {
  // 10 us an instruction: at 100 us the loop has ended.
  CHECK_EQ(messages(run_counter("instr", "instr-time 10us\nexpect at 100us acc = 3\nexpect at end halted stop\n")), "");
  // A program that never stops ends at the default max-time of 10 minutes.
  put("forever.tmc", "loop: WAIT TICKS, 0, 100\n JA loop\n");
  const TestResult& r = run("forever", "program forever.tmc\nexpect at end halted stop\n");
  CHECK_EQ(messages(r), "2: expected the run to end with stop, but the run ended at 600.000000s (max-time 600.000000s)\n");
  // The front end's --max-time replaces the file's.
  tmcl::testrun::RunOptions o;
  o.max_time_given = true;
  o.max_time = 2'000'000;
  CHECK_EQ(messages(run("forever2", "program forever.tmc\nmax-time 1h\nexpect at end time = 2s\n", o)), "");
}

TEST(run_faults_warnings_and_blocked_runs) {
  put("fault.tmc", "CALC LOAD, 5\nUF0 0, 0, 0\nSTOP\n");
  const TestResult& f = run("fault", "program fault.tmc\nexpect never fault\nexpect at end halted stop\nexpect at end acc = 5\n");
  CHECK_EQ(messages(f),
           "2: expected no fault, got one at 0.000040s: UF0 (a customer-specific user function) has no implementation in "
           "the virtual module, at address 1 (fault.tmc:2)\n"
           "3: expected the run to end with stop, but the run ended at 0.000040s (a fault: UF0 (a customer-specific user "
           "function) has no implementation in the virtual module, at address 1 (fault.tmc:2))\n");
  CHECK_EQ(f.failures[0].where, "the program was at fault.tmc:2: UF0 0, 0, 0");
  CHECK_EQ(messages(run("fault-ok", "program fault.tmc\nexpect at end halted fault\n")), "");

  put("warn.tmc", "RSUB\nRSUB\nRSUB\nRSUB\nSTOP\n");
  const TestResult& w = run("warn", "program warn.tmc\nexpect no warnings\n");
  CHECK_EQ(messages(w), "2: expected no run-time warnings, got 4\n");
  CHECK_EQ(w.failures[0].where,
           "at 0.000000s, warn.tmc:1: RSUB with an empty call stack: nothing to return to [return-without-call]\n"
           "at 0.000020s, warn.tmc:2: RSUB with an empty call stack: nothing to return to [return-without-call]\n"
           "at 0.000040s, warn.tmc:3: RSUB with an empty call stack: nothing to return to [return-without-call]\n"
           "and 1 more");
  // --strict makes the warning a fault.
  tmcl::testrun::RunOptions strict;
  strict.strict = true;
  CHECK_EQ(messages(run("strict", "program warn.tmc\nexpect at end halted fault\n", strict)), "");

  put("blocked.tmc", "WAIT REFSW, 0, 0\nSTOP\n");
  CHECK_EQ(messages(run("blocked", "program blocked.tmc\nmax-time 1s\nexpect at end halted blocked\n")), "");
  CHECK_EQ(messages(run("blocked-stop", "program blocked.tmc\nexpect at end halted stop\n")),
           "2: expected the run to end with stop, but the run ended at 600.000000s (blocked: the WAIT at blocked.tmc:1 can "
           "never end: no timer, motion, input or timeout is pending)\n");
  // The VM's own reason (never_ending_wait_reason): a reference search with no switch on its way
  // runs on, which the test says as tmclrun does, not "no motion".
  put("rfs.tmc", "// tmcl-target: tmcm-1110\nRFS START, 0\nWAIT RFS, 0, 0\nSTOP\n");
  CHECK(runtest::has(messages(run("rfs", "program rfs.tmc\nmax-time 1s\nexpect at end halted stop\n")),
                     "(blocked: the WAIT at rfs.tmc:3 can never end: motor 0's reference search runs on, but no switch"));
}

TEST(run_scenario_lines_and_definitions_reach_the_program) {
  // input 0 set at 0.5s: the program takes the other STOP and sets v4.
  CHECK_EQ(messages(run_counter("input", "at 0.5s input 0 = 1\nexpect at end v[4] = 1\n")), "");
  CHECK_EQ(messages(run_counter("no-input", "expect at end v[4] = 0\n")), "");
  put("defined.tmc", "SGP 1, 2, SPEED\nSTOP\n");
  CHECK_EQ(messages(run("defined", "program defined.tmc\ndefine SPEED=40 * 3\nexpect at end v[1] = 120\n")), "");
}

TEST(run_tolerances_at_the_ends_of_64_bits) {
  // The distance of two values is taken without overflow: 2^62 against -2^62 (wrapped, it would
  // be negative and the expectation met).
  CHECK_EQ(messages(run_counter("wide", "expect at end (1 << 62) = -(1 << 62) \xC2\xB1 5\nexpect at end acc = 1 \xC2\xB1 0\n")),
           "2: expected (1 << 62) = -(1 << 62) \xC2\xB1 5 at the end, got 4611686018427387904 (-(1 << 62) is "
           "-4611686018427387904)\n"
           "3: expected acc = 1 \xC2\xB1 0 at the end, got 0\n");
}

TEST(run_an_expression_that_cannot_be_evaluated_fails) {
  const TestResult& r = run_counter("eval", "expect at end ap(300, 0) = 1\nexpect at end v[1] / v[0] = 0\n");
  CHECK_EQ(messages(r),
           "2: cannot evaluate ap(300, 0) = 1 at the end: axis parameter 300 is out of range (0..255)\n"
           "3: cannot evaluate v[1] / v[0] = 0 at the end: division by zero\n");
}

TEST(run_tests_that_cannot_run_are_errors) {
  // An unknown name: the caret under it, a suggestion from the program's labels.
  const TestResult& name = run_counter("name", "expect at end pc = hihg\nexpect at end accc = 1\n");
  CHECK(name.status == TestResult::Error);
  CHECK(has(name.error, "name.tmctest:2:20: error: no register, label or constant named 'hihg'; did you mean 'high'?\n"
                        " expect at end pc = hihg\n                    ^~~~\n"));
  CHECK(has(name.error, "name.tmctest:3:15: error: no register, label or constant named 'accc'; did you mean 'acc'?\n"));
  // The assembler's hexadecimal $FF is a register's name here ($acc, $pc): the caret under the $.
  const TestResult& hex = run_counter("hex", "expect at end v[3] = $FF\n");
  CHECK(hex.status == TestResult::Error);
  CHECK_EQ(hex.error, "hex.tmctest:2:22: error: no register named '$ff' ($pc, $sp, $acc, $x, $flags, $errors, $time, $steps); "
                      "hexadecimal is written 0xFF\n expect at end v[3] = $FF\n                      ^~~\n");
  // A program that does not assemble: the assembler's own diagnostics.
  put("broken.tmc", "SAPP 4, 0, 100\nSTOP\n");
  const TestResult& broken = run("broken", "program broken.tmc\nexpect at end acc = 0\n");
  CHECK(broken.status == TestResult::Error);
  CHECK(has(broken.error, "broken.tmc:1:1: error: unknown instruction mnemonic 'SAPP'"));
  // A missing program, and a missing test file.
  const TestResult& missing = run("missing", "program nowhere.tmc\n");
  CHECK(missing.status == TestResult::Error);
  CHECK(has(missing.error, "nowhere.tmc"));
  tmcl::testrun::ProgramCache cache;
  const TestResult none = tmcl::testrun::run_test_file("none.tmctest", {}, cache);
  CHECK(none.status == TestResult::Error);
  CHECK(has(none.error, "none.tmctest"));
}

TEST(run_a_skipped_test_is_not_run) {
  const TestResult& r = run("skipped", "program nowhere.tmc\nskip the module is not ready\n");
  CHECK(r.status == TestResult::Skip);
  CHECK_EQ(r.skip_reason, "the module is not ready");
}

TEST(run_images_run_without_labels) {
  std::vector<tmcl::Instruction> prog = {{19, 9, 0, 42}, {28, 0, 0, 0}};  // CALC LOAD, 42; STOP
  const std::vector<std::uint8_t> bin = tmcl::write_bin(prog);
  put("image.bin", std::string(bin.begin(), bin.end()));
  const TestResult& r = run("image", "program image.bin\nexpect at end acc = 42\nexpect at end halted stop\n");
  CHECK_EQ(r.error, "");
  CHECK_EQ(messages(r), "");
  CHECK(r.status == TestResult::Pass);
}

// A test file without a `target` line runs on the module a plain tmclrun would: the one the
// program's first line names unless -t was given (RunOptions::target_given).
TEST(run_the_module_is_the_programs_unless_t_is_given) {
  put("named.tmc", "// tmcl-target: tmcm-1110\n  GAP 4, 0    // the maximum speed's default: 1000 here, 51200 on generic\n  STOP\n");
  const std::string test = "program named.tmc\nexpect at end acc = 1000\n";
  CHECK(run("named", test).status == TestResult::Pass);
  tmcl::testrun::RunOptions o;
  o.target = "generic";
  o.target_given = true;
  CHECK_EQ(messages(run("named-t", test, o)), "2: expected acc = 1000 at the end, got 51200\n");
  CHECK(run("named-own", "program named.tmc\ntarget usb-2-sd\nexpect at end acc = 51200\n").status == TestResult::Pass);
}

// Two profiles with the same name are two modules: a test of each, sharing one cache, runs its
// program on its own (the loaded programs are kept by profile, not by its name).
TEST(run_profiles_of_one_name_do_not_share_a_program) {
  put("maxspeed.tmc", "  GAP 4, 0    // 1000 on the TMCM-1110, 51200 on the USB-2-SD\n  STOP\n");
  put("a/mine.profile", "tmcl-profile 1\nname mine\ntitle \"mine\"\nbased-on usb-2-sd\n");
  put("b/mine.profile", "tmcl-profile 1\nname mine\ntitle \"mine\"\nbased-on tmcm-1110\n");
  tmcl::testrun::ProgramCache cache;
  const TestResult a = tmcl::testrun::run_test_file(
      put("a/t.tmctest", "program ../maxspeed.tmc\ntarget ./mine.profile\nexpect at end acc = 51200\n"), {}, cache);
  const TestResult b = tmcl::testrun::run_test_file(
      put("b/t.tmctest", "program ../maxspeed.tmc\ntarget ./mine.profile\nexpect at end acc = 1000\n"), {}, cache);
  CHECK_EQ(a.error + messages(a), "");
  CHECK_EQ(b.error + messages(b), "");
  CHECK(a.status == TestResult::Pass);
  CHECK(b.status == TestResult::Pass);
}

// A bad `define` is shown at its line of the test file, the caret in its value; a note of the
// program's diagnostics that points at one points at that line; each test that shares the
// program sees its own lines. The test file's own mistakes come with them in one go: those of
// an expression's syntax, not names, which need the program's symbols.
TEST(run_define_errors_are_the_test_files) {
  put("speed.tmc", "Speed = 3\n  SGP 0, 2, Speed\n  STOP\n");
  tmcl::testrun::ProgramCache cache;
  const TestResult empty = tmcl::testrun::run_test_file(
      put("empty.tmctest", "program speed.tmc\ndefine X=\nexpect at 1s acc = 1 +\nexpect at end acc = Nope\n"), {}, cache);
  CHECK(empty.status == TestResult::Error);
  CHECK_EQ(empty.error,
           "empty.tmctest:2:10: error: expected a value, found end of line\n define X=\n          ^\n"
           "empty.tmctest:3:23: error: expression ends too early\n expect at 1s acc = 1 +\n                       ^\n");
  // The same program and definitions (one load), the define on another line of another file.
  const TestResult later = tmcl::testrun::run_test_file(
      put("later.tmctest", "program speed.tmc\n\n   define  X=   # empty\n"), {}, cache);
  CHECK_EQ(later.error, "later.tmctest:3:14: error: expected a value, found end of line\n    define  X=   # empty\n              ^\n");
  // An error inside the value, with its did-you-mean.
  const TestResult typo = run("typo", "program speed.tmc\ndefine Y=2 * Sped\n");
  CHECK_EQ(typo.error, "");
  put("uses.tmc", "  SGP 0, 2, Y\n  STOP\nSpeed = 1\n");
  const TestResult uses = run("uses", "program uses.tmc\ndefine Y=2 * Sped\nexpect at end v[0] = (1\n");
  CHECK_EQ(uses.error,
           "uses.tmctest:2:14: error: use of undefined symbol 'Sped'; did you mean 'Speed'?\n define Y=2 * Sped\n              ^~~~\n"
           "uses.tmctest:3:24: error: missing ')'\n expect at end v[0] = (1\n                        ^\n");
  // The program defines it again: the error is the program's, its note at the define's line.
  const TestResult twice = run("twice", "program speed.tmc\n  define Speed=5\n");
  CHECK_EQ(twice.error,
           "speed.tmc:1:1: error: constant 'Speed' redefined with a different value (3; it was 5)\n Speed = 3\n ^~~~~\n"
           "twice.tmctest:2:16: note: first defined here\n   define Speed=5\n                ^\n");
  // -D on the command line stays the command line's.
  tmcl::testrun::RunOptions o;
  o.asm_options.defines = {{"Z", "1 +"}};
  const TestResult cli = run("cli", "program speed.tmc\ndefine X=\n", o);
  CHECK(has(cli.error, "cli.tmctest:2:10: error: expected a value, found end of line\n"));
  CHECK(has(cli.error, "<command line -D Z>:1:4: error:"));
}

// `expect stall M at T ± W` (issue 34) holds when a stall of motor M lies in [T - W, T + W], ends
// included, whichever of its stalls it is; `expect never stall M` fails at the first.
TEST(run_stall_expectations_at_their_edges) {
  // Stop on stall into a hard stop at -3000, then again into the right one at 3000.
  put("stall.tmc",
      "        SAP 140, 0, 4\n"
      "        SAP 181, 0, 200\n"
      "        ROL 0, 400\n"
      "        WAIT TICKS, 0, 100\n"
      "        ROR 0, 400\n"
      "        WAIT TICKS, 0, 100\n"
      "        STOP\n");
  const std::string head = "program stall.tmc\ntarget tmcm-1110\nhardstop left 0 at -3000\nhardstop right 0 at 3000\n";
  // Find both instants from the failures of a test that expects them at 0.
  const TestResult probe = run("stall-probe", head + "expect stall 0 at 0s\n");
  CHECK_EQ(probe.failures.size(), 1u);
  CHECK(!probe.failures.empty() && probe.failures[0].update != "");
  const std::string first = probe.failures.empty() ? "" : probe.failures[0].update;  // the stall nearest 0
  const auto t1 = tmcl::parse_duration(first);
  CHECK(t1.has_value() && *t1 > 0);
  const std::string at = std::to_string(*t1) + "us";
  CHECK(run("stall-exact", head + "expect stall 0 at " + at + "\n").status == TestResult::Pass);
  CHECK(run("stall-edge", head + "expect stall 0 at " + std::to_string(*t1 + 5) + "us ± 5us\n").status == TestResult::Pass);
  const TestResult out = run("stall-out", head + "expect stall 0 at " + std::to_string(*t1 + 6) + "us ± 5us\n");
  CHECK(out.status == TestResult::Fail);
  CHECK_EQ(out.failures.size(), 1u);
  // The second stall, at the right end after 1 s, is met too: any of the motor's stalls counts.
  CHECK(run("stall-second", head + "expect stall 0 at 2s ± 1s\nexpect never stall 1\nexpect never stall 2\n").status ==
        TestResult::Pass);
  CHECK_EQ(messages(run("stall-never", head + "expect never stall 0\n")),
           "5: expected motor 0 never to stall, it stalled at " + first + "\n");
  // 181 = 0: the motor pushes on at the hard stop and never stalls.
  put("nostop.tmc", "        SAP 140, 0, 4\n        ROL 0, 400\n        WAIT TICKS, 0, 100\n        STOP\n");
  CHECK(run("stall-none", "program nostop.tmc\ntarget tmcm-1110\nhardstop left 0 at -3000\nexpect never stall 0\n").status ==
        TestResult::Pass);
}
