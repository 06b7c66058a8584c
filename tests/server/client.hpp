// Test client for the virtual module: starts a server in-process (a thread running serve() on a
// loopback listener, a pseudo-terminal or a socketpair) and talks TMCL to it over the real
// transport. Every read has a timeout, so a broken server fails a test instead of hanging it.
#pragma once

#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <arpa/inet.h>

#include <array>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "frames.hpp"
#include "tmcl/image.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/server.hpp"
#include "tmcl/vm.hpp"

namespace srvtest {

using Clock = std::chrono::steady_clock;

// One connection to the module.
struct Link {
  int fd = -1;
  bool socket = true;
  Link() = default;
  Link(int f, bool is_socket) : fd(f), socket(is_socket) {}
  Link(const Link&) = delete;
  Link& operator=(const Link&) = delete;
  Link(Link&& o) noexcept : fd(o.fd), socket(o.socket) { o.fd = -1; }
  Link& operator=(Link&& o) noexcept {
    close();
    fd = o.fd;
    socket = o.socket;
    o.fd = -1;
    return *this;
  }
  ~Link() { close(); }
  void close() {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
  bool ok() const { return fd >= 0; }

  // Sends everything (waiting for room at most timeout_ms in total).
  bool send(const Bytes& b, int timeout_ms = 5000) {
    std::size_t done = 0;
    const auto end = Clock::now() + std::chrono::milliseconds(timeout_ms);
    while (done < b.size()) {
      ssize_t n = socket ? ::send(fd, b.data() + done, b.size() - done, MSG_NOSIGNAL | MSG_DONTWAIT)
                         : ::write(fd, b.data() + done, b.size() - done);
      if (n > 0) {
        done += static_cast<std::size_t>(n);
        continue;
      }
      if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) return false;
      if (Clock::now() >= end) return false;
      pollfd p{fd, POLLOUT, 0};
      ::poll(&p, 1, 10);
    }
    return true;
  }

  // Exactly n bytes, or nullopt after timeout_ms (or on EOF/error).
  std::optional<Bytes> recv(std::size_t n, int timeout_ms = 3000) {
    Bytes b(n);
    std::size_t got = 0;
    const auto end = Clock::now() + std::chrono::milliseconds(timeout_ms);
    while (got < n) {
      auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now()).count();
      if (left < 0) return std::nullopt;
      pollfd p{fd, POLLIN, 0};
      int rc = ::poll(&p, 1, static_cast<int>(left));
      if (rc <= 0) {
        if (rc < 0 && errno == EINTR) continue;
        return std::nullopt;
      }
      ssize_t k = ::read(fd, b.data() + got, n - got);
      if (k > 0) {
        got += static_cast<std::size_t>(k);
        continue;
      }
      if (k < 0 && (errno == EAGAIN || errno == EINTR)) continue;
      return std::nullopt;
    }
    return b;
  }

  // True when nothing arrives within ms.
  bool silent(int ms) {
    pollfd p{fd, POLLIN, 0};
    return ::poll(&p, 1, ms) == 0;
  }

  // Reads and discards whatever arrives until the line is quiet for quiet_ms.
  std::size_t drain(int quiet_ms = 100) {
    std::size_t total = 0;
    std::uint8_t buf[4096];
    for (int rounds = 0; rounds < 10000; ++rounds) {
      pollfd p{fd, POLLIN, 0};
      if (::poll(&p, 1, quiet_ms) <= 0) break;
      ssize_t k = ::read(fd, buf, sizeof buf);
      if (k <= 0) break;
      total += static_cast<std::size_t>(k);
    }
    return total;
  }

  std::optional<Bytes> request(std::uint8_t op, std::uint8_t type, std::uint8_t motor, std::int32_t value,
                               std::uint8_t addr = 1, int timeout_ms = 3000) {
    if (!send(frame(addr, op, type, motor, value))) return std::nullopt;
    return recv(9, timeout_ms);
  }
};

// A TCP connection to 127.0.0.1:PORT (a server in another process); not ok() when refused.
inline Link connect_loopback(int port) {
  int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return {};
  }
  return Link(fd, true);
}

// ---- an in-process server ----

struct ServerConfig {
  tmcl::Transport transport = tmcl::Transport::Tcp;
  std::string profile = "usb-2-sd";
  std::string motion;  // empty: the profile's
  double time_scale = 20.0;
  std::string host = "127.0.0.1";
  tmcl::ProtocolOptions protocol;
  std::vector<tmcl::Instruction> program;
  bool autostart = false;
  std::string eeprom_path;
};

