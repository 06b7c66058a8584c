// The debugging engine: one engine, two front ends (the gdb-like command line of
// `tmclrun --debug` and the Debug Adapter Protocol of `tmclrun --dap`), as lldb-dap shares
// lldb's. It drives a Vm through run() with step and time limits, breakpoints as VM traps (free
// on the fast path), watchpoints, and reverse execution by checkpoints of the whole machine (VM,
// motion core, scenario position) plus deterministic re-execution. docs/debugger.md.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tmcl/eeprom.hpp"
#include "tmcl/expr.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/vm.hpp"

namespace tmcl::debug {

// ProgramInfo (what the debugger knows of the program) and the expressions (Expr, parse_expr,
// eval_expr, assign_expr) live in the VM's layer (tmcl/expr.hpp), where the test runner uses
// them too; these names keep them reachable as tmcl::debug::NAME.
using tmcl::assign_expr;
using tmcl::eval_expr;
using tmcl::Expr;
using tmcl::parse_expr;
using tmcl::ProgramInfo;

// `ins` (at `address`) with its targets by label and the operands the source wrote with a
// constant by that name ("JC LT, loop", "COMP Limit"); `numbers` gets "loop = 5, ..." for them
// (empty when nothing was named). symbolic.cpp.
std::string named_instruction(const ProgramInfo& info, const Instruction& ins, std::int32_t address, Vm& vm,
                              std::string* numbers = nullptr);

// ---- breakpoints and watchpoints (numbered together, as in gdb) ----
struct Breakpoint {
  int id = 0;
  std::int32_t address = 0;
  std::string location;  // as the user gave it
  bool enabled = true;
  bool temporary = false;
  std::string condition;  // expression text; empty: none
  Expr cond;
  int ignore = 0;         // hits to skip
  int hits = 0;
  std::string log_message;  // DAP logpoints: print instead of stopping ({expr} interpolated)
};
struct Watchpoint {
  int id = 0;
  std::string text;
  Expr expr;
  bool enabled = true;
  std::int64_t old_value = 0;
  bool valid = false;  // old_value was read
  int hits = 0;
};

enum class StopKind : std::uint8_t {
  Entry,       // the program was started and stopped before its first instruction
  Breakpoint,
  Watchpoint,
  Step,        // a step, next, finish, until or advance completed
  Pause,       // interrupted (Ctrl-C, DAP pause)
  Exited,      // STOP executed, the motors came to rest
  Fault,       // runtime fault at vm.halt_pc
  Limit,       // --max-time / --max-steps
  Blocked,     // waiting for an event that can never come
  NotRunning,  // nothing to run
  HistoryStart,// a reverse command reached the oldest checkpoint
};
struct Stop {
  StopKind kind = StopKind::Step;
  int id = 0;                   // breakpoint or watchpoint number
  std::string message;          // fault, limit, or why nothing ran
  std::int64_t old_value = 0, new_value = 0;
};

struct Setup {
  const Profile* profile = nullptr;
  std::string core_name;             // motion core
  SimTime instr_time = 20;
  Limits limits;                     // --max-time / --max-steps
  std::vector<InputEvent> inputs;    // scenario
  std::optional<EepromImage> eeprom; // power-up image
  std::size_t checkpoint_bytes = std::size_t{64} << 20;  // --checkpoint-memory
  std::uint64_t checkpoint_interval = std::uint64_t{1} << 20;  // instructions between checkpoints
  std::uint64_t slice_steps = std::uint64_t{1} << 16;  // instructions between two Engine::on_slice calls
  // Serving a host at the same time (tmclrun --serve --debug): `run` and `start` reset the
  // application (as command 131) instead of power-cycling the module, `kill` stops it (128),
  // and a command that runs the program restarts one the host stopped.
  bool serving = false;
};

class Engine {
 public:
  // `core` must be a fresh core of setup.core_name; the engine owns it.
  Engine(Setup setup, ProgramInfo info, std::unique_ptr<MotionCore> core);
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  Vm& vm() { return *vm_; }
  const ProgramInfo& info() const { return info_; }
  const Setup& setup() const { return setup_; }
  bool running() const { return running_; }  // started and not exited or killed

