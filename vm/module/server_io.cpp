// The virtual module's I/O loop (server.hpp: serve): one transport (TCP, pseudo-terminal or
// stdio), one client at a time, and the real-time pacing of simulated time — the only code in
// the project that reads the wall clock. Simulated time follows the steady clock scaled by
// ServeOptions::time_scale; the loop sleeps in poll() until a request, the next event of the
// program or the motors, the resynchronisation gap, or a stop request.
//
// One client at a time (errata S2): while a TCP client is connected, a second connection is
// accepted and answered with the refusal line (codec.hpp, kBusyRefusal), so its first read
// fails loudly, with a reason, instead of hanging; the refusal is logged. Its side is closed at
// once and what it sends is read and dropped until it closes (closing with unread data would
// reset the connection and could destroy the refusal before the client reads it). A new
// connection after the first one closed is served.
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <iostream>

#include "tmcl/bus.hpp"
#include "tmcl/eeprom.hpp"
#include "tmcl/os_console.hpp"
#include "tmcl/os_files.hpp"
#include "tmcl/os_net.hpp"
#include "tmcl/os_serial.hpp"
#include "tmcl/server.hpp"
#include "pty.hpp"

namespace tmcl {
namespace {

using Clock = std::chrono::steady_clock;

constexpr std::size_t kMaxPendingOutput = 1 << 20;  // stop reading requests beyond this
constexpr auto kPtyStall = std::chrono::milliseconds(1000);  // pty: nobody reads; drop the replies
constexpr std::size_t kMaxRefused = 8;  // refused clients held open at once; beyond: a plain reset
constexpr auto kRefusedHold = std::chrono::milliseconds(2000);  // a refused client's time to close

// ---- signals: a self-pipe, so poll() wakes up ----
std::atomic<int> g_signal_fd{-1};

extern "C" void on_stop_signal(int sig) {
  int fd = g_signal_fd.load();
  if (fd >= 0) {
    const char c = sig == SIGINT ? 'i' : 's';  // a debugger sharing the loop pauses on SIGINT
    os::wake(fd, c);
  }
}

struct SignalGuard {
  bool active = false;
  int pipe_fds[2] = {-1, -1};
  os::SavedSignal old_int, old_term;

