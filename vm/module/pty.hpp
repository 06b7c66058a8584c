// The platform layer, pseudo-terminals and the serial side of the virtual module: `--serve pty`
// where the system has pseudo-terminals (pty_posix.cpp), and a clear refusal where it has none
// (pty_windows.cpp: Windows; a COM port pair such as com0com or tcp: serves instead). Chosen
// when CMake configures (vm/module/CMakeLists.txt).
#pragma once

#include <string>

namespace tmcl {

// A pseudo-terminal whose slave side behaves like a raw serial port. The server keeps the slave
// open itself, so the master never sees a hang-up between two clients. `master` is non-blocking
// and waited on with os::poll. False with `error` set (and nothing left open).
bool open_pty(int& master, int& slave, std::string& path, std::string& error);

// write() on a pseudo-terminal's master or the stdio transport's output.
long write_fd(int fd, const void* data, std::size_t n);

}  // namespace tmcl
