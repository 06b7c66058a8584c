// Running a test on a module (tmclctl PORT test): a smoke test on hardware, not a replacement
// for the simulated run. The program is downloaded and started; when an expectation's instant
// comes by the wall clock its values are polled over the host protocol (each read a request,
// so an instant is met within a few milliseconds at best, and the failure says when the values
// were read); then the run waits for the program to stop, or for max-time, and checks the rest.
// A module cannot be given inputs, and reports no faults or run-time warnings: a test with
// input changes is skipped (one with only machine lines -- switches, hard stops, loads at positions
// -- runs with a note that the machine must match), and `expect never fault` / `expect no warnings` are noted as not
// checked.
#include <algorithm>
#include <chrono>
#include <thread>

#include "tmcl/duration.hpp"
#include "tmcl/fileio.hpp"
#include "tmcl/numbers.hpp"
#include "tmcl/targets.hpp"
#include "tmcl/testrun.hpp"

namespace tmcl::testrun {

namespace {

using Clock = std::chrono::steady_clock;

// The module as expressions read it, with `time` the wall-clock time since the program started.
class TimedReader final : public ExprReader {
 public:
  TimedReader(Module& m, Clock::time_point t0) : m_(m), t0_(t0) {}
  int motors() const override { return m_.motors(); }
  bool reg(Reg r, std::int64_t& out, std::string& error) override {
    if (r != Time) return m_.reg(r, out, error);
    out = std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - t0_).count();
    return true;
  }
  bool var(int n, std::int64_t& out, std::string& error) override { return m_.var(n, out, error); }
  bool axis(int p, int motor, std::int64_t& out, std::string& error) override { return m_.axis(p, motor, out, error); }
  bool global(int bank, int p, std::int64_t& out, std::string& error) override { return m_.global(bank, p, out, error); }
  bool port(int kind, int n, std::int64_t& out, std::string& error) override { return m_.port(kind, n, out, error); }

 private:
  Module& m_;
  Clock::time_point t0_;
};

}  // namespace

