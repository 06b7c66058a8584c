// The platform layer, sockets, on Windows (os_net.hpp): Winsock, started on first use, its
// error codes turned into errno's POSIX names; a loopback TCP pair where POSIX has a pipe; a
// reader thread where POSIX polls standard input itself.
#include <io.h>

#include <cerrno>
#include <cstring>
#include <mutex>
#include <thread>

#include "tmcl/os_net.hpp"

namespace tmcl::os {
namespace {

void start() {
  static std::once_flag once;
  std::call_once(once, [] {
    WSADATA data;
    ::WSAStartup(MAKEWORD(2, 2), &data);
  });
}

int fail() {
  switch (::WSAGetLastError()) {
    case WSAEWOULDBLOCK: errno = EWOULDBLOCK; break;
    case WSAEINPROGRESS: errno = EINPROGRESS; break;
    case WSAEINTR: errno = EINTR; break;
    case WSAECONNREFUSED: errno = ECONNREFUSED; break;
    case WSAECONNRESET: errno = ECONNRESET; break;
    case WSAECONNABORTED: errno = ECONNABORTED; break;
    case WSAETIMEDOUT: errno = ETIMEDOUT; break;
    case WSAEADDRINUSE: errno = EADDRINUSE; break;
    case WSAEADDRNOTAVAIL: errno = EADDRNOTAVAIL; break;
    case WSAEACCES: errno = EACCES; break;
    case WSAENETUNREACH: errno = ENETUNREACH; break;
    case WSAEHOSTUNREACH: errno = EHOSTUNREACH; break;
    case WSAENOTCONN:
    case WSAESHUTDOWN: errno = EPIPE; break;
    case WSAENOTSOCK: errno = EBADF; break;
    default: errno = EIO; break;
  }
  return -1;
}

int as_int(SOCKET s) { return s == INVALID_SOCKET ? fail() : static_cast<int>(s); }

}  // namespace

int open_socket(int family, int type, int protocol) {
  start();
  return as_int(::WSASocketW(family, type, protocol, nullptr, 0, WSA_FLAG_OVERLAPPED | WSA_FLAG_NO_HANDLE_INHERIT));
}

int accept_socket(int listener, sockaddr* from, socklen_t* len) {
  const int fd = as_int(::accept(static_cast<SOCKET>(listener), from, len));
  if (fd >= 0) set_nonblocking(fd);
  return fd;
}

int connect_socket(int fd, const sockaddr* to, socklen_t len) {
  if (::connect(static_cast<SOCKET>(fd), to, len) == 0) return 0;
  fail();
  if (errno == EWOULDBLOCK) errno = EINPROGRESS;  // Winsock's word for a connect under way
  return -1;
}

void set_nonblocking(int fd) {
  u_long on = 1;
  ::ioctlsocket(static_cast<SOCKET>(fd), FIONBIO, &on);
}

long send_socket(int fd, const void* data, std::size_t n, bool) {
  const int chunk = n > (1u << 30) ? (1 << 30) : static_cast<int>(n);
  const int r = ::send(static_cast<SOCKET>(fd), static_cast<const char*>(data), chunk, 0);
  return r == SOCKET_ERROR ? fail() : r;
}

long read_some(int fd, void* data, std::size_t n) {
  const int chunk = n > (1u << 30) ? (1 << 30) : static_cast<int>(n);
  const int r = ::recv(static_cast<SOCKET>(fd), static_cast<char*>(data), chunk, 0);
  return r == SOCKET_ERROR ? fail() : r;
}

void close_socket(int fd) { ::closesocket(static_cast<SOCKET>(fd)); }

int poll(pollfd* fds, nfds_t n, int timeout_ms) {
  if (n == 0) {
    ::Sleep(timeout_ms < 0 ? INFINITE : static_cast<DWORD>(timeout_ms));
    return 0;
  }
  const int r = ::WSAPoll(fds, n, timeout_ms);
  return r == SOCKET_ERROR ? fail() : r;
}

bool wake_pair(int fds[2]) {
  start();
  const int listener = open_socket(AF_INET, SOCK_STREAM, IPPROTO_TCP);
  if (listener < 0) return false;
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  int len = sizeof a;
  const SOCKET l = static_cast<SOCKET>(listener);
  bool ok = ::bind(l, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 && ::listen(l, 1) == 0 &&
            ::getsockname(l, reinterpret_cast<sockaddr*>(&a), &len) == 0;
  fds[0] = fds[1] = -1;
  if (ok) fds[1] = open_socket(AF_INET, SOCK_STREAM, IPPROTO_TCP);
  ok = ok && fds[1] >= 0 && ::connect(static_cast<SOCKET>(fds[1]), reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  if (ok) fds[0] = as_int(::accept(l, nullptr, nullptr));
  ok = ok && fds[0] >= 0;
  if (!ok) fail();
  close_socket(listener);
  if (!ok) {
    for (int i = 0; i < 2; ++i)
      if (fds[i] >= 0) close_socket(fds[i]);
    return false;
  }
  for (int i = 0; i < 2; ++i) set_nonblocking(fds[i]);
  const BOOL one = TRUE;
  ::setsockopt(static_cast<SOCKET>(fds[1]), IPPROTO_TCP, TCP_NODELAY, reinterpret_cast<const char*>(&one), sizeof one);
  return true;
}

void wake(int fd, char byte) { ::send(static_cast<SOCKET>(fd), &byte, 1, 0); }

int pollable_input(int fd) {
  // The thread reads a duplicate of fd, its own: the caller may close fd while the thread still
  // reads (a DAP session ends before the thread has seen the end of its file), and the C library
  // gives that number to the next file opened, whose input the thread would then take.
  const int own = ::_dup(fd);
  if (own < 0) return -1;
  int pair[2];
  if (!wake_pair(pair)) {
    ::_close(own);
    return -1;
  }
  u_long off = 0;  // both ends block: the thread waits for the reader, the reader for input,
  ::ioctlsocket(static_cast<SOCKET>(pair[1]), FIONBIO, &off);  // as they do on a POSIX stdin
  ::ioctlsocket(static_cast<SOCKET>(pair[0]), FIONBIO, &off);
  std::thread([own, out = pair[1]] {
    char buf[65536];
    bool reader_gone = false;
    for (int n; !reader_gone && (n = ::_read(own, buf, sizeof buf)) > 0;) {
      for (int done = 0; done < n;) {
        const int w = ::send(static_cast<SOCKET>(out), buf + done, n - done, 0);
        if (w <= 0) {
          reader_gone = true;
          break;
        }
        done += w;
      }
    }
    ::_close(own);
    ::shutdown(static_cast<SOCKET>(out), SD_SEND);  // end of input: the reader sees it as such
    close_socket(out);
  }).detach();
  return pair[0];
}

void release_pollable_input(int polled, int fd) {
  if (polled >= 0 && polled != fd) close_socket(polled);  // the thread's next send fails: it ends
}

std::string error_text(int err) {
  switch (err) {
    case EWOULDBLOCK: return "Resource temporarily unavailable";
    case EINPROGRESS: return "Operation now in progress";
    case ECONNREFUSED: return "Connection refused";
    case ECONNRESET: return "Connection reset by peer";
    case ECONNABORTED: return "Software caused connection abort";
    case ETIMEDOUT: return "Connection timed out";
    case EADDRINUSE: return "Address already in use";
    case EADDRNOTAVAIL: return "Cannot assign requested address";
    case ENETUNREACH: return "Network is unreachable";
    case EHOSTUNREACH: return "No route to host";
    default: return std::strerror(err);
  }
}

std::string resolve_error_text(int rc) {
  char text[256] = "";
  ::FormatMessageA(FORMAT_MESSAGE_FROM_SYSTEM | FORMAT_MESSAGE_IGNORE_INSERTS, nullptr, static_cast<DWORD>(rc), 0, text,
                   sizeof text, nullptr);
  std::string s = text;
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == '.')) s.pop_back();
  return s.empty() ? "error " + std::to_string(rc) : s;
}

}  // namespace tmcl::os
