// The platform layer, serial ports, on POSIX systems (os_serial.hpp): termios, opened the way
// pyserial does it (shared/reference/protocols.md 5.1): non-blocking, exclusive (TIOCEXCL and
// flock, so a second program gets "port in use"), raw 8N1, modem lines ignored, stale input
// flushed.
#include "tmcl/os_serial.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/file.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace tmcl::os::serial {
namespace {

struct BaudEntry {
  long rate;
  speed_t code;
};
constexpr BaudEntry kBauds[] = {
    {9600, B9600},     {19200, B19200},   {38400, B38400},   {57600, B57600},   {115200, B115200},
    {230400, B230400}, {460800, B460800}, {500000, B500000}, {576000, B576000}, {921600, B921600},
    {1000000, B1000000},
};

}  // namespace

bool valid_baud(long baud) {
  for (const auto& b : kBauds)
    if (b.rate == baud) return true;
  return false;
}

std::intptr_t open(const std::string& path, long baud, std::string& error) {
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

void close(std::intptr_t port) { ::close(static_cast<int>(port)); }

long write(std::intptr_t port, const std::uint8_t* data, std::size_t n) { return ::write(static_cast<int>(port), data, n); }

long read(std::intptr_t port, std::uint8_t* data, std::size_t n) { return ::read(static_cast<int>(port), data, n); }

short wait(std::intptr_t port, short events, int ms) {
  pollfd p{static_cast<int>(port), events, 0};
  return ::poll(&p, 1, ms) > 0 ? p.revents : 0;
}

int pollable(std::intptr_t port, std::string&) { return static_cast<int>(port); }
const bool kPollableIsSocket = false;

}  // namespace tmcl::os::serial
