// Tests for TMCL programs (docs/testing.md): a test file (*.tmctest) names a program, a module
// and a time limit, may change the program's inputs at instants as a scenario does, and states
// what must hold at instants of simulated time, at the end of the run, and throughout it. This
// library reads test files (with the assembler's kind of diagnostics), runs them on the VM, and
// reports: a line per test, JUnit XML, lcov coverage with branches, and rewritten expectations
// (--update). `tmclrun --test`, `tmclctl PORT test` and the language server are its front ends.
//
//   # homing.tmctest
//   program homing.tmc            relative to this file; .tmc, .bin or .dgm
//   target usb-2-sd               default: as for tmclrun (-t, else the program's first line)
//   max-time 60s                  the run ends here unless the program stops first (default 10min)
//   at 2s input 0 = 1             any scenario line (tmcl/scenario.hpp)
//   expect at 1.5s position 0 = 0 ± 10
//   expect at end acc = 0
//   expect at end halted stop     stop | fault | max-time | blocked
//   expect never fault
//   expect no warnings
//   expect stall 0 at 1.769712s   motor 0 stops on stall at that instant (± TOLERANCE: within it)
//   expect never stall 1          motor 1 never stops on stall
#pragma once

#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tmcl/asm/assembler.hpp"
#include "tmcl/diag_text.hpp"
#include "tmcl/expr.hpp"
#include "tmcl/vm.hpp"

