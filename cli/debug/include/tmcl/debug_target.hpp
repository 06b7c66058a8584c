// What the debugger debugs: a target, as gdb has native and remote targets. The front ends (the
// command line, DAP) talk to a Target only; two implement it: the virtual machine (Engine,
// tmcl/debugger.hpp: traps, checkpoints, reverse execution) and a module over the TMCL host
// protocol (ModuleTarget, tmcl/debug_module.hpp: breakpoints by patching program memory). The
// points (breakpoints, watchpoints, their conditions, ignore counts and temporary ones) and how a
// location resolves are the same on both, so they live here; how a program runs, stops and is
// read is each target's. What a target cannot do it says in words (`Target::cannot`), never by
// doing something else. docs/debugger.md.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tmcl/expr.hpp"
#include "tmcl/profile.hpp"

namespace tmcl::debug {

using tmcl::assign_expr;
using tmcl::eval_expr;
using tmcl::Expr;
using tmcl::parse_expr;
using tmcl::ProgramInfo;

class Engine;

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
  NotRunning,  // nothing to run (or the target refused: `message` says why)
  HistoryStart,// a reverse command reached the oldest checkpoint
};
struct Stop {
  StopKind kind = StopKind::Step;
  int id = 0;                   // breakpoint or watchpoint number
  std::string message;          // fault, limit, or why nothing ran
  std::int64_t old_value = 0, new_value = 0;
};

class Target {
 public:
  Target(const Profile& profile, ProgramInfo info) : profile_(&profile), info_(std::move(info)) {}
  virtual ~Target() = default;
  Target(const Target&) = delete;
  Target& operator=(const Target&) = delete;

  const ProgramInfo& info() const { return info_; }
  const Profile& profile() const { return *profile_; }
  bool running() const { return running_; }  // started and not exited or killed
  // The virtual machine's engine, for what only it has (interrupt state, timers, checkpoints,
  // the simulated world); nullptr on a module.
  virtual Engine* machine() { return nullptr; }
  // "the virtual module" / "a module": in messages of what a target cannot do.
  virtual std::string name() const = 0;

  // ---- reading and writing the program's state ----
  virtual bool eval(const Expr& e, std::int64_t& value, std::string& error) = 0;
  // set var LV = value: a register, variable, parameter (or, on the VM, an input).
  virtual bool assign(const Expr& lhs, std::int64_t value, std::string& error) = 0;
  virtual std::int32_t pc() = 0;  // where the program is (the faulting instruction after a fault)
  // Program memory as the target holds it (a module's as read back, breakpoint patches shown as
  // the instructions they cover): program_size() instructions.
  virtual std::int32_t program_size() const = 0;
  virtual Instruction instruction(std::int32_t address) = 0;
  virtual int depth() const = 0;  // call-stack depth plus one inside an interrupt handler
  // The call stack as backtrace shows it, innermost first: the frame at pc; each caller at its
  // CSUB; inside a handler, the interrupted code at the instruction it resumes (`interrupted`).
  // `unknown_above`: frames above the last one exist but the target cannot tell them (a module
  // after a free run).
  struct Frame {
    std::int32_t pc = 0;
    bool interrupted = false;
    int vector = -1;  // interrupted: the interrupt's number
  };
  virtual std::vector<Frame> frames() = 0;
  virtual bool frames_unknown_above() const { return false; }
  // What the stop line adds after the place: ", time 0.020000s" on the VM.
  virtual std::string when() { return ""; }
  // The program's state in words for `info registers` on a module: "stopped", "step, in WAIT".
  virtual std::string status() { return ""; }

  // ---- execution (each returns why it stopped) ----
  // The stepping rules (docs/debugger.md, "Stepping") hold on every target: a stop made by a
  // step, next, finish or until is before the instruction that runs next; a breakpoint counts
  // one hit per execution of its instruction.
  virtual Stop start(bool stop_at_entry) = 0;  // from address 0; runs unless stop_at_entry
  virtual Stop cont() = 0;
  virtual Stop step(std::uint64_t n = 1) = 0;
  virtual Stop next() = 0;
  virtual Stop finish() = 0;
  virtual Stop until(std::int32_t address) = 0;
  virtual void kill() = 0;
  virtual void set_pc(std::int32_t address) = 0;  // jump, DAP goto
  void pause() { pause_.store(true); }  // from a signal handler or another thread
  // Pause from the front end's own thread, with the text the stop carries (Stop::message).
  void pause_for(std::string why) {
    pause_note_ = std::move(why);
    pause_.store(true);
  }
  // `load`: stores PROGRAM on a module (a module target's; the VM loads it at `run`). false with
  // `error` saying why not.
  virtual bool load(std::string& error) {
    error = "load: " + name() + " loads the program itself at `run`";
    return false;
  }
  // Reverse execution: only where there is history. can_reverse says why not.
  virtual bool can_reverse(std::string& why) const = 0;
  virtual Stop reverse_step(std::uint64_t n = 1) = 0;
  virtual Stop reverse_next() = 0;
  virtual Stop reverse_finish() = 0;
  virtual Stop reverse_continue() = 0;
  // "COMMAND: not on a module: WHY" as a stop the front ends print (a refusal, nothing ran).
  Stop cannot(const std::string& command, const std::string& why) const {
    return Stop{StopKind::NotRunning, 0, command + ": not on " + name() + ": " + why, 0, 0};
  }

  // ---- breakpoints and watchpoints ----
  // Resolves a location: label, line, file:line, *address (gdb's forms). false with `error`.
  bool resolve(const std::string& location, std::int32_t& address, std::string& error);
  int add_breakpoint(std::int32_t address, std::string location, bool temporary);
  bool delete_point(int id);
  void delete_all();
  bool enable_point(int id, bool on);
  bool set_condition(int id, const std::string& text, std::string& error);
  bool set_ignore(int id, int count);
  // A watchpoint; false (0) with `error` when EXPR cannot be read or the target cannot watch it.
  virtual int add_watchpoint(const std::string& text, std::string& error);
  std::vector<Breakpoint>& breakpoints() { return breaks_; }
  std::vector<Watchpoint>& watchpoints() { return watches_; }
  // Called while a module's program runs, between two status reads (a VM calls Engine::on_slice
  // instead): a front end reads its other input here (DAP requests) and may pause.
  std::function<void()> on_wait;
  // Where logpoints and the target's notes print (DAP output events, the CLI's standard output).
  std::function<void(const std::string&)> on_output;
  // A log message with {EXPR} replaced by the expression's value.
  std::string interpolate(const std::string& text);

 protected:
  // The points changed (added, deleted, enabled): a target that mirrors them (VM traps) updates.
  virtual void points_changed() {}
  // The breakpoints at `address` have been reached by one execution: counts the hits and
  // evaluates conditions, ignore counts, logpoints and temporary breakpoints, the same on every
  // target. True with `stop` when the program is to stop there.
  bool breakpoint_hit(std::int32_t address, Stop& stop);
  bool watch_changed(Stop& stop);  // an enabled watchpoint's value changed: the stop it makes
  bool watching() const;
  void refresh_watches();
  void note(const std::string& text) {
    if (on_output) on_output(text + "\n");
  }

  const Profile* profile_;
  ProgramInfo info_;
  bool running_ = false;
  std::vector<Breakpoint> breaks_;
  std::vector<Watchpoint> watches_;
  int next_id_ = 1;
  std::atomic<bool> pause_{false};
  std::string pause_note_;  // Stop::message of the next Pause (pause_for)
};

std::string stop_kind_name(StopKind k);

}  // namespace tmcl::debug
