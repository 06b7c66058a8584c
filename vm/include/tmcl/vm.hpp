// The TMCL virtual machine: a plain struct with visible state and a run loop that returns why it
// stopped. Deterministic: simulated time (microseconds) is data; nothing reads the wall clock.
//
//   Vm vm(profile, core);          // core: a MotionCore (motion.hpp), owned by the caller
//   vm.load(program);              // instructions, e.g. from the assembler or read_bin()
//   vm.power_on(&eeprom);          // defaults, then what the EEPROM restores at power-up
//   vm.start(0);
//   RunResult r = vm.run(limits);  // until STOP, a fault, a limit, or blocked forever
//
// The life cycle (start, step, stop_application, reset_application) is the VM's: the virtual
// module's control commands and a debugger call these methods rather than writing registers.
// The state a user inspects (registers, memory, time) is plain public data; the run loop's
// bookkeeping is private.
//
// Standalone mode (run) and direct mode (execute_direct) share one state, as on a real module.
// Semantics where the manuals are silent are recorded in docs/errata.md.
#pragma once

#include <array>
#include <atomic>
#include <bitset>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tmcl/eeprom.hpp"
#include "tmcl/isa.hpp"
#include "tmcl/params.hpp"  // status codes
#include "tmcl/motion.hpp"
#include "tmcl/profile.hpp"

