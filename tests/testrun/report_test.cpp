// What a run reports (tmcl/testrun.hpp): the JUnit XML exactly (escaping included), the lines of
// `tmclrun --test` and its closing line, --update's rewritten files, the order of results with
// several tests at a time, and which files a folder gives.
#include <cstdio>

#include "check.hpp"
#include "os_test.hpp"
#include "helpers.hpp"
#include "text_file.hpp"

using namespace runtest;
using namespace tmcl::testrun;

namespace {

SuiteResult sample() {
  SuiteResult s;
  TestResult pass;
  pass.path = "tests/motion/homing.tmctest";
  pass.seconds = 0.0125;
  TestResult fail;
  fail.status = TestResult::Fail;
  fail.path = "cycles.tmctest";
  fail.seconds = 0.25;
  Failure f1;
  f1.line = 7;
  f1.message = "expected v[3] < 7 & v[4] > \"2\" at 2.5s, got 9";
  f1.where = "the program was at prog.tmc:14 (loop+2): JA loop";
  Failure f2;
  f2.line = 9;
  f2.message = "expected no fault, got one\x01";
  fail.failures = {f1, f2};
  TestResult error;
  error.status = TestResult::Error;
  error.path = "bad.tmctest";
  error.error = "bad.tmctest:1:1: error: unknown line 'programm'\n programm p.tmc\n ^~~~~~~~\n";
  TestResult skip;
  skip.status = TestResult::Skip;
  skip.path = "tests/later.tmctest";
  skip.skip_reason = "needs <hardware>";
  s.tests = {pass, fail, error, skip};
  s.passed = s.failed = s.errors = s.skipped = 1;
  s.seconds = 1.5;
  s.timestamp = "2026-12-03T08:00:00";
  return s;
}

// Runs run_command and returns what it printed on standard output.
std::string command(const std::vector<std::string>& paths, const SuiteOptions& o, int& status) {
  tmcl_test::CapturedFile out, err;
  status = run_command(paths, o, out.get(), err.get());
  return out.text();
}

}  // namespace

TEST(report_junit_xml_exactly) {
  CHECK_EQ(junit_xml(sample(), "tmclrun"),
           "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
           "<testsuites name=\"tmclrun\" tests=\"4\" failures=\"1\" errors=\"1\" skipped=\"1\" time=\"1.500\">\n"
           "  <testsuite name=\"tmclrun\" tests=\"4\" failures=\"1\" errors=\"1\" skipped=\"1\" time=\"1.500\" "
           "timestamp=\"2026-12-03T08:00:00\">\n"
           "    <testcase classname=\"tests.motion\" name=\"homing\" file=\"tests/motion/homing.tmctest\" time=\"0.013\"/>\n"
           "    <testcase classname=\"tmclrun\" name=\"cycles\" file=\"cycles.tmctest\" time=\"0.250\">\n"
           "      <failure message=\"2 expectations failed; the first: expected v[3] &lt; 7 &amp; v[4] &gt; &quot;2&quot; at "
           "2.5s, got 9\" type=\"expectation\">cycles.tmctest:7: expected v[3] &lt; 7 &amp; v[4] &gt; &quot;2&quot; at 2.5s, "
           "got 9\nthe program was at prog.tmc:14 (loop+2): JA loop\ncycles.tmctest:9: expected no fault, got one\n"
           "</failure>\n"
           "    </testcase>\n"
           "    <testcase classname=\"tmclrun\" name=\"bad\" file=\"bad.tmctest\" time=\"0.000\">\n"
           "      <error message=\"the test could not run (a bad test file or program)\" type=\"error\">bad.tmctest:1:1: "
           "error: unknown line &apos;programm&apos;\n programm p.tmc\n ^~~~~~~~\n</error>\n"
           "    </testcase>\n"
           "    <testcase classname=\"tests\" name=\"later\" file=\"tests/later.tmctest\" time=\"0.000\">\n"
           "      <skipped message=\"needs &lt;hardware&gt;\"/>\n"
           "    </testcase>\n"
           "  </testsuite>\n"
           "</testsuites>\n");
}

TEST(report_lines_and_the_closing_line) {
  const SuiteResult s = sample();
  CHECK_EQ(result_text(s.tests[0]), "PASS tests/motion/homing.tmctest\n");
  CHECK_EQ(result_text(s.tests[1]),
           "FAIL cycles.tmctest\n"
           "  cycles.tmctest:7: expected v[3] < 7 & v[4] > \"2\" at 2.5s, got 9\n"
           "    the program was at prog.tmc:14 (loop+2): JA loop\n"
           "  cycles.tmctest:9: expected no fault, got one\x01\n");
  CHECK_EQ(result_text(s.tests[2]), "ERROR bad.tmctest\n");
  CHECK_EQ(result_text(s.tests[3]), "SKIP tests/later.tmctest (needs <hardware>)\n");
  CHECK_EQ(summary_line(s), "1 passed, 1 failed, 1 skipped, 1 error\n");
  SuiteResult ok;
  ok.passed = 3;
  CHECK_EQ(summary_line(ok), "3 passed, 0 failed\n");
}

