// tmclctl's transfer speed (docs/performance.md): download plus verify of a program filling the
// USB-2-SD's program memory (577 instructions) over the pseudo-terminal of `tmclrun --serve pty`,
// through the host library exactly as `tmclctl download` does it, against bare request/reply
// round trips of the very same frames (132, the 577 stores, 133, a 134 per address: write 9
// bytes, read 9 bytes, nothing else), so that the module does the same work in both, over the
// same open port in the same run. Goal: the transfer costs at most 1.2 times the bare round trips, i.e.
// the library's matching, draining and checks add at most 20%. Best of 9 rounds each, interleaved,
// so that load on a shared machine hits both alike.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "tmcl/host/client.hpp"
#include "tmcl/host/port.hpp"
#include "tmcl/host/transfer.hpp"
#include "tmcl/codec.hpp"
#include "spawn.hpp"

namespace {

using Clock = std::chrono::steady_clock;

}  // namespace

int main() {
  std::string pty;
  const pid_t server = tmcl::bench::start_server(
      {TMCL_TMCLRUN, "--serve", "pty", "-t", "usb-2-sd", "--max-wall-time", "120s"}, pty);
  if (server < 0 || pty.empty()) {
    std::fprintf(stderr, "host_bench: cannot start tmclrun --serve pty\n");
    return 1;
  }
  std::string err;
  auto port = tmcl::host::Port::open(pty, 115200, 1000, err);
  if (!port) {
    std::fprintf(stderr, "host_bench: %s\n", err.c_str());
    return 1;
  }
  tmcl::host::Client client(*port, {});
  std::vector<tmcl::Instruction> program;
  for (int i = 0; i < 576; ++i) program.push_back(tmcl::Instruction{5, 4, 0, 1000 + i});  // SAP 4, 0, N
  program.push_back(tmcl::Instruction{28, 0, 0, 0});                                      // STOP
  const int memory = 577;

  // Round trips a download plus verify makes: 132, one per instruction, 133, one 134 per address.
  const int trips = 1 + static_cast<int>(program.size()) + 1 + static_cast<int>(program.size());
  double best_transfer = 1e9, best_bare = 1e9;
  std::vector<std::array<std::uint8_t, 9>> frames;
  frames.push_back(tmcl::encode_request(1, tmcl::Instruction{132, 0, 0, 0}));
  for (const auto& ins : program) frames.push_back(tmcl::encode_request(1, ins));
  frames.push_back(tmcl::encode_request(1, tmcl::Instruction{133, 0, 0, 0}));
  for (int a = 0; a < static_cast<int>(program.size()); ++a) frames.push_back(tmcl::encode_request(1, tmcl::Instruction{134, 0, 0, a}));
  if (static_cast<int>(frames.size()) != trips) return 1;
  for (int round = 0; round < 9; ++round) {
    auto t0 = Clock::now();
    auto d = tmcl::host::download(client, program, 0, memory, {});
    auto v = tmcl::host::verify(client, program, 0, memory, {});
    const double transfer = std::chrono::duration<double>(Clock::now() - t0).count();
    if (d.outcome != tmcl::host::Outcome::Ok || v.outcome != tmcl::host::Outcome::Ok) {
      std::fprintf(stderr, "host_bench: transfer failed: %s%s\n", d.message.c_str(), v.message.c_str());
      return 1;
    }
    t0 = Clock::now();
    std::uint8_t reply[9];
    for (const auto& frame : frames) {
      const auto deadline = Clock::now() + std::chrono::seconds(1);
      if (!port->write_all(frame.data(), frame.size(), deadline, err)) return 1;
      for (std::size_t got = 0; got < 9;) {
        const long n = port->read_some(reply + got, 9 - got, deadline, err);
        if (n <= 0) {
          std::fprintf(stderr, "host_bench: bare round trip failed: %s\n", err.c_str());
          return 1;
        }
        got += static_cast<std::size_t>(n);
      }
    }
    const double bare = std::chrono::duration<double>(Clock::now() - t0).count();
    best_transfer = std::min(best_transfer, transfer);
    best_bare = std::min(best_bare, bare);
  }
  port.reset();
  ::kill(server, SIGTERM);
  int st;
  ::waitpid(server, &st, 0);
  std::printf("tmclctl: download+verify of 577 instructions over a pty, s\t(info)\t%.4f\n", best_transfer);
  std::printf("tmclctl: %d bare round trips over the same pty, s\t(info)\t%.4f\n", trips, best_bare);
  std::printf("tmclctl: download+verify / bare round trips\t<= 1.2\t%.2f\n", best_transfer / best_bare);
  return 0;
}
