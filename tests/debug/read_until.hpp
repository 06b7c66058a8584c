// Reading a debugger process's output until a text shows, for the tests that run tmclrun as a
// process (serve_debug_test.cpp on pipes, prompt_pty_test.cpp on a pseudo-terminal).
#pragma once

#include <poll.h>
#include <unistd.h>

#include <chrono>
#include <string>

namespace dbgtest {

// Reads `fd` into `text` until `what` occurs `count` times in it; false when `deadline_ms`
// passes first or the output ends (end of file, or EIO from a pseudo-terminal nobody holds).
inline bool read_until(int fd, std::string& text, const std::string& what, int count, int deadline_ms) {
  using Clock = std::chrono::steady_clock;
  const auto end = Clock::now() + std::chrono::milliseconds(deadline_ms);
  for (;;) {
    int seen = 0;
    for (std::size_t at = 0; (at = text.find(what, at)) != std::string::npos; at += what.size()) ++seen;
    if (seen >= count) return true;
    auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now()).count();
    if (left <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(left)) <= 0) continue;
    char buf[4096];
    ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) return false;
    text.append(buf, static_cast<std::size_t>(n));
  }
}

}  // namespace dbgtest
