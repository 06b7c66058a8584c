// The platform layer, pseudo-terminals, on Windows (pty.hpp): there are none. A host program
// reaches the virtual module over tcp:, or over a COM port pair (com0com) whose far end it opens.
#include "pty.hpp"

#include <io.h>

namespace tmcl {

bool open_pty(int& master, int& slave, std::string&, std::string& error) {
  master = slave = -1;
  error = "no pseudo-terminals on Windows; use tcp:HOST:PORT or a COM port pair";
  return false;
}

long write_fd(int fd, const void* data, std::size_t n) {
  const unsigned chunk = n > (1u << 30) ? (1u << 30) : static_cast<unsigned>(n);
  return ::_write(fd, data, chunk);
}

}  // namespace tmcl
