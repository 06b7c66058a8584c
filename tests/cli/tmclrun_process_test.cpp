// tmclrun as a process (issue 28 item 1): SIGINT and SIGTERM end an endless run as a limit does,
// with the summary or --json, --csv, --plot and the EEPROM file written, halt "interrupted", and
// the process ending by the signal (status 130, 143); a trace piped into `head` ends when head
// has gone (status 74, the plot still written); and a run that no limit bounds says, after 2 s
// of wall time on a terminal, how far simulated time got and how to bound it (through a pty).
#include <signal.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "check.hpp"
#include "process.hpp"

namespace {

using hosttest::Clock;
using hosttest::Output;

const std::string kRun = TMCL_TMCLRUN;

std::string temp_dir() {
  static std::string dir = [] {
    char t[] = "/tmp/tmclrun-process-XXXXXX";
    return std::string(::mkdtemp(t));
  }();
  return dir;
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = temp_dir() + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A standalone program's main loop: it waits for a button that never comes, and moves meanwhile.
const std::string kForever =
    "  MVP ABS, 0, 5000\n"
    "Loop:\n"
    "  CALCV ADD, 5, 1\n"
    "  GIO 0, 0\n"
    "  JC ZE, Loop\n"
    "  STOP\n";

// Sends `sig` (the callers wait 1 s first: long enough for tmclrun to be running on a loaded machine).
std::function<bool(pid_t)> send(int sig) {
  return [sig](pid_t pid) { return ::kill(pid, sig) == 0; };
}

void show(const Output& o) { std::fprintf(stderr, "  status %d\n  out: %s\n  err: %s\n", o.status, o.out.c_str(), o.err.c_str()); }

// argv with standard output and standard error on one pty, as in a terminal; once `until` is
// shown (or `wait_ms` have passed), SIGINT; then everything up to the end.
Output run_on_pty_then_sigint(std::vector<std::string> argv, const std::string& until, int wait_ms) {
  const auto start = Clock::now();
  return hosttest::run_on_pty(std::move(argv), wait_ms + 30000, [&](pid_t pid, const std::string& shown) {
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - start).count();
    return (has(shown, until) || ms > wait_ms) && ::kill(pid, SIGINT) == 0;
  });
}

}  // namespace

TEST(sigint_ends_an_endless_run_writing_every_output) {
  const std::string prog = write_temp("forever.tmc", kForever);
  const std::string csv = temp_dir() + "/int.csv", svg = temp_dir() + "/int.svg", ee = temp_dir() + "/int.eeprom";
  Output o = hosttest::run({kRun, "--json", "--sample", "1s", "--csv", csv, "--plot", svg, "--eeprom", ee, prog}, 60000, 1000, send(SIGINT));
  CHECK_EQ(o.status, 130);  // ended by SIGINT, after writing everything
  CHECK(has(o.out, "{\"halt\":\"interrupted\",\n \"message\":\"interrupted by SIGINT (Ctrl-C)\""));
  CHECK(has(o.out, "\"vars\":[0,0,0,0,0,"));
  CHECK(slurp(csv).rfind("# time in s", 0) == 0);
  CHECK(has(slurp(csv), "move issued"));
  CHECK(slurp(svg).rfind("<svg ", 0) == 0);
  CHECK(slurp(ee).rfind("tmcl-eeprom 1", 0) == 0);
  CHECK(!has(o.err, "note:"));  // standard error is no terminal
  if (o.status != 130) show(o);
}

TEST(sigterm_ends_a_run_with_its_summary) {
  const std::string prog = write_temp("forever-term.tmc", kForever);
  Output o = hosttest::run({kRun, "-t", "usb-2-sd", prog}, 60000, 1000, send(SIGTERM));
  CHECK_EQ(o.status, 143);
  CHECK(o.out.rfind("halted: interrupted", 0) == 0);
  CHECK(has(o.out, "motor 0: position 5000"));
  if (o.status != 143) show(o);
}