namespace tmcl {

struct Vm;
namespace ops {
struct Internal;  // vm_ops.hpp: the instruction semantics' door to the VM's internals
}

// Comparison flags (set by COMP, by every CALC variant and by every read in standalone mode).
enum Flag : std::uint8_t { kFlagZero = 1, kFlagEqual = 2, kFlagGreater = 4, kFlagLower = 8 };
// Error flags (JC ETO/EAL/EDV/EPO, CLE).
enum ErrorFlag : std::uint8_t { kErrTimeout = 1, kErrAlarm = 2, kErrDeviation = 4, kErrPosition = 8, kErrShutdown = 16 };

// Program state as global parameter 128 reports it.
enum class AppStatus : std::uint8_t { Stopped = 0, Running = 1, Step = 2, Reset = 3 };

// Why run() returned.
enum class Halt : std::uint8_t {
  Stop,       // STOP executed (or the program was stopped); motion has been run to rest
  Fault,      // runtime fault: see RunResult::message
  StepLimit,  // Limits::max_steps instructions executed
  TimeLimit,  // simulated time reached Limits::until
  Blocked,    // waiting for an event that can never come (no timer, motion, input or timeout)
  NotRunning, // run() called while the program is stopped and no motion is pending
  Break,      // a debugger trap (Vm::set_trap) at pc: the instruction there has not executed
  Interrupted,  // Limits::stop was set from outside (a signal, a closed output): between instructions
};
std::string_view halt_name(Halt h);

// Where run() must stop at the latest. Both are totals, not budgets: run() returns when
// Vm::steps reaches max_steps (a WAIT counts as one instruction) or Vm::now reaches until.
struct Limits {
  std::uint64_t max_steps = UINT64_MAX;
  SimTime until = kNever;
  // With max_steps: StepLimit only once the next thing to happen is an instruction. A WAIT in
  // progress goes on to its end and a due interrupt is entered first, so pc is the instruction
  // that runs next (a debugger's step stops there: docs/debugger.md, "Stepping").
  bool to_instruction = false;
  // A request from outside to end the run, set asynchronously (a signal handler, another thread,
  // a trace that can no longer write; lock-free, so a signal handler may set it): once *stop is
  // true, run() returns Halt::Interrupted between two instructions, within kStopPollSteps
  // instructions or at the next instant a WAIT sleeps to. A run() called again goes on exactly
  // as if it had not returned. Null: nothing to ask.
  const std::atomic<bool>* stop = nullptr;
  static constexpr std::uint64_t kStopPollSteps = 1 << 16;
};

struct RunResult {
  Halt halt;
  std::string message;  // for Fault, Blocked and limits: what happened
};

// A WAIT in progress. Part of the interrupt context: a WAIT interrupted by a handler goes on.
struct WaitState {
  bool active = false;
  std::uint8_t kind = 0;  // WAIT type: 0 TICKS, 1 POS, 2 REFSW, 3 LIMSW, 4 RFS
  std::uint8_t motor = 0;
  SimTime deadline = kNever;  // TICKS: end; others: timeout (kNever: none)
};

struct InterruptContext {
  std::int32_t pc = 0;  // where to resume (the interrupted instruction, or a WAIT)
  std::int32_t acc = 0;
  std::int32_t x = 0;
  std::uint8_t flags = 0;
  WaitState wait;
  int stack_depth = 0;  // call-stack depth at entry: RSUB inside the handler cannot go below it
  int vector = -1;
};

struct Timer {
  std::uint32_t period_ms = 0;  // bank 3, parameters 0..2; 0 = off
  SimTime next = kNever;
};

// A motor's switches as the program sees them (WAIT LIMSW/REFSW, interrupts 27-32): closed when
// a timed scenario line or the position (a switch placed at positions) closes them.
struct MotorSwitches {
  bool left = false, right = false, home = false;
  std::uint8_t timed = 0, placed = 0;  // bit (1 << SwitchInput): closed by that source
};

// A direct-mode reply: status 100 ok, 2 invalid command, 3 wrong type, 4 invalid value,
// 6 not available on this module.
struct DirectReply {
  std::uint8_t status;
  std::int32_t value;
};
// (the kStatus names: params.hpp)

// A mistake the manuals let pass silently (the instruction is ignored), noticed as it happens:
// tmclrun prints these in its summary, trace and JSON; with Vm::strict each is a fault instead.
struct RuntimeWarning {
  enum Kind : std::uint8_t {
    CallStackFull,       // CSUB/CALL with 8 return addresses on the stack (E5)
    ReturnWithoutCall,   // RSUB with nothing to return to (E6)
    RetiOutsideHandler,  // RETI while no interrupt is being served (E13)
    HandlerWithoutReti,  // a handler that ends otherwise than with RETI (STOP, a jump out; E42, E43)
    ValueOutOfRange,     // SAP/SGP/AAP/AGP/ROR/ROL with a value outside the parameter's range or value set (E3, E51)
    NoSuchMotor,         // an instruction naming a motor the module does not have (E51)
    NotWritable,         // SAP/SGP/AAP/AGP on a read-only or unknown parameter (E51)
    NoSuchPort,          // GIO/SIO on a port the profile does not list (E53)
    NoSuchCoordinate,    // MVP COORD of a coordinate the module lacks, or on a module without coordinates (M32)
    NotSimulated,        // a note, not a warning (but under --strict): EI of an interrupt nothing raises (E52),
                         // a parameter the profile marks not-simulated written or read (E77)
    RampSetting,         // MVP whose ramp cannot start it, or that the manual forbids (E47)
    NoSuchType,          // MVP/MVPA/MVPXA of a type other than ABS, REL, COORD (from a .bin; E80)
  };
  SimTime at = 0;        // the instruction's start
  std::int32_t pc = 0;   // its address
  Kind kind = CallStackFull;
  std::string message;   // without the place: "CSUB to 12 ignored: ..."
  bool note = false;     // a note (NotSimulated without --strict): in Vm::notes, not a warning
};
std::string_view warning_kind_name(RuntimeWarning::Kind k);  // "call-stack-full", ...

// Observer for --trace; every callback gets the instant. Null by default (no cost).
class TraceSink {
 public:
  virtual ~TraceSink() = default;
  // Called after an instruction executed; `at` is its start time, `pc` its address.
  virtual void instruction(const Vm& vm, SimTime at, std::int32_t pc, const Instruction& ins) = 0;
  virtual void interrupt_enter(const Vm& vm, int vector, std::int32_t from_pc) = 0;
  virtual void interrupt_leave(const Vm& vm, std::int32_t to_pc) = 0;
  virtual void motion_event(const Vm& vm, const MotionEvent& ev) = 0;
  virtual void wait_end(const Vm& vm, std::int32_t pc, bool timeout) = 0;
  virtual void input_event(const Vm& vm, const std::string& what) = 0;
  // Called right after instruction() when that instruction recorded a run-time warning.
  virtual void warning(const Vm& vm, const RuntimeWarning& w) { (void)vm, (void)w; }
};

// One external input change at an instant (from a scenario, or pushed by a server).
struct InputEvent {
  enum Kind : std::uint8_t { Digital, Analog, StopLeft, StopRight, Home, Slip, Placed, Load, HardStop, LoadZone };
  SimTime at = 0;
  Kind kind = Digital;
  int index = 0;  // input number, or motor
  std::int32_t value = 0;
  int line = 0;   // scenario line (0: not from a file)
  // Placed (at 0): switch `input` of motor `index` is closed while the motor's physical position
  // lies in [from, to] (MotionCore::place_switch; scenario `switch left 0 at -20000`).
  SwitchInput input = SwitchInput::StopLeft;
  std::int64_t from = 0, to = 0;
  // Load (timed): from `at` on, motor `index` carries a load of `value` % of its holding torque.
  // HardStop (at 0): a mechanical end of motor `index` at physical position `from`, on side
  // `input` (StopLeft: the shaft cannot go below it; StopRight: above it). LoadZone (at 0): a load
  // of `value` % while the shaft is in [from, to]. (MotionCore::set_load, place_hard_stop, place_load.)
  bool placed_kind() const { return kind == Placed || kind == HardStop || kind == LoadZone; }
};

struct Vm {
  static constexpr int kStackDepth = 8;
  static constexpr int kTimers = 3;
  static constexpr int kPorts = kPortCount;  // port numbers of each I/O bank; the profile says which exist

