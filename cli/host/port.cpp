// The host's byte line (port.hpp): serial devices through the platform layer's serial port
// (serial.hpp), TCP through a non-blocking socket (os_net.hpp), both waited on against a deadline
// so that a silent module or a stuck line costs at most the timeout.
#include "tmcl/host/port.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string_view>

#include "tmcl/os_serial.hpp"
#include "tmcl/codec.hpp"
#include "tmcl/os_net.hpp"

namespace tmcl::host {
namespace {

const volatile std::sig_atomic_t* g_cancel = nullptr;

bool cancelled() { return g_cancel != nullptr && *g_cancel != 0; }

int poll_ms(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  if (left <= 0) return 0;
  // Wake up now and then so that a cancel flag set by a signal that poll() did not see counts.
  return static_cast<int>(left > 100 ? 100 : left + 1);
}

int open_tcp(const std::string& spec, int connect_ms, std::string& error) {
  std::string rest = spec.substr(4), host, port;
  if (!rest.empty() && rest.front() == '[') {
    const auto close = rest.find(']');
    if (close == std::string::npos || close + 1 >= rest.size() || rest[close + 1] != ':') {
      error = "bad port '" + spec + "': use tcp:HOST:PORT, tcp:[v6]:PORT";
      return -1;
    }
    host = rest.substr(1, close - 1);
    port = rest.substr(close + 2);
  } else if (const auto colon = rest.rfind(':'); colon != std::string::npos) {
    host = rest.substr(0, colon);
    port = rest.substr(colon + 1);
  }
  if (host.empty() || port.empty()) {
    error = "bad port '" + spec + "': use tcp:HOST:PORT";
    return -1;
  }
  addrinfo hints{};
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* res = nullptr;
  if (int rc = ::getaddrinfo(host.c_str(), port.c_str(), &hints, &res); rc != 0) {
    error = spec + ": " + os::resolve_error_text(rc);
    return -1;
  }
  int fd = -1;
  error = spec + ": cannot connect";
  for (addrinfo* a = res; a && fd < 0; a = a->ai_next) {
    fd = os::open_socket(a->ai_family, a->ai_socktype, a->ai_protocol);
    if (fd < 0) continue;
    os::set_nonblocking(fd);
    int rc = os::connect_socket(fd, a->ai_addr, static_cast<socklen_t>(a->ai_addrlen));
    if (rc != 0 && errno == EINPROGRESS) {
      pollfd p = os::poll_entry(fd, POLLOUT);
      const auto deadline = Clock::now() + std::chrono::milliseconds(connect_ms);
      int pr = 0;
      while ((pr = os::poll(&p, 1, poll_ms(deadline))) == 0 && Clock::now() < deadline && !cancelled()) {
      }
      int err = 0;
      socklen_t len = sizeof err;
      if (pr > 0 && ::getsockopt(fd, SOL_SOCKET, SO_ERROR, reinterpret_cast<char*>(&err), &len) == 0 && err == 0) {
        rc = 0;
      } else {
        errno = pr > 0 ? err : ETIMEDOUT;
        rc = -1;
      }
    }
    if (rc != 0) {
      error = spec + ": cannot connect: " + os::error_text(errno);
      os::close_socket(fd);
      fd = -1;
      continue;
    }
    int one = 1;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, reinterpret_cast<const char*>(&one), sizeof one);
  }
  ::freeaddrinfo(res);
  return fd;
}

}  // namespace

bool valid_baud(long baud) { return os::serial::valid_baud(baud); }

void Port::set_cancel_flag(const volatile std::sig_atomic_t* flag) { g_cancel = flag; }

std::unique_ptr<Port> Port::open(const std::string& spec, long baud, int connect_ms, std::string& error) {
  const bool tcp = spec.rfind("tcp:", 0) == 0;
  const std::intptr_t fd = tcp ? open_tcp(spec, connect_ms, error) : os::serial::open(spec, baud, error);
  if (fd < 0) return nullptr;
  return std::unique_ptr<Port>(new Port(fd, spec, !tcp));
}

Port::~Port() { close(); }

void Port::close() {
  if (fd_ < 0) return;
  if (serial_) os::serial::close(fd_);
  else os::close_socket(static_cast<int>(fd_));
  fd_ = -1;
  refusal_ = name_ + ": the port was closed";
}

