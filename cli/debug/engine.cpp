// The engine's forward execution: breakpoints (VM traps), watchpoints, stepping by instruction,
// over subroutines and handlers, out of frames, to a location or an instant. Every command runs
// the VM through run() with step and time limits; the chunks between checkpoints are also where
// a pause request is noticed. Reverse execution is in reverse.cpp.
#include <algorithm>
#include <cctype>
#include <sstream>

#include "tmcl/debugger.hpp"
#include "tmcl/duration.hpp"
#include "tmcl/scenario.hpp"

namespace tmcl::debug {

// ---- Engine: set-up and points ----

Engine::Engine(Setup setup, ProgramInfo info, std::unique_ptr<MotionCore> core)
    : Target(*setup.profile, std::move(info)), setup_(std::move(setup)), core_(std::move(core)) {
  vm_ = std::make_unique<Vm>(*setup_.profile, *core_);
  vm_->instr_time = setup_.instr_time;
  vm_->load(info_.program);
  for (std::size_t a = 0; a < info_.program.size(); ++a) vm_->source_of.push_back(info_.place(static_cast<std::int32_t>(a)));
  vm_->power_on(setup_.eeprom ? &*setup_.eeprom : nullptr);
  vm_->add_inputs(setup_.inputs);
  reversible_ = core_->clone() != nullptr;
  checkpoint_size_ = sizeof(Vm) + sizeof(Checkpoint) + 2048 +
                     static_cast<std::size_t>(setup_.profile->motors) * (256 * 5 + 4 * static_cast<std::size_t>(setup_.profile->coords) + 512);
}

int Engine::depth() const { return vm_->sp + (vm_->in_handler ? 1 : 0); }

bool Engine::at_instruction() const {
  const Vm& vm = *vm_;
  if (vm.wait.active || vm.next_wakeup() <= vm.now) return false;
  if (!vm.global_enable || vm.in_handler || vm.status != AppStatus::Running) return true;
  for (std::size_t w = 0; w < vm.pending.size(); ++w)
    if (vm.pending[w] & vm.enabled[w]) return false;
  return true;
}

std::vector<Engine::Frame> Engine::frames() {
  const Vm& vm = *vm_;
  std::vector<Frame> out;
  out.push_back({vm.faulted() && vm.halt_pc >= 0 ? vm.halt_pc : vm.pc, false});
  // A return address is the instruction after its CSUB (or CALL): the caller is at the call.
  auto caller = [&](int i) { out.push_back({vm.stack[static_cast<std::size_t>(i)] - 1, false}); };
  const int bottom = vm.in_handler ? std::clamp(vm.saved.stack_depth, 0, vm.sp) : 0;
  for (int i = vm.sp - 1; i >= bottom; --i) caller(i);
  if (vm.in_handler) {
    out.push_back({vm.saved.pc, true});
    for (int i = bottom - 1; i >= 0; --i) caller(i);
  }
  return out;
}

bool Engine::set_input(InputEvent ev, std::string& error) {
  if (!running_) {
    error = "The program is not being run.";
    return false;
  }
  Vm& vm = *vm_;
  ev.at = vm.now;
  ev.line = 0;
  vm.add_inputs({ev});
  // Applied now, as the run loop applies a scenario's event that is due: no instruction runs
  // (the step limit is where it is), a WAIT in progress and a latched interrupt stay as they are.
  if (vm.status == AppStatus::Running) vm.run(Limits{vm.steps, vm.now, false});
  state_changed();
  return true;
}

bool Engine::set_machine(InputEvent ev, std::string& error) {
  Vm& vm = *vm_;
  const bool hard = ev.kind == InputEvent::HardStop;
  // Asked of a copy of the core: the real one would turn a refusal into a fault of every run.
  if (std::unique_ptr<MotionCore> probe = vm.motion->clone()) {
    const bool ok = hard                                 ? probe->place_hard_stop(ev.index, ev.input, ev.from)
                    : ev.kind == InputEvent::LoadZone    ? probe->place_load(ev.index, ev.from, ev.to, ev.value)
                                                         : probe->set_load(ev.index, ev.value);
    if (!ok) {
      error = "the motion core '" + std::string(vm.motion->name()) + "' cannot model " + (hard ? "hard stops" : "loads") +
              " on " + std::string(vm.profile->name);
      return false;
    }
  }
  if (!ev.placed_kind()) return set_input(ev, error);
  ev.at = 0;
  ev.line = 0;
  vm.add_inputs({ev});  // placed at once, and again at every power-on (`run`)
  state_changed();
  return true;
}

bool Engine::is_machine_line(const std::string& line) {
  return line == "hardstop" || line == "load" || line.rfind("hardstop ", 0) == 0 || line.rfind("load ", 0) == 0;
}

// The scenario reader reads the line, so the prompt takes exactly what a scenario file does and
// says the same about a mistake; the timed load is the line `at TIME load MOTOR = P%` at this
// instant.
bool Engine::set_machine(const std::string& line, std::string& error) {
  static const char* kUsage =
      "usage: set var hardstop left|right MOTOR at POSITION, set var load MOTOR = P%, set var load MOTOR from POSITION to "
      "POSITION = P%";
  std::istringstream in(line);
  std::vector<std::string> w;
  for (std::string x; in >> x;) w.push_back(x);
  const bool timed = !w.empty() && w[0] == "load" && std::find(w.begin(), w.end(), "from") == w.end();
  if (w.empty() || (timed && (w.size() != 4 || w[2] != "="))) return error = kUsage, false;
  const Profile& profile = *vm_->profile;
  ScenarioOptions options;
  options.motors = profile.motors;
  options.module = std::string(profile.name);
  options.profile = &profile;
  options.from_start = false;  // the carriage is where the run has taken it
  std::vector<InputEvent> events;
  std::vector<FileDiag> diags;
  if (!parse_scenario(timed ? "at 0s " + line : line, "", events, diags, options))
    return error = diags.empty() ? kUsage : diags.front().message, false;
  if (events.size() != 1) return error = kUsage, false;
  return set_machine(events.front(), error);
}

bool Engine::assign(const Expr& lhs, std::int64_t value, std::string& error) {
  if (lhs.root >= 0) {
    const Expr::Node& n = lhs.nodes[static_cast<std::size_t>(lhs.root)];
    if (n.kind == Expr::Node::In || n.kind == Expr::Node::Ain) {
      Expr index = lhs;
      index.root = n.a;
      std::int64_t port = 0;
      if (!eval_expr(index, *vm_, port, error)) return false;
      if (port < 0 || port >= Vm::kPorts) {
        error = "port " + std::to_string(port) + " is out of range (0.." + std::to_string(Vm::kPorts - 1) + ")";
        return false;
      }
      if (value < INT32_MIN || value > INT32_MAX) {
        error = std::to_string(value) + " does not fit 32 bits";
        return false;
      }
      InputEvent ev;
      ev.kind = n.kind == Expr::Node::In ? InputEvent::Digital : InputEvent::Analog;
      ev.index = static_cast<int>(port);
      ev.value = static_cast<std::int32_t>(value);
      return set_input(ev, error);
    }
  }
  if (!assign_expr(lhs, *vm_, value, error)) return false;
  state_changed();
  return true;
}

void Engine::set_traps() {
  std::vector<std::uint8_t> want(static_cast<std::size_t>(std::max(vm_->program_size, 0)), 0);
  for (const auto& b : breaks_)
    if (b.enabled && b.address >= 0 && b.address < vm_->program_size) want[static_cast<std::size_t>(b.address)] = 1;
  std::vector<std::uint8_t> vars;
  if (watching() && watch_by_traps(&vars))
    for (std::size_t a = 0; a < want.size(); ++a)
      if (writes_var(vm_->program[a], vars)) want[a] = 1;
  if (temp_trap_ >= 0 && static_cast<std::size_t>(temp_trap_) < want.size()) want[static_cast<std::size_t>(temp_trap_)] = 1;
  for (std::int32_t a : exit_traps_)
    if (a >= 0 && static_cast<std::size_t>(a) < want.size()) want[static_cast<std::size_t>(a)] = 1;
  for (std::size_t a = 0; a < want.size(); ++a)
    if (vm_->trapped(static_cast<std::int32_t>(a)) != (want[a] != 0)) vm_->set_trap(static_cast<std::int32_t>(a), want[a] != 0);
}

// ---- execution ----

Stop Engine::start(bool stop_at_entry) {
  if (setup_.serving)
    vm_->reset_application();  // the host's parameters, variables and moving motors stay
  else
    vm_->power_on(setup_.eeprom ? &*setup_.eeprom : nullptr);
  vm_->start(0);
  running_ = true;
  pause_.store(false);
  pause_note_.clear();
  checkpoints_.clear();
  next_checkpoint_ = 0;
  for (auto& b : breaks_) b.hits = 0;
  refresh_watches();
  checked_steps_ = UINT64_MAX;  // a breakpoint at address 0 stops `run`
  if (stop_at_entry) {
    if (reversible_) take_checkpoint();
    checked_steps_ = vm_->steps;  // ... and `start`, which stops there: continue goes on
    checked_pc_ = vm_->pc;
    return Stop{StopKind::Entry, 0, "", 0, 0};
  }
  return cont();
}

void Engine::kill() {
  running_ = false;
  checkpoints_.clear();
  if (setup_.serving)
    vm_->stop_application();  // as the host's 128: the module itself stays as it is
  else
    vm_->power_on(setup_.eeprom ? &*setup_.eeprom : nullptr);
}

void Engine::external_change() {
  if (vm_->status == AppStatus::Running || vm_->status == AppStatus::Step) running_ = true;
  state_changed();
}

void Engine::set_pc(std::int32_t address) {
  vm_->pc = address;
  vm_->wait = WaitState{};
  state_changed();
}

RunResult Engine::exec(std::uint64_t max_steps, SimTime until) {
  const std::uint64_t user_steps = setup_.limits.max_steps;
  max_steps = std::min(max_steps, user_steps);
  until = std::min(until, setup_.limits.until);
  const bool slicing = on_slice && !no_slice_ && !in_slice_;
  for (;;) {
    if (slicing && (vm_->steps >= next_slice_ || vm_->now >= slice_bound_)) {
      in_slice_ = true;
      slice_bound_ = on_slice();
      in_slice_ = false;
      next_slice_ = vm_->steps + std::max<std::uint64_t>(setup_.slice_steps, 1);
    }
    if (pause_.exchange(false)) {
      paused_ = true;
      return RunResult{Halt::StepLimit, "paused"};
    }
    if (reversible_ && vm_->steps >= next_checkpoint_) take_checkpoint();
    const std::uint64_t interval = std::max<std::uint64_t>(setup_.checkpoint_interval, 1);
    std::uint64_t mark = (vm_->steps / interval + 1) * interval;
    if (slicing) mark = std::min(mark, next_slice_);
    const SimTime bound = slicing ? std::min(until, std::max(slice_bound_, vm_->now)) : until;
    // Every step limit of the debugger's own stops before an instruction (Limits::to_instruction);
    // the user's --max-steps stops where a plain run stops.
    const std::uint64_t limit = std::min(max_steps, mark);
    RunResult r = vm_->run(Limits{limit, bound, limit < user_steps});
    if (r.halt == Halt::StepLimit && vm_->steps < max_steps) continue;  // a checkpoint or slice mark
    if (r.halt == Halt::TimeLimit && vm_->now < until) continue;        // the slice's time bound
    return r;
  }
}

RunResult Engine::exec_over_trap(std::uint64_t max_steps, SimTime until) {
  std::int32_t at = vm_->pc;
  if (vm_->trapped(at) && vm_->steps < max_steps && vm_->now < until) {
    vm_->set_trap(at, false);
    RunResult r = exec(vm_->steps + 1, until);
    vm_->set_trap(at, true);
    if (r.halt != Halt::StepLimit || vm_->steps >= max_steps || paused_) return r;
  }
  return exec(max_steps, until);
}

bool Engine::check_break(Stop& stop) {
  checked_steps_ = vm_->steps;
  checked_pc_ = vm_->pc;
  return breakpoint_hit(vm_->pc, stop);
}

std::string Engine::when() { return ", time " + format_time(vm_->now); }

// One instruction with the watchpoints checked after it. When a watched value that depends on
// time (time itself, a motor's position) changed while time jumped (a WAIT, an idle handler
// wait), the exact instant is searched for by re-running the step from a copy of the machine
// with a time limit: the change is reported at the first microsecond it shows.
bool Engine::watched_step(const Goal& g, Stop& stop, RunResult& r) {
  bool timed = false;
  for (const auto& w : watches_) timed = timed || (w.enabled && w.expr.uses_time());
  std::optional<Vm> before;
  std::unique_ptr<MotionCore> core_before;
  const std::uint64_t steps0 = vm_->steps;
  const SimTime t0 = vm_->now;
  std::vector<Watchpoint> saved;
  if (timed && reversible_) {
    before.emplace(vm_->checkpoint());
    core_before = core_->clone();
    saved = watches_;
  }
  r = exec_over_trap(std::min(g.max_steps, steps0 + 1), g.until);
  if (paused_ || r.halt == Halt::Break) return false;
  Stop s;
  if (!watch_changed(s)) return false;
  if (before && vm_->now - t0 > vm_->instr_time && r.halt != Halt::Fault) {
    auto redo = [&](SimTime until) {
      vm_->restore(*before);
      core_ = core_before->clone();
      vm_->motion = core_.get();
      watches_ = saved;
      return exec_over_trap(steps0 + 1, until);
    };
    SimTime lo = t0, hi = vm_->now;
    no_slice_ = true;  // re-runs from a copy: no host may see (or change) these states
    while (hi - lo > 1) {
      SimTime mid = lo + (hi - lo) / 2;
      redo(mid);
      Stop probe;
      (watch_changed(probe) ? hi : lo) = mid;
    }
    r = redo(hi);
    no_slice_ = false;
    watch_changed(s);
  }
  stop = s;
  return true;
}

Stop Engine::go(const Goal& g) {
  paused_ = false;
  if (!running_) return Stop{StopKind::NotRunning, 0, "the program is not being run", 0, 0};
  // A host stopped, stepped or reset the program meanwhile (serving): it runs on from pc.
  if (setup_.serving && vm_->status != AppStatus::Running) vm_->start(vm_->pc);
  // The first on_slice comes after a slice of instructions, so a run that stops soon reads no
  // requests meanwhile (a scripted client's next requests wait for the stop); serving paces
  // time from the first instruction.
  next_slice_ = vm_->steps + std::max<std::uint64_t>(setup_.slice_steps, 1);
  if (setup_.serving) slice_bound_ = vm_->now;
  std::int32_t temp = g.temp_addr;
  if (temp >= 0 && temp < vm_->program_size) temp_trap_ = temp;  // set_traps() keeps it while points change (on_slice)
  if (g.below >= 0) {
    // Where the frames above `below` can be left: their return addresses (reached after RSUB),
    // RETI when in a handler and RST (executed one at a time, then the depth is looked at).
    for (int i = 0; i < vm_->sp; ++i) exit_traps_.push_back(vm_->stack[static_cast<std::size_t>(i)]);
    for (std::int32_t a = 0; a < vm_->program_size; ++a) {
      auto op = static_cast<Op>(vm_->program[static_cast<std::size_t>(a)].op);
      if (op == Op::RST || (op == Op::RETI && vm_->in_handler)) exit_traps_.push_back(a);
    }
  }
  set_traps();
  struct Untrap {
    Engine& e;
    ~Untrap() {
      e.temp_trap_ = -1;
      e.exit_traps_.clear();
      e.set_traps();
    }
  } untrap{*this};
  // Watchpoints on user variables trap the instructions that may write them (set_traps), so
  // the run stays on the fast path; any other watchpoint needs one instruction at a time.
  const bool single = watching() && !watch_by_traps();
  for (bool first = true;; first = false) {
    // Here the machine is before an instruction (a trap, or one instruction stepped), except
    // on the first round, which may start in a WAIT or with an interrupt due.
    if (!first && g.below >= 0 && depth() <= g.below) return landed();
    if (vm_->trapped(vm_->pc) && (!first || (!counted() && at_instruction()))) {
      if (!first && vm_->pc == temp && depth() <= g.depth) return landed();
      Stop s;
      if (check_break(s)) return s;
    }
    RunResult r;
    if (single || vm_->trapped(vm_->pc)) {
      // One instruction (a breakpoint's, a variable writer's, or every one), then watchpoints.
      Stop s;
      if (single) {
        if (watched_step(g, s, r)) return s;
      } else {
        r = exec_over_trap(std::min(g.max_steps, vm_->steps + 1), g.until);
        if (!paused_ && r.halt != Halt::Break && watching() && watch_changed(s)) return s;
      }
      if (r.halt == Halt::StepLimit && !paused_ && vm_->steps < g.max_steps && vm_->now < g.until) continue;
    } else {
      r = exec(g.max_steps, g.until);
    }
    if (paused_) {
      Stop s{StopKind::Pause, 0, std::move(pause_note_), 0, 0};
      pause_note_.clear();
      return s;
    }
    if (r.halt == Halt::Break) continue;  // reported at the top of the loop
    bool user_steps = vm_->steps >= setup_.limits.max_steps, user_time = vm_->now >= setup_.limits.until;
    if (r.halt == Halt::StepLimit && vm_->steps >= g.max_steps && !user_steps) return landed();
    if (r.halt == Halt::TimeLimit && vm_->now >= g.until && !user_time) return Stop{StopKind::Step, 0, "", 0, 0};
    return from_result(r);
  }
}

Stop Engine::landed() {
  Stop s;
  if (vm_->trapped(vm_->pc) && at_instruction() && check_break(s)) return s;
  return Stop{StopKind::Step, 0, "", 0, 0};
}

// The user variables the enabled watchpoints read, when they read nothing else (constants and
// operators aside): such watchpoints are served by traps on the instructions that may write
// those variables.
bool Engine::watch_by_traps(std::vector<std::uint8_t>* vars) const {
  std::vector<std::uint8_t> want(256, 0);
  for (const auto& w : watches_) {
    if (!w.enabled) continue;
    const auto& nodes = w.expr.nodes;
    // Nodes under a Var index must be constant.
    std::function<bool(int)> constant = [&](int i) {
      if (i < 0) return true;
      const auto& n = nodes[static_cast<std::size_t>(i)];
      if (n.kind == Expr::Node::Num) return true;
      if (n.kind == Expr::Node::Unary || n.kind == Expr::Node::Binary) return constant(n.a) && constant(n.b);
      return false;
    };
    for (const auto& n : nodes) {
      if (n.kind == Expr::Node::Num || n.kind == Expr::Node::Unary || n.kind == Expr::Node::Binary) continue;
      if (n.kind != Expr::Node::Var || !constant(n.a)) return false;
      Expr sub = w.expr;
      sub.root = n.a;
      std::int64_t v = 0;
      std::string err;
      if (!eval_expr(sub, *vm_, v, err) || v < 0 || v > 255) return false;
      want[static_cast<std::size_t>(v)] = 1;
    }
  }
  if (vars) *vars = std::move(want);
  return true;
}

bool Engine::writes_var(const Instruction& ins, const std::vector<std::uint8_t>& vars) {
  auto in = [&](int n) { return vars[static_cast<std::size_t>(n & 255)] != 0; };
  switch (static_cast<Op>(ins.op)) {
    case Op::CALCVV:
    case Op::CALCVA:
    case Op::CALCVX:
    case Op::CALCV: return in(ins.motor);
    case Op::DJNZ:
    case Op::POPV: return in(ins.type);
    case Op::SIV:
    case Op::AIV: return true;  // indexed by X: any variable
    case Op::SGP:
    case Op::AGP:
    case Op::RSGP: return ins.motor == 2 && in(ins.type);
    default: return false;
  }
}

Stop Engine::from_result(const RunResult& r) {
  switch (r.halt) {
    case Halt::Stop: running_ = false; return Stop{StopKind::Exited, 0, r.message, 0, 0};
    case Halt::Fault: running_ = false; return Stop{StopKind::Fault, 0, r.message, 0, 0};
    case Halt::StepLimit:
    case Halt::TimeLimit:
    case Halt::Interrupted: return Stop{StopKind::Limit, 0, r.message, 0, 0};
    case Halt::Blocked: return Stop{StopKind::Blocked, 0, r.message, 0, 0};
    case Halt::NotRunning: running_ = false; return Stop{StopKind::NotRunning, 0, r.message, 0, 0};
    case Halt::Break: return Stop{StopKind::Breakpoint, 0, r.message, 0, 0};
  }
  return Stop{StopKind::NotRunning, 0, r.message, 0, 0};
}

Stop Engine::cont() { return go(Goal{}); }

Stop Engine::step(std::uint64_t n) {
  if (!running_) return Stop{StopKind::NotRunning, 0, "the program is not being run", 0, 0};
  if (n == 0) return Stop{StopKind::Step, 0, "", 0, 0};
  if (!at_instruction()) {
    // A WAIT in progress ends, or a due interrupt is entered: no instruction runs, and that is
    // the first step when it moved the program (not when only an event was due).
    const std::int32_t pc = vm_->pc;
    const bool handler = vm_->in_handler, waiting = vm_->wait.active;
    Goal settle;
    settle.max_steps = vm_->steps;
    Stop s = go(settle);
    if (s.kind != StopKind::Step) return s;
    if ((vm_->pc != pc || vm_->in_handler != handler || waiting) && --n == 0) return s;
  }
  Goal g;
  g.max_steps = vm_->steps + n;
  return go(g);
}

Stop Engine::finish() {
  if (!running_) return Stop{StopKind::NotRunning, 0, "the program is not being run", 0, 0};
  int d = depth();
  if (d == 0) return Stop{StopKind::NotRunning, 0, "\"finish\" not meaningful in the outermost frame", 0, 0};
  Goal g;
  g.below = d - 1;
  return go(g);
}

Stop Engine::next() {
  if (!running_) return Stop{StopKind::NotRunning, 0, "the program is not being run", 0, 0};
  // The frame whose next instruction is the goal: this one, or the caller's when the
  // instruction leaves this frame.
  int goal = depth();
  if (at_instruction()) {
    switch (static_cast<Op>(vm_->program[static_cast<std::size_t>(vm_->pc)].op)) {
      case Op::RSUB:
        if (vm_->sp > (vm_->in_handler ? vm_->saved.stack_depth : 0)) goal = depth() - 1;
        break;
      case Op::RETI:
        if (vm_->in_handler) goal = vm_->saved.stack_depth;
        break;
      case Op::RST: goal = 0; break;
      default: break;
    }
  }
  Stop s = step(1);
  if (s.kind != StopKind::Step || depth() <= goal) return s;
  Goal g;
  g.below = goal;  // out of the CSUB or the handler entered meanwhile
  return go(g);
}

Stop Engine::until(std::int32_t address) {
  Goal g;
  g.temp_addr = address;
  g.depth = depth();
  return go(g);
}

Stop Engine::advance(SimTime duration) {
  Goal g;
  g.until = vm_->now + duration;
  return go(g);
}

}  // namespace tmcl::debug