  // ---- configuration (set before power_on) ----
  const Profile* profile;
  MotionCore* motion;
  SimTime instr_time = 20;        // per instruction, microseconds (tmclrun --instr-time)
  TraceSink* trace = nullptr;
  // Called for every motion event as the VM handles it (e.g. a server's position-reached reply,
  // command 138). Empty by default; never on the instruction fast path.
  std::function<void(const Vm&, const MotionEvent&)> on_motion_event;

  // ---- program memory: `program` ends with one sentinel (opcode 0) past the last instruction ----
  std::vector<Instruction> program;
  std::int32_t program_size = 0;  // without the sentinel
  // Where a .tmc program came from (tmclrun fills it), for fault messages: "prog.tmc:12".
  std::vector<std::string> source_of;

  // ---- registers ----
  std::int32_t pc = 0;
  std::int32_t acc = 0;
  std::int32_t x = 0;
  std::uint8_t flags = 0;   // Flag bits
  std::uint8_t errors = 0;  // ErrorFlag bits
  std::array<std::int32_t, kStackDepth> stack{};
  int sp = 0;
  std::array<std::int32_t, kStackDepth> data_stack{};  // PUSHA/PUSHX/PUSHV, POPA/POPX/POPV
  int dsp = 0;
  AppStatus status = AppStatus::Stopped;
  WaitState wait;

  // ---- memory ----
  std::array<std::int32_t, 256> vars{};                // bank 2
  std::array<std::int32_t, 256> bank0{};               // bank 0 (128..133 are computed)
  std::array<std::int32_t, 256> bank3{};               // bank 3 (interrupt configuration)
  std::vector<std::array<std::int32_t, 256>> axis;     // per motor, parameters the core does not own
  std::vector<std::array<bool, 256>> axis_written;     // which of those were ever written (for JSON)
  std::vector<std::vector<std::int32_t>> coords;       // per motor, profile->coords entries
  std::array<std::int32_t, kPorts> inputs{};           // digital inputs (GIO n, 0)
  std::array<std::int32_t, kPorts> analog{};           // analog inputs (GIO n, 1)
  std::array<std::int32_t, kPorts> outputs{};          // digital outputs (SIO n, 2 / GIO n, 2)
  std::array<std::int32_t, kPorts> settings{};         // SIO n, 0: input settings (pull-ups, input range)
  std::vector<MotorSwitches> switches;
  EepromImage eeprom;
  bool eeprom_dirty = false;

