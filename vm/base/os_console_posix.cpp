// The platform layer, console and signals, on POSIX systems (os_console.hpp).
#include <sys/ioctl.h>
#include <sys/time.h>
#include <unistd.h>

#include "tmcl/os_console.hpp"

namespace tmcl::os {

void init_console() {}

bool terminal_raw(int fd, SavedTerminal& saved, bool& have_saved) {
  if (!have_saved && ::tcgetattr(fd, &saved.mode) == 0) have_saved = true;
  if (!have_saved) return false;
  termios raw = saved.mode;
  // No echo, no line buffering, Ctrl-C/Ctrl-Z/Ctrl-S as keys, Enter as \r; output unchanged.
  raw.c_lflag &= static_cast<tcflag_t>(~(ECHO | ICANON | ISIG | IEXTEN));
  raw.c_iflag &= static_cast<tcflag_t>(~(IXON | ICRNL | INLCR | IGNCR));
  raw.c_cc[VMIN] = 1;
  raw.c_cc[VTIME] = 0;
  ::tcsetattr(fd, TCSADRAIN, &raw);
  return true;
}

void terminal_restore(int fd, const SavedTerminal& saved) { ::tcsetattr(fd, TCSADRAIN, &saved.mode); }

int terminal_width(int fd) {
  winsize ws{};
  return ::ioctl(fd, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0 ? ws.ws_col : 80;
}

void catch_signal(int sig, SignalHandler handler, bool restart, SavedSignal* old) {
  struct sigaction sa {};
  sa.sa_handler = handler;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = restart ? SA_RESTART : 0;
  ::sigaction(sig, &sa, old ? &old->action : nullptr);
}

void restore_signal(int sig, const SavedSignal& old) { ::sigaction(sig, &old.action, nullptr); }

void default_signal(int sig) {
  struct sigaction sa {};
  sa.sa_handler = SIG_DFL;
  sigemptyset(&sa.sa_mask);
  ::sigaction(sig, &sa, nullptr);
}

void ignore_broken_pipe() {
  struct sigaction ign {};
  ign.sa_handler = SIG_IGN;
  sigemptyset(&ign.sa_mask);
  ::sigaction(SIGPIPE, &ign, nullptr);
}

void arm_timer(int ms, SignalHandler handler) {
  if (ms > 0) catch_signal(SIGALRM, handler, true);
  itimerval t{};
  t.it_value.tv_sec = ms / 1000;
  t.it_value.tv_usec = (ms % 1000) * 1000;
  ::setitimer(ITIMER_REAL, &t, nullptr);
  if (ms <= 0) default_signal(SIGALRM);
}

void die_by_signal(int sig) {
  default_signal(sig);
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, sig);
  ::sigprocmask(SIG_UNBLOCK, &set, nullptr);
  std::raise(sig);
  ::_exit(128 + sig);  // not reached: the default action of SIGINT and SIGTERM ends the process
}

}  // namespace tmcl::os