  bool install() {
    if (!os::wake_pair(pipe_fds)) return false;
    g_signal_fd.store(pipe_fds[1]);
    // No restart: a blocked write returns EINTR and the loop sees the stop.
    os::catch_signal(SIGINT, on_stop_signal, false, &old_int);
    os::catch_signal(SIGTERM, on_stop_signal, false, &old_term);
    os::ignore_broken_pipe();  // a vanished reader is an error code, not a death
    active = true;
    return true;
  }
  ~SignalGuard() {
    if (!active) return;
    os::restore_signal(SIGINT, old_int);
    os::restore_signal(SIGTERM, old_term);
    g_signal_fd.store(-1);
    os::close_socket(pipe_fds[0]);
    os::close_socket(pipe_fds[1]);
  }
};

struct Fd {
  int fd = -1;
  Fd() = default;
  explicit Fd(int f) : fd(f) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() { reset(); }
  void reset(int f = -1) {
    if (fd >= 0) os::close_socket(fd);
    fd = f;
  }
  int release() {
    int f = fd;
    fd = -1;
    return f;
  }
};

std::string address_text(const sockaddr_storage& ss) {
  char buf[INET6_ADDRSTRLEN] = "?";
  if (ss.ss_family == AF_INET) {
    const auto* a = reinterpret_cast<const sockaddr_in*>(&ss);
    ::inet_ntop(AF_INET, &a->sin_addr, buf, sizeof buf);
    return std::string(buf) + ":" + std::to_string(ntohs(a->sin_port));
  }
  const auto* a = reinterpret_cast<const sockaddr_in6*>(&ss);
  ::inet_ntop(AF_INET6, &a->sin6_addr, buf, sizeof buf);
  return "[" + std::string(buf) + "]:" + std::to_string(ntohs(a->sin6_port));
}

bool is_loopback(const sockaddr_storage& ss) {
  if (ss.ss_family == AF_INET) {
    const auto* a = reinterpret_cast<const sockaddr_in*>(&ss);
    return (ntohl(a->sin_addr.s_addr) >> 24) == 127;
  }
  const auto* a = reinterpret_cast<const sockaddr_in6*>(&ss);
  return IN6_IS_ADDR_LOOPBACK(&a->sin6_addr) != 0;
}

// Opens the listening socket: the first address HOST resolves to that binds.
int open_listener(const ServeOptions& opt, std::string& where, bool& loopback, std::string& error) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
  addrinfo* res = nullptr;
  const std::string port = std::to_string(opt.port);
  if (int rc = ::getaddrinfo(opt.host.c_str(), port.c_str(), &hints, &res); rc != 0) {
    error = "cannot resolve '" + opt.host + "': " + os::resolve_error_text(rc);
    return -1;
  }
  int fd = -1;
  for (addrinfo* ai = res; ai; ai = ai->ai_next) {
    fd = os::open_socket(ai->ai_family, ai->ai_socktype, ai->ai_protocol);
    if (fd < 0) continue;
    int one = 1;
    const auto* on = reinterpret_cast<const char*>(&one);  // Winsock's options are char*
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, on, sizeof one);
    if (ai->ai_family == AF_INET6) ::setsockopt(fd, IPPROTO_IPV6, IPV6_V6ONLY, on, sizeof one);
    if (::bind(fd, ai->ai_addr, static_cast<socklen_t>(ai->ai_addrlen)) == 0 && ::listen(fd, 8) == 0) break;
    error = "cannot listen on " + opt.host + ":" + port + ": " + os::error_text(errno);
    os::close_socket(fd);
    fd = -1;
  }
  ::freeaddrinfo(res);
  if (fd < 0) {
    if (error.empty()) error = "cannot listen on " + opt.host + ":" + port;
    return -1;
  }
  sockaddr_storage ss{};
  socklen_t len = sizeof ss;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&ss), &len);
  where = address_text(ss);
  loopback = is_loopback(ss);
  os::set_nonblocking(fd);
  return fd;
}

// Writes as much of `out` as the descriptor takes now; removes it. False: the peer is gone.
bool flush_some(int fd, std::vector<std::uint8_t>& out, bool socket) {
  std::size_t done = 0;
  while (done < out.size()) {
    long n = socket ? os::send_socket(fd, out.data() + done, out.size() - done, true)
                    : write_fd(fd, out.data() + done, out.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) break;  // a signal: the loop looks at it, then writes again
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;
    out.erase(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(done));
    return false;
  }
  out.erase(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(done));
  return true;
}

enum class ReadResult { Data, Again, Closed };

ReadResult read_into(int fd, Line& module, std::vector<std::uint8_t>& buf) {
  for (;;) {
    long n = os::read_some(fd, buf.data(), buf.size());
    if (n > 0) {
      module.receive(buf.data(), static_cast<std::size_t>(n));
      return ReadResult::Data;
    }
    if (n == 0) return ReadResult::Closed;
    if (errno == EINTR) return ReadResult::Again;
    if (errno == EAGAIN || errno == EWOULDBLOCK) return ReadResult::Again;
    return ReadResult::Closed;
  }
}

}  // namespace