  // ---- interrupts ----
  std::array<std::int32_t, 256> vectors{};   // handler address, -1 = not defined
  std::array<std::uint64_t, 4> enabled{};  // bit n: interrupt n enabled (EI n)
  std::array<std::uint64_t, 4> pending{};  // bit n: latched, waiting to be served
  bool global_enable = false;
  bool in_handler = false;
  InterruptContext saved;
  std::array<Timer, kTimers> timers{};

  // ---- time and counters ----
  SimTime now = 0;
  std::uint64_t steps = 0;
  std::int64_t tick_offset_ms = 0;  // global 132 = now/1000 + tick_offset_ms
  std::uint32_t random_state = 1;   // global 133
  std::int32_t halt_pc = -1;        // address of the STOP or faulting instruction

  // ---- run-time warnings (cleared by power_on); recorded only on the rare paths ----
  static constexpr std::size_t kMaxWarnings = 100;
  bool strict = false;                    // tmclrun --strict: a warning is a runtime fault
  std::vector<RuntimeWarning> warnings;   // the first kMaxWarnings
  std::uint64_t warnings_total = 0;       // including those past the cap
  RuntimeWarning last_warning;            // the latest, for the trace even past the cap
  // Notes: what the run does not simulate though the program relies on it (E52), once each; with
  // --strict each is a warning (and so a fault) instead. Cleared by power_on.
  std::vector<RuntimeWarning> notes;
  // Optional, from the front end's control-flow analysis (tmcl::analyze): per address, non-zero
  // where the instruction is an interrupt handler's own code. When set, a handler that goes on
  // outside that code without a call of its own (a jump out, or running on into other code) is a
  // run-time warning, once per interrupt served, as -Wreti warns of it before the run (E43).
  std::vector<std::uint8_t> handler_code;
  bool handler_left_ = false;             // this handler's jump out was reported

  // ---- coverage (tmclrun --test --coverage): per address, how often the instruction ran, and for
  // JC, CALL and DJNZ how often its condition held (it jumped, or called). Empty: nothing is
  // counted and the run loop runs its plain form. count_coverage() sizes both to the program
  // (after load); start() and power_on() keep the counts.
  std::vector<std::uint64_t> executed, taken;
  void count_coverage();

  // ---- external inputs queued by time ----
  std::vector<InputEvent> inputs_queue;  // sorted by time; consumed from input_next
  std::size_t input_next = 0;
  // Switches, hard stops and loads placed at positions (InputEvent::placed_kind): they belong to the machine, not to time,
  // so add_inputs places them at once and power_on again on the reset core, program or not.
  std::vector<InputEvent> placed;

  Vm(const Profile& p, MotionCore& core);

