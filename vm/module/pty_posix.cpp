// The platform layer, pseudo-terminals, on POSIX systems (pty.hpp).
#include "pty.hpp"

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>

namespace tmcl {

bool open_pty(int& master, int& slave, std::string& path, std::string& error) {
  master = slave = -1;
  auto fail = [&](const std::string& what) {
    error = what;
    if (slave >= 0) ::close(slave);
    if (master >= 0) ::close(master);
    master = slave = -1;
    return false;
  };
  master = ::posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0)
    return fail(std::string("cannot create a pseudo-terminal: ") + std::strerror(errno));
  char name[256];
  if (::ptsname_r(master, name, sizeof name) != 0)
    return fail(std::string("cannot name the pseudo-terminal: ") + std::strerror(errno));
  path = name;
  slave = ::open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (slave < 0) return fail("cannot open " + path + ": " + std::strerror(errno));
  termios t{};
  if (::tcgetattr(slave, &t) == 0) {  // raw: 8 data bits, no echo, no line editing, no CR/LF mapping
    t.c_iflag &= ~static_cast<tcflag_t>(IGNBRK | BRKINT | PARMRK | ISTRIP | INLCR | IGNCR | ICRNL | IXON | IXOFF);
    t.c_oflag &= ~static_cast<tcflag_t>(OPOST);
    t.c_lflag &= ~static_cast<tcflag_t>(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
    t.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB);
    t.c_cflag |= CS8 | CREAD | CLOCAL;
    t.c_cc[VMIN] = 1;
    t.c_cc[VTIME] = 0;
    ::tcsetattr(slave, TCSANOW, &t);
  }
  ::fcntl(master, F_SETFD, FD_CLOEXEC);
  ::fcntl(master, F_SETFL, ::fcntl(master, F_GETFL) | O_NONBLOCK);
  return true;
}

long write_fd(int fd, const void* data, std::size_t n) { return ::write(fd, data, n); }

}  // namespace tmcl