  // ---- breakpoints and watchpoints ----
  // Resolves a location: label, line, file:line, *address (gdb's forms). false with `error`.
  bool resolve(const std::string& location, std::int32_t& address, std::string& error) const;
  int add_breakpoint(std::int32_t address, std::string location, bool temporary);
  bool delete_point(int id);
  void delete_all();
  bool enable_point(int id, bool on);
  bool set_condition(int id, const std::string& text, std::string& error);
  bool set_ignore(int id, int count);
  int add_watchpoint(const std::string& text, std::string& error);
  std::vector<Breakpoint>& breakpoints() { return breaks_; }
  std::vector<Watchpoint>& watchpoints() { return watches_; }
  // Where logpoints print (DAP output events, the CLI's standard output).
  std::function<void(const std::string&)> on_output;
  // A log message with {EXPR} replaced by the expression's value.
  std::string interpolate(const std::string& text);

  // ---- execution (each returns why it stopped) ----
  // The stepping rules (docs/debugger.md, "Stepping"): a stop made by a step, next, finish or
  // until is always before an instruction, the one that runs next (a WAIT in progress has ended,
  // a due interrupt has been entered), so the stops are the instructions as --trace lists them.
  // A breakpoint counts one hit per execution of its instruction, also when a step lands on it.
  Stop start(bool stop_at_entry);  // power on, pc 0; runs unless stop_at_entry
  Stop cont();
  // n instructions, a WAIT with its wait, into CSUB and into a handler entered before the next
  // instruction (the handler's first instruction is a stop). From a WAIT in progress or with an
  // interrupt due, the first step only finishes the WAIT or enters the handler.
  Stop step(std::uint64_t n = 1);
  // One instruction of this frame: over CSUB and over handlers entered meanwhile, never over
  // an instruction of this frame; after RSUB or RETI, the caller's (interrupted code's) next one.
  Stop next();
  Stop finish();                   // until this frame is left (RSUB, RETI), before the caller's next instruction
  Stop until(std::int32_t address);// run to address (or a breakpoint), at this depth or above
  Stop advance(SimTime duration);  // run for that much simulated time
  void kill();
  void pause() { pause_.store(true); }  // from a signal handler or another thread
  // Pause from the front end's own thread (inside on_slice), with the text the stop carries
  // (Stop::message of the Pause), e.g. "Program stopped by the host (command 128)."
  void pause_for(std::string why) {
    pause_note_ = std::move(why);
    pause_.store(true);
  }
  // Called between slices of a run (every Setup::slice_steps instructions, and whenever
  // simulated time reaches the bound it returned last): a front end serves its other inputs
  // here (DAP requests, a virtual module's host) and may call pause_for() or change points.
  // Returns how far simulated time may go before the next call (kNever: no bound), which is how
  // a server paces the program by the wall clock. Never called while a reverse command or a
  // watchpoint's search re-executes.
  std::function<SimTime()> on_slice;
  // The machine was changed from outside the debugger (a host's request while serving):
  // history starts again here, watchpoints take the values as they are, and a program the
  // host started counts as running.
  void external_change();
  // Moves pc (DAP goto, `jump`); history before it stays, a reverse step comes back here.
  void set_pc(std::int32_t address);

  // ---- reverse execution ----
  Stop reverse_step(std::uint64_t n = 1);
  Stop reverse_next();
  Stop reverse_finish();
  Stop reverse_continue();
  bool can_reverse(std::string& why) const;
  std::size_t checkpoint_count() const { return checkpoints_.size(); }
  std::size_t checkpoint_memory() const;
  // After a change to the machine's state (set var, set pc): history starts again here.
  void state_changed();

  int depth() const;  // call-stack depth plus one inside an interrupt handler
  // Whether the next thing to happen is the instruction at pc: no WAIT in progress, no
  // interrupt or event due first. Every stop of a step is; a pause or a time limit may not be.
  bool at_instruction() const;

  // The call stack as backtrace shows it, innermost first: the frame at pc; each caller at its
  // CSUB; inside a handler, the interrupted code at the instruction it resumes (`interrupted`,
  // described by vm().saved), then its callers.
  struct Frame {
    std::int32_t pc = 0;
    bool interrupted = false;
  };
  std::vector<Frame> frames() const;

