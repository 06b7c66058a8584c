// The platform layer, serial ports, as the host's Port (port.hpp) uses them: a device opened
// exclusively, raw 8N1 at a baud rate, read and written without blocking and waited on with a
// timeout. One implementation per system, chosen when CMake configures: serial_posix.cpp
// (termios; a device path such as /dev/ttyACM0), serial_windows.cpp (COM3, \\.\COM12).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "tmcl/os_net.hpp"  // POLLIN, POLLOUT, POLLERR, POLLHUP

namespace tmcl::host::serial {

// The baud rates a port accepts (9600 to 1000000, those Linux has a Bnnn constant for).
bool valid_baud(long baud);
// Opens the port: a descriptor (a HANDLE on Windows), or -1 with `error` naming it and why.
std::intptr_t open(const std::string& path, long baud, std::string& error);
void close(std::intptr_t port);
// What the port takes now / has now: the count, or -1 with errno set (EAGAIN: nothing now).
long write(std::intptr_t port, const std::uint8_t* data, std::size_t n);
long read(std::intptr_t port, std::uint8_t* data, std::size_t n);
// Waits at most `ms` for POLLIN or POLLOUT: the events that came, POLLHUP or POLLERR when the
// line is gone, 0 when none came.
short wait(std::intptr_t port, short events, int ms);

}  // namespace tmcl::host::serial
