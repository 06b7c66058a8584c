// Coverage (Coverage, lcov_tracefile, coverage_summary): line, branch and function counts checked
// exactly on a small program with a subroutine in an include file, an interrupt handler, a loop
// and a branch never taken; summed over tests and over programs that share a file.
#include "check.hpp"
#include "helpers.hpp"

using namespace runtest;
using namespace tmcl::testrun;

namespace {

// Line by line what runs: the loop three times (DJNZ jumps twice), JC EQ always (line 10 never
// runs), the timer's handler twice during the 250 ms wait, the subroutine in lib.tmc three times.
const char* kMain =
    "        VECT 0, tick           // 1\n"
    "        SGP 0, 3, 100          // 2  timer 0 every 100 ms\n"
    "        EI 0\n"
    "        EI 255\n"
    "        SGP 0, 2, 3            // 5  v0 = 3\n"
    "loop:   CSUB twice             // 6\n"
    "        DJNZ 0, loop           // 7\n"
    "        COMP 6                 // 8\n"
    "        JC EQ, six             // 9\n"
    "        SGP 5, 2, 1            // 10 never\n"
    "six:    WAIT TICKS, 0, 25      // 11 250 ms\n"
    "        STOP                   // 12\n"
    "tick:   CALCV ADD, 1, 1        // 13\n"
    "        RETI                   // 14\n"
    "#include \"lib.tmc\"\n";
const char* kLib =
    "// twice: acc += 2\n"
    "twice:  CALC ADD, 1\n"
    "        CALC ADD, 1\n"
    "        RSUB\n";

Coverage covered(const std::vector<std::string>& tests) {
  put("main.tmc", kMain);
  put("lib.tmc", kLib);
  RunOptions o;
  o.coverage = true;
  ProgramCache cache;
  Coverage c;
  for (std::size_t i = 0; i < tests.size(); ++i) {
    const std::string name = "cov" + std::to_string(i) + ".tmctest";
    put(name, tests[i]);
    TestResult r = run_test_file(name, o, cache);
    CHECK_EQ(r.error, "");
    CHECK_EQ(messages(r), "");
    c.add(r);
  }
  return c;
}

const char* kTest = "program main.tmc\nexpect at end v[1] = 2\nexpect at end acc = 6\nexpect at end v[5] = 0\n";

}  // namespace

TEST(coverage_counts_lines_branches_and_functions_exactly) {
  const std::string dir = scratch();
  CHECK_EQ(lcov_tracefile(covered({kTest})),
           "SF:" + dir + "/lib.tmc\n"
           "FN:2,twice\nFNDA:3,twice\nFNF:1\nFNH:1\n"
           "BRF:0\nBRH:0\n"
           "DA:2,3\nDA:3,3\nDA:4,3\n"
           "LF:3\nLH:3\n"
           "end_of_record\n"
           "SF:" + dir + "/main.tmc\n"
           "FN:13,tick\nFNDA:2,tick\nFNF:1\nFNH:1\n"
           "BRDA:7,0,0,2\nBRDA:7,0,1,1\nBRDA:9,0,0,1\nBRDA:9,0,1,0\n"
           "BRF:4\nBRH:3\n"
           "DA:1,1\nDA:2,1\nDA:3,1\nDA:4,1\nDA:5,1\nDA:6,3\nDA:7,3\nDA:8,1\nDA:9,1\nDA:10,0\nDA:11,1\nDA:12,1\nDA:13,2\n"
           "DA:14,2\n"
           "LF:14\nLH:13\n"
           "end_of_record\n");
}

TEST(coverage_sums_tests_and_programs_that_share_a_file) {
  // Two tests of main.tmc double every count; other.tmc calls lib.tmc's subroutine once more.
  put("other.tmc", "CSUB twice\nSTOP\n#include \"lib.tmc\"\n");
  const Coverage c = covered({kTest, kTest, "program other.tmc\nexpect at end acc = 2\n"});
  const auto files = c.files();
  CHECK_EQ(files.size(), 3u);
  const Coverage::File& lib = files.at(scratch() + "/lib.tmc");
  CHECK_EQ(lib.lines.at(2), 7u);
  CHECK_EQ(lib.functions.at("twice").calls, 7u);
  const Coverage::File& main = files.at(scratch() + "/main.tmc");
  CHECK_EQ(main.lines.at(6), 6u);
  CHECK_EQ(main.lines.at(10), 0u);
  CHECK_EQ(main.branches.at({7, 0}).taken, 4u);
  CHECK_EQ(main.branches.at({7, 0}).not_taken, 2u);
  CHECK_EQ(main.functions.at("tick").calls, 4u);
  CHECK_EQ(files.at(scratch() + "/other.tmc").lines.size(), 2u);
}