struct ServeLoop::Impl {
  Vm& vm;
  const ServeOptions& opt;
  std::ostream& log;
  std::ostream& announce;
  SignalGuard signals;
  Line module;  // one module, or a bus of them, with faults if asked (bus.hpp)
  Fd listener, client, pty_master, pty_slave;
  std::intptr_t serial_port = -1;  // Serial: the open port (os_serial.hpp)
  int serial_fd = -1;              // ... and the descriptor the loop polls for it
  struct Refused {  // a second client that was told it is refused, until it closes
    int fd;
    Clock::time_point until;
  };
  std::vector<Refused> refused;
  double scale = 1.0;
  Clock::time_point wall0, started, last_rx, last_write, spin_until;
  SimTime sim0 = 0;
  std::vector<std::uint8_t> buf = std::vector<std::uint8_t>(64 << 10);
  bool stop = false;
  bool dropped_note = false;
  bool extra_ready = false;
  std::chrono::microseconds spin;
  int in_fd = -1, out_fd = -1;

  Impl(Vm& v, const ServeOptions& o)
      : vm(v),
        opt(o),
        log(o.log ? *o.log : std::cerr),
        announce(o.announce ? *o.announce : (o.transport == Transport::Stdio ? std::cerr : std::cout)),
        module(v, o),
        spin(o.spin_us) {}
  ~Impl() {
    for (const Refused& r : refused) os::close_socket(r.fd);
    if (opt.transport == Transport::Stdio) os::release_pollable_input(in_fd, opt.in_fd);
  }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  void note(const std::string& s) {
    if (!opt.quiet) log << "tmclrun: " << s << std::endl;
  }
  SimTime target_at(Clock::time_point t) const {
    return sim0 + static_cast<SimTime>(std::chrono::duration<double, std::micro>(t - wall0).count() * scale);
  }
  void advance_now() {
    const Clock::time_point t = Clock::now();
    module.advance(target_at(t));
    if (module.take_power_cycle()) {  // simulated time restarted at 0
      wall0 = t;
      sim0 = vm.now;
    }
  }
  // The descriptor that carries the protocol right now (-1: no client).
  int data_fd() const {
    switch (opt.transport) {
      case Transport::Tcp: return client.fd;
      case Transport::Pty: return pty_master.fd;
      case Transport::Stdio: return in_fd;
      case Transport::Serial: return serial_fd;
    }
    return -1;
  }
  int write_fd() const { return opt.transport == Transport::Stdio ? out_fd : data_fd(); }
  bool writes_to_socket() const {
    return opt.transport == Transport::Tcp || (opt.transport == Transport::Serial && os::serial::kPollableIsSocket);
  }
  void close_client(const char* why) {
    note(std::string("client disconnected") + why);
    client.reset();
    module.drop_partial();
    module.output().clear();
  }
  void flush();
  void refuse(int fd, const sockaddr_storage& from);
  void drop_refused(std::size_t i) {
    os::close_socket(refused[i].fd);
    refused.erase(refused.begin() + static_cast<std::ptrdiff_t>(i));
  }
  int open();
  bool poll_once(int max_wait_ms, int extra_fd);
  int close();
};