  // Changes the world outside the program from the prompt (set var in(0) = 1, a stop switch, an
  // analog input) as a scenario line at this instant would: the event joins the VM's queue of
  // timed inputs and is applied at once (an edge may latch an interrupt, entered before the next
  // instruction). History starts again here. false with `error` when the program is not running.
  bool set_input(InputEvent ev, std::string& error);
  // The machine's mechanics from the prompt (set var hardstop|load, as the scenario lines): a
  // hard stop or a load zone (InputEvent::placed_kind) belongs to the machine and is placed at
  // once, before `run` too; a timed load goes through set_input at this instant. A core that
  // cannot model it refuses here with `error` naming the core, instead of faulting the program.
  bool set_machine(InputEvent ev, std::string& error);
  // The same from the words of a scenario line, without its `at TIME` for a timed load:
  // `hardstop left 0 at -20000`, `load 0 = 40%`, `load 0 from 5000 to 6000 = 80%` (the CLI's
  // `set var`, DAP's evaluate in the debug console); `error` says what is wrong with the line.
  bool set_machine(const std::string& line, std::string& error);
  static bool is_machine_line(const std::string& line);  // it starts with `hardstop` or `load`
  // set var LV = value: a register, variable or parameter through assign_expr, an input
  // (in(n), ain(n)) through set_input.
  bool assign(const Expr& lhs, std::int64_t value, std::string& error);

 private:
  struct Checkpoint {
    std::uint64_t steps;
    Vm vm;
    std::unique_ptr<MotionCore> core;
  };
  struct Goal {
    std::uint64_t max_steps = UINT64_MAX;  // stop (Step) when steps reach this
    SimTime until = kNever;                // stop (Step) when time reaches this
    std::int32_t temp_addr = -1;           // stop (Step) at this address ...
    int depth = -1;                        // ... when the depth is at most this
    int below = -1;                        // stop (Step) before the first instruction at this depth or less
  };
  Stop go(const Goal& g);
  RunResult exec(std::uint64_t max_steps, SimTime until);  // with checkpoints and pause
  RunResult exec_over_trap(std::uint64_t max_steps, SimTime until);
  Stop from_result(const RunResult& r);
  Stop landed();  // a step's stop before the instruction at pc: a breakpoint there counts
  bool counted() const { return checked_steps_ == vm_->steps && checked_pc_ == vm_->pc; }
  bool watched_step(const Goal& g, Stop& stop, RunResult& r);
  bool check_break(Stop& stop);  // a Break at pc: stop here? (conditions, ignore counts)
  bool watch_changed(Stop& stop);
  bool watching() const;
  bool watch_by_traps(std::vector<std::uint8_t>* vars = nullptr) const;
  static bool writes_var(const Instruction& ins, const std::vector<std::uint8_t>& vars);
  void refresh_watches();
  void take_checkpoint();
  void restore_checkpoint(const Checkpoint& cp);
  const Checkpoint* checkpoint_before(std::uint64_t steps) const;
  void replay_to(std::uint64_t steps);  // from the last checkpoint at or before `steps`
  void set_traps();
  Stop reverse_scan(int kind);

  Setup setup_;
  ProgramInfo info_;
  std::unique_ptr<MotionCore> core_;
  std::unique_ptr<Vm> vm_;
  bool running_ = false;
  std::vector<Breakpoint> breaks_;
  std::vector<Watchpoint> watches_;
  int next_id_ = 1;
  std::atomic<bool> pause_{false};
  std::vector<Checkpoint> checkpoints_;
  std::uint64_t next_checkpoint_ = 0;
  std::size_t checkpoint_size_ = 0;  // bytes of one checkpoint (estimate)
  bool reversible_ = true;
  bool paused_ = false;
  std::string pause_note_;        // Stop::message of the next Pause (pause_for)
  std::int32_t temp_trap_ = -1;   // go()'s temporary trap, kept when points change meanwhile
  std::vector<std::int32_t> exit_traps_;  // go()'s traps where a frame may be left (Goal::below)
  // Where the breakpoints at pc were last checked (steps, pc): that execution has had its hit.
  std::uint64_t checked_steps_ = UINT64_MAX;
  std::int32_t checked_pc_ = -1;
  std::uint64_t next_slice_ = 0;  // on_slice is due when steps reach this ...
  SimTime slice_bound_ = kNever;  // ... or time reaches this
  bool in_slice_ = false;         // on_slice is running (no nested call)
  bool no_slice_ = false;         // a watchpoint's search re-executes: no on_slice
};

std::string stop_kind_name(StopKind k);

}  // namespace tmcl::debug
