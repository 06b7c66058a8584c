// The host side of the TMCL protocol (USB-2-SD manual 3.1, 3.2; shared/reference/protocols.md 6):
// one request, then the reply that belongs to it, over a Port.
//
// A reply belongs to the request when its checksum is right, it is addressed to our host address,
// comes from the module address we sent to and echoes our command. Everything else that arrives
// is drained and counted: replies with a bad checksum, from another address or for another
// command, replies left over from an earlier request (stale), and the unasked second reply of
// command 138 (status 128), which is kept as an event. When several matching replies are buffered
// the last one wins: a module answers in order, so earlier ones are stale copies.
// Two replies have no ordinary layout (docs/virtual-module.md): 136 type 0 is the host address and
// eight ASCII characters without a checksum; 134 type 0 is the host address and the stored
// instruction with a checksum. 137 is never answered.
//
// A silent module or a corrupted reply is retried (after letting late bytes settle) up to
// `retries` times; then the request fails with a message naming the port, the module address and
// what was sent. Resending repeats the command: callers pass retry=false where that would do harm
// (stores in download mode) and recover themselves.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tmcl/host/port.hpp"
#include "tmcl/isa.hpp"

namespace tmcl::host {

inline constexpr std::uint8_t kStatusOk = 100, kStatusLoaded = 101, kStatusPositionReached = 128;

// "success", "wrong checksum", "invalid value", ... ("status 42" for an unknown code).
std::string status_text(std::uint8_t status);
// Bytes as upper-case hex pairs separated by spaces ("01 04 00 ..."), for messages and --raw.
std::string hex(const std::uint8_t* p, std::size_t n);

struct Reply {
  std::uint8_t status = 0;
  std::uint8_t op = 0;
  std::int32_t value = 0;
  std::array<std::uint8_t, 9> bytes{};
  Instruction stored;   // 134 type 0: the instruction read back
  std::string version;  // 136 type 0: the eight characters
};

enum class Fail : std::uint8_t { None, NoReply, Port, Cancelled };

struct Result {
  Fail fail = Fail::None;
  Reply reply;
  std::string error;  // when fail != None
  int attempts = 0;
  bool ok() const { return fail == Fail::None; }
};

struct ClientOptions {
  std::uint8_t module = 1;  // -a
  std::uint8_t host = 2;    // --host-address
  int timeout_ms = 1000;    // per attempt
  int retries = 2;          // further attempts after the first
  int settle_ms = 100;      // after a timeout, late bytes are read and dropped this long (capped at the timeout)
  // Every frame sent (out = true) and every 9 bytes received, for --raw.
  std::function<void(bool out, const std::uint8_t* bytes, std::size_t n)> on_frame;
};

class Client {
 public:
  Client(Port& port, ClientOptions options) : port_(port), opt_(std::move(options)) {}

  Result request(const Instruction& ins, bool retry = true);
  // 138 position-reached replies received so far (oldest first); taking them clears the list.
  std::vector<Reply> take_events();
  // Replies from another module than the one asked, with a right checksum and a known status:
  // late answers to an earlier request (a bus scan finds slow modules by them). Oldest first,
  // the last 64 kept; taking them clears the list.
  std::vector<Reply> take_strays();
  // Reads what arrives until `until` without asking anything: events and strays are kept, the
  // rest dropped.
  void listen(Clock::time_point until);

  // "SAP 4, 0, 51200 [01 05 04 00 00 00 C8 00 D2] to module 1 on /dev/pts/3"
  std::string describe(const Instruction& ins) const;
  Port& port() { return port_; }
  const ClientOptions& options() const { return opt_; }
  void set_module(std::uint8_t address) { opt_.module = address; }
  void set_timeout(int ms) { opt_.timeout_ms = ms; }
  void set_retries(int n) { opt_.retries = n; }

  struct Stats {
    std::uint64_t requests = 0, retries = 0, drained = 0, corrupted = 0, events = 0;
  };
  const Stats& stats() const { return stats_; }

 private:
  enum class Scan { Need, Found, Corrupt };
  Scan scan(const Instruction& ins, Reply& found);
  void drain_now();
  void settle(Clock::time_point until);
  bool send(const Instruction& ins, std::string& error);

  Port& port_;
  ClientOptions opt_;
  std::vector<std::uint8_t> rx_;
  std::vector<Reply> events_;
  std::vector<Reply> strays_;
  Stats stats_;
  bool unclean_ = true;  // the last request saw trouble (or there was none yet): drain first
};

}  // namespace tmcl::host
