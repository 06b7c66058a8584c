// The platform layer, serial ports, as the host's Port (cli/host/port.cpp) and a virtual module
// served on a serial line (vm/module/server_io.cpp) use them: a device opened exclusively, raw
// 8N1 at a baud rate, read and written without blocking and waited on with a timeout. One implementation per system, chosen when CMake configures: os_serial_posix.cpp
// (termios; a device path such as /dev/ttyACM0), os_serial_windows.cpp (COM3, \\.\COM12).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "tmcl/os_net.hpp"  // POLLIN, POLLOUT, POLLERR, POLLHUP

namespace tmcl::os::serial {

// The baud rates a port accepts (9600 to 1000000, those Linux has a Bnnn constant for).
inline constexpr long kBaudRates[] = {9600, 19200, 38400, 57600, 115200, 230400, 460800, 500000, 576000, 921600, 1000000};
bool valid_baud(long baud);
// "9600, 19200, ... 921600 or 1000000", for messages and help texts.
std::string baud_rates_text();
// Whether NAME is a COM port's short name, "COM" (any case) and a number: "COM3", "com12".
bool is_com_name(std::string_view name);
// Opens the port: a descriptor (a HANDLE on Windows), or -1 with `error` naming it and why.
std::intptr_t open(const std::string& path, long baud, std::string& error);
void close(std::intptr_t port);
// What the port takes now / has now: the count, or -1 with errno set (EAGAIN: nothing now).
long write(std::intptr_t port, const std::uint8_t* data, std::size_t n);
long read(std::intptr_t port, std::uint8_t* data, std::size_t n);
// Waits at most `ms` for POLLIN or POLLOUT: the events that came, POLLHUP or POLLERR when the
// line is gone, 0 when none came.
short wait(std::intptr_t port, short events, int ms);
// The open port as a descriptor a poll() loop waits on (tmclrun --serve COM5): on POSIX the
// port's own; on Windows, where a COM port cannot be polled, one end of a socket pair that two
// threads join to the port (until the port is closed). Non-blocking. -1 with `error`.
int pollable(std::intptr_t port, std::string& error);
// Whether pollable()'s descriptor is a socket (send/recv) rather than a file (write/read).
extern const bool kPollableIsSocket;

}  // namespace tmcl::os::serial
