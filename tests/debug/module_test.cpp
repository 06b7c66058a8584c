// Nothing lost on the module (tmclctl PORT debug, docs/debugger.md "Debugging on a module"): a
// session ended by SIGTERM or SIGHUP while the program runs with its breakpoint patched leaves
// the program as loaded; after kill -9 the patch is on the module, upload warns about it and the
// next session puts it back and says so; a module that goes silent for a while (the --faults
// injector) gets its patches removed when it answers again, one that never comes back is named
// with the addresses still patched. tmclrun --serve and tmclctl run as processes.
#include <csignal>
#include <memory>

#include "check.hpp"
#include "tmclctl_test.hpp"
#include "tmcl/asm/assembler.hpp"
#include "tmcl/image.hpp"
#include "tmcl/profile.hpp"

namespace module_test {

using namespace hosttest;

// An endless loop with a breakpoint on a branch it never takes: the program runs freely with
// the patch in place until something ends the session.
const char* kProgram =
    "start:\n"
    "  SGP 1, 2, 0\n"
    "loop:\n"
    "  GGP 1, 2\n"
    "  CALC ADD, 1\n"
    "  AGP 1, 2\n"
    "  COMP -1\n"
    "  JC EQ, never\n"
    "  JA loop\n"
    "never:\n"
    "  STOP\n";
constexpr int kNever = 7;  // the address of `never`

std::string program_file() { return write_temp("endless.tmc", kProgram); }

// tmclctl with `during(pid)` called from `during_ms` on (process.hpp), a 5 s reply timeout unless
// the arguments give one.
Output ctl_during(std::vector<std::string> args, int during_ms, const std::function<bool(pid_t)>& during) {
  bool timeout = false;
  for (const auto& a : args) timeout = timeout || a == "--timeout";
  if (!timeout) args.insert(args.begin(), {"--timeout", "5s"});
  args.insert(args.begin(), kCtl);
  return hosttest::run(args, 30000, during_ms, during);
}

std::string commands(const std::string& name, const std::string& text) { return write_temp(name, text); }

std::vector<std::uint8_t> assembled(const std::string& path) {
  tmcl::AsmOptions opt;
  opt.profile = tmcl::find_profile("generic");
  tmcl::DiskReader reader;
  return tmcl::write_bin(tmcl::assemble({path}, opt, reader).program);
}

// The module's program memory as upload reads it, compared with the program.
bool memory_is_program(const Server& server, const std::string& prog, Output* upload = nullptr) {
  const std::string bin = temp_dir() + "/after.bin";
  Output u = ctl({server.port(), "upload", "-o", bin});
  show(u);
  if (upload) *upload = u;
  const auto want = assembled(prog);
  return u.status == 0 && slurp(bin) == std::string(want.begin(), want.end());
}

// A session that runs into the endless loop; `signal` is sent once the program has run 300 ms.
Output session_ended_by(const Server& server, const std::string& prog, int signal) {
  const std::string cmds = commands("run.cmds", "break never\nrun\n");
  return ctl_during({server.port(), "debug", "--debug-commands", cmds, prog}, 300, [signal](pid_t pid) {
    ::kill(pid, signal);
    return true;
  });
}

void ended_by_signal(int signal) {
  Server server(kRun, {"--serve", "tcp:127.0.0.1:0"});
  const std::string prog = program_file();
  CHECK_EQ(ctl({"-q", server.port(), "download", prog}).status, 0);
  Output o = session_ended_by(server, prog, signal);
  show(o);
  CHECK_EQ(o.status, 143);
  CHECK(has(o.out, "Program paused."));
  CHECK(has(o.out, "[session ended by a signal; program memory is as loaded]"));
  CHECK(memory_is_program(server, prog));
}

TEST(sigterm_while_running_removes_the_patches) { ended_by_signal(SIGTERM); }
TEST(sighup_while_running_removes_the_patches) { ended_by_signal(SIGHUP); }

TEST(kill_9_leaves_a_patch_that_the_next_session_restores) {
  Server server(kRun, {"--serve", "tcp:127.0.0.1:0"});
  const std::string prog = program_file();
  CHECK_EQ(ctl({"-q", server.port(), "download", prog}).status, 0);
  Output killed = session_ended_by(server, prog, SIGKILL);
  CHECK_EQ(killed.status, 128 + SIGKILL);
  // The program spins on the patch now; upload sees the jump to itself and warns.
  Output up;
  CHECK(!memory_is_program(server, prog, &up));
  CHECK(has(up.err, "address " + std::to_string(kNever) + " holds a jump to itself (JA " + std::to_string(kNever) + ")"));
  // The next session recognises its own patch, puts the instruction back and says so.
  const std::string none = commands("none.cmds", "info registers\n");
  Output again = ctl({server.port(), "debug", "--debug-commands", none, prog});
  show(again);
  CHECK_EQ(again.status, 0);
  CHECK(has(again.out, "Restored address 7 to STOP: a breakpoint's JA 7 that an earlier session left on the module."));
  CHECK(!has(again.out, "differs"));
  CHECK(memory_is_program(server, prog));
}

TEST(a_silent_module_gets_its_patches_back_when_it_answers_again) {
  // The 40th reply to 135 and every request for the next 1.5 s are lost: the module is silent
  // while the program runs patched, and answers again within --reconnect.
  Server server(kRun, {"--serve", "tcp:127.0.0.1:0", "--faults", "silence=1500ms@cmd=135#40"});
  const std::string prog = program_file();
  CHECK_EQ(ctl({"-q", server.port(), "download", prog}).status, 0);
  const std::string cmds = commands("silent.cmds", "break never\nrun\nprint v[1] > 0\n");
  Output o = ctl({"--timeout", "200ms", "--retries", "1", server.port(), "debug", "--reconnect", "10s", "--debug-commands", cmds,
                  prog});
  show(o);
  CHECK_EQ(o.status, 0);
  CHECK(has(o.out, "Program stopped: the connection to the module was lost (it came back)."));
  CHECK(has(o.out, "$1 = 1"));
  CHECK(memory_is_program(server, prog));
}

TEST(a_module_that_never_comes_back_is_named_with_the_addresses_still_patched) {
  const std::string prog = program_file();
  auto server = std::make_unique<Server>(kRun, std::vector<std::string>{"--serve", "tcp:127.0.0.1:0"});
  const std::string port = server->port();
  CHECK_EQ(ctl({"-q", port, "download", prog}).status, 0);
  const std::string cmds = commands("gone.cmds", "break never\nrun\n");
  Output o = ctl_during({"--timeout", "200ms", "--retries", "1", port, "debug", "--reconnect", "1s", "--debug-commands", cmds, prog},
                        300, [&server](pid_t) {
                   server.reset();  // the module goes away for good
                   return true;
                 });
  show(o);
  CHECK_EQ(o.status, 69);
  CHECK(has(o.out, "The module does not answer"));
  CHECK(has(o.out, "Program memory is still patched at address 7 (a jump to itself each)"));
}

// A lost reply to a patch's store is not answered by storing again (that would write the jump
// at the next address too): 132 points the module at the address first (errata H2). The reply
// to the patch's JA store is dropped (the first JA stored is the download's); the session goes
// on and the memory is as loaded afterwards.
TEST(a_lost_reply_to_a_patch_store_is_not_stored_twice) {
  Server server(kRun, {"--serve", "tcp:127.0.0.1:0", "--faults", "drop@cmd=JA#2"});
  const std::string prog = program_file();
  CHECK_EQ(ctl({"-q", server.port(), "download", prog}).status, 0);
  const std::string cmds = commands("drop.cmds", "break loop\nrun\ncontinue\nprint v[1]\n");
  Output o = ctl({"--timeout", "300ms", server.port(), "--raw", "debug", "--debug-commands", cmds, prog});
  show(o);
  CHECK_EQ(o.status, 0);
  CHECK(has(o.out, "$1 = 1"));
  // The JA store went out twice, with 132 (to address 1) between.
  const std::string store = "> 01 16 00 00 00 00 00 01 18", point = "> 01 84 00 00 00 00 00 01 86";
  const auto first = o.out.find(store);
  CHECK(first != std::string::npos);
  const auto again = o.out.find(point, first);
  CHECK(again != std::string::npos && o.out.find(store, again) != std::string::npos);
  CHECK(memory_is_program(server, prog));
}

// tmclrun --dap attaches to a module by itself: `attach` with the port (the module as it is),
// a breakpoint, `restart` running the program to it and `continue` once more, a variable read over the host protocol, disconnect; the program memory is as loaded after it.
std::string frame(const std::string& body) { return "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body; }

TEST(tmclrun_dap_attaches_to_a_module) {
  Server server(kRun, {"--serve", "tcp:127.0.0.1:0"});
  const std::string prog = program_file();
  CHECK_EQ(ctl({"-q", server.port(), "download", prog}).status, 0);
  const std::string requests = write_temp(
      "attach.requests",
      frame(R"({"seq":1,"type":"request","command":"initialize","arguments":{"adapterID":"tmcl"}})") +
          frame(R"({"seq":2,"type":"request","command":"attach","arguments":{"port":")" + server.port() + R"(","program":")" + prog +
                R"("}})") +
          frame(R"({"seq":3,"type":"request","command":"setFunctionBreakpoints","arguments":{"breakpoints":[{"name":"loop"}]}})") +
          frame(R"({"seq":4,"type":"request","command":"configurationDone"})") +
          frame(R"({"seq":5,"type":"request","command":"restart"})") +
          frame(R"({"seq":6,"type":"request","command":"continue","arguments":{"threadId":1}})") +
          frame(R"({"seq":7,"type":"request","command":"evaluate","arguments":{"expression":"v[1]","context":"watch"}})") +
          frame(R"({"seq":8,"type":"request","command":"disconnect"})"));
  Output o = hosttest::run({"/bin/sh", "-c", "'" + kRun + "' --dap < '" + requests + "'"});
  show(o);
  CHECK_EQ(o.status, 0);
  CHECK(has(o.out, R"("command":"attach","body":{})"));
  // An attach resets nothing: the downloaded program is not running, and is said so; restart runs it.
  CHECK(has(o.out, R"("reason":"entry")") && has(o.out, "The program is not running on the module"));
  CHECK(has(o.out, R"("reason":"breakpoint")"));
  CHECK(has(o.out, R"("command":"evaluate","body":{"result":"1")"));
  CHECK(memory_is_program(server, prog));
}

}  // namespace module_test
