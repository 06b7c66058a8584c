// RunControl (run_control.hpp): the signal handlers only set flags (async-signal-safe); the VM
// polls the one it is given, and run() reads the others when the VM has stopped.
#include "tmcl/run_control.hpp"

#include <atomic>
#include <csignal>
#include <string>

#include "tmcl/duration.hpp"
#include "tmcl/os_console.hpp"

namespace tmcl {
namespace {

std::atomic<bool> g_stop{false};            // what the VM polls (Limits::stop); lock-free
static_assert(std::atomic<bool>::is_always_lock_free, "a signal handler sets it");
volatile std::sig_atomic_t g_signal = 0;    // SIGINT or SIGTERM that asked for the end
volatile std::sig_atomic_t g_note_due = 0;  // the wall-clock note's timer went off
volatile std::sig_atomic_t g_closed = 0;    // a trace could not write

os::SavedSignal g_old_int, g_old_term;
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

void install(int sig, void (*handler)(int), os::SavedSignal* old) {
  os::catch_signal(sig, handler, true, old);  // restart: the trace's writes go on
}

}  // namespace

RunControl::RunControl(bool note, std::FILE* note_to, int note_after_ms) {
  g_stop = false;
  g_signal = 0;
  g_note_due = 0;
  g_closed = 0;
  install(SIGINT, on_signal, &g_old_int);
  install(SIGTERM, on_signal, &g_old_term);
  os::ignore_broken_pipe();
  g_note = note;
  g_note_ms = note_after_ms;
  g_note_to = note_to;
  if (note) {
    os::arm_timer(note_after_ms > 0 ? note_after_ms : 1, on_alarm);
  }
}

RunControl::~RunControl() {
  if (g_note) {
    os::arm_timer(0, nullptr);
  }
  if (g_signal == 0) {  // after a signal, the default action stays (end_by_signal)
    os::restore_signal(SIGINT, g_old_int);
    os::restore_signal(SIGTERM, g_old_term);
  }
}

RunResult RunControl::run(Vm& vm, Limits limits) {
  limits.stop = &g_stop;
  for (;;) {
    RunResult r = vm.run(limits);
    if (r.halt != Halt::Interrupted) return r;
    if (g_signal != 0) {
      // A second Ctrl-C while the outputs are written ends tmclrun at once.
      os::default_signal(SIGINT);
      os::default_signal(SIGTERM);
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
  os::die_by_signal(sig);
}

}  // namespace tmcl
