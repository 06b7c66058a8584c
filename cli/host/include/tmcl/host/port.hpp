// A byte line to a TMCL module, as a host sees it: a serial device (a USB CDC port, a USB-UART
// bridge, the pseudo-terminal of `tmclrun --serve pty`) or a TCP connection (a serial-over-
// Ethernet bridge, `tmclrun --serve tcp`). Every read and write has a deadline, so nothing here
// can hang; a cancel flag (set by a SIGINT handler) ends a wait early.
//
// Serial ports are opened the way pyserial does it (shared/reference/protocols.md 5.1): non-
// blocking, exclusive (TIOCEXCL and flock, so a second program gets "port in use"), raw 8N1 at
// the requested baud rate, modem lines ignored, stale input flushed. A TCP connection whose
// first bytes are the virtual module's busy refusal (codec.hpp, kBusyRefusal) fails every read
// and write from then on with "module busy with another client".
#pragma once

#include <chrono>
#include <csignal>
#include <cstdint>
#include <memory>
#include <string>

namespace tmcl::host {

using Clock = std::chrono::steady_clock;

// The baud rates a serial port accepts (those with a Linux Bnnn constant, 9600 to 1000000).
bool valid_baud(long baud);

class Port {
 public:
  // Opens "tcp:HOST:PORT" (HOST may be [v6]) or a serial device path. `connect_ms` bounds a TCP
  // connect. Null with `error` naming the port and the reason.
  static std::unique_ptr<Port> open(const std::string& spec, long baud, int connect_ms, std::string& error);
  ~Port();
  Port(const Port&) = delete;
  Port& operator=(const Port&) = delete;

  // Writes every byte before `deadline`. False with `error` on a timeout, a cancel or a lost line.
  bool write_all(const std::uint8_t* data, std::size_t n, Clock::time_point deadline, std::string& error);
  // Waits until some bytes arrive or `deadline` passes. Returns the count read, 0 when the
  // deadline passed (or, with a zero deadline, nothing is buffered), -1 with `error` when the
  // line is gone or the server refused us (busy), -2 when cancelled.
  long read_some(std::uint8_t* data, std::size_t n, Clock::time_point deadline, std::string& error);

  // Gives the line up (a lost serial device's lock, a dead socket) so that it can be opened again;
  // every later read and write fails.
  void close();

  const std::string& name() const { return name_; }
  bool is_serial() const { return serial_; }

  // Set by a signal handler: waits return -2 / false soon after it becomes non-zero.
  static void set_cancel_flag(const volatile std::sig_atomic_t* flag);

 private:
  Port(std::intptr_t fd, std::string name, bool serial) : fd_(fd), name_(std::move(name)), serial_(serial) {}
  long read_raw(std::uint8_t* data, std::size_t n, Clock::time_point deadline, std::string& error);
  bool refused(std::uint8_t* data, long& got, std::size_t n, Clock::time_point deadline);
  // Waits at most `ms` for POLLIN or POLLOUT; the poll() events that came (0: none).
  short wait(short events, int ms);
  std::intptr_t fd_;  // a socket, a serial device's descriptor, or (Windows) its HANDLE
  std::string name_;
  bool serial_;
  bool first_read_ = true;  // TCP: nothing received yet (the busy refusal comes first or never)
  std::string refusal_;     // non-empty once the server refused us: every later call fails with it
};

}  // namespace tmcl::host
