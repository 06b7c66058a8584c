// The prompt on a real terminal: tmclrun --debug as a process on a pseudo-terminal (its
// controlling terminal, TERM=xterm), fed the bytes a terminal sends for the keys (escape
// sequences for arrows, Home/End, Delete and Ctrl-arrows, control characters), the screen read
// back. Completion (commands, labels, the parameter names of the included USB-2-SD.inc), history
// (and its file, here a temporary one through TMCLRUN_HISTORY), Ctrl-R and Ctrl-G, the editing
// keys, Ctrl-L, Ctrl-C at the prompt and Ctrl-C pausing a running program (the terminal's own
// mode while a command runs), Ctrl-D; and while serving, the server's notes "client connected"
// and "refused a second client" printed above the prompt, with the half-typed line drawn again
// after each. Each wait is for text with a generous deadline, never a sleep.
#include "check.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <sys/wait.h>
#include <termios.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <vector>

#include "client.hpp"
#include "read_until.hpp"

using namespace srvtest;

namespace {

constexpr int kPromptDeadlineMs = 60000;

const char* kPromptProgram = R"(#include USB-2-SD.inc
        SGP 1, 2, 0
loop:   CSUB bump
        JA loop
bump:   GGP 1, 2
        CALC ADD, 1
        AGP 1, 2
        RSUB
)";

struct OnPty {
  pid_t pid = -1;
  int master = -1;
  std::string screen;  // everything the process wrote to the terminal