int ServeLoop::Impl::open() {
  if (opt.handle_signals && !signals.install()) {
    log << "tmclrun: error: cannot install signal handlers: " << os::error_text(errno) << std::endl;
    return 71;
  }
  module.set_on_message([this](const std::string& s) { note(s); });
  const bool autostart_param = vm.profile->global_param(0, 77) && vm.bank0[77] != 0;
  if ((opt.autostart || autostart_param) && vm.program_size > 0) vm.start(0);

  // ---- the transport ----
  std::string ready;
  std::string error;
  switch (opt.transport) {
    case Transport::Tcp: {
      bool loopback = true;
      listener.reset(open_listener(opt, ready, loopback, error));
      if (listener.fd < 0) {
        log << "tmclrun: error: " << error << std::endl;
        return 71;
      }
      if (!loopback) note("warning: listening on a non-loopback address; anyone who reaches it can move the motors");
      break;
    }
    case Transport::Pty: {
      int master = -1, slave = -1;
      if (!open_pty(master, slave, ready, error)) {
        log << "tmclrun: error: " << error << std::endl;
        return 71;
      }
      pty_master.reset(master);
      pty_slave.reset(slave);
      break;
    }
    case Transport::Stdio: ready = "stdio"; break;
    case Transport::Serial: {
      serial_port = os::serial::open(opt.serial_port, opt.serial_baud, error);
      if (serial_port >= 0) serial_fd = os::serial::pollable(serial_port, error);
      if (serial_fd < 0) {
        log << "tmclrun: error: " << error << std::endl;
        return 71;
      }
      ready = opt.serial_port;
      break;
    }
  }
  if (!opt.quiet && opt.transport != Transport::Stdio) {
    if (opt.transport == Transport::Tcp) announce << "listening on " << ready << std::endl;
    else if (opt.transport == Transport::Serial) announce << "serving on " << ready << " at " << opt.serial_baud << " baud" << std::endl;
    else announce << ready << std::endl;
  }
  if (opt.on_ready) opt.on_ready(ready);

  // ---- pacing ----
  scale = opt.time_scale > 0 ? opt.time_scale : 1.0;
  wall0 = started = last_rx = last_write = spin_until = Clock::now();
  sim0 = vm.now;
  in_fd = opt.transport == Transport::Stdio ? os::pollable_input(opt.in_fd) : -1;
  out_fd = opt.transport == Transport::Stdio ? opt.out_fd : -1;
  return 0;
}

// A second client: the refusal line, then our side closed; kept open to drain until it closes.
void ServeLoop::Impl::refuse(int fd, const sockaddr_storage& from) {
  note("refused a second client from " + address_text(from) + ": one client at a time");
  if (refused.size() >= kMaxRefused) {
    linger lg{1, 0};  // a flood of them: a reset is all they get
    ::setsockopt(fd, SOL_SOCKET, SO_LINGER, reinterpret_cast<const char*>(&lg), sizeof lg);
    os::close_socket(fd);
    return;
  }
  os::send_socket(fd, kBusyRefusal.data(), kBusyRefusal.size(), true);
  ::shutdown(fd, os::kShutWrite);
  refused.push_back({fd, Clock::now() + kRefusedHold});
}

void ServeLoop::Impl::flush() {
  std::vector<std::uint8_t>& out = module.output();
  if (out.empty()) {
    if (opt.transport == Transport::Pty) last_write = Clock::now();
    return;
  }
  const int fd = write_fd();
  if (fd < 0) {
    out.clear();  // nobody to tell: replies and events are lost, as on an unplugged line
    return;
  }
  const std::size_t before = out.size();
  if (!flush_some(fd, out, writes_to_socket())) {
    if (opt.transport == Transport::Tcp) close_client("");
    else if (opt.transport == Transport::Stdio) stop = true;
    else out.clear();
  }
  if (opt.transport != Transport::Pty && opt.transport != Transport::Serial) return;
  // A pseudo-terminal or serial line has no "disconnected": replies nobody reads for a second are
  // dropped, as a serial line drops them, so the next client does not receive stale answers.
  const Clock::time_point t = Clock::now();
  if (out.empty() || out.size() < before) {
    last_write = t;
  } else if (t - last_write > kPtyStall) {
    if (!dropped_note) note("nobody reads the pseudo-terminal: dropping replies");
    dropped_note = true;
    out.clear();
    last_write = t;
  }
}

