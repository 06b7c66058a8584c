// The platform layer, serial ports, on Windows (os_serial.hpp): a COM port by its name ("COM3") or
// its device path ("\\.\COM12"; COM10 and above need it in Windows' own calls, the short name is
// turned into it here). Opened without sharing (a second program gets "port in use"), raw 8N1
// with no flow control, reads that return at once with what has arrived, stale input purged.
// Waiting for input looks at the driver's queue every millisecond: simpler than overlapped I/O,
// and a request/reply protocol at 9600 to 1000000 baud loses nothing to it.
#include "tmcl/os_serial.hpp"

#include <windows.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>

#include "tmcl/os_files.hpp"

namespace tmcl::os::serial {
namespace {


HANDLE handle(std::intptr_t port) { return reinterpret_cast<HANDLE>(port); }

// "COM3", "com12" -> "\\.\COM12"; "/dev/null" -> "NUL" (os_files.hpp); anything else as it is.
std::string device_path(const std::string& name) {
  if (is_com_name(name)) return "\\\\.\\COM" + name.substr(3);
  return os::native_path(name);
}

std::string last_error_text() {
  const DWORD code = ::GetLastError();
  char text[256] = "";
  ::FormatMessageA(FORMAT_MESSAGE_FROM_SYSTEM | FORMAT_MESSAGE_IGNORE_INSERTS, nullptr, code, 0, text, sizeof text, nullptr);
  std::string s = text;
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == '.' || s.back() == ' ')) s.pop_back();
  return s.empty() ? "error " + std::to_string(code) : s;
}

}  // namespace

bool valid_baud(long baud) { return std::find(std::begin(kBaudRates), std::end(kBaudRates), baud) != std::end(kBaudRates); }

std::intptr_t open(const std::string& path, long baud, std::string& error) {
  const std::string device = device_path(path);
  HANDLE h = ::CreateFileA(device.c_str(), GENERIC_READ | GENERIC_WRITE, 0, nullptr, OPEN_EXISTING, 0, nullptr);
  if (h == INVALID_HANDLE_VALUE) {
    const DWORD code = ::GetLastError();
    if (code == ERROR_ACCESS_DENIED || code == ERROR_SHARING_VIOLATION) error = path + ": port in use by another program";
    else if (code == ERROR_FILE_NOT_FOUND || code == ERROR_PATH_NOT_FOUND) error = path + ": " + std::strerror(ENOENT);
    else error = path + ": " + last_error_text();
    return -1;
  }
  auto fail = [&](const std::string& what) {
    error = path + ": " + what;
    ::CloseHandle(h);
    return std::intptr_t{-1};
  };
  DCB dcb{};
  dcb.DCBlength = sizeof dcb;
  if (::GetFileType(h) != FILE_TYPE_CHAR || !::GetCommState(h, &dcb))
    return fail("not a serial port (a tty device or tcp:HOST:PORT is needed)");  // the words of serial_posix.cpp
  dcb.BaudRate = static_cast<DWORD>(baud);
  dcb.ByteSize = 8;
  dcb.Parity = NOPARITY;
  dcb.StopBits = ONESTOPBIT;
  dcb.fBinary = TRUE;
  dcb.fParity = FALSE;
  dcb.fOutxCtsFlow = FALSE;
  dcb.fOutxDsrFlow = FALSE;
  dcb.fDsrSensitivity = FALSE;
  dcb.fOutX = FALSE;
  dcb.fInX = FALSE;
  dcb.fNull = FALSE;
  dcb.fAbortOnError = FALSE;
  dcb.fDtrControl = DTR_CONTROL_ENABLE;
  dcb.fRtsControl = RTS_CONTROL_ENABLE;
  if (!::SetCommState(h, &dcb)) return fail("cannot set raw 8N1 at " + std::to_string(baud) + " baud: " + last_error_text());
  DCB back{};  // the driver may take a setting and keep another: read back what matters
  back.DCBlength = sizeof back;
  if (!::GetCommState(h, &back) || back.ByteSize != 8 || back.BaudRate != static_cast<DWORD>(baud))
    return fail("the driver refused raw 8N1 at " + std::to_string(baud) + " baud");
  COMMTIMEOUTS t{};
  t.ReadIntervalTimeout = MAXDWORD;  // with both totals 0: a read returns at once
  t.WriteTotalTimeoutConstant = 1000;  // a line that takes nothing: the write returns short
  if (!::SetCommTimeouts(h, &t)) return fail("cannot set the timeouts: " + last_error_text());
  ::PurgeComm(h, PURGE_RXCLEAR | PURGE_TXCLEAR | PURGE_RXABORT | PURGE_TXABORT);
  return reinterpret_cast<std::intptr_t>(h);
}

