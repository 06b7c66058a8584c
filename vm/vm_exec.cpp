// The run loop. The fast path costs one predictable branch per instruction: a counter of the
// instructions that start before `next_check_` (the earliest timer, motion event, input or time
// limit) and within the step limit. Everything else (interrupt entry, WAIT, events, limits) is
// the slow path in service(). A WAIT never spins: the slow path jumps time to the next event.
#include <algorithm>
#include <optional>

#include "tmcl/vm.hpp"
#include "vm_ops.hpp"

namespace tmcl {
namespace {

std::string wait_text(const Vm& vm) {
  std::int32_t at = vm.pc;
  const Instruction& ins = vm.program[static_cast<std::size_t>(at)];
  static constexpr const char* kNames[] = {"TICKS", "POS", "REFSW", "LIMSW", "RFS"};
  return std::string("WAIT ") + kNames[ins.type <= 4 ? ins.type : 0] + " at " + vm.where(at);
}

}  // namespace

// A reference search is motion that runs on: the module would search until RFS STOP; say so
// rather than "no motion" (issue 25).
std::string never_ending_wait_reason(const Vm& vm) {
  if (vm.wait.kind == kw::Wait::RFS && !vm.motion->reference_done(vm.wait.motor))
    return " can never end: motor " + std::to_string(vm.wait.motor) +
           "'s reference search runs on, but no switch on its way can end it and no timer, input or timeout is"
           " pending (the module would search until RFS STOP; give WAIT RFS a timeout, or run with --max-time)";
  if (vm.wait.kind == 1) {
    if (std::string why = vm.motion->move_problem(vm.wait.motor); !why.empty() && why.starts_with("the move cannot start"))
      return " can never end: motor " + std::to_string(vm.wait.motor) + "'s " + why.substr(4);
    if (std::string why = vm.motion->stop_reason(vm.wait.motor); !why.empty())  // issue 41
      return " can never end: motor " + std::to_string(vm.wait.motor) + " " + why +
             ", and no timer, motion, input or timeout is pending";
  }
  return " can never end: no timer, motion, input or timeout is pending";
}

namespace {

RunResult step_limit(const Vm& vm) {
  return RunResult{Halt::StepLimit, "stopped after " + std::to_string(vm.steps) + " instructions (--max-steps)"};
}

// A motion core that keeps announcing an event at an instant it never gets past would make the
// VM loop forever at one instant; after this many rounds that is reported as a fault.
constexpr int kMaxRoundsPerInstant = 1'000'000;

bool stop_requested(const Limits& lim) { return lim.stop && lim.stop->load(std::memory_order_relaxed); }
const char* const kInterrupted = "interrupted from outside";

std::string stuck_core(const Vm& vm) {
  return "the motion core '" + std::string(vm.motion->name()) + "' keeps reporting an event at " + std::to_string(vm.now) +
         " us without getting past it (a bug in the core)";
}

}  // namespace

// The run loop's parts: static members of a nested struct, so they reach the VM's private
// bookkeeping (next_check_, fault_set_, code_, ...) that nothing outside the VM touches.
struct Vm::Loop {
  static RunResult settle(Vm& vm, const Limits& lim);
  static std::optional<RunResult> service(Vm& vm, const Limits& lim);
  static void unknown_instruction(Vm& vm, std::int32_t at);
  static void execute(Vm& vm, std::int32_t at);
  static void count_branch(Vm& vm, std::int32_t at);
  static RunResult run_traced(Vm& vm, const Limits& lim);
  static std::uint64_t burst_length(const Vm& vm, const Limits& lim);
  template <bool kCount>
  static RunResult run_fast(Vm& vm, const Limits& lim);
};

// After STOP (or a fault): let the motors finish what they were told, up to the time limit.
RunResult Vm::Loop::settle(Vm& vm, const Limits& lim) {
  int rounds = 0;
  for (SimTime last = -1;; last = vm.now) {
    SimTime t = vm.motion->next_event();
    if (t == kNever) break;
    if (stop_requested(lim)) return {Halt::Interrupted, kInterrupted};
    rounds = vm.now == last ? rounds + 1 : 0;
    if (rounds > kMaxRoundsPerInstant) return {Halt::Fault, stuck_core(vm)};
    if (t > lim.until) {
      vm.now = std::max(vm.now, lim.until);
      vm.sync_motion();
      return {Halt::TimeLimit, "the program stopped, but the motors were still moving at the time limit"};
    }
    vm.now = std::max(vm.now, t);
    vm.sync_motion();
  }
  if (vm.fault_set_) return {Halt::Fault, vm.fault_message_};
  if (vm.halt_pc < 0) return {Halt::NotRunning, "the program is not running"};
  return {Halt::Stop, "STOP at " + vm.where(vm.halt_pc)};
}

// The slow path: brings the world up to `now`, ends or continues a WAIT, enters interrupts,
// sleeps until the next event while waiting. Returns a result when run() must return.
std::optional<RunResult> Vm::Loop::service(Vm& vm, const Limits& lim) {
  if (vm.trap_hit) {
    vm.trap_hit = false;
    return RunResult{Halt::Break, "breakpoint at " + vm.where(vm.pc)};
  }
  int rounds = 0;
  for (SimTime last = -1;; last = vm.now) {
    // Before anything changes at this instant, so that the next run() starts here again.
    if (stop_requested(lim)) return RunResult{Halt::Interrupted, kInterrupted};
    rounds = vm.now == last ? rounds + 1 : 0;
    if (rounds > kMaxRoundsPerInstant) vm.fault(stuck_core(vm));
    if (vm.fault_set_) return settle(vm, lim);
    // Commands and queries advance the core themselves; here only its events matter.
    if (vm.motion->next_event() <= vm.now) vm.sync_motion();
    while (vm.input_next < vm.inputs_queue.size() && vm.inputs_queue[vm.input_next].at <= vm.now)
      vm.apply_input(vm.inputs_queue[vm.input_next++]);
    vm.fire_due_timers();
    if (vm.status != AppStatus::Running) return settle(vm, lim);
    const bool at_limit = vm.steps >= lim.max_steps;
    if (at_limit && !lim.to_instruction) return step_limit(vm);
    if (vm.wait.active) {
      int w = vm.wait_check();
      if (w != 0) {
        vm.wait.active = false;
        if (vm.trace) vm.trace->wait_end(vm, vm.pc, w == 2);
        ++vm.pc;
      }
    }
    vm.try_enter_interrupt();
    if (at_limit && !vm.wait.active) return step_limit(vm);  // to_instruction: pc runs next
    if (vm.now >= lim.until) return RunResult{Halt::TimeLimit, "simulated time limit reached (--max-time)"};
    SimTime wake = vm.next_wakeup();
    if (!vm.wait.active) {
      vm.next_check_ = std::min(wake, lim.until);
      if (vm.next_check_ <= vm.now) vm.next_check_ = vm.now + 1;  // never spin on a stale instant
      return std::nullopt;
    }
    if (wake == kNever && lim.until == kNever) return RunResult{Halt::Blocked, wait_text(vm) + never_ending_wait_reason(vm)};
    vm.now = std::max(vm.now, std::min(wake, lim.until));
  }
}

// Reports an instruction the table dispatch did not know (code_[] maps every opcode the profile
// lacks to 0): says which of the four reasons applies.
void Vm::Loop::unknown_instruction(Vm& vm, std::int32_t at) {
  const Instruction& raw = vm.program[static_cast<std::size_t>(at)];
  const OpInfo* info = op_info(raw.op);
  if (at == vm.program_size)
    vm.fault("ran past the end of the program (address " + std::to_string(at) + ")");
  else if (!info)
    vm.fault("unknown opcode " + std::to_string(raw.op) + " at " + vm.where(at));
  else if (info->control)
    vm.fault("control command " + std::to_string(raw.op) + " cannot run in a program, at " + vm.where(at));
  else
    vm.fault(std::string(info->mnemonic) + " is not available on " + std::string(vm.profile->name) + ", at " + vm.where(at));
}

// One instruction through the table dispatch (every row of opcodes.def), registers in `vm`.
// Never inlined: the semantics of every instruction (with every run-time check) would otherwise
// grow run_fast() until the compiler stops inlining the fast path's own primitives (issue 42:
// the run-time checks of 69203f1 made the CALC/DJNZ loop 1.6x slower that way).
[[gnu::noinline]] void Vm::Loop::execute(Vm& vm, std::int32_t at) {
  bool known = false;
  if (vm.code_[static_cast<std::size_t>(at)].op != 0) ops::dispatch<false>(vm, vm.program[static_cast<std::size_t>(at)], known);
  if (!known) [[unlikely]] {
    if (vm.trapped(at)) {
      // A debugger trap: undo the instruction's time and count, leave run() from the slow path.
      vm.now -= vm.instr_time;
      --vm.steps;
      if (!vm.executed.empty()) --vm.executed[static_cast<std::size_t>(at)];
      vm.trap_hit = true;
      vm.next_check_ = vm.now;
      return;
    }
    unknown_instruction(vm, at);
  }
}

// Coverage: after the instruction at `at` ran through the table dispatch, counts a JC, CALL or
// DJNZ whose condition held. The flags a JC or CALL tested are unchanged by it; a DJNZ's variable
// is already decremented. A jump that faulted (its target outside the program) did not happen.
void Vm::Loop::count_branch(Vm& vm, std::int32_t at) {
  const Instruction& ins = vm.program[static_cast<std::size_t>(at)];
  bool held = false;
  if (ins.op == static_cast<std::uint8_t>(Op::JC) || ins.op == static_cast<std::uint8_t>(Op::CALL))
    held = ops::condition(vm, ins.type);
  else if (ins.op == static_cast<std::uint8_t>(Op::DJNZ))
    held = vm.vars[ins.type] != 0;
  if (held && !vm.fault_set_) ++vm.taken[static_cast<std::size_t>(at)];
}

// Traced execution: one instruction at a time, each reported after it ran.
RunResult Vm::Loop::run_traced(Vm& vm, const Limits& lim) {
  for (;;) {
    if (vm.now >= vm.next_check_ || vm.steps >= lim.max_steps || stop_requested(lim)) {
      if (auto r = service(vm, lim)) return *r;
      continue;
    }
    const std::int32_t at = vm.pc;
    const SimTime t0 = vm.now;
    const bool was_in_handler = vm.in_handler;
    const std::uint64_t warned = vm.warnings_total;
    const std::size_t noted = vm.notes.size();
    if (vm.in_handler && !vm.handler_code.empty() && vm.check_handler_code()) continue;  // --strict: a fault
    vm.now += vm.instr_time;
    ++vm.steps;
    if (!vm.executed.empty()) ++vm.executed[static_cast<std::size_t>(at)];
    execute(vm, at);
    if (vm.trap_hit) continue;
    if (!vm.executed.empty()) count_branch(vm, at);
    vm.trace->instruction(vm, t0, at, vm.program[static_cast<std::size_t>(at)]);
    if (vm.warnings_total != warned || vm.notes.size() != noted) vm.trace->warning(vm, vm.last_warning);
    if (was_in_handler && !vm.in_handler) vm.trace->interrupt_leave(vm, vm.pc);  // RETI (or RST)
  }
}

// How many instructions start before the next check instant and within the step limit. Every
// instruction advances time by exactly instr_time, so the fast loop needs one counter instead of
// two comparisons.
std::uint64_t Vm::Loop::burst_length(const Vm& vm, const Limits& lim) {
  if (vm.now >= vm.next_check_ || vm.steps >= lim.max_steps || stop_requested(lim)) return 0;
  if (vm.in_handler && !vm.handler_code.empty()) return 1;  // check_handler_code() before each
  std::uint64_t n = lim.max_steps - vm.steps;
  if (lim.stop) n = std::min(n, Limits::kStopPollSteps);  // service() looks at the request
  if (vm.next_check_ != kNever && vm.instr_time > 0) {
    auto by_time = static_cast<std::uint64_t>((vm.next_check_ - vm.now + vm.instr_time - 1) / vm.instr_time);
    n = std::min(n, by_time);
  }
  return n;
}

// Untraced execution. Between two checks the hot registers live in locals (the compiler cannot
// keep struct fields in registers across the calls of the slow instructions). The most frequent
// pure instructions run inline through the same primitives as vm_ops.hpp (arith, flags_of,
// compare_flags, condition); every other instruction, and every case that could fault, writes
// the registers back and goes through the table dispatch. kCount: the same loop counting every
// instruction and every branch taken (Vm::executed, Vm::taken), for coverage.
template <bool kCount>
RunResult Vm::Loop::run_fast(Vm& vm, const Limits& lim) {
  using namespace ops;
  for (;;) {
    if (vm.in_handler && !vm.handler_code.empty() && vm.check_handler_code()) continue;  // --strict: a fault
    std::uint64_t total = burst_length(vm, lim);
    if (total == 0) {
      if (auto r = service(vm, lim)) return *r;
      continue;
    }
    const Instruction* const code = vm.code_.data();
    const SimTime dt = vm.instr_time;
    SimTime base_now = vm.now;
    std::uint64_t base_steps = vm.steps;
    std::uint64_t left = total;
    std::int32_t pc = vm.pc, acc = vm.acc;
    std::uint8_t flags = vm.flags;
    std::uint64_t* const executed = vm.executed.data();
    std::uint64_t* const taken = vm.taken.data();
    while (left != 0) {
      --left;
      const Instruction& ins = code[pc];
      if constexpr (kCount) ++executed[pc];
      switch (ins.op) {
// The ALU part of CALC t / CALCV t on `dst`, shared by the plain and the fused forms.
#define TMCL_ALU(t, dst)             \
  if constexpr (t == NOT)            \
    dst = ~dst;                      \
  else                               \
    dst = arith_of<t>(dst, ins.value); \
  flags = flags_of(dst);
// The DJNZ half of a fused form; when the budget ends between the two halves, the DJNZ runs on
// its own after the check. [[unlikely]]: the fused path one straight line (vm_bench's guard
// measured it twice: without it the same instructions ran up to 1.5x slower).
#define TMCL_FUSED_DJNZ()                                              \
  if (left == 0) [[unlikely]] {                                        \
    ++pc;                                                              \
    continue;                                                          \
  }                                                                    \
  --left;                                                              \
  {                                                                    \
    const Instruction& d = code[pc + 1];                               \
    std::int32_t& n = vm.vars[d.type];                                 \
    n = wrap(static_cast<std::uint32_t>(n) - 1u);                      \
    if constexpr (kCount) {                                            \
      ++executed[pc + 1];                                              \
      taken[pc + 1] += n != 0;                                         \
    }                                                                  \
    pc = n != 0 ? d.value : pc + 2;                                    \
  }                                                                    \
  continue;
#define TMCL_FAST_CALC(t)                 \
  case kFastCalc + t:                     \
    TMCL_ALU(t, acc)                      \
    ++pc;                                 \
    continue;                             \
  case kFusedCalc + t:                    \
    TMCL_ALU(t, acc)                      \
    TMCL_FUSED_DJNZ()                     \
  case kFastCalcV + t: {                  \
    std::int32_t& v = vm.vars[ins.motor]; \
    TMCL_ALU(t, v)                        \
    ++pc;                                 \
    continue;                             \
  }                                       \
  case kFusedCalcV + t: {                 \
    std::int32_t& v = vm.vars[ins.motor]; \
    TMCL_ALU(t, v)                        \
    TMCL_FUSED_DJNZ()                     \
  }
        TMCL_FAST_CALC(ADD)
        TMCL_FAST_CALC(SUB)
        TMCL_FAST_CALC(MUL)
        TMCL_FAST_CALC(DIV)
        TMCL_FAST_CALC(MOD)
        TMCL_FAST_CALC(AND)
        TMCL_FAST_CALC(OR)
        TMCL_FAST_CALC(XOR)
        TMCL_FAST_CALC(NOT)
        TMCL_FAST_CALC(LOAD)
#undef TMCL_FAST_CALC
#undef TMCL_FUSED_DJNZ
#undef TMCL_ALU
        case kFastCalcV + COMP:
          flags = compare_flags(vm.vars[ins.motor], ins.value);
          ++pc;
          continue;
        case static_cast<std::uint8_t>(Op::COMP):
          flags = compare_flags(acc, ins.value);
          ++pc;
          continue;
        case kFastJA:  // targets checked by decode_for_run: one outside the program faults the slow way
          pc = ins.value;
          continue;
        case kFastJC: {
          const bool jump = fast_condition(flags, vm.errors, ins);
          if constexpr (kCount) taken[pc] += jump;
          pc = jump ? ins.value : pc + 1;
          continue;
        }
        case kFastDJNZ: {
          std::int32_t& v = vm.vars[ins.type];
          v = wrap(static_cast<std::uint32_t>(v) - 1u);
          if constexpr (kCount) taken[pc] += v != 0;
          pc = v != 0 ? ins.value : pc + 1;
          continue;
        }
        default: break;
      }
      // The slow way: registers back into the struct, table dispatch, registers out again.
      std::uint64_t done = total - left;
      vm.now = base_now + static_cast<SimTime>(done) * dt;
      vm.steps = base_steps + done;
      vm.pc = pc;
      vm.acc = acc;
      vm.flags = flags;
      execute(vm, pc);
      // Only a CALL can take its branch here: a JC or DJNZ comes this way when it faults.
      if constexpr (kCount)
        if (ins.op == static_cast<std::uint8_t>(Op::CALL) && !vm.trap_hit) count_branch(vm, pc);
      pc = vm.pc;
      acc = vm.acc;
      flags = vm.flags;
      base_now = vm.now;
      base_steps = vm.steps;
      // Inside a handler with its code known, back to the top: the next instruction is checked.
      total = left = vm.in_handler && !vm.handler_code.empty() ? 0 : burst_length(vm, lim);
    }
    std::uint64_t done = total - left;
    vm.now = base_now + static_cast<SimTime>(done) * dt;
    vm.steps = base_steps + done;
    vm.pc = pc;
    vm.acc = acc;
    vm.flags = flags;
  }
}

RunResult Vm::run(const Limits& limits) {
  if (!unplaceable_.empty()) {
    fault(unplaceable_);
    return {Halt::Fault, unplaceable_};
  }
  if (status != AppStatus::Running && !fault_set_) return Loop::settle(*this, limits);
  next_check_ = 0;
  if (trace) return Loop::run_traced(*this, limits);
  return executed.empty() ? Loop::run_fast<false>(*this, limits) : Loop::run_fast<true>(*this, limits);
}

}  // namespace tmcl