bool ServeLoop::Impl::poll_once(int max_wait_ms, int extra_fd) {
  std::vector<std::uint8_t>& out = module.output();
  extra_ready = false;
  if (stop) return false;
  advance_now();
  flush();
  if (stop) return false;

  const Clock::time_point now = Clock::now();
  if (opt.max_wall_ms > 0 && now - started >= std::chrono::milliseconds(opt.max_wall_ms)) {
    note("stopping: time limit of the server reached");
    return false;
  }

  // Right after a request, look for the next one for a few microseconds before sleeping in
  // poll(): a host that sends its next request as soon as it has the reply then costs one
  // wake-up per round trip instead of two (the round-trip benchmark doubles).
  if (spin_until > now && opt.transport != Transport::Stdio && data_fd() >= 0 && out.size() < kMaxPendingOutput) {
    ReadResult r = read_into(data_fd(), module, buf);
    if (r == ReadResult::Data) {
      last_rx = Clock::now();
      spin_until = last_rx + spin;
      return true;
    }
    if (r == ReadResult::Again) return true;
    spin_until = now;
    if (opt.transport == Transport::Tcp) close_client("");
    return true;
  }

  // How long poll may sleep.
  std::int64_t timeout_ms = 1000;
  const SimTime wake = module.next_wakeup();
  if (wake != kNever) {
    const double ahead_us = static_cast<double>(wake - target_at(now)) / scale;
    const double ms = ahead_us / 1000.0;
    timeout_ms = ms <= 1.0 ? 1 : ms >= 1000.0 ? 1000 : static_cast<std::int64_t>(ms) + 1;
  }
  if (module.window_pending()) {
    auto left = std::chrono::duration_cast<std::chrono::milliseconds>(last_rx + std::chrono::milliseconds(opt.resync_gap_ms) - now).count();
    if (left <= 0) {
      module.gap_elapsed();
      return true;
    }
    timeout_ms = std::min<std::int64_t>(timeout_ms, left);
  }
  if (opt.max_wall_ms > 0) {
    auto left = std::chrono::duration_cast<std::chrono::milliseconds>(started + std::chrono::milliseconds(opt.max_wall_ms) - now).count();
    timeout_ms = std::max<std::int64_t>(0, std::min<std::int64_t>(timeout_ms, left + 1));
  }
  if (max_wait_ms >= 0) timeout_ms = std::min<std::int64_t>(timeout_ms, max_wait_ms);
  for (std::size_t i = refused.size(); i-- > 0;) {
    if (refused[i].until <= now) {
      drop_refused(i);
      continue;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(refused[i].until - now).count() + 1;
    timeout_ms = std::min<std::int64_t>(timeout_ms, left);
  }

  pollfd fds[6 + kMaxRefused];
  nfds_t nfds = 0;
  int i_signal = -1, i_stop = -1, i_listen = -1, i_data = -1, i_out = -1, i_extra = -1;
  if (signals.active) {
    i_signal = static_cast<int>(nfds);
    fds[nfds++] = os::poll_entry(signals.pipe_fds[0], POLLIN);
  }
  if (opt.stop_fd >= 0) {
    i_stop = static_cast<int>(nfds);
    fds[nfds++] = os::poll_entry(opt.stop_fd, POLLIN);
  }
  if (listener.fd >= 0) {
    i_listen = static_cast<int>(nfds);
    fds[nfds++] = os::poll_entry(listener.fd, POLLIN);
  }
  const bool backlog = out.size() >= kMaxPendingOutput;
  if (data_fd() >= 0) {
    i_data = static_cast<int>(nfds);
    short ev = backlog ? 0 : POLLIN;
    if (!out.empty() && write_fd() == data_fd()) ev |= POLLOUT;
    fds[nfds++] = os::poll_entry(data_fd(), ev);
  }
  if (out_fd >= 0 && out_fd != in_fd && !out.empty()) {
    if (os::kPollsFiles) {
      i_out = static_cast<int>(nfds);
      fds[nfds++] = os::poll_entry(out_fd, POLLOUT);
    } else {
      flush();  // Windows: a file or a pipe takes a blocking write
    }
  }
  if (extra_fd >= 0) {
    i_extra = static_cast<int>(nfds);
    fds[nfds++] = os::poll_entry(extra_fd, POLLIN);
  }
  const int i_refused = static_cast<int>(nfds);
  for (const Refused& r : refused) fds[nfds++] = os::poll_entry(r.fd, POLLIN);

  int rc = os::poll(fds, nfds, static_cast<int>(timeout_ms));
  if (rc < 0) {
    if (errno == EINTR) return true;
    log << "tmclrun: error: poll: " << os::error_text(errno) << std::endl;
    return false;
  }
  if (rc == 0) return true;
  if (i_signal >= 0 && (fds[i_signal].revents & POLLIN)) {
    // SIGINT with on_interrupt (a debugger's Ctrl-C) pauses the program; anything else stops.
    char c[64];
    bool terminate = !opt.on_interrupt, interrupt = false;
    for (long n; (n = os::read_some(signals.pipe_fds[0], c, sizeof c)) > 0;)
      for (long i = 0; i < n; ++i) (c[i] == 'i' ? interrupt : terminate) = true;
    if (terminate) {
      note("stopping on signal");
      return false;
    }
    if (interrupt) opt.on_interrupt();
  }
  if (i_stop >= 0 && fds[i_stop].revents) return false;
  if (i_extra >= 0 && fds[i_extra].revents) extra_ready = true;
  // Refused clients: what they send is dropped; once they close (or fail), so do we.
  for (std::size_t i = refused.size(); i-- > 0;) {
    if (!fds[static_cast<std::size_t>(i_refused) + i].revents) continue;
    char sink[512];
    long n;
    while ((n = os::read_some(refused[i].fd, sink, sizeof sink)) > 0) {
    }
    if (n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) drop_refused(i);
  }

  if (i_data >= 0 && fds[i_data].revents) {
    const short re = fds[i_data].revents;
    if (re & (POLLIN | POLLHUP | POLLERR)) {
      advance_now();  // the request sees the module as it is now
      ReadResult r = read_into(data_fd(), module, buf);
      if (r == ReadResult::Data) {
        last_rx = Clock::now();
        spin_until = last_rx + spin;
      }
      if (r == ReadResult::Closed) {
        if (opt.transport == Transport::Tcp) {
          close_client("");
        } else if (opt.transport == Transport::Stdio) {
          flush();
          return false;  // end of input ends the session
        } else if (opt.transport == Transport::Serial) {
          note("the serial line " + opt.serial_port + " is gone (unplugged?): stopping");
          return false;
        }
      }
    }
    if ((re & POLLOUT) && data_fd() >= 0) flush();
  }
  if (i_out >= 0 && (fds[i_out].revents & (POLLOUT | POLLERR | POLLHUP))) flush();

  if (i_listen >= 0 && (fds[i_listen].revents & POLLIN)) {
    sockaddr_storage ss{};
    socklen_t len = sizeof ss;
    int fd = os::accept_socket(listener.fd, reinterpret_cast<sockaddr*>(&ss), &len);
    if (fd >= 0) {
      if (client.fd >= 0) {
        // The current client may have closed an instant ago: read what it left first.
        advance_now();
        if (read_into(client.fd, module, buf) == ReadResult::Closed) close_client("");
      }
      if (client.fd >= 0) {
        refuse(fd, ss);
      } else {
        int one = 1;
        ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, reinterpret_cast<const char*>(&one), sizeof one);
        client.reset(fd);
        module.drop_partial();
        note("client connected from " + address_text(ss));
      }
    }
  }
  return true;
}