  ~OnPty() {
    if (master >= 0) ::close(master);
    if (pid > 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
  }
  void keys(const std::string& bytes) { CHECK(::write(master, bytes.data(), bytes.size()) == static_cast<ssize_t>(bytes.size())); }
  // Keys typed at the prompt: once the editor has the terminal (raw mode), as a user types them.
  void type(const std::string& bytes) {
    CHECK(raw());
    keys(bytes);
  }
  // Reads until `what` occurs `count` times on the screen (or the deadline passes, or the end).
  bool wait_for(const std::string& what, int count = 1) { return dbgtest::read_until(master, screen, what, count, kPromptDeadlineMs); }
  // Waits until the terminal is in the mode a command runs in (its own: Ctrl-C a signal), or in
  // the editor's raw mode (keys typed before it would be taken by the terminal's line
  // discipline): read from the pseudo-terminal's settings.
  bool mode(bool raw) {
    const auto end = Clock::now() + std::chrono::milliseconds(kPromptDeadlineMs);
    termios tio{};
    auto is_raw = [&] { return (tio.c_lflag & (ISIG | ICANON)) == 0; };
    while (::tcgetattr(master, &tio) == 0 && is_raw() != raw && Clock::now() < end) ::poll(nullptr, 0, 1);
    return is_raw() == raw;
  }
  bool cooked() { return mode(false); }
  bool raw() { return mode(true); }
  int status() {
    while (wait_for("\x01")) {
    }
    int st = 0;
    const auto end = Clock::now() + std::chrono::milliseconds(kPromptDeadlineMs);
    while (::waitpid(pid, &st, WNOHANG) == 0) {
      if (Clock::now() > end) {  // still running after the deadline
        ::kill(pid, SIGKILL);
        ::waitpid(pid, &st, 0);
        pid = -1;
        return -1;
      }
      ::poll(nullptr, 0, 5);
    }
    pid = -1;
    return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  }
};

bool spawn(OnPty& t, std::vector<const char*> args, const std::string& history) {
  args.insert(args.begin(), "tmclrun");
  args.push_back(nullptr);
  t.master = ::posix_openpt(O_RDWR | O_NOCTTY);
  if (t.master < 0 || ::grantpt(t.master) != 0 || ::unlockpt(t.master) != 0) return false;
  const std::string slave = ::ptsname(t.master);
  winsize ws{};
  ws.ws_row = 24;
  ws.ws_col = 80;
  ::ioctl(t.master, TIOCSWINSZ, &ws);
  t.pid = ::fork();
  if (t.pid == 0) {
    ::setsid();
    int s = ::open(slave.c_str(), O_RDWR);
    ::ioctl(s, TIOCSCTTY, 0);
    ::dup2(s, 0);
    ::dup2(s, 1);
    ::dup2(s, 2);
    ::close(t.master);
    ::setenv("TERM", "xterm", 1);
    ::setenv("TMCLRUN_HISTORY", history.c_str(), 1);
    ::execv(TMCL_TMCLRUN, const_cast<char* const*>(args.data()));
    ::_exit(127);
  }
  return t.pid > 0;
}

// Connects a client to the server while "print 4" is half typed at the prompt: its note (up to
// `end`) must come out on a line of its own, the typed line erased before it ("\r", erase to the
// end of the line) and drawn again after it (the `redraws`th time the line shows).
Link note_above_the_line(OnPty& t, int port, const std::string& note, const std::string& end, int redraws) {
  const std::size_t typed = t.screen.size();
  Link client = connect_loopback(port);
  CHECK(client.ok());
  CHECK(t.wait_for(note));
  CHECK(t.wait_for("(tmdb) print 4", redraws));
  const std::string after = t.screen.substr(typed);
  const std::size_t at = after.find("\r\x1b[Ktmclrun: " + note);
  if (at == std::string::npos) {
    ::tmcl_test::fail(__FILE__, __LINE__, "the note was not printed after erasing the line: " + note);
    return client;
  }
  const std::size_t line_end = after.find(end + "\r\n", at), redraw = after.find("\r(tmdb) print 4", at);
  CHECK(line_end != std::string::npos && redraw != std::string::npos && line_end < redraw);
  CHECK(after.find("(tmdb)") == redraw + 1);  // no prompt drawn before the note
  return client;
}

std::string read_all(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace

TEST(the_prompt_edits_completes_and_keeps_history_on_a_terminal) {
  const std::string prog = "prompt_pty_prog.tmc", history = "prompt_pty_history";
  std::ofstream(prog) << kPromptProgram;
  std::ofstream(history) << "print 41 + 1\n";  // from an earlier session
  OnPty t;
  CHECK(spawn(t, {"--debug", prog.c_str()}, history));
  CHECK(t.wait_for("(tmdb) "));
  // Tab completes a command and a label.
  t.type("bre\tbu\t\r");
  CHECK(t.wait_for("Breakpoint 1 at bump (address 3)"));
  CHECK(t.screen.find("(tmdb) break bump ") != std::string::npos);
  t.type("run\r");
  CHECK(t.wait_for("Breakpoint 1, bump (address 3)"));
  // Each line typed and what it shows: the editing keys as a terminal sends them.
  const struct {
    const char* keys;
    const char* shows;
  } kTyped[] = {
      {"prin v[1]\x1b[H\x1b[C\x1b[C\x1b[C\x1b[Ct\r", "$1 = 0"},  // Home, Right; a character inserted
      {"\x1b[A\x1b[A\x1b[A\x1b[A\r", "$2 = 42"},                // Up into the earlier session's history
      {"\x12" "brea\r", "Breakpoint 2 at bump (address 3)"},        // Ctrl-R: the newest "brea"; Enter runs it
      {"p 7 junk\x17\r", "$3 = 7"},                                  // Ctrl-W
      {"nonsense\x15p 8\r", "$4 = 8"},                               // Ctrl-U
      {"p 9\x01\x0bp 10\r", "$5 = 10"},                               // Ctrl-A, Ctrl-K
      {"p 1\x01\x05 + 10\x1bOH\x1bOF * 2\r", "$6 = 21"},              // Ctrl-E, Home and End (ESC O H, ESC O F)
      {"p 12\x1b[D\x1b[3~\r", "$7 = 1\r\n"},                         // Left, Delete (ESC [ 3 ~): the 2 goes
      {"p 2\x01\x1b[F * 3\r", "$8 = 6\r\n"},                         // End as ESC [ F
      {"p 56\x02+\x06" "0\r", "$9 = 65\r\n"},                         // Ctrl-B, Ctrl-F: p 5+60
      {"p 7 * 8\x1b[1;5D\x1b[1;5D-\x1b[1;5C" "0\r", "$10 = -560\r\n"}, // Ctrl-Left twice, Ctrl-Right: p -70 * 8
      {"\x1b[A\x1b[A\x1b[B\r", "$11 = -560\r\n"},                     // Up, Up, Down: the newest entry again
      {"p 4\x0c", "\x1b[H\x1b[2J\r(tmdb) p 4\x1b[K"},                  // Ctrl-L: the screen cleared, the line drawn again
      {"\r", "$12 = 4\r\n"},
      {"p 6\x12" "brea\x07\r", "$13 = 6\r\n"},                        // Ctrl-G ends Ctrl-R with the line as it was
      {"p AP_Act\t", "(tmdb) p AP_Actual\x1b[K"},                      // a parameter name of the included USB-2-SD.inc
      {"\t\t", "AP_ActualPosition  AP_ActualSpeed"},                  // ... and the candidates
      {"Pos\t* 100\r", "$14 = 100\r\n"},                             // completed with a blank after it
      {"i\t\t", "ignore  info"},                                     // a second Tab lists the candidates
  };
  for (const auto& k : kTyped) {
    t.type(k.keys);
    if (!t.wait_for(k.shows)) ::tmcl_test::fail(__FILE__, __LINE__, std::string("not shown after typing them: ") + k.shows);
  }
  CHECK(t.screen.find("(reverse-i-search)`brea': break bump") != std::string::npos);
  // Ctrl-C at the prompt drops the line; the next one runs.
  t.type("\x03p 3\r");
  CHECK(t.wait_for("^C"));
  CHECK(t.wait_for("$15 = 3"));
  // While a command runs the terminal is in its own mode: Ctrl-C pauses the program.
  t.type("delete\rcontinue\r");
  CHECK(t.wait_for("continue\x1b[K\r\x1b[15C\r\r\n"));  // Enter taken: the program runs
  CHECK(t.cooked());
  t.keys("\x03");
  CHECK(t.wait_for("Program paused."));
  t.type("\x04");  // Ctrl-D on an empty line: quit
  CHECK(t.wait_for("quit"));
  CHECK_EQ(t.status(), 0);
  const std::string kept = read_all(history);
  CHECK(kept.find("print 41 + 1\nbreak bump \nrun\nprint v[1]\nprint 41 + 1\nbreak bump \n") == 0);
  CHECK(kept.find("\ncontinue\n") != std::string::npos);
  if (::tmcl_test::failures() || std::getenv("PROMPT_PTY_TEST_DUMP")) std::fprintf(stderr, "screen:\n%s\n", t.screen.c_str());
  std::remove(prog.c_str());
  std::remove(history.c_str());
}

TEST(server_notes_are_printed_above_the_prompt_not_inside_the_line_being_typed) {
  ::signal(SIGPIPE, SIG_IGN);
  const std::string prog = "prompt_pty_serve.tmc", history = "prompt_pty_serve_history";
  std::ofstream(prog) << kPromptProgram;
  OnPty t;
  CHECK(spawn(t, {"--serve", "tcp:127.0.0.1:0", "--debug", prog.c_str()}, history));
  CHECK(t.wait_for("listening on 127.0.0.1:"));
  CHECK(t.wait_for("(tmdb) "));
  const std::size_t at = t.screen.find("listening on 127.0.0.1:");
  const int port = std::atoi(t.screen.c_str() + at + 23);
  t.type("print 4");
  CHECK(t.wait_for("(tmdb) print 4"));
  // The first client's note and a second one's refusal: each above the line being typed.
  Link host = note_above_the_line(t, port, "client connected from 127.0.0.1:", "", 2);
  Link second = note_above_the_line(t, port, "refused a second client from 127.0.0.1:", ": one client at a time", 3);
  t.type("\r");
  CHECK(t.wait_for("$1 = 4"));
  t.type("quit\r");
  CHECK_EQ(t.status(), 0);
  if (::tmcl_test::failures() || std::getenv("PROMPT_PTY_TEST_DUMP")) std::fprintf(stderr, "screen:\n%s\n", t.screen.c_str());
  std::remove(prog.c_str());
  std::remove(history.c_str());
}