namespace tmcl::testrun {

inline constexpr SimTime kDefaultMaxTime = 600 * 1000 * kUsPerMs;  // 10 minutes

// ---- a test file ----
enum class Compare : std::uint8_t { Eq, Ne, Lt, Le, Gt, Ge };
std::string_view compare_text(Compare c);  // "=", "!=", "<", ...

// How the run ended, as `expect at end halted` names it.
enum class End : std::uint8_t { Stop, Fault, MaxTime, Blocked };
std::string_view end_name(End e);  // "stop", "fault", "max-time", "blocked"

struct Expectation {
  enum Kind : std::uint8_t { At, AtEnd, Halted, NeverFault, NoWarnings, NoNotes, Stall, NeverStall } kind = At;
  int line = 0;          // in the test file
  int col = 0;           // of the word after `expect`
  SimTime at = 0;        // At, Stall: the instant
  // Stall, NeverStall: the motor whose stall event (stop on stall, docs/motion.md) is meant; a
  // Stall holds when one of its stalls lies within `within` of `at` (`right` is the instant as
  // written, at `right_col`, for --update; `tolerance` the tolerance as written).
  int motor = 0;
  SimTime within = 0;
  std::string when;      // the instant as written ("1.5s"), or "end"
  // At, AtEnd: LEFT OP RIGHT [± TOLERANCE], each an expression (tmcl/expr.hpp)
  std::string left, right, tolerance;
  int left_col = 0, right_col = 0, tolerance_col = 0;  // 1-based columns in the line
  Compare op = Compare::Eq;
  Expr left_expr, right_expr, tolerance_expr;  // bound to the program by bind_expectations
  End halted = End::Stop;  // Halted
  std::string text;        // as written after `expect`, without a comment
};

// LEFT OP RIGHT [± TOLERANCE] as written, and whether it holds for these values.
std::string condition_text(const Expectation& e);
bool holds(const Expectation& e, std::int64_t left, std::int64_t right, std::int64_t tolerance);

struct Define {  // define NAME=VALUE (as -D)
  std::string name, value;
  int line = 0, col = 0;  // where VALUE starts in the test file (a bad value is shown there)
};

struct TestFile {
  std::string path;     // as given
  std::string program;  // the program's path, relative to the current folder
  int program_line = 0;
  std::string target;   // as written; empty: as for tmclrun (see module)
  int target_line = 0;
  // The module the test runs on, as resolve_target takes it: the `target` line (a relative
  // profile path made relative to the current folder), else, as for a plain tmclrun, -t when
  // given, else what the program's first line names (// tmcl-target: NAME), else -t's default.
  std::string module;
  std::string motion;   // empty: the module's default core
  SimTime instr_time = -1;  // -1: RunOptions::instr_time
  SimTime max_time = kDefaultMaxTime;
  bool max_time_given = false;
  std::vector<Define> defines;
  std::vector<InputEvent> inputs;  // the scenario lines
  std::vector<Expectation> expects;
  std::string skip;  // skip REASON: not run, reported as skipped
  bool skipped = false;
  std::vector<std::string> lines;  // the file's text, line by line
};

// Reads a test file. Every bad line is a diagnostic (FILE:LINE:COL, the line, a caret, a "did
// you mean"), all of them in line order; false when there is any. A file without a `target`
// line runs on `default_target` when `target_given` (tmclrun -t, tmclctl's module), else on
// what its program's first line names, else on `default_target` (TestFile::module); that module
// also numbers the scenario lines' motors.
bool parse_test_file(const std::string& text, const std::string& path, const std::string& default_target,
                     TestFile& out, std::vector<FileDiag>& diags, bool target_given);
// The profile of TestFile::module (a name or a profile file, as for -t; targets.hpp); null with
// `error` when there is none such.
const Profile* test_profile(const TestFile& test, std::string* error = nullptr);

// ---- the program a test runs ----
// A program loaded once for every test that runs it with the same module and definitions.
struct Program {
  ProgramInfo info;
  const Profile* profile = nullptr;
  std::vector<std::string> places;          // per address "prog.tmc:12" (the VM's source_of)
  std::vector<std::uint8_t> handler_code;   // the analysis' handler regions (Vm::handler_code)
  std::vector<std::string> paths;           // per file of info.files: its absolute path, or "" (bundled)
  struct Function {
    std::string name;
    std::int32_t entry = 0;
  };
  std::vector<Function> functions;          // subroutines and interrupt handlers
  std::string messages;                     // the assembler's warnings
};

// ---- running ----
struct RunOptions {
  std::string target = "generic";  // for files without `target` (tmclrun -t) ...
  bool target_given = false;       // ... and whose program's first line names none, unless -t was given
  std::string motion;              // tmclrun --motion
  SimTime instr_time = 20;         // for files without `instr-time`
  bool max_time_given = false;     // tmclrun --max-time: replaces the files' limits
  SimTime max_time = kDefaultMaxTime;
  AsmOptions asm_options;          // -I, -D, -W (the files' `define`s are added)
  bool strict = false;             // a run-time warning is a fault (tmclrun --strict)
  bool coverage = false;           // count executions (Coverage)
  int error_limit = kDefaultErrorLimit;
  std::string tool = "tmclrun";    // names the program in its messages
};

// One unmet expectation.
struct Failure {
  int line = 0;          // the expectation's line in the test file
  std::string message;   // "expected v[3] = 7 at 2.5s, got 6"
  std::string where;     // "the program was at homing.tmc:14 (loop+2):   JA loop", or ""
  std::string update;    // --update: the new text of the expectation's value, or "" (cannot)
  int update_col = 0;    // where that value starts in the line (1-based) ...
  int update_len = 0;    // ... and its length
  std::string no_update;  // --update, when `update` is "": why the failure is not rewritten
};

struct TestResult {
  enum Status : std::uint8_t { Pass, Fail, Error, Skip } status = Pass;
  std::string path;        // the test file as found
  std::vector<Failure> failures;
  std::string error;       // Error: the diagnostics (a bad test file or program), rendered
  std::string skip_reason;
  std::string messages;    // the assembler's warnings for the program, rendered
  std::vector<std::string> notes;  // "FILE:LINE: note: ..." (what a module cannot check)
  double seconds = 0;      // wall time of the test
  SimTime ended_at = 0;    // simulated instant the run ended
  std::shared_ptr<const Program> program;
  std::vector<std::uint64_t> executed, taken;  // coverage counts per address (RunOptions::coverage)
};

// Loads programs once per (file, module, definitions); safe to share between threads.
class ProgramCache {
 public:
  ProgramCache();
  ~ProgramCache();
  // The program of `test`, or null with the rendered diagnostics in `error`, except those of the
  // test's `define` lines, which are diagnostics of the test file at those lines in `test_diags`.
  std::shared_ptr<const Program> get(const TestFile& test, const Profile& profile, const RunOptions& options,
                                     std::string& error, std::vector<FileDiag>& test_diags);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Binds every expectation's expressions to the program's labels and constants; false with a
// diagnostic for each one that does not parse.
bool bind_expectations(TestFile& test, const ProgramInfo& info, std::vector<FileDiag>& diags);
// Without a program (it does not assemble): the expressions' mistakes that need no names (a
// missing operand, an unbalanced parenthesis); a name is taken for a known one.
bool check_expectations(const TestFile& test, std::vector<FileDiag>& diags);

// Reads, checks and runs one test file.
TestResult run_test_file(const std::string& path, const RunOptions& options, ProgramCache& cache);
// The same with the file's text at hand (an editor's buffer).
TestResult run_test_source(const std::string& path, const std::string& text, const RunOptions& options, ProgramCache& cache);
// Reads a test file's text and binds it to its program (loaded through `cache`); every problem
// is a diagnostic of the test file in `diags`, except the program's own, rendered in
// `program_error`. The program is null when it could not be loaded.
std::shared_ptr<const Program> check_test_source(const std::string& path, const std::string& text, const RunOptions& options,
                                                 ProgramCache& cache, TestFile& test, std::vector<FileDiag>& diags,
                                                 std::string& program_error);
// Runs a parsed and bound test on the VM.
TestResult run_test(const TestFile& test, std::shared_ptr<const Program> program, const RunOptions& options);

// ---- on a module (tmclctl PORT test) ----
// A module as a test runs on it: expressions read its state over the host protocol (ExprReader),
// and it stores, starts, watches and stops the program.
class Module : public ExprReader {
 public:
  // Stores `program` (and verifies it), then starts it from address 0; false with `error`.
  virtual bool load_and_start(const std::vector<Instruction>& program, std::string& error) = 0;
  // Whether the program still runs; false with `error` when the module does not answer.
  virtual bool running(bool& out, std::string& error) = 0;
  virtual void stop() = 0;  // stops the program (max-time reached)
  virtual bool cancelled() const { return false; }  // Ctrl-C: the test ends as an error
};
// Runs one test file on the module by the wall clock: values polled when their instant comes,
// then the end awaited (the program stops, or max-time). A test that changes inputs in time, or
// written for another module than options.target, is skipped; `switch` lines (the machine) and
// `never fault` and `no warnings` become notes (a module simulates none of them).
TestResult run_test_live(const std::string& path, const RunOptions& options, ProgramCache& cache, Module& module);

// ---- several tests ----
// The test files named: files as given, folders searched for *.tmctest (sorted). A path that
// does not exist is an error in `error`.
bool find_tests(const std::vector<std::string>& paths, std::vector<std::string>& out, std::string& error);

struct SuiteOptions {
  RunOptions run;
  int jobs = 0;            // tests at a time; 0: one per core
  std::string junit;      // --junit FILE
  std::string coverage;   // --coverage FILE (lcov)
  bool coverage_summary = false;
  bool update = false;
  // How one test runs: empty, on the VM (run_test_file); tmclctl runs them on a module.
  std::function<TestResult(const std::string& path, ProgramCache& cache)> run_one;
};

struct SuiteResult {
  std::vector<TestResult> tests;  // in the order of the files
  int passed = 0, failed = 0, errors = 0, skipped = 0;
  int updated = 0;  // --update: failed tests rewritten to what the run did (no longer in `failed`)
  double seconds = 0;
  std::string timestamp;  // when the run started, UTC: "2026-12-03T08:00:00" (JUnit's timestamp)
};

// Runs the tests `jobs` at a time, calling `done` for each result in the files' order as soon as
// it and every one before it have finished.
SuiteResult run_suite(const std::vector<std::string>& files, const SuiteOptions& options,
                      const std::function<void(const TestResult&)>& done);

// The text of one test's result: "PASS path" or "FAIL path" with a line per failure, "SKIP path
// (reason)", or "ERROR path" with the diagnostics.
std::string result_text(const TestResult& r);
// "N passed, N failed" (", N skipped", ", N errors" where some were).
std::string summary_line(const SuiteResult& s);

// `tmclrun --test`: runs `paths`, prints to `out` (results, summary) and `err` (diagnostics of
// files that could not be written), writes the reports. The exit status: 0 every test passed
// (or was skipped), 1 a test failed, 65 a test file or its program is bad, 74 a report could
// not be written.
int run_command(const std::vector<std::string>& paths, const SuiteOptions& options, std::FILE* out, std::FILE* err);

// ---- reports ----
// JUnit XML as Jenkins, GitLab and GitHub read it: one testsuite, one testcase per test file.
std::string junit_xml(const SuiteResult& s, const std::string& suite_name);

// Coverage summed over tests: the counts of each program (add), and per source file and line
// (files), which is how the reports show them; tests of different programs that share a file
// (an include) add up in its lines.
class Coverage {
 public:
  void add(const TestResult& r);

  struct Branch {
    bool ran = false;  // the branch instruction ran at least once
    std::uint64_t taken = 0, not_taken = 0;
  };
  struct Function {
    int line = 0;
    std::uint64_t calls = 0;  // entries: runs of its first instruction less jumps to it
  };
  struct File {
    std::map<int, std::uint64_t> lines;                // line -> runs of its instructions
    std::map<std::pair<int, int>, Branch> branches;    // (line, block) -> outcomes
    std::map<std::string, Function> functions;         // by name
  };
  // By absolute path; files not on disk (bundled includes) are left out.
  std::map<std::string, File> files() const;

 private:
  struct Sums {
    std::shared_ptr<const Program> program;
    std::vector<std::uint64_t> executed, taken;
  };
  std::vector<Sums> sums_;
};
std::string lcov_tracefile(const Coverage& c);
// Lines and branches covered per file, then the lines never run and the lines of branches that
// ran with an outcome no test saw ("branches never taken", "branches always taken").
std::string coverage_summary(const Coverage& c);

}  // namespace tmcl::testrun
