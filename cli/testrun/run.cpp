// Running one test on the VM. The run stops at each instant an expectation names (the VM's own
// time limit, so the state seen there is what `tmclrun --max-time INSTANT` prints), checks the
// expectations of that instant, and goes on; then it runs to its end (STOP with the motors at
// rest, a fault, blocked, or max-time) and checks the rest. Expectations are expressions of the
// debugger's vocabulary (tmcl/expr.hpp), evaluated through the VM's own access rules.
#include <algorithm>
#include <chrono>

#include "tmcl/duration.hpp"
#include "tmcl/fileio.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/numbers.hpp"
#include "tmcl/testrun.hpp"

namespace tmcl::testrun {

namespace {

End end_of(Halt h) {
  switch (h) {
    case Halt::Fault: return End::Fault;
    case Halt::Blocked: return End::Blocked;
    case Halt::TimeLimit:
    case Halt::StepLimit: return End::MaxTime;
    default: return End::Stop;
  }
}

// The address the program is at: where it stopped or faulted, else the next instruction.
std::int32_t program_address(const Vm& vm) {
  return vm.status != AppStatus::Running && vm.halt_pc >= 0 ? vm.halt_pc : vm.pc;
}

// "the program was at homing.tmc:14 (loop+2): WAIT TICKS, 0, 50"
std::string program_place(const Program& p, const Vm& vm) {
  const std::int32_t at = program_address(vm);
  std::string place = p.info.place(at);
  std::string s = "the program was at " + (place.empty() ? "address " + std::to_string(at) : place);
  const std::string fn = p.info.function_of(at);
  if (!fn.empty()) s += " (" + fn + ")";
  if (const std::string* text = p.info.source_text(at)) {
    const auto b = text->find_first_not_of(" \t");
    if (b != std::string::npos) s += ": " + text->substr(b, text->find_last_not_of(" \t\r") - b + 1);
  }
  return s;
}

// A run's note as a test result shows it: "prog.tmc:12: note: MESSAGE (at 1.5s)".
std::string note_text(const Program& p, const RuntimeWarning& n) {
  const std::string place = p.info.place(n.pc);
  return (place.empty() ? "address " + std::to_string(n.pc) : place) + ": note: " + n.message + " (at " + format_time(n.at) + ")";
}

bool is_literal(const std::string& text) {
  std::int64_t v = 0;
  return parse_int(text, INT64_MIN, INT64_MAX, v);
}


class Checker {
 public:
  Checker(const Program& p, Vm& vm, TestResult& r) : p_(p), vm_(vm), r_(r) {}

  // An expectation with a comparison, at the current instant.
  void compare(const Expectation& e) {
    const std::string when = e.kind == Expectation::AtEnd ? "the end" : e.when;
    std::int64_t left = 0, right = 0, tolerance = 0;
    std::string error;
    if (!eval_expr(e.left_expr, vm_, left, error) || !eval_expr(e.right_expr, vm_, right, error) ||
        (!e.tolerance.empty() && !eval_expr(e.tolerance_expr, vm_, tolerance, error))) {
      fail(e, "cannot evaluate " + condition_text(e) + " at " + when + ": " + error, program_place(p_, vm_)).no_update =
          "it could not be evaluated, so there is no value to write";
      return;
    }
    if (tolerance < 0) {
      fail(e, "the tolerance of " + condition_text(e) + " is negative (" + std::to_string(tolerance) + ")", "").no_update =
          "its tolerance is negative: fix it by hand";
      return;
    }
    if (holds(e, left, right, tolerance)) return;
    std::string msg = "expected " + condition_text(e) + " at " + when + ", got " + std::to_string(left);
    if (!is_literal(e.right)) msg += " (" + e.right + " is " + std::to_string(right) + ")";
    Failure& f = fail(e, msg, program_place(p_, vm_));
    // A number is rewritten as a number, a duration (`$time = 2s`) as a duration.
    const bool duration = !is_literal(e.right) && parse_duration(e.right).has_value();
    if (e.op == Compare::Eq && (is_literal(e.right) || duration)) {
      f.update = duration ? format_time(left) : std::to_string(left);
      f.update_col = e.right_col;
      f.update_len = static_cast<int>(e.right.size());
    } else if (e.op != Compare::Eq) {
      f.no_update = "only an '=' expectation is rewritten; this one compares with '" + std::string(compare_text(e.op)) + "'";
    } else {
      f.no_update = "its value '" + e.right + "' is an expression; only a number or a duration is rewritten";
    }
  }

