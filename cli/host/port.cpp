// The host's byte line (port.hpp): serial devices through termios, TCP through a non-blocking
// socket, both waited on with poll() against a deadline so that a silent module or a stuck line
// costs at most the timeout.
#include "tmcl/host/port.hpp"

#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <string_view>

#include "tmcl/codec.hpp"

namespace tmcl::host {
namespace {

const volatile std::sig_atomic_t* g_cancel = nullptr;

bool cancelled() { return g_cancel != nullptr && *g_cancel != 0; }

struct BaudEntry {
  long rate;
  speed_t code;
};
constexpr BaudEntry kBauds[] = {
    {9600, B9600},     {19200, B19200},   {38400, B38400},   {57600, B57600},   {115200, B115200},
    {230400, B230400}, {460800, B460800}, {500000, B500000}, {576000, B576000}, {921600, B921600},
    {1000000, B1000000},
};

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
    error = spec + ": " + ::gai_strerror(rc);
    return -1;
  }
  int fd = -1;
  error = spec + ": cannot connect";
  for (addrinfo* a = res; a && fd < 0; a = a->ai_next) {
    fd = ::socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) continue;
    int rc = ::connect(fd, a->ai_addr, a->ai_addrlen);
    if (rc != 0 && errno == EINPROGRESS) {
      pollfd p{fd, POLLOUT, 0};
      const auto deadline = Clock::now() + std::chrono::milliseconds(connect_ms);
      int pr = 0;
      while ((pr = ::poll(&p, 1, poll_ms(deadline))) == 0 && Clock::now() < deadline && !cancelled()) {
      }
      int err = 0;
      socklen_t len = sizeof err;
      if (pr > 0 && ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len) == 0 && err == 0) {
        rc = 0;
      } else {
        errno = pr > 0 ? err : ETIMEDOUT;
        rc = -1;
      }
    }
    if (rc != 0) {
      error = spec + ": cannot connect: " + std::strerror(errno);
      ::close(fd);
      fd = -1;
      continue;
    }
    int one = 1;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  }
  ::freeaddrinfo(res);
  return fd;
}

int open_serial(const std::string& path, long baud, std::string& error) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    error = path + ": " + std::strerror(errno);
    return -1;
  }
  auto fail = [&](const std::string& what) {
    error = path + ": " + what;
    ::close(fd);
    return -1;
  };
  if (!::isatty(fd)) return fail("not a serial port (a tty device or tcp:HOST:PORT is needed)");
  // Exclusive: the kernel refuses later opens (EBUSY, except for root), flock stops cooperating
  // programs (pyserial's exclusive=True) and a second tmclctl, root or not.
  if (::ioctl(fd, TIOCEXCL) != 0 && errno != ENOTTY) return fail(std::string("cannot lock: ") + std::strerror(errno));
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0)
    return fail(errno == EWOULDBLOCK ? "port in use by another program" : std::string("cannot lock: ") + std::strerror(errno));
  termios t{};
  if (::tcgetattr(fd, &t) != 0) return fail(std::string("cannot read the line settings: ") + std::strerror(errno));
  ::cfmakeraw(&t);
  t.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  t.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | CRTSCTS | PARENB | CSIZE);
  t.c_cflag |= CS8 | CLOCAL | CREAD;
  t.c_cc[VMIN] = 0;
  t.c_cc[VTIME] = 0;
  speed_t code = B9600;
  for (const auto& b : kBauds)
    if (b.rate == baud) code = b.code;
  ::cfsetispeed(&t, code);
  ::cfsetospeed(&t, code);
  if (::tcsetattr(fd, TCSANOW, &t) != 0) return fail(std::string("cannot set raw 8N1: ") + std::strerror(errno));
  termios back{};  // tcsetattr succeeds if any change applied: read back what matters
  if (::tcgetattr(fd, &back) != 0 || (back.c_lflag & ICANON) || (back.c_cflag & CSIZE) != CS8 || ::cfgetospeed(&back) != code)
    return fail("the driver refused raw 8N1 at " + std::to_string(baud) + " baud");
  ::tcflush(fd, TCIOFLUSH);
  return fd;
}

}  // namespace

bool valid_baud(long baud) {
  for (const auto& b : kBauds)
    if (b.rate == baud) return true;
  return false;
}

void Port::set_cancel_flag(const volatile std::sig_atomic_t* flag) { g_cancel = flag; }

std::unique_ptr<Port> Port::open(const std::string& spec, long baud, int connect_ms, std::string& error) {
  const bool tcp = spec.rfind("tcp:", 0) == 0;
  const int fd = tcp ? open_tcp(spec, connect_ms, error) : open_serial(spec, baud, error);
  if (fd < 0) return nullptr;
  return std::unique_ptr<Port>(new Port(fd, spec, !tcp));
}

Port::~Port() {
  if (fd_ >= 0) ::close(fd_);
}

bool Port::write_all(const std::uint8_t* data, std::size_t n, Clock::time_point deadline, std::string& error) {
  if (!refusal_.empty()) {
    error = refusal_;
    return false;
  }
  std::size_t done = 0;
  while (done < n) {
    const ssize_t w = serial_ ? ::write(fd_, data + done, n - done) : ::send(fd_, data + done, n - done, MSG_NOSIGNAL);
    if (w > 0) {
      done += static_cast<std::size_t>(w);
      continue;
    }
    if (w < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
      error = "cannot write to " + name_ + ": " + std::strerror(errno);
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
    pollfd p{fd_, POLLOUT, 0};
    ::poll(&p, 1, poll_ms(deadline));
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
    const ssize_t r = ::read(fd_, data, n);
    if (r > 0) return static_cast<long>(r);
    if ((r == 0 && !serial_) || (r <= 0 && hung_up)) {
      error = name_ + (serial_ ? ": the line was hung up (device unplugged or server gone)"
                               : ": the connection was closed by the other end");
      return -1;
    }
    if (r < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
      error = "cannot read from " + name_ + ": " + std::strerror(errno);
      return -1;
    }
    if (cancelled()) return -2;
    if (Clock::now() >= deadline) return 0;
    pollfd p{fd_, POLLIN, 0};
    const int pr = ::poll(&p, 1, poll_ms(deadline));
    if (pr > 0 && (p.revents & (POLLERR | POLLHUP))) {
      if (!(p.revents & POLLIN) || hung_up) {
        error = name_ + ": the line was hung up (device unplugged or server gone)";
        return -1;
      }
      hung_up = true;  // read what is left, then report
    }
  }
}

}  // namespace tmcl::host
