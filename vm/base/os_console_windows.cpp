// The platform layer, console and signals, on Windows (os_console.hpp).
#include <fcntl.h>
#include <io.h>
#include <windows.h>

#include <cstdio>
#include <cstdlib>

#include "tmcl/os_console.hpp"

namespace tmcl::os {
namespace {

SignalHandler g_term = nullptr;  // SIGTERM's handler: Ctrl-Break and the console closing
SignalHandler g_int = nullptr;   // SIGINT's: the C library forgets a handler once it ran

extern "C" void on_int(int sig) {
  std::signal(SIGINT, on_int);  // caught again next time, as POSIX sigaction does
  if (SignalHandler h = g_int) h(sig);
}
HANDLE g_timer = nullptr;
SignalHandler g_timer_handler = nullptr;

BOOL WINAPI on_console_event(DWORD event) {
  if (event == CTRL_BREAK_EVENT || event == CTRL_CLOSE_EVENT) {
    if (SignalHandler h = g_term) {
      h(SIGTERM);
      return TRUE;
    }
  }
  return FALSE;  // Ctrl-C: the C library's handler (signal(SIGINT)) sees it
}

void CALLBACK on_timer(void*, BOOLEAN) {
  if (SignalHandler h = g_timer_handler) h(0);
}

}  // namespace

void init_console() {
  for (int fd = 0; fd <= 2; ++fd) ::_setmode(fd, _O_BINARY);
  ::SetConsoleOutputCP(CP_UTF8);
  ::SetConsoleCP(CP_UTF8);
  // A crash shows no dialog box waiting for a click: the process ends and says so.
  ::SetErrorMode(SEM_FAILCRITICALERRORS | SEM_NOGPFAULTERRORBOX);
}

bool terminal_raw(int fd, SavedTerminal& saved, bool& have_saved) {
  HANDLE h = reinterpret_cast<HANDLE>(::_get_osfhandle(fd));
  DWORD mode = 0;
  if (!have_saved && ::GetConsoleMode(h, &mode)) {
    saved.mode = mode;
    have_saved = true;
  }
  if (!have_saved) return false;
  // Keys as they are typed, virtual-terminal sequences for the arrows (as on a POSIX terminal).
  mode = (static_cast<DWORD>(saved.mode) & ~static_cast<DWORD>(ENABLE_ECHO_INPUT | ENABLE_LINE_INPUT | ENABLE_PROCESSED_INPUT)) |
         ENABLE_VIRTUAL_TERMINAL_INPUT;
  ::SetConsoleMode(h, mode);
  return true;
}

void terminal_restore(int fd, const SavedTerminal& saved) {
  ::SetConsoleMode(reinterpret_cast<HANDLE>(::_get_osfhandle(fd)), static_cast<DWORD>(saved.mode));
}

int terminal_width(int fd) {
  CONSOLE_SCREEN_BUFFER_INFO info{};
  if (!::GetConsoleScreenBufferInfo(reinterpret_cast<HANDLE>(::_get_osfhandle(fd)), &info)) return 80;
  const int w = info.srWindow.Right - info.srWindow.Left + 1;
  return w > 0 ? w : 80;
}

void catch_signal(int sig, SignalHandler handler, bool, SavedSignal* old) {
  if (sig == SIGTERM) {
    if (old) old->handler = g_term;
    if (!g_term) ::SetConsoleCtrlHandler(on_console_event, TRUE);
    g_term = handler;
    return;
  }
  if (sig == SIGINT) {
    if (old) old->handler = g_int ? g_int : SIG_DFL;
    g_int = handler;
    std::signal(SIGINT, on_int);
    return;
  }
  SignalHandler prev = std::signal(sig, handler);
  if (old) old->handler = prev == SIG_ERR ? SIG_DFL : prev;
}

void restore_signal(int sig, const SavedSignal& old) {
  if (sig == SIGTERM) {
    g_term = old.handler == SIG_DFL ? nullptr : old.handler;
    return;
  }
  if (sig == SIGINT && old.handler && old.handler != SIG_DFL && old.handler != SIG_IGN) {
    g_int = old.handler;
    std::signal(SIGINT, on_int);
    return;
  }
  if (sig == SIGINT) g_int = nullptr;
  std::signal(sig, old.handler ? old.handler : SIG_DFL);
}

void default_signal(int sig) {
  if (sig == SIGTERM) g_term = nullptr;
  if (sig == SIGINT) g_int = nullptr;
  if (sig != SIGTERM) std::signal(sig, SIG_DFL);
}

void ignore_broken_pipe() {}

void arm_timer(int ms, SignalHandler handler) {
  if (g_timer) {
    ::DeleteTimerQueueTimer(nullptr, g_timer, INVALID_HANDLE_VALUE);
    g_timer = nullptr;
  }
  g_timer_handler = handler;
  if (ms > 0) ::CreateTimerQueueTimer(&g_timer, nullptr, on_timer, nullptr, static_cast<DWORD>(ms), 0, WT_EXECUTEONLYONCE);
}

void die_by_signal(int sig) {
  std::fflush(nullptr);
  std::_Exit(128 + sig);
}

}  // namespace tmcl::os