  // An expectation at an instant the run never reached.
  void after_end(const Expectation& e, const std::string& end) {
    fail(e, "expected " + condition_text(e) + " at " + e.when + ", but " + end, "").no_update =
        "the run ended before " + e.when + ", so there is no value at that instant; move the instant, or let the run "
        "go on (max-time)";
  }

  void halted(const Expectation& e, End end, const std::string& how) {
    if (e.halted == end) return;
    Failure& f = fail(e, "expected the run to end with " + std::string(end_name(e.halted)) + ", but " + how, program_place(p_, vm_));
    f.update = std::string(end_name(end));
    f.update_col = e.right_col;
    f.update_len = static_cast<int>(e.right.size());
  }

  // `expect stall M at T ± W`: one of motor M's stalls (`stalls`: instant, motor; in time order)
  // lies in [T - W, T + W]; --update writes the instant of the one nearest T.
  void stall(const Expectation& e, const std::vector<std::pair<SimTime, int>>& stalls, const std::string& end) {
    const std::string what = "motor " + std::to_string(e.motor) + " to stall at " + e.when +
                             (e.tolerance.empty() ? std::string() : " \xC2\xB1 " + e.tolerance);
    const std::pair<SimTime, int>* nearest = nullptr;
    auto distance = [&](SimTime t) { return t > e.at ? t - e.at : e.at - t; };
    for (const auto& st : stalls)
      if (st.second == e.motor && (!nearest || distance(st.first) < distance(nearest->first))) nearest = &st;
    if (nearest && distance(nearest->first) <= e.within) return;
    if (!nearest) {
      fail(e, "expected " + what + ", but it never stalled (" + end + ")", "").no_update =
          "motor " + std::to_string(e.motor) + " never stalled, so there is no instant to write";
      return;
    }
    Failure& f = fail(e, "expected " + what + ", it stalled at " + format_time(nearest->first), "");
    f.update = format_time(nearest->first);
    f.update_col = e.right_col;
    f.update_len = static_cast<int>(e.right.size());
  }

  void never_stall(const Expectation& e, const std::vector<std::pair<SimTime, int>>& stalls) {
    for (const auto& st : stalls)
      if (st.second == e.motor) {
        fail(e, "expected motor " + std::to_string(e.motor) + " never to stall, it stalled at " + format_time(st.first), "")
            .no_update = "a stall is not a value to rewrite";
        return;
      }
  }

  void never_fault(const Expectation& e, const RunResult& res) {
    if (res.halt != Halt::Fault) return;
    fail(e, "expected no fault, got one at " + format_time(vm_.now) + ": " + res.message, program_place(p_, vm_)).no_update =
        "a fault is not a value to rewrite";
  }

  // The run's notes: what it does not simulate though the program relies on it (docs/tmclrun.md).
  void no_notes(const Expectation& e) {
    if (vm_.notes.empty()) return;
    std::string list;
    for (const RuntimeWarning& n : vm_.notes) list += std::string(list.empty() ? "" : "\n") + note_text(p_, n);
    fail(e, "expected no notes, got " + std::to_string(vm_.notes.size()), list).no_update = "a note is not a value to rewrite";
  }

  void no_warnings(const Expectation& e) {
    if (vm_.warnings_total == 0) return;
    std::string msg = "expected no run-time warnings, got " + std::to_string(vm_.warnings_total);
    std::string list;
    for (std::size_t i = 0; i < vm_.warnings.size() && i < 3; ++i) {
      const RuntimeWarning& w = vm_.warnings[i];
      std::string place = p_.info.place(w.pc);
      list += std::string(list.empty() ? "" : "\n") + "at " + format_time(w.at) + ", " +
              (place.empty() ? "address " + std::to_string(w.pc) : place) + ": " + w.message + " [" +
              std::string(warning_kind_name(w.kind)) + "]";
    }
    if (vm_.warnings_total > 3) list += "\nand " + std::to_string(vm_.warnings_total - 3) + " more";
    fail(e, msg, list).no_update = "a run-time warning is not a value to rewrite";
  }

 private:
  Failure& fail(const Expectation& e, std::string message, std::string where) {
    Failure f;
    f.line = e.line;
    f.message = std::move(message);
    f.where = std::move(where);
    r_.failures.push_back(std::move(f));
    return r_.failures.back();
  }

