// tmclrun --serve as a separate process for the server tests: started with its arguments, its
// announcement line read ("listening on 127.0.0.1:PORT"), connected to over loopback TCP, and
// reaped (bounded) after a signal.
#pragma once

#include <sys/wait.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "check.hpp"
#include "client.hpp"

namespace srvtest {

struct Child {
  pid_t pid = -1;
  int out = -1;  // its stdout
  std::string line;
};

// Starts TMCL_TMCLRUN with `args` and reads its first line (waiting at most 5 s).
inline Child spawn_tmclrun(const std::vector<std::string>& args) {
  Child c;
  int p[2];
  if (::pipe(p) != 0) return c;
  std::vector<std::string> all{TMCL_TMCLRUN};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  c.pid = ::fork();
  if (c.pid == 0) {
    ::dup2(p[1], 1);
    ::close(p[0]);
    ::close(p[1]);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(p[1]);
  c.out = p[0];
  const auto end = Clock::now() + std::chrono::seconds(5);
  char ch;
  while (Clock::now() < end) {
    pollfd pf{c.out, POLLIN, 0};
    if (::poll(&pf, 1, 100) <= 0) continue;
    if (::read(c.out, &ch, 1) != 1 || ch == '\n') break;
    c.line += ch;
  }
  return c;
}

// Waits (bounded) for the child; returns its exit status or -1.
inline int reap(Child& c) {
  for (int i = 0; i < 500; ++i) {
    int st = 0;
    if (::waitpid(c.pid, &st, WNOHANG) == c.pid) {
      ::close(c.out);
      return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ::kill(c.pid, SIGKILL);
  ::waitpid(c.pid, nullptr, 0);
  ::close(c.out);
  return -1;
}

// The connection to the server whose announcement is `announce`.
inline Link connect_to(const std::string& announce) {
  return connect_loopback(std::stoi(announce.substr(announce.rfind(':') + 1)));
}

// What the host-side tests send most (a unity build puts their files in one unit: one copy here).
inline constexpr auto kRor = static_cast<std::uint8_t>(tmcl::Op::ROR);
inline constexpr auto kMst = static_cast<std::uint8_t>(tmcl::Op::MST);
inline constexpr auto kMvp = static_cast<std::uint8_t>(tmcl::Op::MVP);
inline constexpr auto kSap = static_cast<std::uint8_t>(tmcl::Op::SAP);
inline constexpr auto kGap = static_cast<std::uint8_t>(tmcl::Op::GAP);

// A request that must be answered with status 100, as a host library insists; its value. A
// failure names the request and what came back.
inline std::int32_t ask(Link& l, std::uint8_t op, std::uint8_t type, std::uint8_t motor, std::int32_t value) {
  auto r = l.request(op, type, motor, value);
  if (!r || (*r)[2] != 100)
    ::tmcl_test::fail(__FILE__, __LINE__, "request " + std::to_string(op) + ", " + std::to_string(type) + ", " + std::to_string(motor) +
                                              " answered " + (r ? "status " + std::to_string((*r)[2]) : std::string("nothing")));
  return r ? value_of(*r) : 0;
}

inline void sleep_ms(int ms) { std::this_thread::sleep_for(std::chrono::milliseconds(ms)); }

}  // namespace srvtest
