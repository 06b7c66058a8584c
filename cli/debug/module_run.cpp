// The module target's execution (debug_module.hpp): start, step, next, finish, until and
// continue with the control commands 128-131 and 135, breakpoints by patches while the program
// runs freely, and every stop leaving program memory as loaded.
#include <algorithm>
#include <thread>
#include <utility>

#include "module_commands.hpp"
#include "tmcl/debug_module.hpp"

namespace tmcl::debug {
namespace {

using module_cmd::code;
using module_cmd::ctl;
// A run that stops this soon reads no other input meanwhile (Target::on_wait), as the VM's first
// slice: a scripted DAP client's requests wait for the stop, so its session is the same every time.
constexpr auto kQuiet = std::chrono::milliseconds(500);
bool is_call(const Instruction& i) { return i.op == code(Op::CSUB) || i.op == code(Op::CALL); }

}  // namespace

void ModuleTarget::waiting() {
  if (on_wait && std::chrono::steady_clock::now() - command_start_ >= kQuiet) on_wait();
}

Stop ModuleTarget::refused(const std::string& command) const {
  return Stop{StopKind::NotRunning, 0,
              command + ": the module's program differs from " + setup_.program_name + " (" + differs_ + "): `load` downloads it",
              0, 0};
}

// The module stopped answering: nothing more is asked; what is left patched is named.
Stop ModuleTarget::failed(const std::string& error) {
  lost_ = true;
  running_ = false;
  std::string text = "The module does not answer: " + error;
  if (!patched_.empty()) {
    std::string where;
    for (const auto& p : patched_) where += (where.empty() ? "" : ", ") + std::to_string(p.first);
    text += "\nProgram memory is still patched at address" + std::string(patched_.size() == 1 ? " " : "es ") + where +
            " (a jump to itself each): the next `tmclctl PORT debug PROGRAM` puts them back.";
  }
  return Stop{StopKind::NotRunning, 0, text, 0, 0};
}

// A stop: where the program is, A and X read at once (before any direct read).
Stop ModuleTarget::stopped_here(StopKind kind, std::string message) {
  Stop s{kind, 0, std::move(message), 0, 0};
  Status st;
  std::string error;
  if (!read_status(st, error)) return failed(error);
  pc_ = st.pc;
  mode_ = st.mode;
  waiting_ = st.wait;
  regs_valid_ = false;
  if (!read_registers(error)) return failed(error);
  return s;
}

bool ModuleTarget::hit_at_pc(Stop& stop) {
  if (counted_pc_ == pc_) return false;
  counted_pc_ = pc_;
  if (!regs_valid_) {
    std::string error;
    if (!read_registers(error)) return false;
  }
  return breakpoint_hit(pc_, stop);
}

Stop ModuleTarget::hold(bool& ok) {
  ok = true;
  command_start_ = std::chrono::steady_clock::now();
  if (mode_ != 1) return Stop{};
  std::int32_t ignored = 0;
  std::string error;
  if (!ask(ctl(Op::StopApplication), ignored, error)) return ok = false, failed(error);
  Stop s = stopped_here(StopKind::Step);
  ok = s.kind == StopKind::Step;
  stack_.clear();  // it ran freely: the frames it is in are not known
  stack_known_ = false;
  return s;
}

Stop ModuleTarget::halt() {
  bool ok = true;
  Stop s = hold(ok);
  if (!ok) return s;
  return Stop{StopKind::Pause, 0, "", 0, 0};
}

std::optional<Stop> ModuleTarget::attached(bool stop) {
  if (mode_ == 1 && !stop) return std::nullopt;
  const bool was_running = mode_ == 1;
  if (was_running) {
    Stop s = halt();
    if (s.kind != StopKind::Pause) return s;
  }
  Stop s{StopKind::Entry, 0, "", 0, 0};
  const std::string at = "address " + std::to_string(pc_);
  if (was_running) {
    s.message = "Stopped the program where it was running on the module (128), at " + at + ".";
  } else if (running_) {
    s.message = "The program on the module is held at " + at + " (" + status() + "), as it was.";
  } else {
    s.message = "The program is not running on the module (" + status() + ", at " + at + "): `restart` runs it from address 0.";
  }
  return s;
}

Stop ModuleTarget::step_one() {
  const std::int32_t at = pc_;
  const Instruction ins = instruction(at);
  std::string error;
  counted_pc_ = -1;
  // 130 is not repeated when its reply is lost: it would run a second instruction.
  host::Result r = client_->request(ctl(Op::StepApplication), false);
  if (!r.ok() && r.fail != host::Fail::NoReply) return failed(r.error);
  Status st;
  // A firmware whose 130 answers only when a WAIT is over may answer nothing else meanwhile:
  // the status is asked again until --reconnect (its late reply to 130 is then dropped).
  if (!read_status(st, error) && (!reconnected(error) || !read_status(st, error))) return failed(error);
  if (!r.ok() && st.pc == at && !st.wait)
    return stopped_here(StopKind::Pause, "The module's reply to the step (130) was lost and the program is still at address " +
                                             std::to_string(at) + ": it was not sent again (it may run an instruction twice).");
  // A WAIT in progress (errata D2): with patches, the instruction after it becomes a jump to
  // itself and the program runs until it spins there, so the step ends right after the WAIT
  // whether the firmware's 130 returns at once during a WAIT or only when it is over; without,
  // 130 is sent again until 135's wait flag is clear (a firmware that ends the WAIT and runs the
  // next instruction in one 130 then stops one further on).
  if (st.wait && setup_.patch && at + 1 < program_size()) {
    Stop s = run_to_mark(at + 1);
    if (s.kind != StopKind::Step) return s;
    st.pc = pc_;
    st.wait = false;
    st.mode = 2;  // held after the WAIT by our own 128, not ended
  }
  while (st.wait) {
    if (pause_.exchange(false)) return stopped_here(StopKind::Pause, std::exchange(pause_note_, {}));
    std::this_thread::sleep_for(std::chrono::milliseconds(setup_.poll_ms));
    waiting();
    r = client_->request(ctl(Op::StepApplication), false);
    if (!r.ok() && r.fail != host::Fail::NoReply) return failed(r.error);
    if (!read_status(st, error)) return failed(error);
  }
  // The frames seen entered and left while stepping.
  if (st.mode != 0) track(at, ins, st.pc);
  const bool ended = st.mode == 0;
  Stop s = stopped_here(StopKind::Step);
  if (s.kind != StopKind::Step) return s;
  if (ended) {  // the program ended (STOP), or the module stopped it
    running_ = false;
    const bool stop = ins.op == code(Op::STOP);
    return Stop{StopKind::Exited, 0,
                stop ? "STOP at address " + std::to_string(at)
                     : "the module stopped the program at address " + std::to_string(pc_) + " (it does not say why)",
                0, 0};
  }
  return s;
}

std::vector<std::int32_t> ModuleTarget::destinations(std::int32_t at, const Instruction& ins) const {
  switch (static_cast<Op>(ins.op)) {
    case Op::JA:
    case Op::CSUB:
    case Op::RST: return {ins.value};
    case Op::JC:
    case Op::CALL:
    case Op::DJNZ: return {ins.value, at + 1};
    case Op::WAIT: return {at, at + 1};  // its own address while it waits
    case Op::RSUB:
      if (!stack_.empty() && !stack_.back().interrupted) return {stack_.back().pc + 1};
      return {};
    case Op::RETI:
      if (!stack_.empty() && stack_.back().interrupted) return {stack_.back().pc};
      return {};
    default: return {at + 1};
  }
}

void ModuleTarget::track(std::int32_t at, const Instruction& ins, std::int32_t to) {
  last_delta_ = 0;
  const std::vector<std::int32_t> goes = destinations(at, ins);
  // What the instruction itself did, had it gone to `where`.
  auto effect = [&](std::int32_t where) {
    switch (static_cast<Op>(ins.op)) {
      case Op::CSUB:
      case Op::CALL:
        if (where == ins.value && where != at + 1) stack_.push_back({at, false, -1}), last_delta_ = 1;
        break;
      case Op::RSUB:
        if (!stack_.empty() && !stack_.back().interrupted) stack_.pop_back();
        last_delta_ = -1;
        break;
      case Op::RETI:  // a handler this session saw entered; one entered while running freely balances itself
        if (!stack_.empty() && stack_.back().interrupted) stack_.pop_back(), last_delta_ = -1;
        break;
      case Op::RST:
        stack_.clear();
        stack_known_ = true;
        last_delta_ = -(1 << 20);  // every frame left
        break;
      default: break;
    }
  };
  if (goes.empty() || std::find(goes.begin(), goes.end(), to) != goes.end()) return effect(to);
  // Not where the instruction goes: an interrupt was entered (errata D7). At a handler's first
  // instruction: after the instruction, which went to its only destination, where RETI resumes;
  // one instruction into a handler: before it, so RETI resumes at it.
  std::vector<std::pair<int, std::int32_t>> handlers;  // the vectors the program's VECTs name
  for (std::int32_t a = 0; a < program_size(); ++a)
    if (const Instruction& v = memory_[static_cast<std::size_t>(a)]; v.op == code(Op::VECT)) handlers.emplace_back(v.type, v.value);
  for (const auto& [vector, handler] : handlers)
    if (to == handler && goes.size() == 1) {
      effect(goes[0]);
      stack_.push_back({goes[0], true, vector});
      last_delta_ += 1;
      return;
    }
  for (const auto& [vector, handler] : handlers) {
    if (handler < 0 || handler >= program_size()) continue;
    const std::vector<std::int32_t> next = destinations(handler, memory_[static_cast<std::size_t>(handler)]);
    if (std::find(next.begin(), next.end(), to) != next.end() && to != handler) {
      stack_.push_back({at, true, vector});
      last_delta_ = 1;
      return;
    }
  }
  // Somewhere else: what happened is not told (a conditional jump interrupted, a handler not
  // named by a VECT). The frames above are unknown from here.
  stack_.clear();
  stack_known_ = false;
}

Stop ModuleTarget::start(bool stop_at_entry) {
  if (!loaded()) return refused(stop_at_entry ? "start" : "run");
  std::int32_t ignored = 0;
  std::string error;
  if (!ask(ctl(Op::ResetApplication), ignored, error)) return failed(error);
  running_ = true;
  stack_.clear();
  stack_known_ = true;
  for (auto& b : breaks_) b.hits = 0;
  Stop s = stopped_here(StopKind::Entry);
  if (s.kind != StopKind::Entry) return s;
  refresh_watches();
  counted_pc_ = stop_at_entry ? pc_ : -1;  // `run` stops at a breakpoint on address 0; `start` does not count it
  if (stop_at_entry) return s;
  return cont();
}

void ModuleTarget::kill() {
  std::int32_t ignored = 0;
  std::string error;
  if (ask(ctl(Op::StopApplication), ignored, error)) stopped_here(StopKind::Step);
  running_ = false;
}

Stop ModuleTarget::cont() {
  if (!loaded()) return refused("continue");
  if (!running_) return Stop{StopKind::NotRunning, 0, "The program is not being run.", 0, 0};
  return run({}, -1);
}

Stop ModuleTarget::step(std::uint64_t n) {
  if (!loaded()) return refused("step");
  if (!running_) return Stop{StopKind::NotRunning, 0, "The program is not being run.", 0, 0};
  bool ok = true;
  if (Stop h = hold(ok); !ok) return h;
  Stop s;
  for (std::uint64_t i = 0; i < n; ++i) {
    if (pause_.exchange(false)) return stopped_here(StopKind::Pause, std::exchange(pause_note_, {}));
    s = step_one();
    if (s.kind != StopKind::Step) return s;
    Stop b;
    if (hit_at_pc(b)) return b;
    if (watching() && watch_changed(b)) return b;
  }
  return s;
}

Stop ModuleTarget::next() {
  if (!loaded()) return refused("next");
  if (!running_) return Stop{StopKind::NotRunning, 0, "The program is not being run.", 0, 0};
  bool ok = true;
  if (Stop h = hold(ok); !ok) return h;
  if (!is_call(instruction(pc_)) || waiting_) return step(1);
  // Over the call: to the instruction after it, in this frame (a recursive call returns there
  // from deeper frames first: the depth is counted).
  return run({pc_ + 1}, 0);
}

Stop ModuleTarget::finish() {
  if (!loaded()) return refused("finish");
  if (!running_) return Stop{StopKind::NotRunning, 0, "The program is not being run.", 0, 0};
  if (stack_.empty()) {
    if (stack_known_) return Stop{StopKind::NotRunning, 0, "\"finish\" not meaningful in the outermost frame.", 0, 0};
    return cannot("finish", "the caller is unknown: no command reads the module's call stack, and the program ran freely "
                            "since this frame was entered");
  }
  // To where the frame returns (after its call, or where the interrupted code resumes), one
  // frame out.
  const Frame& top = stack_.back();
  return run({top.interrupted ? top.pc : top.pc + 1}, -1);
}

Stop ModuleTarget::until(std::int32_t address) {
  if (!loaded()) return refused("until");
  if (!running_) return Stop{StopKind::NotRunning, 0, "The program is not being run.", 0, 0};
  return run({address}, 0);
}

// The program runs (129) with jumps to themselves at `marks` until it spins at one, stops by
// itself (`ended`) or a pause comes (`paused`); then it is stopped (128) and every patch removed.
// A Step stop when that went well.
Stop ModuleTarget::free_run(const std::vector<std::int32_t>& marks, bool tracking, bool& paused, bool& ended) {
  std::string error;
  if (!patch(marks, error)) {
    std::string ignored;
    if (!restore(ignored)) return failed(error);
    return Stop{StopKind::NotRunning, 0, "the breakpoints could not be written: " + error, 0, 0};
  }
  std::int32_t ignored = 0;
  counted_pc_ = -1;
  if (!tracking) {  // the frames it enters and leaves meanwhile are not seen
    stack_.clear();
    stack_known_ = false;
  }
  if (!ask(ctl(Op::RunApplication), ignored, error)) return failed(error);
  // Runs until the pc reaches a patch (the program spins there), the program stops, or a pause.
  Status st;
  for (;;) {
    if (pause_.exchange(false)) {
      paused = true;
      break;
    }
    if (!read_status(st, error)) {
      // The line is gone: the patches go back when the port comes back within the timeout.
      if (!reconnected(error)) return failed(error);
      if (!read_status(st, error)) return failed(error);
      note("The connection to the module was lost and came back.");
      paused = true;
      pause_note_ = "Program stopped: the connection to the module was lost (it came back).";
      break;
    }
    if (st.mode != 1) {
      ended = true;
      break;
    }
    if (std::find(marks.begin(), marks.end(), st.pc) != marks.end()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(setup_.poll_ms));
    waiting();
  }
  if (!ended && !ask(ctl(Op::StopApplication), ignored, error)) return failed(error);
  if (!unpatch(error)) {
    std::string message;
    if (!restore(message)) return failed(error);
  }
  return Stop{};
}

// Runs to the instruction after a WAIT in progress at pc (a jump to itself there).
Stop ModuleTarget::run_to_mark(std::int32_t mark) {
  bool paused = false, ended = false;
  // The WAIT's own frame: no call was made (a handler that ran meanwhile returned by itself).
  if (Stop f = free_run({mark}, true, paused, ended); f.kind != StopKind::Step) return f;
  if (paused) return stopped_here(StopKind::Pause, std::exchange(pause_note_, {}));
  Stop s = stopped_here(StopKind::Step);
  if (s.kind == StopKind::Step && ended) {
    running_ = false;
    return Stop{StopKind::Exited, 0, "the module stopped the program at address " + std::to_string(pc_) + " (it does not say why)", 0, 0};
  }
  return s;
}

Stop ModuleTarget::run(const std::vector<std::int32_t>& temps, int goal) {
  bool ok = true;
  if (Stop h = hold(ok); !ok) return h;
  auto is_temp = [&](std::int32_t a) { return std::find(temps.begin(), temps.end(), a) != temps.end(); };
  auto has_break = [&](std::int32_t a) {
    return std::any_of(breaks_.begin(), breaks_.end(), [&](const Breakpoint& b) { return b.enabled && b.address == a; });
  };
  // With a place to reach, the depth counts: the instructions that change it are marks too.
  const bool tracking = !temps.empty();
  std::vector<std::int32_t> depth_marks;
  if (tracking)
    for (std::int32_t a = 0; a < program_size(); ++a)
      if (const Op op = static_cast<Op>(instruction(a).op); op == Op::CSUB || op == Op::CALL || op == Op::RSUB || op == Op::RETI || op == Op::RST)
        depth_marks.push_back(a);
  auto changes_depth = [&](std::int32_t a) { return std::find(depth_marks.begin(), depth_marks.end(), a) != depth_marks.end(); };
  int rel = 0;  // frames deeper than at the start
  bool first = true;
  // Watchpoints, and breakpoints without patches: one instruction at a time.
  const bool stepping = watching() || !setup_.patch;
  for (;; first = false) {
    Stop stop;
    if (!first) {
      waiting();  // a breakpoint whose condition keeps failing: other input between its hits
      if (pause_.exchange(false)) return stopped_here(StopKind::Pause, std::exchange(pause_note_, {}));
    }
    if (!first && is_temp(pc_) && rel <= goal) {
      if (hit_at_pc(stop)) return stop;
      return stopped_here(StopKind::Step);
    }
    if (hit_at_pc(stop)) return stop;  // this execution's hit, unless this stop counted it
    if (stepping || has_break(pc_) || is_temp(pc_) || changes_depth(pc_) || waiting_) {
      // Over the instruction at pc (a breakpoint's, a mark's, or one a WAIT holds) before patching.
      if (pause_.exchange(false)) return stopped_here(StopKind::Pause, std::exchange(pause_note_, {}));
      Stop s = step_one();
      if (s.kind != StopKind::Step) return s;
      rel += last_delta_;
      if (watching() && watch_changed(stop)) return stop;
      continue;
    }
    std::vector<std::int32_t> marks = temps;
    marks.insert(marks.end(), depth_marks.begin(), depth_marks.end());
    for (const auto& b : breaks_)
      if (b.enabled) marks.push_back(b.address);
    std::sort(marks.begin(), marks.end());
    marks.erase(std::unique(marks.begin(), marks.end()), marks.end());
    bool paused = false, ended = false;
    if (Stop f = free_run(marks, tracking, paused, ended); f.kind != StopKind::Step) return f;
    if (paused) return stopped_here(StopKind::Pause, std::exchange(pause_note_, {}));
    Stop s = stopped_here(StopKind::Step);
    if (s.kind != StopKind::Step) return s;
    if (ended) {
      running_ = false;
      const std::int32_t at = instruction(pc_).op == code(Op::STOP) ? pc_ : pc_ - 1;
      const bool at_stop = at >= 0 && instruction(at).op == code(Op::STOP);
      return Stop{StopKind::Exited, 0,
                  at_stop ? "STOP at address " + std::to_string(at)
                          : "the module stopped the program at address " + std::to_string(pc_) + " (it does not say why)",
                  0, 0};
    }
  }
}

}  // namespace tmcl::debug