TEST(a_trace_piped_into_head_ends_when_head_has_gone) {
  // `tmclrun --trace forever.tmc | head -n 3`: the trace cannot be written once head has its
  // lines; the run ends (exit status 74, as for any output that cannot be written) and still
  // writes its plot. The shell writes tmclrun's own status to a file.
  const std::string prog = write_temp("forever-head.tmc", kForever);
  const std::string svg = temp_dir() + "/head.svg", status = temp_dir() + "/head.status";
  const std::string cmd = "{ " + kRun + " --trace --plot " + svg + " " + prog + "; echo $? > " + status + "; } | head -n 3";
  Output o = hosttest::run({"/bin/sh", "-c", cmd}, 60000);
  CHECK_EQ(o.status, 0);
  CHECK_EQ(slurp(status), std::string("74\n"));
  CHECK(has(o.out, "CALCV ADD, 5, 1"));
  CHECK(has(o.err, "tmclrun: error: cannot write standard output"));
  CHECK(slurp(svg).rfind("<svg ", 0) == 0);
}

TEST(an_unbounded_run_on_a_terminal_says_how_far_it_got_after_two_seconds) {
  const std::string prog = write_temp("forever-note.tmc", kForever);
  Output o = run_on_pty_then_sigint({kRun, prog}, "tmclrun: note:", 20000);
  CHECK_EQ(o.status, 130);
  const std::size_t note = o.out.find("tmclrun: note: still running after 2 s, at simulated time ");
  CHECK(note != std::string::npos);
  CHECK(has(o.out, "--max-time DURATION bounds a run; Ctrl-C ends it with its summary"));
  CHECK(has(o.out, "halted: interrupted"));
  CHECK(o.out.find("halted: interrupted") > note);  // the run went on after the note
  if (note == std::string::npos) show(o);
}

TEST(a_bounded_run_gives_no_note) {
  // With --max-time (here far away) the user has bounded the run: no note, however long it takes.
  const std::string prog = write_temp("forever-bounded.tmc", kForever);
  Output o = run_on_pty_then_sigint({kRun, "--max-time", "1000h", prog}, "never shown", 2600);
  CHECK_EQ(o.status, 130);
  CHECK(!has(o.out, "note:"));
  CHECK(has(o.out, "halted: interrupted"));
}

TEST(a_debugger_continue_with_commands_not_from_a_terminal_gets_the_note) {
  // `printf 'run\n' | tmclrun --debug forever.tmc` (here the commands come from a file, as from a
  // pipe: not a terminal) with standard error on a terminal: the unbounded run says how far it
  // got after 2 s, as a plain run does, and Ctrl-C pauses it; then the commands end (quit).
  const std::string prog = write_temp("forever-debug.tmc", kForever);
  const std::string commands = write_temp("forever-debug.cmd", "run\n");
  Output o = run_on_pty_then_sigint({"/bin/sh", "-c", "exec " + kRun + " --debug " + prog + " < " + commands},
                                    "tmclrun: note:", 20000);
  const std::size_t note = o.out.find("tmclrun: note: still running after 2 s, at simulated time ");
  CHECK(note != std::string::npos);
  CHECK(has(o.out, "(no --max-time or --max-steps): --max-time DURATION bounds a run; Ctrl-C pauses it"));
  CHECK(has(o.out, "Program paused."));
  CHECK(o.out.find("Program paused.") > note);
  if (note == std::string::npos) show(o);
}

TEST(a_bounded_debugger_run_gives_no_note) {
  const std::string prog = write_temp("forever-debug-bounded.tmc", kForever);
  const std::string commands = write_temp("forever-debug-bounded.cmd", "run\n");
  Output o = run_on_pty_then_sigint(
      {"/bin/sh", "-c", "exec " + kRun + " --debug --max-time 1000h " + prog + " < " + commands}, "never shown", 2600);
  CHECK(!has(o.out, "note:"));
  CHECK(has(o.out, "Program paused."));
}
