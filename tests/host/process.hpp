// Process helpers for the tmclctl tests: start `tmclrun --serve` as a separate process and read
// the line it announces (a pty path or "listening on HOST:PORT"), and run tmclctl capturing its
// exit status, standard output and standard error (through pipes, or with both on a pty as in a
// terminal). Every wait has a deadline: a hung tool fails the test (it is killed) instead of
// hanging the suite.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <termios.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace hosttest {

using Clock = std::chrono::steady_clock;

struct Output {
  int status = -1;  // exit status; 128 + signal when killed by one
  std::string out, err;
};

inline std::vector<char*> c_args(std::vector<std::string>& args) {
  std::vector<char*> v;
  for (auto& a : args) v.push_back(a.data());
  v.push_back(nullptr);
  return v;
}

// Runs argv; from `during_ms` on, `during(pid)` is called every 20 ms or so until it returns true
// (to send a signal once something has happened, say).
inline Output run(std::vector<std::string> argv, int timeout_ms = 30000, int during_ms = -1,
                  const std::function<bool(pid_t)>& during = {}) {
  int out[2], err[2];
  if (::pipe(out) != 0 || ::pipe(err) != 0) return {};
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(out[1], 1);
    ::dup2(err[1], 2);
    const int null = ::open("/dev/null", O_RDONLY);
    ::dup2(null, 0);
    ::close(out[0]);
    ::close(err[0]);
    auto args = c_args(argv);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  ::close(out[1]);
  ::close(err[1]);
  Output o;
  const auto start = Clock::now();
  bool fired = during_ms < 0;
  int open_fds = 2;
  pollfd fds[2] = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
  while (open_fds > 0) {
    const auto elapsed = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - start).count();
    if (!fired && elapsed >= during_ms) fired = during(pid);
    if (elapsed > timeout_ms) {
      ::kill(pid, SIGKILL);
      o.err += "\n[test: killed after " + std::to_string(timeout_ms) + " ms]";
      break;
    }
    if (::poll(fds, 2, 20) <= 0) continue;
    for (auto& p : fds) {
      if (p.fd < 0 || !(p.revents & (POLLIN | POLLHUP))) continue;
      char buf[4096];
      const ssize_t n = ::read(p.fd, buf, sizeof buf);
      if (n <= 0) {
        ::close(p.fd);
        p.fd = -1;
        --open_fds;
        continue;
      }
      (p.fd == out[0] ? o.out : o.err).append(buf, static_cast<std::size_t>(n));
    }
  }
  for (auto& p : fds)
    if (p.fd >= 0) ::close(p.fd);
  int st = 0;
  ::waitpid(pid, &st, 0);
  o.status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
  return o;
}

// Runs argv with standard output and standard error on one pty (raw, so the text arrives as
// written), as in a terminal; standard input is /dev/null. Output::out holds what the pty
// showed, Output::err is empty. `during(pid, shown so far)`, when given, is called every 20 ms
// or so until it returns true (to send a signal once something has been shown, say).
inline Output run_on_pty(std::vector<std::string> argv, int timeout_ms = 30000,
                         const std::function<bool(pid_t, const std::string&)>& during = {}) {
  Output o;
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) return o;
  const int slave = ::open(::ptsname(master), O_RDWR | O_NOCTTY);
  if (slave < 0) {
    ::close(master);
    return o;
  }
  termios t{};
  ::tcgetattr(slave, &t);
  ::cfmakeraw(&t);
  ::tcsetattr(slave, TCSANOW, &t);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(slave, 1);
    ::dup2(slave, 2);
    const int null = ::open("/dev/null", O_RDONLY);
    ::dup2(null, 0);
    ::close(master);
    ::close(slave);
    auto args = c_args(argv);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  ::close(slave);
  const auto deadline = Clock::now() + std::chrono::milliseconds(timeout_ms);
  bool fired = !during;
  for (;;) {
    if (!fired) fired = during(pid, o.out);
    if (Clock::now() > deadline) {
      ::kill(pid, SIGKILL);
      o.out += "\n[test: killed after " + std::to_string(timeout_ms) + " ms]";
      break;
    }
    pollfd p{master, POLLIN, 0};
    if (::poll(&p, 1, 20) <= 0) continue;
    char buf[4096];
    const ssize_t n = ::read(master, buf, sizeof buf);
    if (n <= 0) break;  // EIO: the last holder of the pty's other side has gone
    o.out.append(buf, static_cast<std::size_t>(n));
  }
  ::close(master);
  int st = 0;
  ::waitpid(pid, &st, 0);
  o.status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
  return o;
}

// A `tmclrun --serve` process; stopped with SIGTERM when the object goes.
class Server {
 public:
  // `args` after "tmclrun": e.g. {"--serve", "pty", "-t", "usb-2-sd"}.
  Server(const std::string& tmclrun, std::vector<std::string> args) {
    args.insert(args.begin(), tmclrun);
    args.push_back("--max-wall-time");
    args.push_back("120s");  // a test that dies cannot leave a server behind for long
    int out[2];
    if (::pipe(out) != 0) return;
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(out[1], 1);
      const int null = ::open("/dev/null", O_RDWR);
      ::dup2(null, 0);
      ::dup2(null, 2);
      ::close(out[0]);
      auto a = c_args(args);
      ::execv(a[0], a.data());
      ::_exit(127);
    }
    ::close(out[1]);
    fd_ = out[0];
    std::string line;
    const auto deadline = Clock::now() + std::chrono::seconds(10);
    while (line.find('\n') == std::string::npos && Clock::now() < deadline) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 50) <= 0) continue;
      char c[256];
      const ssize_t n = ::read(fd_, c, sizeof c);
      if (n <= 0) break;
      line.append(c, static_cast<std::size_t>(n));
    }
    line = line.substr(0, line.find('\n'));
    const std::string tcp = "listening on ";
    port_ = line.rfind(tcp, 0) == 0 ? "tcp:" + line.substr(tcp.size()) : line;
  }
  ~Server() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      int st;
      ::waitpid(pid_, &st, 0);
    }
    if (fd_ >= 0) ::close(fd_);
  }
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;
  const std::string& port() const { return port_; }

 private:
  pid_t pid_ = -1;
  int fd_ = -1;
  std::string port_;
};

}  // namespace hosttest