TEST(coverage_a_branch_that_never_ran_is_a_dash) {
  // The loop below is jumped over: its DJNZ never runs.
  put("skip.tmc", "JA done\nback: DJNZ 0, back\ndone: STOP\n");
  const std::string t = lcov_tracefile(covered({"program skip.tmc\nexpect at end halted stop\n"}));
  CHECK(has(t, "SF:" + scratch() + "/skip.tmc\nFNF:0\nFNH:0\nBRDA:2,0,0,-\nBRDA:2,0,1,-\nBRF:2\nBRH:0\n"
                "DA:1,1\nDA:2,0\nDA:3,1\nLF:3\nLH:2\nend_of_record\n"));
}

TEST(coverage_a_conditional_call_counts_as_a_call) {
  // sub runs twice: once by a taken CALL EQ, once by CSUB. A CALL is a call, not a jump into sub.
  put("calls.tmc", "COMP 0\nCALL EQ, sub\nCSUB sub\nSTOP\nsub: CALC ADD, 1\nRSUB\n");
  const std::string t = lcov_tracefile(covered({"program calls.tmc\nexpect at end acc = 2\n"}));
  CHECK(has(t, "FN:5,sub\nFNDA:2,sub\nFNF:1\nFNH:1\n"));
  CHECK(has(t, "DA:5,2\n"));
  // A jump back to a subroutine's entry still is not a call of it: sub runs twice, called once.
  put("again.tmc", "CSUB sub\nSTOP\nsub: CALC ADD, 1\nCOMP 1\nJC EQ, sub\nRSUB\n");
  const std::string u = lcov_tracefile(covered({"program again.tmc\nexpect at end acc = 2\n"}));
  CHECK(has(u, "FN:3,sub\nFNDA:1,sub\n"));
  CHECK(has(u, "DA:3,2\n"));
}

TEST(coverage_summary_lists_what_never_ran) {
  CHECK_EQ(coverage_summary(covered({kTest})),
           "coverage: lines 16/17 (94.1%), branches 3/4 (75.0%) in 2 files\n"
           "  lib.tmc: lines 3/3 (100.0%), branches 0/0\n"
           "  main.tmc: lines 13/14 (92.9%), branches 3/4 (75.0%)\n"
           "    never run: 10\n"
           "    branches always taken: 9\n");  // JC EQ, six: acc is always 6
  // A branch that ran and never jumped, one that always jumped, one that never ran (its line is
  // listed as never run, not again as a branch).
  put("branchy.tmc", "CALC LOAD, 1\nCOMP 5\nJC EQ, 3\nJC NE, 4\nSTOP\nJC EQ, 0\n");
  CHECK(has(coverage_summary(covered({"program branchy.tmc\n"})),
            "  branchy.tmc: lines 5/6 (83.3%), branches 2/6 (33.3%)\n    never run: 6\n    branches never taken: 3\n"
            "    branches always taken: 4\n"));
  put("gaps.tmc", "JA 4\nCALC ADD, 1\nCALC ADD, 1\nCALC ADD, 1\nSTOP\nCALC ADD, 1\n");
  CHECK(has(coverage_summary(covered({"program gaps.tmc\n"})), "  gaps.tmc: lines 2/6 (33.3%), branches 0/0\n    never run: 2-4, 6\n"));
}

TEST(coverage_is_empty_without_counts) {
  Coverage c;
  TestResult r;  // an error result: no program, no counts
  c.add(r);
  CHECK_EQ(lcov_tracefile(c), "");
  CHECK_EQ(coverage_summary(c), "coverage: lines 0/0, branches 0/0 in 0 files\n");
}
