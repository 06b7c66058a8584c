// The platform layer, sockets: the BSD socket calls the virtual module's server and the host's
// TCP line make, with what differs between systems behind a function. One implementation per
// system, chosen when CMake configures (os_net_posix.cpp, os_net_windows.cpp).
//
// A socket is an int everywhere (a Windows SOCKET is a handle that fits one). Every function
// here sets errno on failure, with POSIX names on Windows too (EWOULDBLOCK, EINPROGRESS, ...),
// so callers test errno as they always have. On Windows only sockets can be waited on, so
// whatever os::poll waits on is a socket there: the wake-up pair is one, and so is what
// pollable_input makes of a file descriptor.
#pragma once

#include <cstddef>
#include <string>

#if defined(_WIN32)
#include <winsock2.h>
#include <ws2tcpip.h>
using nfds_t = unsigned long;
#else
#include <arpa/inet.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#endif

namespace tmcl::os {

#if defined(_WIN32)
inline constexpr int kShutWrite = SD_SEND;
inline constexpr bool kPollsFiles = false;  // os::poll waits on sockets only
#else
inline constexpr int kShutWrite = SHUT_WR;
inline constexpr bool kPollsFiles = true;
#endif

// A stream socket, not inherited by child processes; -1 with errno set.
int open_socket(int family, int type, int protocol);
// accept(): the new connection non-blocking and not inherited; -1 with errno set.
int accept_socket(int listener, sockaddr* from, socklen_t* len);
// connect() on a non-blocking socket: 0, or -1 with errno (EINPROGRESS: wait for POLLOUT).
int connect_socket(int fd, const sockaddr* to, socklen_t len);
void set_nonblocking(int fd);
// send() that never raises SIGPIPE; `dont_wait`: never blocks either.
long send_socket(int fd, const void* data, std::size_t n, bool dont_wait);
// read() of what os::poll waits on (a socket, a pipe, a terminal; on Windows a socket).
long read_some(int fd, void* data, std::size_t n);
// close() of what os::poll waits on.
void close_socket(int fd);
// One entry of os::poll's table.
inline pollfd poll_entry(int fd, short events) {
  pollfd p{};
  p.fd = static_cast<decltype(p.fd)>(fd);
  p.events = events;
  return p;
}
// poll(); on Windows sockets only.
int poll(pollfd* fds, nfds_t n, int timeout_ms);
// A connected pair: what is written into [1] makes [0] readable (a self-pipe for signals).
// Both ends non-blocking. False with errno set.
bool wake_pair(int fds[2]);
// Writes one byte into a wake pair's [1] (safe in a signal handler).
void wake(int fd, char byte);
// What os::poll can wait on for input arriving on file descriptor `fd` (standard input): the
// descriptor itself on POSIX; on Windows a socket that a thread fills with what it reads from
// a duplicate of `fd` (the caller may close `fd` at any time), closed at its end of input. -1 with
// errno set.
int pollable_input(int fd);
// Done with what pollable_input(fd) made: closes the socket on Windows (its thread ends at its
// next send); nothing on POSIX, where it is `fd` itself.
void release_pollable_input(int polled, int fd);
// strerror(): on Windows also the names its C library has no text for (ECONNREFUSED, ...), in
// glibc's words.
std::string error_text(int err);
// The text of a getaddrinfo() error.
std::string resolve_error_text(int rc);

}  // namespace tmcl::os
