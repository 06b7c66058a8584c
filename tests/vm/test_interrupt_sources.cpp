// Every interrupt vector of every bundled profile, on the module's own motion core: either the
// VM raises it from what raises it on the module (a timer's period, a move reaching its target, a
// stall at a hard stop (stop on stall 181, or the TMCM-351's threshold 205), an encoder slip
// beyond 212, a stop switch, an input edge) or tmcl::not_simulated_reason (vm/interrupts.cpp)
// declares it not simulated, which gives a run its note on EI. A vector that is neither fails,
// naming the profile and the vector.
#include <string>
#include <vector>

#include "check.hpp"
#include "machine.hpp"
#include "tmcl/interrupts.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/profile.hpp"
#include "tmcl/vm.hpp"

using namespace vmtest;
using tmcl::InputEvent;
using tmcl::VectorSource;

namespace {

constexpr int kHandler = 30;

tmcl::InputEvent event(InputEvent::Kind kind, tmcl::SimTime at, int index, std::int32_t value) {
  InputEvent e;
  e.kind = kind, e.at = at, e.index = index, e.value = value;
  return e;
}

// Runs `body` from 0 on module `p` with its own core, with `vector` pointing at a handler that
// counts its calls in user variable 0 and with the global enable on; returns the count.
std::int32_t handler_calls(const tmcl::Profile& p, int vector, std::vector<tmcl::Instruction> body,
                           std::vector<InputEvent> inputs) {
  std::vector<tmcl::Instruction> prog = {I(Op::VECT, vector, 0, kHandler), I(Op::EI, vector), I(Op::EI, 255)};
  prog.insert(prog.end(), body.begin(), body.end());
  prog.push_back(I(Op::WAIT, 0, 0, 300));  // 3 s for the source to happen
  prog.resize(kHandler, I(Op::STOP));
  prog.push_back(I(Op::GGP, 0, 2));
  prog.push_back(I(Op::CALC, 0, 0, 1));  // ADD 1
  prog.push_back(I(Op::AGP, 0, 2));
  prog.push_back(I(Op::RETI));
  auto core = tmcl::make_profile_motion_core(p);
  tmcl::Vm vm(p, *core);
  vm.power_on(nullptr);
  vm.load(prog);
  vm.add_inputs(std::move(inputs));
  vm.start(0);
  const tmcl::RunResult r = vm.run(tmcl::Limits{1'000'000, 60'000'000});
  if (r.halt != tmcl::Halt::Stop) return -1;
  return vm.vars[0];
}

// How vector n is raised on the module: a program and scenario events that raise it at least once.
std::int32_t raise_it(const tmcl::Profile& p, int n, tmcl::VectorKind k) {
  const int m = k.index;
  // About 12000 microsteps/s, well above the speed stallGuard2 measures at: 400 in the TMC429's
  // units (pulse divisor 3, its default), 12800 on a core in pps.
  auto core = tmcl::make_profile_motion_core(p);
  tmcl::Vm powered(p, *core);
  powered.power_on(nullptr);
  // (Asked of motor 0: the units are every motor's, and m is an input's number for an input change.)
  const std::int32_t speed = core->physical(0, 2, 400) ? 400 : 12800;
  switch (k.source) {
    case VectorSource::Timer: return handler_calls(p, n, {I(Op::SGP, n, 3, 100)}, {});
    case VectorSource::TargetReached: return handler_calls(p, n, {I(Op::MVP, 0, m, 100)}, {});
    case VectorSource::Stall: {  // the hard stop at 3000 stops the shaft
      InputEvent hard = event(InputEvent::HardStop, 0, m, 0);
      hard.input = tmcl::SwitchInput::StopRight, hard.from = 3000;
      // stallGuard2: stop on stall (181) from speed 1 on; the TMCM-351's stallGuard (no 181, E75):
      // its detection threshold 205 at the lowest, 1
      const std::vector<tmcl::Instruction> arm = p.axis_param(181)
                                                     ? std::vector{I(Op::SAP, 174, m, 0), I(Op::SAP, 181, m, 1)}
                                                     : std::vector{I(Op::SAP, 205, m, 1)};
      std::vector<tmcl::Instruction> body = arm;
      body.push_back(I(Op::ROR, 0, m, speed));
      return handler_calls(p, n, body, {hard});
    }
    case VectorSource::Deviation:  // a slip of 1000 microsteps at 1 s, beyond the 212 of 100
      return handler_calls(p, n, {I(Op::SAP, 212, m, 100), I(Op::ROR, 0, m, speed)}, {event(InputEvent::Slip, 1'000'000, m, -1000)});
    case VectorSource::StopLeft:
    case VectorSource::StopRight: {
      const auto kind = k.source == VectorSource::StopLeft ? InputEvent::StopLeft : InputEvent::StopRight;
      return handler_calls(p, n, {I(Op::SGP, n, 3, 3)}, {event(kind, 1'000'000, m, 1)});
    }
    case VectorSource::InputChange:
      return handler_calls(p, n, {I(Op::SGP, n, 3, 3)}, {event(InputEvent::Digital, 1'000'000, m, 1)});
    case VectorSource::PositionCompare:  // declared not simulated (vm/interrupts.cpp)
    case VectorSource::GlobalEnable:
    case VectorSource::Unknown: break;
  }
  return 0;
}

}  // namespace

TEST(every_profile_vector_is_raised_or_declared_not_simulated) {
  int raised = 0, declared = 0;
  for (const tmcl::Profile* p : tmcl::all_profiles()) {
    if (p->any_parameter) continue;  // generic: every number, no module's list
    auto core = tmcl::make_profile_motion_core(*p);
    for (const tmcl::InterruptVector& v : p->vectors) {
      const tmcl::VectorKind k = tmcl::vector_kind(v.number);
      if (k.source == VectorSource::GlobalEnable) continue;  // the switch, not a source
      if (!tmcl::not_simulated_reason(*p, core->name(), v.number).empty()) {
        ++declared;
        continue;
      }
      const std::int32_t calls = raise_it(*p, v.number, k);
      if (calls < 1)
        tmcl_test::fail(__FILE__, __LINE__,
                        std::string(p->name) + ": vector " + std::to_string(v.number) + " (" + std::string(v.name) + ", " +
                            tmcl::vector_source_text(k) + ") is neither raised (" + std::to_string(calls) +
                            " calls) nor declared not simulated");
      ++raised;
    }
  }
  CHECK(raised > 100);
  CHECK(declared > 5);
}