  // ---- life cycle: loading, power, and what the control commands and a debugger do ----
  // Replaces program memory (the VM appends its own sentinel).
  void load(const std::vector<Instruction>& prog);
  // Power-up: every register, parameter and variable to its default, then what `image`
  // restores (user variables, axis parameters, coordinates, bank 0). Time restarts at 0.
  void power_on(const EepromImage* image = nullptr);
  // Program memory in the EEPROM, on a module whose profile says `program-memory N eeprom`:
  // store_program() copies program memory into `eeprom` (a download's end, the program of a
  // run with an EEPROM file; docs/errata.md E55); a module that keeps it in RAM stores nothing.
  bool program_in_eeprom() const;
  void store_program();
  // Starts (or continues) the program at `address` (control command 129); clears a fault.
  void start(std::int32_t address);
  // Control command 130: exactly one instruction from `pc` at the current instant (a WAIT is
  // entered, or checked and left when over, never jumped over), then the program waits in
  // AppStatus::Step. Motion
  // and inputs are brought up to the new instant.
  RunResult step();
  // Control command 128: a running or stepping program stops where it is; the motors finish
  // what they were told (the next run() lets them).
  void stop_application();
  // Control command 131: the program stops, pc 0, stacks, registers, flags and interrupt state
  // cleared; status AppStatus::Reset.
  void reset_application();
  // RST and the reset above: stack, registers, flags, interrupt state cleared (pc and status
  // unchanged).
  void reset_interpreter();
  // Queues external input changes (sorted by time, stable); places the switches at positions.
  void add_inputs(std::vector<InputEvent> events);
  // The instant of the next timed input not yet applied (kNever: none), and applying those due
  // at `now`: the run loop does both itself while a program runs; a module driven by its host
  // alone (TmclModule::advance) brings the world to each such instant and applies it.
  SimTime next_input_at() const { return input_next < inputs_queue.size() ? inputs_queue[input_next].at : kNever; }
  void apply_due_inputs();

  // Runs the program until STOP, a fault, a limit, or blocked forever.
  RunResult run(const Limits& limits);
  // Direct mode: one command from a host. Reads do not touch the accumulator.
  DirectReply execute_direct(const Instruction& ins);

  // ---- reads for output, tests and a debugger ----
  std::int32_t axis_param(int motor, int param);  // through the core where it owns the number
  std::int32_t global_param(int bank, int param);
  std::int32_t tick_ms() const;
  bool motion_pending() const { return motion->next_event() != kNever; }
  bool faulted() const { return fault_set_; }                          // since the last start()
  const std::string& fault_message() const { return fault_message_; }  // empty without a fault
  bool is_enabled(int n) const { return (enabled[n >> 6] >> (n & 63)) & 1; }
  SimTime next_wakeup() const;     // earliest timer, motion event, input, WAIT deadline
  void sync_motion();              // advance the core to `now`, handle its events
  std::string where(std::int32_t address) const;  // "address 12 (prog.tmc:13)"

  // ---- debugger traps (cli/debug): run() returns Halt::Break before executing a trapped
  // address. A trap decodes to opcode 0 in the run loop's code, so the fast path pays nothing
  // for it; only the slow path that reports unknown instructions looks at `traps`.
  std::vector<std::uint8_t> traps;  // per address, 1 = trapped; empty when none was ever set
  bool trap_hit = false;            // set by the run loop, cleared when run() returns Break
  void set_trap(std::int32_t address, bool on);
  bool trapped(std::int32_t address) const {
    return address >= 0 && static_cast<std::size_t>(address) < traps.size() && traps[static_cast<std::size_t>(address)];
  }
  // Checkpoints for reverse execution (cli/debug): a copy of the whole machine without program
  // memory, its decoded form, traps, sources and the input queue (which do not change while
  // debugging, so a checkpoint shares the live VM's), and restoring one. The motion core is
  // copied on its own (MotionCore::clone); restore() keeps this VM's core, trace and hooks.
  Vm checkpoint();
  void restore(const Vm& checkpoint);

