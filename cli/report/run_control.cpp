// RunControl (run_control.hpp): the signal handlers only set flags (async-signal-safe); the VM
// polls the one it is given, and run() reads the others when the VM has stopped.
#include "tmcl/run_control.hpp"

#include <sys/time.h>

#include <atomic>
#include <csignal>
#include <string>
#include <unistd.h>

#include "tmcl/duration.hpp"

namespace tmcl {
namespace {

std::atomic<bool> g_stop{false};            // what the VM polls (Limits::stop); lock-free
static_assert(std::atomic<bool>::is_always_lock_free, "a signal handler sets it");
volatile std::sig_atomic_t g_signal = 0;    // SIGINT or SIGTERM that asked for the end
volatile std::sig_atomic_t g_note_due = 0;  // the wall-clock note's timer went off
volatile std::sig_atomic_t g_closed = 0;    // a trace could not write

struct sigaction g_old_int {}, g_old_term {}, g_old_alrm {};
bool g_note = false;
int g_note_ms = 0;
std::FILE* g_note_to = nullptr;

extern "C" void on_signal(int sig) {
  g_signal = sig;
  g_stop = true;
}

extern "C" void on_alarm(int) {
  g_note_due = 1;
  g_stop = true;
}

void install(int sig, void (*handler)(int), struct sigaction* old) {
  struct sigaction sa {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;  // the trace's writes go on
  ::sigaction(sig, &sa, old);
}

void default_action(int sig) {
  struct sigaction sa {};
  sa.sa_handler = SIG_DFL;
  sigemptyset(&sa.sa_mask);
  ::sigaction(sig, &sa, nullptr);
}

void set_timer(int ms) {
  itimerval t{};
  t.it_value.tv_sec = ms / 1000;
  t.it_value.tv_usec = (ms % 1000) * 1000;
  ::setitimer(ITIMER_REAL, &t, nullptr);
}

}  // namespace

RunControl::RunControl(bool note, std::FILE* note_to, int note_after_ms) {
  g_stop = false;
  g_signal = 0;
  g_note_due = 0;
  g_closed = 0;
  install(SIGINT, on_signal, &g_old_int);
  install(SIGTERM, on_signal, &g_old_term);
  struct sigaction ign {};
  ign.sa_handler = SIG_IGN;
  sigemptyset(&ign.sa_mask);
  ::sigaction(SIGPIPE, &ign, nullptr);
  g_note = note;
  g_note_ms = note_after_ms;
  g_note_to = note_to;
  if (note) {
    install(SIGALRM, on_alarm, &g_old_alrm);
    set_timer(note_after_ms > 0 ? note_after_ms : 1);
  }
}

RunControl::~RunControl() {
  if (g_note) {
    set_timer(0);
    ::sigaction(SIGALRM, &g_old_alrm, nullptr);
  }
  if (g_signal == 0) {  // after a signal, the default action stays (end_by_signal)
    ::sigaction(SIGINT, &g_old_int, nullptr);
    ::sigaction(SIGTERM, &g_old_term, nullptr);
  }
}

RunResult RunControl::run(Vm& vm, Limits limits) {
  limits.stop = &g_stop;
  for (;;) {
    RunResult r = vm.run(limits);
    if (r.halt != Halt::Interrupted) return r;
    if (g_signal != 0) {
      // A second Ctrl-C while the outputs are written ends tmclrun at once.
      default_action(SIGINT);
      default_action(SIGTERM);
      r.message = g_signal == SIGINT ? "interrupted by SIGINT (Ctrl-C)" : "interrupted by SIGTERM";
      return r;
    }
    if (g_closed != 0) {
      r.message = "the trace's output was closed";
      return r;
    }
    if (g_note_due == 0) return r;  // not ours: nothing else sets the flag
    g_note_due = 0;
    g_stop = false;
    if (g_signal != 0 || g_closed != 0) g_stop = true;  // one that came in between is kept
    if (g_note_to) {
      std::fprintf(g_note_to,
                   "tmclrun: note: still running after %g s, at simulated time %s (no --max-time or "
                   "--max-steps): --max-time DURATION bounds a run; Ctrl-C ends it with its summary\n",
                   g_note_ms / 1000.0, format_time(vm.now).c_str());
      std::fflush(g_note_to);
    }
  }
}

void RunControl::output_closed() {
  g_closed = 1;
  g_stop = true;
}

bool RunControl::output_was_closed() const { return g_closed != 0; }

int RunControl::ended_by() { return g_signal; }

void RunControl::end_by_signal() {
  const int sig = g_signal;
  if (sig == 0) return;
  default_action(sig);
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, sig);
  ::sigprocmask(SIG_UNBLOCK, &set, nullptr);
  std::raise(sig);
  ::_exit(128 + sig);  // not reached: the default action of SIGINT and SIGTERM ends the process
}

}  // namespace tmcl
