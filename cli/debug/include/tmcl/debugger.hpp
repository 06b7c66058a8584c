// The virtual machine as the debugger's target (tmcl/debug_target.hpp; the other is a module,
// tmcl/debug_module.hpp); one engine, two front ends (the gdb-like command line of
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

#include "tmcl/debug_target.hpp"
#include "tmcl/eeprom.hpp"
#include "tmcl/expr.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/vm.hpp"

namespace tmcl::debug {

// `ins` (at `address`) with its targets by label and the operands the source wrote with a
// constant by that name ("JC LT, loop", "COMP Limit"); `numbers` gets "loop = 5, ..." for them
// (empty when nothing was named). symbolic.cpp.
std::string named_instruction(const ProgramInfo& info, const Instruction& ins, std::int32_t address, Target& target,
                              std::string* numbers = nullptr);

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

// The virtual machine as a debugger's target (debug_target.hpp).
class Engine final : public Target {
 public:
  // `core` must be a fresh core of setup.core_name; the engine owns it.
  Engine(Setup setup, ProgramInfo info, std::unique_ptr<MotionCore> core);

  Vm& vm() { return *vm_; }
  const Setup& setup() const { return setup_; }
  Engine* machine() override { return this; }
  std::string name() const override { return "the virtual module"; }
  bool eval(const Expr& e, std::int64_t& value, std::string& error) override { return eval_expr(e, *vm_, value, error); }
  std::int32_t pc() override { return vm_->faulted() && vm_->halt_pc >= 0 ? vm_->halt_pc : vm_->pc; }
  std::int32_t program_size() const override { return vm_->program_size; }
  Instruction instruction(std::int32_t address) override { return vm_->program[static_cast<std::size_t>(address)]; }
  std::string when() override;

  // ---- execution (each returns why it stopped) ----
  // The stepping rules (docs/debugger.md, "Stepping"): a stop made by a step, next, finish or
  // until is always before an instruction, the one that runs next (a WAIT in progress has ended,
  // a due interrupt has been entered), so the stops are the instructions as --trace lists them.
  // A breakpoint counts one hit per execution of its instruction, also when a step lands on it.
  Stop start(bool stop_at_entry) override;  // power on, pc 0; runs unless stop_at_entry
  Stop cont() override;
  // n instructions, a WAIT with its wait, into CSUB and into a handler entered before the next
  // instruction (the handler's first instruction is a stop). From a WAIT in progress or with an
  // interrupt due, the first step only finishes the WAIT or enters the handler.
  Stop step(std::uint64_t n = 1) override;
  // One instruction of this frame: over CSUB and over handlers entered meanwhile, never over
  // an instruction of this frame; after RSUB or RETI, the caller's (interrupted code's) next one.
  Stop next() override;
  Stop finish() override;          // until this frame is left (RSUB, RETI), before the caller's next instruction
  Stop until(std::int32_t address) override;  // run to address (or a breakpoint), at this depth or above
  Stop advance(SimTime duration);  // run for that much simulated time
  void kill() override;
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
  void set_pc(std::int32_t address) override;

  // ---- reverse execution ----
  Stop reverse_step(std::uint64_t n = 1) override;
  Stop reverse_next() override;
  Stop reverse_finish() override;
  Stop reverse_continue() override;
  bool can_reverse(std::string& why) const override;
  std::size_t checkpoint_count() const { return checkpoints_.size(); }
  std::size_t checkpoint_memory() const;
  // After a change to the machine's state (set var, set pc): history starts again here.
  void state_changed();

  int depth() const override;
  // Whether the next thing to happen is the instruction at pc: no WAIT in progress, no
  // interrupt or event due first. Every stop of a step is; a pause or a time limit may not be.
  bool at_instruction() const;

  // The call stack as backtrace shows it, innermost first: the frame at pc; each caller at its
  // CSUB; inside a handler, the interrupted code at the instruction it resumes (`interrupted`,
  // described by vm().saved), then its callers.
  std::vector<Frame> frames() override;

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
  bool assign(const Expr& lhs, std::int64_t value, std::string& error) override;

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
  bool check_break(Stop& stop);  // a Break at pc: stop here? (Target::breakpoint_hit)
  void points_changed() override { set_traps(); }
  bool watch_by_traps(std::vector<std::uint8_t>* vars = nullptr) const;
  static bool writes_var(const Instruction& ins, const std::vector<std::uint8_t>& vars);
  void take_checkpoint();
  void restore_checkpoint(const Checkpoint& cp);
  const Checkpoint* checkpoint_before(std::uint64_t steps) const;
  void replay_to(std::uint64_t steps);  // from the last checkpoint at or before `steps`
  void set_traps();
  Stop reverse_scan(int kind);

  Setup setup_;
  std::unique_ptr<MotionCore> core_;
  std::unique_ptr<Vm> vm_;
  std::vector<Checkpoint> checkpoints_;
  std::uint64_t next_checkpoint_ = 0;
  std::size_t checkpoint_size_ = 0;  // bytes of one checkpoint (estimate)
  bool reversible_ = true;
  bool paused_ = false;
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

}  // namespace tmcl::debug