TEST(report_update_rewrites_failing_values_and_says_which) {
  put("upd/prog.tmc", "CALC LOAD, 5\nSGP 2, 2, 9\nSTOP\n");
  put("upd/a.tmctest",
      "program prog.tmc\r\n"
      "expect at end acc = 4    # was right once\r\n"
      "expect at 10us acc = 1   # the state after the instruction under way at 10 us\r\n"
      "expect at end v[2] = 9\r\n"
      "expect at end v[2] = acc \xC2\xB1 1\r\n"
      "expect at end acc < 3\r\n"
      "expect at end halted fault\r\n");
  SuiteOptions o;
  o.update = true;
  int status = -1;
  const std::string out = command({"upd"}, o, status);
  CHECK_EQ(out,
           "FAIL upd/a.tmctest\n"
           "  upd/a.tmctest:2: expected acc = 4 at the end, got 5\n"
           "    the program was at upd/prog.tmc:3: STOP\n"
           "  upd/a.tmctest:3: expected acc = 1 at 10us, got 5\n"
           "    the program was at upd/prog.tmc:2: SGP 2, 2, 9\n"
           "  upd/a.tmctest:5: expected v[2] = acc \xC2\xB1 1 at the end, got 9 (acc is 5)\n"
           "    the program was at upd/prog.tmc:3: STOP\n"
           "  upd/a.tmctest:6: expected acc < 3 at the end, got 5\n"
           "    the program was at upd/prog.tmc:3: STOP\n"
           "  upd/a.tmctest:7: expected the run to end with fault, but the run ended at 0.000060s (STOP at upd/prog.tmc:3)\n"
           "    the program was at upd/prog.tmc:3: STOP\n"
           "updated upd/a.tmctest:2: 5 (was 4)\n"
           "updated upd/a.tmctest:3: 5 (was 1)\n"
           "not updated: upd/a.tmctest:5: its value 'acc' is an expression; only a number or a duration is rewritten\n"
           "not updated: upd/a.tmctest:6: only an '=' expectation is rewritten; this one compares with '<'\n"
           "updated upd/a.tmctest:7: stop (was fault)\n"
           "0 passed, 1 failed\n");
  CHECK_EQ(status, 1);  // two failures could not be rewritten
  CHECK_EQ(tmcl_test::read_text("upd/a.tmctest"),
           "program prog.tmc\r\n"
           "expect at end acc = 5    # was right once\r\n"
           "expect at 10us acc = 5   # the state after the instruction under way at 10 us\r\n"
           "expect at end v[2] = 9\r\n"
           "expect at end v[2] = acc \xC2\xB1 1\r\n"
           "expect at end acc < 3\r\n"
           "expect at end halted stop\r\n");
  // When every failure was rewritten, the files now describe the program: status 0.
  put("upd2/prog.tmc", "CALC LOAD, 5\nSTOP\n");
  put("upd2/b.tmctest", "program prog.tmc\nexpect at end acc = 4\n");
  command({"upd2"}, o, status);
  CHECK_EQ(status, 0);
  CHECK_EQ(tmcl_test::read_text("upd2/b.tmctest"), "program prog.tmc\nexpect at end acc = 5\n");
  o.update = false;
  CHECK_EQ(command({"upd2"}, o, status), "PASS upd2/b.tmctest\n1 passed, 0 failed\n");
  CHECK_EQ(status, 0);
}

TEST(report_results_come_in_file_order_whatever_the_jobs) {
  put("many/prog.tmc", "CALC LOAD, N\nWAIT TICKS, 0, N\nSTOP\n");
  std::string expected;
  for (int i = 0; i < 24; ++i) {
    const std::string name = "many/t" + std::string(i < 10 ? "0" : "") + std::to_string(i) + ".tmctest";
    put(name, "program prog.tmc\ndefine N=" + std::to_string(24 - i) + "\nexpect at end acc = " +
                  std::to_string(i % 5 == 0 ? 0 : 24 - i) + "\n");
    expected += (i % 5 == 0 ? "FAIL " : "PASS ") + name + "\n";
    if (i % 5 == 0)
      expected += "  " + name + ":3: expected acc = 0 at the end, got " + std::to_string(24 - i) +
                  "\n    the program was at many/prog.tmc:3: STOP\n";
  }
  expected += "19 passed, 5 failed\n";
  for (int jobs : {1, 4}) {
    SuiteOptions o;
    o.jobs = jobs;
    int status = -1;
    CHECK_EQ(command({"many"}, o, status), expected);
    CHECK_EQ(status, 1);
  }
}

TEST(report_which_files_run) {
  put("found/b.tmctest", "");
  put("found/a.tmctest", "");
  put("found/sub/c.tmctest", "");
  put("found/notes.txt", "");
  std::vector<std::string> files;
  std::string error;
  CHECK(find_tests({"found", "./found/a.tmctest", "found/notes.txt"}, files, error));
  CHECK_EQ(error, "");
  CHECK_EQ(files.size(), 4u);
  CHECK_EQ(files[0], "found/a.tmctest");
  CHECK_EQ(files[1], "found/b.tmctest");
  CHECK_EQ(files[2], "found/sub/c.tmctest");
  CHECK_EQ(files[3], "found/notes.txt");  // named on its own: run as a test file
  CHECK(!find_tests({"found", "nowhere"}, files, error));
  CHECK_EQ(error, "'nowhere': no such file or folder");
  put("empty/readme.txt", "");
  int status = -1;
  CHECK_EQ(command({"empty"}, {}, status), "");
  CHECK_EQ(status, 65);
}
