// The platform layer, sockets, on POSIX systems (os_net.hpp): the calls themselves.
#include <fcntl.h>
#include <unistd.h>

#include <cstring>

#include "tmcl/os_net.hpp"

namespace tmcl::os {

int open_socket(int family, int type, int protocol) { return ::socket(family, type | SOCK_CLOEXEC, protocol); }

int accept_socket(int listener, sockaddr* from, socklen_t* len) {
  return ::accept4(listener, from, len, SOCK_NONBLOCK | SOCK_CLOEXEC);
}

int connect_socket(int fd, const sockaddr* to, socklen_t len) { return ::connect(fd, to, len); }

void set_nonblocking(int fd) { ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK); }

long send_socket(int fd, const void* data, std::size_t n, bool dont_wait) {
  return ::send(fd, data, n, MSG_NOSIGNAL | (dont_wait ? MSG_DONTWAIT : 0));
}

long read_some(int fd, void* data, std::size_t n) { return ::read(fd, data, n); }

void close_socket(int fd) { ::close(fd); }

int poll(pollfd* fds, nfds_t n, int timeout_ms) { return ::poll(fds, n, timeout_ms); }

bool wake_pair(int fds[2]) {
  if (::pipe(fds) != 0) return false;
  for (int i = 0; i < 2; ++i) {
    ::fcntl(fds[i], F_SETFD, FD_CLOEXEC);
    set_nonblocking(fds[i]);
  }
  return true;
}

void wake(int fd, char byte) { [[maybe_unused]] ssize_t n = ::write(fd, &byte, 1); }

int pollable_input(int fd) { return fd; }

void release_pollable_input(int, int) {}  // the descriptor itself: the caller's to close

std::string error_text(int err) { return std::strerror(err); }

std::string resolve_error_text(int rc) { return ::gai_strerror(rc); }

}  // namespace tmcl::os