void close(std::intptr_t port) { ::CloseHandle(handle(port)); }

long write(std::intptr_t port, const std::uint8_t* data, std::size_t n) {
  DWORD done = 0;
  const DWORD chunk = static_cast<DWORD>(std::min<std::size_t>(n, 1u << 20));
  if (!::WriteFile(handle(port), data, chunk, &done, nullptr)) {
    errno = EIO;
    return -1;
  }
  if (done == 0) {
    errno = EAGAIN;
    return -1;
  }
  return static_cast<long>(done);
}

long read(std::intptr_t port, std::uint8_t* data, std::size_t n) {
  DWORD got = 0;
  const DWORD chunk = static_cast<DWORD>(std::min<std::size_t>(n, 1u << 20));
  if (!::ReadFile(handle(port), data, chunk, &got, nullptr)) {
    errno = EIO;
    return -1;
  }
  if (got == 0) {
    errno = EAGAIN;
    return -1;
  }
  return static_cast<long>(got);
}

short wait(std::intptr_t port, short events, int ms) {
  if (events & POLLOUT) return POLLOUT;  // writes wait in WriteFile, up to its timeout
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
  for (;;) {
    DWORD errors = 0;
    COMSTAT stat{};
    if (!::ClearCommError(handle(port), &errors, &stat)) return POLLHUP;
    if (stat.cbInQue > 0) return POLLIN;
    if (std::chrono::steady_clock::now() >= deadline) return 0;
    ::Sleep(1);
  }
}

// Two threads between the port and a socket pair, so the server's WSAPoll loop sees the line as
// it sees a TCP client: one copies what arrives (waiting as wait() does), one writes what the
// server sends. Both end when the port is closed or the server's end of the pair goes.
int pollable(std::intptr_t port, std::string& error) {
  int pair[2];
  if (!os::wake_pair(pair)) {
    error = "cannot make a socket pair for the serial line: " + os::error_text(errno);
    return -1;
  }
  u_long blocking = 0;
  ::ioctlsocket(static_cast<SOCKET>(pair[1]), FIONBIO, &blocking);
  os::set_nonblocking(pair[0]);
  const SOCKET host_end = static_cast<SOCKET>(pair[1]);
  std::thread([port, host_end] {
    std::uint8_t buf[4096];
    for (;;) {
      const short ev = wait(port, POLLIN, 50);
      if (ev & (POLLHUP | POLLERR)) break;
      if (!(ev & POLLIN)) continue;
      const long n = read(port, buf, sizeof buf);
      if (n < 0 && errno != EAGAIN) break;
      for (long done = 0; done < n;) {
        const int w = ::send(host_end, reinterpret_cast<const char*>(buf) + done, static_cast<int>(n - done), 0);
        if (w <= 0) return;  // the server is gone
        done += w;
      }
    }
    ::shutdown(host_end, SD_SEND);  // the line is gone: the server reads its end
  }).detach();
  std::thread([port, host_end] {
    char buf[4096];
    for (int n; (n = ::recv(host_end, buf, sizeof buf, 0)) > 0;) {
      for (long done = 0; done < n;) {
        const long w = write(port, reinterpret_cast<const std::uint8_t*>(buf) + done, static_cast<std::size_t>(n - done));
        if (w < 0 && errno != EAGAIN) return;
        if (w > 0) done += w;
      }
    }
  }).detach();
  return pair[0];
}
const bool kPollableIsSocket = true;

}  // namespace tmcl::os::serial
