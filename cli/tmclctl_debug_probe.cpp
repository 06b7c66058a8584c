// tmclctl PORT debug --probe (tmclctl_debug_probe.hpp; docs/tmclctl.md, "debug --probe").
#include "tmclctl_debug_probe.hpp"

#include <cinttypes>
#include <cstdio>

#include "tmcl/host/commands.hpp"
#include "tmcl/host/debug_probe.hpp"
#include "tmcl/host/probe.hpp"

namespace {

namespace host = tmcl::host;

int exit_status(host::Outcome o) {
  switch (o) {
    case host::Outcome::Ok: return 0;
    case host::Outcome::Mismatch: return 1;
    case host::Outcome::BadStatus: return 2;
    case host::Outcome::NoReply: return 69;
    case host::Outcome::Port: return 74;
    case host::Outcome::Cancelled: return 130;
  }
  return 74;
}

// "address 1, firmware 0015V114 (0x000F010E), USB-2-SD (firmware 1.14)", from 136 types 0 and 1.
std::string describe_module(host::Client& client, int module) {
  std::string text = "address " + std::to_string(module);
  const host::Result v0 = client.request(tmcl::Instruction{static_cast<std::uint8_t>(tmcl::Op::GetFirmwareVersion), 0, 0, 0});
  if (!v0.ok() || v0.reply.version.empty()) return text + ", firmware not reported (136)";
  text += ", firmware " + v0.reply.version;
  const host::Result v1 = client.request(tmcl::Instruction{static_cast<std::uint8_t>(tmcl::Op::GetFirmwareVersion), 1, 0, 0});
  if (v1.ok() && v1.reply.status == host::kStatusOk) {
    char buf[16];
    std::snprintf(buf, sizeof buf, " (0x%08" PRIX32 ")", static_cast<std::uint32_t>(v1.reply.value));
    text += buf;
  }
  if (const tmcl::Profile* p = host::profile_for_firmware(v0.reply.version)) text += ", " + std::string(p->title);
  return text;
}

}  // namespace

int tmclctl_debug_probe(host::Client& client, const tmcl::Profile& profile, int module, volatile std::sig_atomic_t* stop) {
  host::DebugProbeOptions options;
  options.module = describe_module(client, module);
  options.memory = profile.program_memory;
  options.before_restore = [stop] { *stop = 0; };
  const host::DebugProbeResult r = host::debug_probe(client, options);
  std::fputs(r.report.c_str(), stdout);
  std::fflush(stdout);
  if (r.outcome != host::Outcome::Ok) std::fprintf(stderr, "tmclctl: error: %s\n", r.message.c_str());
  return exit_status(r.outcome);
}
