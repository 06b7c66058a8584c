// A bus scan (tmclctl scan): every address of a range is asked for its firmware version (136
// type 1, then type 0 for the string), without retries, each with a short timeout, since most
// addresses are empty and each empty one costs the whole timeout.
//
// The timeout is short by default, and shorter on TCP (a virtual module, or a serial-over-
// Ethernet bridge) than on a serial port. A module slower than it is still found: its reply
// arrives while a later address is asked, from its own address, and the client keeps such late
// replies (Client::take_strays); the module is then asked again with time to answer, and with
// the default timeout the wait per address doubles from then on, since the line is slower than
// assumed. After the last address the line is listened to a little longer for the same reason.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "tmcl/host/client.hpp"
#include "tmcl/host/transfer.hpp"
#include "tmcl/profile.hpp"

namespace tmcl::host {

inline constexpr int kScanTimeoutSerialMs = 50, kScanTimeoutTcpMs = 10, kScanTimeoutMaxMs = 1000;

// The default wait per address: 50 ms on a serial port, 10 ms on TCP.
int default_scan_timeout_ms(const Port& port);

struct ScanOptions {
  int from = 1, to = 255;  // --range A-B, both included
  int timeout_ms = kScanTimeoutSerialMs;
  bool adapt = true;       // the timeout is a default: double it when a module answers late
};

struct ScanFound {
  int address = 0;
  std::int32_t binary = 0;  // 136 type 1
  std::string version;      // 136 type 0, "?" when it did not come
  const Profile* profile = nullptr;  // the module type, where a profile knows the version
  bool late = false;        // found by a reply that came after the timeout
  int timeout_ms = 0;       // the wait per address from now on
};

struct ScanResult {
  Fail fail = Fail::None;  // Port: the line is gone (error); Cancelled: Ctrl-C
  std::string error;
  int found = 0;
};

// Scans `options.from`..`to` over `client` (its module address and timeout are changed). Each
// module is reported to `on_found` as it is found; `progress` after each address, with (done,
// total).
ScanResult scan_bus(Client& client, const ScanOptions& options, const std::function<void(const ScanFound&)>& on_found,
                    const Progress& progress);

}  // namespace tmcl::host
