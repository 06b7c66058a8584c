// The bus scan (scan.hpp): short waits per address, late replies still counted.
#include "tmcl/host/scan.hpp"

#include <algorithm>
#include <set>

#include "tmcl/host/commands.hpp"
#include "tmcl/host/probe.hpp"

namespace tmcl::host {
namespace {
constexpr int kScanConfirmMs = 500;  // asking a module known to be there
}  // namespace

int default_scan_timeout_ms(const Port& port) { return port.is_serial() ? kScanTimeoutSerialMs : kScanTimeoutTcpMs; }

ScanResult scan_bus(Client& client, const ScanOptions& options, const std::function<void(const ScanFound&)>& on_found,
                    const Progress& progress) {
  const auto version = [](std::uint8_t type) {
    return Instruction{static_cast<std::uint8_t>(Op::GetFirmwareVersion), type, 0, 0};
  };
  ScanResult result;
  std::set<int> found;
  int timeout = options.timeout_ms;
  client.set_retries(0);
  // A module that answered: its version string (asked with time to answer, the timeout may be
  // short), reported.
  const auto report = [&](int address, std::int32_t binary, bool late) {
    ScanFound f{address, binary, "?", nullptr, late, timeout};
    client.set_module(static_cast<std::uint8_t>(address));
    client.set_timeout(std::max(timeout, kScanConfirmMs));
    if (Result v = client.request(version(0)); v.ok()) f.version = v.reply.version;
    client.set_timeout(timeout);
    f.profile = profile_for_firmware(f.version);
    found.insert(address);
    ++result.found;
    on_found(f);
  };
  // A module that answered late: asked again with time to answer.
  const auto confirm = [&](int address) {
    client.set_module(static_cast<std::uint8_t>(address));
    client.set_timeout(std::max(timeout, kScanConfirmMs));
    const Result r = client.request(version(1));
    client.set_timeout(timeout);
    if (r.ok()) {
      report(address, r.reply.value, true);
    } else if (r.fail != Fail::NoReply) {
      result.fail = r.fail;
      result.error = r.error;
    }
  };
  // Late replies: modules slower than the timeout.
  const auto late_ones = [&](int asked_up_to) {
    std::set<int> late;
    for (const Reply& s : client.take_strays()) {
      const int a = s.bytes[1];
      if (s.op == static_cast<std::uint8_t>(Op::GetFirmwareVersion) && a >= options.from && a <= asked_up_to && !found.count(a))
        late.insert(a);
    }
    for (int a : late) {
      if (options.adapt) timeout = std::min(timeout * 2, kScanTimeoutMaxMs);
      confirm(a);
      if (result.fail != Fail::None) return;
    }
  };
  const int total = options.to - options.from + 1;
  for (int a = options.from; a <= options.to; ++a) {
    client.set_module(static_cast<std::uint8_t>(a));
    client.set_timeout(timeout);
    const Result r = client.request(version(1));
    if (r.fail == Fail::Port || r.fail == Fail::Cancelled) {
      result.fail = r.fail;
      result.error = r.error;
      return result;
    }
    if (r.ok() && !found.count(a)) report(a, r.reply.value, false);
    late_ones(a);
    if (result.fail != Fail::None) return result;
    if (progress) progress(a - options.from + 1, total);
  }
  // The last addresses' replies may still be on their way.
  client.listen(Clock::now() + std::chrono::milliseconds(std::max(4 * timeout, 100)));
  late_ones(options.to);
  return result;
}

}  // namespace tmcl::host
