// VM benchmarks (issue 4): the dispatch loop on a compute-bound CALC ADD / DJNZ loop with a timer
// interrupt enabled (so the interrupt and timer checks are in place), and two waiting programs:
// an hour of 10 ms WAITs with a 1 ms timer interrupt, and pure waiting. The programs are
// instruction lists (the assembler is not on the measured path). Wall time is measured here,
// never inside the VM. Prints "figure<TAB>goal<TAB>measured" rows for tests/bench/run_all.sh.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "tmcl/motion.hpp"
#include "tmcl/vm.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using tmcl::Instruction;
using tmcl::Op;

Instruction I(Op op, int type = 0, int motor = 0, std::int32_t value = 0) {
  return Instruction{static_cast<std::uint8_t>(op), static_cast<std::uint8_t>(type), static_cast<std::uint8_t>(motor), value};
}

struct Measured {
  double seconds;
  std::uint64_t steps;
  tmcl::SimTime simulated;
  bool stopped;
};

Measured run(const std::vector<Instruction>& prog, tmcl::SimTime instr_time) {
  auto core = tmcl::make_ideal_motion_core();
  tmcl::Vm vm(tmcl::generic_profile(), *core);
  vm.instr_time = instr_time;
  vm.load(prog);
  vm.power_on(nullptr);
  vm.start(0);
  auto t0 = Clock::now();
  tmcl::RunResult r = vm.run({});
  double s = std::chrono::duration<double>(Clock::now() - t0).count();
  return {s, vm.steps, vm.now, r.halt == tmcl::Halt::Stop};
}

}  // namespace

int main() {
  // 1. Dispatch: 10^8 iterations of CALC ADD, 1 / DJNZ; timer 0 every second with its
  //    interrupt enabled (fires ~4000 times over the 4000 simulated seconds).
  const std::int32_t iterations = 100'000'000;
  std::vector<Instruction> dispatch = {
      I(Op::SGP, 0, 2, iterations), I(Op::VECT, 0, 0, 9), I(Op::SGP, 0, 3, 1000), I(Op::EI, 0), I(Op::EI, 255),
      I(Op::CALC, 0, 0, 1), I(Op::DJNZ, 0, 0, 5), I(Op::STOP), I(Op::STOP),
      I(Op::CALCV, 0, 1, 1), I(Op::RETI)};
  Measured d = run(dispatch, 20);
  double ns = d.seconds * 1e9 / static_cast<double>(d.steps);
  std::printf("vm dispatch: CALC ADD/DJNZ loop, 1e8 iterations, timer interrupt on (ns per instruction)\t<= 1\t%.3f%s\n", ns,
              d.stopped ? "" : " (did not stop!)");

  // 1a. A loop the superinstruction does not cover (CALC ADD / COMP / JC): the plain dispatch.
  std::vector<Instruction> plain = {
      I(Op::VECT, 0, 0, 8), I(Op::SGP, 0, 3, 1000), I(Op::EI, 0), I(Op::EI, 255),
      I(Op::CALC, 0, 0, 1), I(Op::COMP, 0, 0, 66'666'667), I(Op::JC, 6, 0, 4), I(Op::STOP), I(Op::RETI)};
  Measured q = run(plain, 20);
  std::printf("vm dispatch: CALC ADD/COMP/JC loop, 2e8 instructions, no superinstruction (ns per instruction)\t<= 1\t%.3f%s\n",
              q.seconds * 1e9 / static_cast<double>(q.steps), q.stopped ? "" : " (did not stop!)");

  // 1b. The same loop in Lua 5.4 (the yardstick), when lua5.4 is installed.
  const char* lua =
      "lua5.4 -e 'local a, n = 0, 100000000; local t = os.clock(); "
      "while n ~= 0 do a = a + 1; n = n - 1 end; print((os.clock() - t) * 1e9 / 100000000)' 2>/dev/null";
  double lua_ns = 0;
  if (std::FILE* p = popen(lua, "r")) {
    if (std::fscanf(p, "%lf", &lua_ns) != 1) lua_ns = 0;
    pclose(p);
  }
  if (lua_ns > 0) {
    std::printf("lua 5.4: the same loop (ns per iteration)\t-\t%.3f\n", lua_ns);
    std::printf("vm dispatch vs lua 5.4: ns per TMCL instruction / lua ns per iteration\t<= 0.5\t%.3f\n", ns / lua_ns);
  } else {
    std::printf("lua 5.4: the same loop (ns per iteration)\t-\tnot measured (lua5.4 not installed)\n");
  }

  // 2. An hour of WAIT TICKS, 0, 1 with a 1 ms timer interrupt counting in a variable.
  std::vector<Instruction> ticks = {
      I(Op::SGP, 1, 2, 360'000), I(Op::VECT, 0, 0, 8), I(Op::SGP, 0, 3, 1), I(Op::EI, 0), I(Op::EI, 255),
      I(Op::WAIT, 0, 0, 1), I(Op::DJNZ, 1, 0, 5), I(Op::STOP),
      I(Op::CALCV, 0, 2, 1), I(Op::RETI)};
  Measured w = run(ticks, 20);
  std::printf("vm waiting: 1 h of 10 ms WAITs with a 1 ms timer interrupt (x real time)\t>= 10000\t%.0f%s\n",
              static_cast<double>(w.simulated) / 1e6 / w.seconds, w.stopped ? "" : " (did not stop!)");

  // 3. Pure waiting: 100,000 one-hour WAITs.
  std::vector<Instruction> pure = {I(Op::SGP, 1, 2, 100'000), I(Op::WAIT, 0, 0, 360'000), I(Op::DJNZ, 1, 0, 1), I(Op::STOP)};
  Measured p = run(pure, 20);
  std::printf("vm waiting: pure WAIT TICKS, 100000 simulated hours (x real time)\t>= 100000000\t%.3g%s\n",
              static_cast<double>(p.simulated) / 1e6 / p.seconds, p.stopped ? "" : " (did not stop!)");
  return d.stopped && w.stopped && p.stopped ? 0 : 1;
}