int ServeLoop::Impl::close() {
  std::vector<std::uint8_t>& out = module.output();
  if (!out.empty() && write_fd() >= 0) flush_some(write_fd(), out, writes_to_socket());
  client.reset();
  while (!refused.empty()) drop_refused(refused.size() - 1);
  listener.reset();
  pty_master.reset();
  pty_slave.reset();
  if (serial_fd >= 0 && os::serial::kPollableIsSocket) os::close_socket(serial_fd);
  if (serial_port >= 0) os::serial::close(serial_port);
  serial_fd = -1;
  serial_port = -1;
  if (!opt.eeprom_path.empty()) {
    std::string err;
    if (!save_eeprom_file(opt.eeprom_path, vm.eeprom, err)) {
      log << "tmclrun: error: " << err << std::endl;
      return 74;
    }
  }
  return 0;
}

ServeLoop::ServeLoop(Vm& vm, const ServeOptions& options) : impl_(std::make_unique<Impl>(vm, options)) {}
ServeLoop::~ServeLoop() = default;
int ServeLoop::open() { return impl_->open(); }
bool ServeLoop::poll_once(int max_wait_ms, int extra_fd) { return impl_->poll_once(max_wait_ms, extra_fd); }
bool ServeLoop::extra_ready() const { return impl_->extra_ready; }
int ServeLoop::close() { return impl_->close(); }