  const Program& p_;
  Vm& vm_;
  TestResult& r_;
};

// "the run ended at 1.200040s (STOP at prog.tmc:30)"
std::string end_text(const Program& p, const Vm& vm, const RunResult& res, End end, SimTime max_time) {
  std::string s = "the run ended at " + format_time(vm.now) + " (";
  switch (end) {
    case End::Stop: s += "STOP"; break;
    case End::Fault: s += "a fault: " + res.message; break;
    case End::MaxTime: s += "max-time " + format_time(max_time); break;
    case End::Blocked: s += "blocked: " + res.message; break;
  }
  if (end == End::Stop && vm.halt_pc >= 0) {
    const std::string place = p.info.place(vm.halt_pc);
    s += " at " + (place.empty() ? "address " + std::to_string(vm.halt_pc) : place);
  }
  return s + ")";
}

}  // namespace

std::string condition_text(const Expectation& e) {
  std::string s = e.left + " " + std::string(compare_text(e.op)) + " " + e.right;
  if (!e.tolerance.empty()) s += " \xC2\xB1 " + e.tolerance;
  return s;
}

bool holds(const Expectation& e, std::int64_t left, std::int64_t right, std::int64_t tolerance) {
  switch (e.op) {
    case Compare::Eq: {
      // The distance in unsigned arithmetic: no overflow, whatever two 64-bit values they are.
      const auto l = static_cast<std::uint64_t>(left), r = static_cast<std::uint64_t>(right);
      return (left > right ? l - r : r - l) <= static_cast<std::uint64_t>(tolerance);
    }
    case Compare::Ne: return left != right;
    case Compare::Lt: return left < right;
    case Compare::Le: return left <= right;
    case Compare::Gt: return left > right;
    case Compare::Ge: return left >= right;
  }
  return false;
}

TestResult run_test(const TestFile& t, std::shared_ptr<const Program> program, const RunOptions& o) {
  TestResult r;
  r.path = t.path;
  r.program = program;
  r.messages = program->messages;
  const Program& p = *program;
  const std::string core_name = !t.motion.empty() ? t.motion : !o.motion.empty() ? o.motion : std::string(p.profile->default_motion);
  std::unique_ptr<MotionCore> core = make_motion_core(core_name);
  if (!core) core = make_ideal_motion_core();
  Vm vm(*p.profile, *core);
  vm.instr_time = t.instr_time >= 0 ? t.instr_time : o.instr_time;
  vm.strict = o.strict;
  vm.handler_code = p.handler_code;
  vm.load(p.info.program);
  vm.source_of = p.places;
  vm.power_on(nullptr);
  vm.add_inputs(t.inputs);
  // The stall events (stop on stall), for `expect stall` and `expect never stall`.
  std::vector<std::pair<SimTime, int>> stalls;
  for (const Expectation& e : t.expects)
    if (e.kind == Expectation::Stall || e.kind == Expectation::NeverStall) {
      vm.on_motion_event = [&stalls](const Vm&, const MotionEvent& ev) {
        if (ev.kind == MotionEventKind::Stall) stalls.emplace_back(ev.at, ev.motor);
      };
      break;
    }
  if (o.coverage) vm.count_coverage();
  vm.start(0);
  const SimTime max_time = o.max_time_given ? o.max_time : t.max_time;

  Checker check(p, vm, r);
  std::vector<const Expectation*> timed;
  for (const Expectation& e : t.expects)
    if (e.kind == Expectation::At) timed.push_back(&e);
  std::stable_sort(timed.begin(), timed.end(), [](const Expectation* a, const Expectation* b) { return a->at < b->at; });

  RunResult res{Halt::TimeLimit, ""};
  bool ended = false;
  // Runs to `until` unless the run ends first; true when the machine is at `until`.
  auto advance = [&](SimTime until) {
    if (ended) return false;
    res = vm.run({UINT64_MAX, until});
    const bool paused = res.halt == Halt::TimeLimit;
    ended = !paused || until >= max_time;
    return paused;
  };
  for (std::size_t i = 0; i < timed.size();) {
    const SimTime at = timed[i]->at;
    const bool there = at <= max_time && advance(at);
    if (!there && !ended) advance(max_time);
    for (; i < timed.size() && timed[i]->at == at; ++i) {
      if (there)
        check.compare(*timed[i]);
      else
        check.after_end(*timed[i], end_text(p, vm, res, end_of(res.halt), max_time));
    }
  }
  if (!ended) advance(max_time);
  End end = end_of(res.halt);
  // With a time limit the VM jumps a WAIT that nothing can end to the limit; the run was blocked.
  if (end == End::MaxTime && vm.status == AppStatus::Running && vm.wait.active && vm.next_wakeup() == kNever) {
    end = End::Blocked;
    const std::string place = p.info.place(vm.pc);
    res.message = "the WAIT at " + (place.empty() ? "address " + std::to_string(vm.pc) : place) + never_ending_wait_reason(vm);
  }
  for (const Expectation& e : t.expects) {
    switch (e.kind) {
      case Expectation::At: break;
      case Expectation::AtEnd: check.compare(e); break;
      case Expectation::Halted: check.halted(e, end, end_text(p, vm, res, end, max_time)); break;
      case Expectation::NeverFault: check.never_fault(e, res); break;
      case Expectation::NoWarnings: check.no_warnings(e); break;
      case Expectation::NoNotes: check.no_notes(e); break;
      case Expectation::Stall: check.stall(e, stalls, end_text(p, vm, res, end, max_time)); break;
      case Expectation::NeverStall: check.never_stall(e, stalls); break;
    }
  }
  std::stable_sort(r.failures.begin(), r.failures.end(), [](const Failure& a, const Failure& b) { return a.line < b.line; });
  r.status = r.failures.empty() ? TestResult::Pass : TestResult::Fail;
  for (const RuntimeWarning& n : vm.notes) r.notes.push_back(note_text(p, n));  // shown with the result, and in JUnit
  r.ended_at = vm.now;
  if (o.coverage) {
    r.executed = std::move(vm.executed);
    r.taken = std::move(vm.taken);
  }
  return r;
}

std::shared_ptr<const Program> check_test_source(const std::string& path, const std::string& text, const RunOptions& options,
                                                 ProgramCache& cache, TestFile& t, std::vector<FileDiag>& diags,
                                                 std::string& program_error) {
  parse_test_file(text, path, options.target, t, diags, options.target_given);
  // The program is loaded even when the file has errors, so that the expressions' errors (which
  // need its labels) are reported with the others in one go; without it, those that need none.
  const Profile* profile = test_profile(t);
  std::shared_ptr<const Program> program;
  if (profile && !t.program.empty()) program = cache.get(t, *profile, options, program_error, diags);
  if (program)
    bind_expectations(t, program->info, diags);
  else
    check_expectations(t, diags);
  std::stable_sort(diags.begin(), diags.end(),
                   [](const FileDiag& a, const FileDiag& b) { return a.line != b.line ? a.line < b.line : a.col < b.col; });
  return program;
}

TestResult run_test_file(const std::string& path, const RunOptions& options, ProgramCache& cache) {
  std::vector<std::uint8_t> bytes;
  std::string err;
  if (!read_file(path, bytes, err, kMaxScenarioBytes)) {
    TestResult r;
    r.path = path;
    r.status = TestResult::Error;
    r.error = options.tool + ": error: " + err + "\n";
    return r;
  }
  return run_test_source(path, std::string(bytes.begin(), bytes.end()), options, cache);
}

TestResult run_test_source(const std::string& path, const std::string& text, const RunOptions& options, ProgramCache& cache) {
  const auto t0 = std::chrono::steady_clock::now();
  auto finish = [&](TestResult r) {
    r.path = path;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  };
  auto error = [&](std::string diagnostics) {
    TestResult r;
    r.status = TestResult::Error;
    r.error = std::move(diagnostics);
    return finish(std::move(r));
  };
  TestFile t;
  std::vector<FileDiag> diags;
  if (parse_test_file(text, path, options.target, t, diags, options.target_given) && t.skipped) {  // a skipped test is not loaded
    TestResult r;
    r.status = TestResult::Skip;
    r.skip_reason = t.skip;
    return finish(std::move(r));
  }
  diags.clear();
  std::string err;
  std::shared_ptr<const Program> program = check_test_source(path, text, options, cache, t, diags, err);
  if (!diags.empty() || !program) return error(render_file_diags(diags, options.error_limit) + err);
  return finish(run_test(t, std::move(program), options));
}

}  // namespace tmcl::testrun