  // Parameter access with the profile's rules. Return a direct-mode status.
  std::uint8_t set_axis(int motor, int param, std::int32_t value);
  std::uint8_t get_axis(int motor, int param, std::int32_t& value);
  std::uint8_t set_global(int bank, int param, std::int32_t value);
  std::uint8_t get_global(int bank, int param, std::int32_t& value);
  std::uint8_t store_axis(int motor, int param);
  std::uint8_t restore_axis(int motor, int param);
  std::uint8_t store_global(int bank, int param);
  std::uint8_t restore_global(int bank, int param);
  std::uint8_t set_coord(int motor, int n, std::int32_t value);  // SCO/ACO incl. bank-255 forms
  std::uint8_t get_coord(int motor, int n, std::int32_t& value); // GCO incl. bank-255 form
  std::uint8_t capture_coord(int motor, int n, std::int32_t& value);
  std::uint8_t set_io(int port, int bank, std::int32_t value);
  std::uint8_t get_io(int port, int bank, std::int32_t& value);
  // The port numbers of `bank` GIO (write: false) or SIO (write: true) reaches, "0, 1, 2, 255" ("none").
  std::string ports_text(int bank, bool write) const;
  std::uint8_t move(int type, int motor, std::int32_t value);
  std::uint8_t rotate(int motor, std::int64_t velocity);
  std::uint8_t motor_stop(int motor);
  std::uint8_t rfs(int type, int motor, std::int32_t& value);
  bool motor_ok(int motor) const { return motor >= 0 && motor < profile->motors; }
  // The profile row whose range refuses `value` for axis parameter `param`, or for a global
  // parameter of bank 0 or 3 (axis: false): the active profile's, else, for a parameter the
  // motion core owns, the row it checks against; nullptr when no range refuses it. For messages:
  // the run-time warning `value-out-of-range` and the debugger's `set`.
  const ParamInfo* range_refusing(bool axis, int bank, int param, std::int64_t value) const;

 private:
  // The run loop (vm_exec.cpp) and the instruction semantics (vm_ops.hpp) reach the internals
  // below; nothing else does.
  struct Loop;
  friend struct ops::Internal;

  std::vector<Instruction> code_;  // what the run loop executes: `program` pre-decoded (opcode 0
                                   // where the profile lacks the command: faults with a message)
  SimTime next_check_ = 0;         // the run loop leaves its fast path when now >= next_check_
  bool fault_set_ = false;
  std::string fault_message_;
  std::string unplaceable_;  // a placed switch the core refused: every run() is this fault
  std::vector<MotionEvent> event_buf_;
  // The parameters the profile marks not-simulated (axis, bank 0, bank 3), set by power_on: the
  // one test on the parameter instructions' path.
  std::array<std::bitset<256>, 3> not_simulated_params_{};

  void fault(std::string message);
  bool warn(RuntimeWarning::Kind kind, std::string message);  // true: strict made it a fault
  // EI n of a vector nothing raises on this module and core (interrupts.hpp): a note once, a
  // warning under --strict; true when --strict made it a fault.
  bool note_not_simulated(int vector);
  // An instruction (`mnemonic`, `read` for GAP/GGP) that uses a parameter whose profile line says
  // not-simulated= (axis: bank -1): a note once per parameter per run, a warning under --strict;
  // true when --strict made it a fault.
  bool note_not_simulated_param(int bank, int number, std::string_view mnemonic, bool read);
  // A note whose message starts with `once` has been given already: nothing; else `message` as a
  // note (a warning under --strict; true when that made it a fault).
  bool note_once(std::string_view once, std::string message);
  // Before the instruction at pc runs inside a handler: reports it when it is outside the
  // handler's code (handler_code); true when --strict made that a fault.
  bool check_handler_code();
  void handle_motion_event(const MotionEvent& ev);
  void apply_input(const InputEvent& ev);
  // A switch closed or opened by one source (timed: a scenario line; else its position): the
  // program's view, the trace and the interrupts follow the switch as both sources close it.
  void switch_source(int motor, SwitchInput input, bool timed, bool level);
  void raise(int vector);          // latch an interrupt if it is enabled and has a vector
  bool try_enter_interrupt();
  void fire_due_timers();
  int wait_check();                // 0 still waiting, 1 condition met, 2 timed out (ETO set)
  void set_timer(int n, std::int32_t period_ms);
  void set_bank3(int param, std::int32_t value);  // bank3[param], restarting a timer (0 … 2)
  bool vector_ok(int n) const;
  bool jump_ok(std::int32_t target);  // faults when the target is outside the program
  void decode_all();  // rebuilds code_[] from program[]
};

// Why the WAIT the VM is in can never end (nothing pending can end it), as " can never end: ...":
// the run's Blocked message, and the test runner's for a run cut at its max-time.
std::string never_ending_wait_reason(const Vm& vm);

}  // namespace tmcl