TestResult run_test_live(const std::string& path, const RunOptions& options, ProgramCache& cache, Module& module) {
  const auto t_begin = Clock::now();
  TestResult r;
  r.path = path;
  auto finish = [&](TestResult::Status status) {
    r.status = status;
    r.seconds = std::chrono::duration<double>(Clock::now() - t_begin).count();
    return r;
  };
  std::vector<std::uint8_t> bytes;
  std::string err;
  if (!read_file(path, bytes, err, kMaxScenarioBytes)) {
    r.error = options.tool + ": error: " + err + "\n";
    return finish(TestResult::Error);
  }
  const std::string text(bytes.begin(), bytes.end());
  TestFile t;
  std::vector<FileDiag> diags;
  // Switches, hard stops and loads at positions (`switch left 0 at -20000`, `hardstop left 0 at
  // -20000`) describe the machine, which the hardware has: such a test runs, with a note that the machine must match. Input changes in time are
  // what a host cannot make: such a test is skipped.
  const bool parsed = parse_test_file(text, path, options.target, t, diags, options.target_given);
  const auto changes = std::find_if(t.inputs.begin(), t.inputs.end(), [](const InputEvent& e) { return !e.placed_kind(); });
  if (parsed && (t.skipped || changes != t.inputs.end() || (!t.target.empty() && test_profile(t) != resolve_target(options.target).profile))) {
    r.skip_reason = t.skipped ? t.skip
                    : changes != t.inputs.end()
                        ? "its scenario lines change the program's inputs, which a module's host cannot"
                        : "written for " + t.target + ", and the module is " + options.target + " (-t)";
    return finish(TestResult::Skip);
  }
  if (parsed && !t.inputs.empty())
    r.notes.push_back(path + ":" + std::to_string(t.inputs.front().line) +
                      ": note: the switch, hardstop and load lines describe the machine; on a module they are not "
                      "simulated: the machine's switches, ends and loads must be where they say");
  diags.clear();
  std::shared_ptr<const Program> program = check_test_source(path, text, options, cache, t, diags, err);
  if (!diags.empty() || !program) {
    r.error = render_file_diags(diags, options.error_limit) + err;
    return finish(TestResult::Error);
  }
  r.program = program;
  r.messages = program->messages;
  if (!module.load_and_start(program->info.program, err)) {
    r.error = path + ": error: " + err + "\n";
    return finish(TestResult::Error);
  }
  const Clock::time_point t0 = Clock::now();
  TimedReader reader(module, t0);
  auto since = [&] { return std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - t0).count(); };
  auto where = [&]() -> std::string {
    std::int64_t pc = 0;
    std::string ignored;
    if (!module.reg(ExprReader::Pc, pc, ignored)) return "";
    const std::string place = program->info.place(static_cast<std::int32_t>(pc));
    return "the program was at " + (place.empty() ? "address " + std::to_string(pc) : place);
  };
  auto fail = [&](const Expectation& e, std::string message, std::string at) {
    Failure f;
    f.line = e.line;
    f.message = std::move(message);
    f.where = std::move(at);
    r.failures.push_back(std::move(f));
  };
  // Reads and compares one expectation now; `when` says at which instant it was due.
  auto check = [&](const Expectation& e, const std::string& when) {
    std::int64_t left = 0, right = 0, tolerance = 0;
    std::string error;
    const SimTime read_at = since();
    if (!eval_expr(e.left_expr, reader, left, error) || !eval_expr(e.right_expr, reader, right, error) ||
        (!e.tolerance.empty() && !eval_expr(e.tolerance_expr, reader, tolerance, error)))
      return fail(e, "cannot read " + condition_text(e) + " at " + when + ": " + error, "");
    if (!holds(e, left, right, tolerance)) fail(e, "expected " + condition_text(e) + " at " + when + ", got " + std::to_string(left) + " (read at " + format_time(read_at) + ")", where());
  };

  const SimTime max_time = options.max_time_given ? options.max_time : t.max_time;
  std::vector<const Expectation*> timed;
  for (const Expectation& e : t.expects)
    if (e.kind == Expectation::At) timed.push_back(&e);
  std::stable_sort(timed.begin(), timed.end(), [](const Expectation* a, const Expectation* b) { return a->at < b->at; });
  bool stopped = false;
  for (const Expectation* e : timed) {
    if (module.cancelled()) break;
    if (e->at > max_time) {
      fail(*e, "expected " + condition_text(*e) + " at " + e->when + ", but max-time is " + format_time(max_time), "");
      continue;
    }
    std::this_thread::sleep_until(t0 + std::chrono::microseconds(e->at));
    check(*e, e->when);
  }
  // The end: the program stops by itself, or max-time stops it.
  const auto deadline = t0 + std::chrono::microseconds(max_time);
  for (;;) {
    bool running = true;
    if (!module.running(running, err)) {
      r.error = path + ": error: " + err + "\n";
      return finish(TestResult::Error);
    }
    if (!running) {
      stopped = true;
      break;
    }
    if (Clock::now() >= deadline || module.cancelled()) break;
    std::this_thread::sleep_for(std::min<Clock::duration>(deadline - Clock::now(), std::chrono::milliseconds(10)));
  }
  if (!stopped) module.stop();
  r.ended_at = since();
  const End end = stopped ? End::Stop : End::MaxTime;
  for (const Expectation& e : t.expects) {
    if (e.kind == Expectation::AtEnd) {
      check(e, "the end");
    } else if (e.kind == Expectation::Halted && e.halted != end) {
      fail(e, "expected the run to end with " + std::string(end_name(e.halted)) + ", but the program " +
                  (stopped ? "stopped" : "was still running at max-time " + format_time(max_time)) + " (after " +
                  format_time(r.ended_at) + ")",
           "");
    } else if (e.kind == Expectation::NeverFault || e.kind == Expectation::NoWarnings) {
      r.notes.push_back(path + ":" + std::to_string(e.line) + ": note: '" + e.text +
                        "' is not checked on a module (a module reports no faults or warnings)");
    } else if (e.kind == Expectation::NoNotes) {
      r.notes.push_back(path + ":" + std::to_string(e.line) + ": note: '" + e.text +
                        "' is not checked on a module (a module simulates nothing: it has no notes)");
    } else if (e.kind == Expectation::Stall || e.kind == Expectation::NeverStall) {
      r.notes.push_back(path + ":" + std::to_string(e.line) + ": note: '" + e.text +
                        "' is not checked on a module (its host sees no stall event, only 208 when it asks)");
    }
  }
  std::stable_sort(r.failures.begin(), r.failures.end(), [](const Failure& a, const Failure& b) { return a.line < b.line; });
  if (module.cancelled()) {
    r.error = path + ": error: interrupted\n";
    return finish(TestResult::Error);
  }
  return finish(r.failures.empty() ? TestResult::Pass : TestResult::Fail);
}

}  // namespace tmcl::testrun
