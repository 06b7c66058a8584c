// Debugging while serving: tmclrun --serve tcp:127.0.0.1:0 --debug prog.tmc as a separate
// process, debugger commands on a pipe, and the test as the module's host over TCP. While the
// program is held at a breakpoint the module answers GGP/SAP/MVP/GAP and its motor moves; a
// host's SGP is seen by the program, a host's 130 steps it over the breakpoint and shows in the
// debugger, and the debugger's continue goes on from there; a host's 128 shows as a stop in the
// debugger, 129 continues it, SIGINT (Ctrl-C) pauses the program and the server stays. Also
// tmclrun --dap over a pipe: pause stops a running endless loop. Every wait is for an event with
// a generous deadline (a loaded machine), never a sleep.
#include "check.hpp"

#include <signal.h>
#include <sys/wait.h>

#include <fstream>
#include <vector>

#include "client.hpp"
#include "read_until.hpp"

using namespace srvtest;
using tmcl::Op;

namespace {

constexpr int kDeadlineMs = 60000;

// kGgp and kSgp come from client.hpp.
const std::uint8_t kSap = static_cast<std::uint8_t>(Op::SAP), kGap = static_cast<std::uint8_t>(Op::GAP),
                   kMvp = static_cast<std::uint8_t>(Op::MVP), kStop = static_cast<std::uint8_t>(Op::StopApplication),
                   kRun = static_cast<std::uint8_t>(Op::RunApplication), kStep = static_cast<std::uint8_t>(Op::StepApplication);

struct Debuggee {
  pid_t pid = -1;
  int in = -1, out = -1;
  std::string text;  // everything read from its standard output so far