bool Port::write_all(const std::uint8_t* data, std::size_t n, Clock::time_point deadline, std::string& error) {
  if (!refusal_.empty()) {
    error = refusal_;
    return false;
  }
  std::size_t done = 0;
  while (done < n) {
    const long w = serial_ ? os::serial::write(fd_, data + done, n - done)
                           : os::send_socket(static_cast<int>(fd_), data + done, n - done, false);
    if (w > 0) {
      done += static_cast<std::size_t>(w);
      continue;
    }
    if (w < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
      error = "cannot write to " + name_ + ": " + os::error_text(errno);
      return false;
    }
    if (cancelled()) {
      error = "interrupted";
      return false;
    }
    if (Clock::now() >= deadline) {
      error = "cannot write to " + name_ + ": the line takes no data (timeout)";
      return false;
    }
    wait(POLLOUT, poll_ms(deadline));
  }
  return true;
}

long Port::read_some(std::uint8_t* data, std::size_t n, Clock::time_point deadline, std::string& error) {
  if (!refusal_.empty()) {
    error = refusal_;
    return -1;
  }
  long got = read_raw(data, n, deadline, error);
  if (got <= 0 || serial_ || !first_read_) return got;
  first_read_ = false;
  if (!refused(data, got, n, deadline)) return got;
  error = refusal_;
  return -1;
}

// The first bytes of a TCP connection: the busy refusal, or the start of a reply. A refusal
// split after fewer bytes than its prefix is completed first (a reply never starts like it: its
// third byte, the status, would be 's'), then read to its end of line for the message.
bool Port::refused(std::uint8_t* data, long& got, std::size_t n, Clock::time_point deadline) {
  const std::string_view prefix = kBusyPrefix;
  auto matches = [&] {
    const std::size_t k = std::min(static_cast<std::size_t>(got), prefix.size());
    return std::string_view(reinterpret_cast<const char*>(data), k) == prefix.substr(0, k);
  };
  const auto soon = std::min(deadline, Clock::now() + std::chrono::milliseconds(100));
  std::string ignored;
  while (matches() && static_cast<std::size_t>(got) < prefix.size() && static_cast<std::size_t>(got) < n) {
    const long more = read_raw(data + got, n - static_cast<std::size_t>(got), soon, ignored);
    if (more <= 0) break;
    got += more;
  }
  if (!matches() || static_cast<std::size_t>(got) < prefix.size()) return false;
  std::string line(reinterpret_cast<const char*>(data), static_cast<std::size_t>(got));
  std::uint8_t buf[256];
  for (long more; line.find('\n') == std::string::npos && line.size() < 512 &&
                  (more = read_raw(buf, sizeof buf, soon, ignored)) > 0;)
    line.append(reinterpret_cast<const char*>(buf), static_cast<std::size_t>(more));
  line = line.substr(0, line.find('\n'));
  for (char& c : line)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7E) c = '?';
  refusal_ = name_ + ": module busy with another client (the server said \"" + line +
             "\"); try again when that client has disconnected";
  return true;
}

long Port::read_raw(std::uint8_t* data, std::size_t n, Clock::time_point deadline, std::string& error) {
  bool hung_up = false;
  for (;;) {
    const long r = serial_ ? os::serial::read(fd_, data, n) : os::read_some(static_cast<int>(fd_), data, n);
    if (r > 0) return static_cast<long>(r);
    if ((r == 0 && !serial_) || (r <= 0 && hung_up)) {
      error = name_ + (serial_ ? ": the line was hung up (device unplugged or server gone)"
                               : ": the connection was closed by the other end");
      return -1;
    }
    if (r < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
      error = "cannot read from " + name_ + ": " + os::error_text(errno);
      return -1;
    }
    if (cancelled()) return -2;
    if (Clock::now() >= deadline) return 0;
    const short revents = wait(POLLIN, poll_ms(deadline));
    if (revents & (POLLERR | POLLHUP)) {
      if (!(revents & POLLIN) || hung_up) {
        error = name_ + ": the line was hung up (device unplugged or server gone)";
        return -1;
      }
      hung_up = true;  // read what is left, then report
    }
  }
}

short Port::wait(short events, int ms) {
  if (serial_) return os::serial::wait(fd_, events, ms);
  pollfd p = os::poll_entry(static_cast<int>(fd_), events);
  return os::poll(&p, 1, ms) > 0 ? p.revents : 0;
}

}  // namespace tmcl::host
