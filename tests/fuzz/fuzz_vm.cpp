// Fuzzes the VM on arbitrary programs: the first byte picks the module profile and motion core,
// the rest are 7-byte instruction records. The program runs with a step bound and a simulated
// time bound; a few records are also sent as direct-mode commands between two run slices, as a
// host would while a program runs. With a ramp core, motor 0 has switches placed at positions
// taken from the second record (so reference searches and limit stops meet them). Checks: no
// crash, no hang, the bounds hold.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "tmcl/motion.hpp"
#include "tmcl/profile.hpp"
#include "tmcl/vm.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* profiles[] = {"usb-2-sd", "tmc2300-eval", "generic"};
  static const char* cores[] = {"tmc4361", "linear", "ideal", "tmc429"};
  const tmcl::Profile* profile = tmcl::find_profile(profiles[data[0] % 3]);
  auto core = tmcl::make_motion_core(cores[(data[0] / 3) % 4]);
  if (!profile || !core) return 0;
  std::vector<tmcl::Instruction> program;
  for (std::size_t off = 1; off + 7 <= size && program.size() < 2048; off += 7)
    program.push_back({data[off], data[off + 1], data[off + 2],
                       static_cast<std::int32_t>((std::uint32_t{data[off + 3]} << 24) | (std::uint32_t{data[off + 4]} << 16) |
                                                 (std::uint32_t{data[off + 5]} << 8) | data[off + 6])});
  if (program.empty()) return 0;
  tmcl::Vm vm(*profile, *core);
  vm.load(program);
  vm.power_on();
  if (core->name() != "ideal" && size >= 15) {
    auto at = [&](std::size_t i) { return static_cast<std::int64_t>(static_cast<std::int8_t>(data[8 + i])) * 997; };
    std::vector<tmcl::InputEvent> sw(3);
    sw[0].input = tmcl::SwitchInput::StopLeft, sw[0].from = INT64_MIN, sw[0].to = -std::abs(at(0)) - 1;
    sw[1].input = tmcl::SwitchInput::StopRight, sw[1].from = std::abs(at(1)) + 1, sw[1].to = INT64_MAX;
    sw[2].input = tmcl::SwitchInput::Home, sw[2].from = std::min(at(2), at(3)), sw[2].to = std::max(at(2), at(3));
    for (auto& e : sw) e.kind = tmcl::InputEvent::Placed;
    vm.add_inputs(sw);
  }
  vm.start(0);
  tmcl::Limits limits;
  limits.max_steps = 20000;
  limits.until = 3600LL * 1000 * 1000;  // one simulated hour
  (void)vm.run(limits);
  if (vm.steps > limits.max_steps) __builtin_trap();
  for (std::size_t i = 0; i < program.size() && i < 16; ++i) (void)vm.execute_direct(program[i]);
  limits.max_steps = vm.steps + 20000;
  (void)vm.run(limits);
  if (vm.steps > limits.max_steps) __builtin_trap();
  return 0;
}