  ~Debuggee() {
    if (in >= 0) ::close(in);
    if (out >= 0) ::close(out);
    if (pid > 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  }
  void say(const std::string& commands) {
    CHECK(::write(in, commands.data(), commands.size()) == static_cast<ssize_t>(commands.size()));
  }
  // Reads until `what` occurs `count` times in the output (or the deadline passes).
  bool wait_for(const std::string& what, int count = 1) { return dbgtest::read_until(out, text, what, count, kDeadlineMs); }
  int finish() {
    ::close(in);
    in = -1;
    while (wait_for("\x01")) {
    }  // read to the end
    int st = 0;
    ::waitpid(pid, &st, 0);
    pid = -1;
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  }
};

bool spawn(Debuggee& d, std::vector<const char*> args) {
  args.insert(args.begin(), "tmclrun");
  args.push_back(nullptr);
  int to[2], from[2];
  if (::pipe(to) != 0 || ::pipe(from) != 0) return false;
  d.pid = ::fork();
  if (d.pid == 0) {
    ::dup2(to[0], 0);
    ::dup2(from[1], 1);
    ::close(to[1]);
    ::close(from[0]);
    ::execv(TMCL_TMCLRUN, const_cast<char* const*>(args.data()));
    ::_exit(127);
  }
  ::close(to[0]);
  ::close(from[1]);
  d.in = to[1];
  d.out = from[0];
  return d.pid > 0;
}

std::optional<std::int32_t> ask(Link& l, std::uint8_t op, std::uint8_t type, std::uint8_t motor, std::int32_t value) {
  auto r = l.request(op, type, motor, value, 1, kDeadlineMs);
  if (!r || (*r)[2] != 100) return std::nullopt;
  return value_of(*r);
}

}  // namespace

TEST(the_host_is_served_while_the_program_is_held_and_control_commands_show_in_the_debugger) {
  ::signal(SIGPIPE, SIG_IGN);
  const std::string prog = "serve_debug_prog.tmc";
  std::ofstream(prog) << "        SGP 1, 2, 0\nloop:   GGP 1, 2\n        CALC ADD, 1\n        AGP 1, 2\n"
                         "        WAIT TICKS, 0, 1\n        JA loop\n";
  Debuggee d;
  CHECK(spawn(d, {"--serve", "tcp:127.0.0.1:0", "--debug", prog.c_str()}));
  CHECK(d.wait_for("listening on 127.0.0.1:"));
  std::size_t at = d.text.find("listening on 127.0.0.1:");
  CHECK(at != std::string::npos);
  if (at == std::string::npos) return;
  const int port = std::atoi(d.text.c_str() + at + 23);

  d.say("break loop\nrun\n");
  CHECK(d.wait_for("Breakpoint 1, loop (address 1)"));

  // Held at the breakpoint: the module answers, the motor moves, the program does not run.
  Link host = connect_loopback(port);
  CHECK(host.ok());
  CHECK(ask(host, kGgp, 1, 2, 0) == std::optional<std::int32_t>(0));
  CHECK(ask(host, kSap, 4, 0, 2000).has_value());    // maximum speed
  CHECK(ask(host, kMvp, 0, 0, 1000000).has_value()); // MVP ABS, far away
  std::optional<std::int32_t> pos;
  const auto end = Clock::now() + std::chrono::milliseconds(kDeadlineMs);
  while ((pos = ask(host, kGap, 1, 0, 0)) && *pos == 0 && Clock::now() < end) ::poll(nullptr, 0, 10);
  CHECK(pos && *pos > 0);  // time and motion go on while the program is held
  CHECK(ask(host, kGgp, 1, 2, 0) == std::optional<std::int32_t>(0));  // the program has not run
  CHECK(ask(host, kSgp, 1, 2, 41).has_value());  // the host writes v[1] ...
  CHECK(ask(host, kStep, 0, 0, 0).has_value());  // ... and steps the program over the breakpoint
  CHECK(d.wait_for("[the host stepped the program (command 130)]\nloop+1 (address 2)"));

  d.say("print v[1]\ncontinue\n");
  CHECK(d.wait_for("$1 = 41"));
  CHECK(d.wait_for("Breakpoint 1, loop (address 1)", 2));
  d.say("print v[1]\n");
  CHECK(d.wait_for("$2 = 42"));  // the program went on from the host's value and step

  // A host's stop while the program runs is a stop in the debugger.
  d.say("delete\ncontinue\n");
  CHECK(d.wait_for("(tmdb) continue", 2));
  CHECK(ask(host, kStop, 0, 0, 0).has_value());
  CHECK(d.wait_for("Program stopped: the host stopped the program (command 128)."));
  // A host's run continues it in the debugger; Ctrl-C pauses the program, not the server.
  CHECK(ask(host, kRun, 0, 0, 0).has_value());
  CHECK(d.wait_for("[the host started the program (command 129): continuing]"));
  ::kill(d.pid, SIGINT);
  CHECK(d.wait_for("Program paused."));
  CHECK(ask(host, kGgp, 1, 2, 0).has_value());  // still serving
  d.say("info registers\nquit\n");
  CHECK_EQ(d.finish(), 0);
  CHECK(d.text.find("status   running") != std::string::npos);
  if (::tmcl_test::failures() || std::getenv("SERVE_DEBUG_TEST_DUMP")) std::fprintf(stderr, "transcript:\n%s\n", d.text.c_str());
  std::remove(prog.c_str());
}

TEST(serve_with_debug_refuses_stdio_and_dap) {
  for (const char* spec : {"stdio"}) {
    pid_t pid = ::fork();
    if (pid == 0) {
      int null = ::open("/dev/null", O_RDWR);
      ::dup2(null, 0);
      ::dup2(null, 1);
      ::dup2(null, 2);
      ::execl(TMCL_TMCLRUN, "tmclrun", "--serve", spec, "--debug", "x.tmc", static_cast<char*>(nullptr));
      ::_exit(127);
    }
    int st = 0;
    ::waitpid(pid, &st, 0);
    CHECK(WIFEXITED(st) && WEXITSTATUS(st) == 64);
  }
}

// DAP pause over a real pipe, with the program running when the request arrives (the adapter
// polls its standard input between slices): stopped with reason pause, the stack is valid, and
// the program runs on after continue until a second pause.
TEST(dap_pause_over_a_pipe_stops_a_running_endless_loop) {
  const std::string prog = "dap_pipe_prog.tmc";
  std::ofstream(prog) << "        SGP 1, 2, 0\nloop:   GGP 1, 2\n        CALC ADD, 1\n        AGP 1, 2\n        JA loop\n";
  Debuggee d;
  CHECK(spawn(d, {"--dap"}));
  int seq = 0;
  auto request = [&](const std::string& body) {
    std::string text = "{\"seq\":" + std::to_string(++seq) + ",\"type\":\"request\"," + body + "}";
    d.say("Content-Length: " + std::to_string(text.size()) + "\r\n\r\n" + text);
  };
  request(R"("command":"initialize","arguments":{})");
  request(R"("command":"launch","arguments":{"program":")" + prog + R"("})");
  request(R"("command":"configurationDone")");
  CHECK(d.wait_for(R"("command":"configurationDone")"));
  request(R"("command":"threads")");  // answered while the program runs
  CHECK(d.wait_for(R"("command":"threads")"));
  CHECK(d.text.find(R"("event":"stopped")") == std::string::npos);
  request(R"("command":"pause","arguments":{"threadId":1})");
  CHECK(d.wait_for(R"("reason":"pause")"));
  request(R"("command":"stackTrace","arguments":{"threadId":1})");
  CHECK(d.wait_for(R"("command":"stackTrace","body":{"stackFrames":[{"id":0)"));
  request(R"("command":"continue","arguments":{"threadId":1})");
  CHECK(d.wait_for(R"("command":"continue")"));
  request(R"("command":"pause","arguments":{"threadId":1})");
  CHECK(d.wait_for(R"("reason":"pause")", 2));
  request(R"("command":"disconnect")");
  CHECK_EQ(d.finish(), 0);
  CHECK(d.text.find(R"("command":"disconnect")") != std::string::npos);
  std::remove(prog.c_str());
}