struct Server {
  std::unique_ptr<tmcl::MotionCore> core;
  std::unique_ptr<tmcl::Vm> vm;
  tmcl::ServeOptions opt;
  std::thread thread;
  int stop_pipe[2] = {-1, -1};
  int pair[2] = {-1, -1};  // stdio: [0] client end, [1] server end
  int line_master = -1;    // serial: a pseudo-terminal whose slave the server opens as its port
  std::mutex mu;
  std::condition_variable cv;
  std::string ready;
  bool is_ready = false;
  int result = -1;
  std::ostringstream log;

  explicit Server(const ServerConfig& cfg) {
    const tmcl::Profile* p = tmcl::find_profile(cfg.profile);
    core = tmcl::make_motion_core(cfg.motion.empty() ? p->default_motion : cfg.motion);
    vm = std::make_unique<tmcl::Vm>(*p, *core);
    vm->load(cfg.program);
    vm->power_on(nullptr);
    opt.transport = cfg.transport;
    opt.host = cfg.host;
    opt.port = 0;
    opt.time_scale = cfg.time_scale;
    opt.protocol = cfg.protocol;
    opt.autostart = cfg.autostart;
    opt.eeprom_path = cfg.eeprom_path;
    opt.handle_signals = false;
    opt.max_wall_ms = 60000;  // never outlive a broken test
    opt.announce = &log;
    opt.log = &log;
    if (::pipe(stop_pipe) != 0) return;
    opt.stop_fd = stop_pipe[0];
    if (cfg.transport == tmcl::Transport::Stdio) {
      if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, pair) != 0) return;
      opt.in_fd = opt.out_fd = pair[1];
    }
    if (cfg.transport == tmcl::Transport::Serial) {  // a serial line: the host at the master end
      line_master = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
      if (line_master < 0 || ::grantpt(line_master) != 0 || ::unlockpt(line_master) != 0) return;
      opt.serial_port = ::ptsname(line_master);
      termios t{};
      ::tcgetattr(line_master, &t);
      ::cfmakeraw(&t);
      ::tcsetattr(line_master, TCSANOW, &t);
    }
    opt.on_ready = [this](const std::string& s) {
      std::lock_guard<std::mutex> g(mu);
      ready = s;
      is_ready = true;
      cv.notify_all();
    };
    thread = std::thread([this] { result = tmcl::serve(*vm, opt); });
    std::unique_lock<std::mutex> g(mu);
    cv.wait_for(g, std::chrono::seconds(5), [this] { return is_ready; });
  }

  int port() const { return std::stoi(ready.substr(ready.rfind(':') + 1)); }

  // A fresh connection over this server's transport.
  Link connect() {
    switch (opt.transport) {
      case tmcl::Transport::Tcp: {
        const bool v6 = !ready.empty() && ready[0] == '[';
        int fd = ::socket(v6 ? AF_INET6 : AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
        int one = 1;
        ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
        int rc;
        if (v6) {
          sockaddr_in6 a{};
          a.sin6_family = AF_INET6;
          a.sin6_port = htons(static_cast<std::uint16_t>(port()));
          a.sin6_addr = in6addr_loopback;
          rc = ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
        } else {
          sockaddr_in a{};
          a.sin_family = AF_INET;
          a.sin_port = htons(static_cast<std::uint16_t>(port()));
          a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
          rc = ::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
        }
        if (rc != 0) {
          ::close(fd);
          return {};
        }
        return Link(fd, true);
      }
      case tmcl::Transport::Pty: {
        int fd = ::open(ready.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
        if (fd < 0) return {};
        termios t{};  // what a serial library does on open: raw, 8N1
        ::tcgetattr(fd, &t);
        ::cfmakeraw(&t);
        ::tcsetattr(fd, TCSANOW, &t);
        ::tcflush(fd, TCIFLUSH);
        return Link(fd, false);
      }
      case tmcl::Transport::Stdio: {
        int fd = ::dup(pair[0]);
        return Link(fd, true);
      }
      case tmcl::Transport::Serial: return Link(::dup(line_master), false);
    }
    return {};
  }

  int stop() {
    if (thread.joinable()) {
      [[maybe_unused]] ssize_t n = ::write(stop_pipe[1], "x", 1);
      thread.join();
    }
    return result;
  }

  ~Server() {
    stop();
    for (int fd : {stop_pipe[0], stop_pipe[1], pair[0], pair[1], line_master})
      if (fd >= 0) ::close(fd);
  }
};

// SIGPIPE must not kill the test when a server closes a connection under a write.
inline const bool kSigpipeIgnored = [] {
  ::signal(SIGPIPE, SIG_IGN);
  return true;
}();

}  // namespace srvtest