int serve(Vm& vm, const ServeOptions& opt) {
  ServeLoop loop(vm, opt);
  if (int rc = loop.open(); rc != 0) return rc;
  while (loop.poll_once()) {
  }
  return loop.close();
}

bool parse_serve_spec(std::string_view spec, ServeOptions& options, std::string& error) {
  if (spec == "pty") {
    options.transport = Transport::Pty;
    return true;
  }
  if (spec == "stdio") {
    options.transport = Transport::Stdio;
    return true;
  }
  // A serial line: "COM5", "\\.\COM12" (Windows) or a device path ("/dev/ttyUSB0"), and
  // ":BAUD" after it for another rate than the modules' default 9600.
  if (os::serial::is_com_name(spec.substr(0, spec.find(':'))) || spec.substr(0, 4) == "\\\\.\\" || os::is_absolute(spec)) {
    std::string_view port = spec;
    long baud = 9600;
    if (const std::size_t colon = spec.rfind(':'); colon != std::string_view::npos && colon + 1 < spec.size() &&
                                                   spec.find_first_not_of("0123456789", colon + 1) == std::string_view::npos) {
      port = spec.substr(0, colon);
      baud = spec.size() - colon - 1 > 7 ? 0 : std::stol(std::string(spec.substr(colon + 1)));
      if (!os::serial::valid_baud(baud)) {
        error = "--serve PORT:BAUD: '" + std::string(spec.substr(colon + 1)) + "' is not a baud rate (" +
                os::serial::baud_rates_text() + ")";
        return false;
      }
    }
    options.transport = Transport::Serial;
    options.serial_port = std::string(port);
    options.serial_baud = baud;
    return true;
  }
  if (spec.substr(0, 4) != "tcp:") {
    error = "--serve takes tcp:HOST:PORT, pty, stdio or a serial port (COM3, /dev/ttyUSB0), not '" + std::string(spec) + "'";
    return false;
  }
  std::string_view rest = spec.substr(4);
  std::string host = "127.0.0.1";
  std::string_view port;
  if (!rest.empty() && rest.front() == '[') {  // [v6]:port
    std::size_t close = rest.find(']');
    if (close == std::string_view::npos || close + 1 >= rest.size() || rest[close + 1] != ':') {
      error = "--serve tcp:[ADDRESS]:PORT: '" + std::string(spec) + "' is incomplete";
      return false;
    }
    host = std::string(rest.substr(1, close - 1));
    port = rest.substr(close + 2);
  } else if (std::size_t colon = rest.rfind(':'); colon != std::string_view::npos) {
    host = std::string(rest.substr(0, colon));
    port = rest.substr(colon + 1);
    if (host.find(':') != std::string::npos) {
      error = "--serve: write an IPv6 address in brackets, e.g. tcp:[::1]:2001";
      return false;
    }
  } else {
    port = rest;
  }
  if (host.empty() || port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string_view::npos ||
      std::stoi(std::string(port)) > 65535) {
    error = "--serve tcp:HOST:PORT: bad host or port in '" + std::string(spec) + "'";
    return false;
  }
  options.transport = Transport::Tcp;
  options.host = host;
  options.port = std::stoi(std::string(port));
  return true;
}

}  // namespace tmcl
