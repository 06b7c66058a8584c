// The platform layer, console and signals: what a tool does to its standard streams at start,
// and how Ctrl-C, a request to end, a timer and a vanished reader reach it. One implementation
// per system, chosen when CMake configures (os_console_posix.cpp, os_console_windows.cpp).
//
// On Windows there are no POSIX signals: Ctrl-C is SIGINT, Ctrl-Break and the console closing
// are SIGTERM (the C library calls the handler on a thread of its own, which sets flags only, as
// a signal handler does); the timer is a thread-pool timer; there is no SIGPIPE to ignore (a
// write to a closed pipe fails with EPIPE).
#pragma once

#include <csignal>

#if !defined(_WIN32)
#include <signal.h>
#include <termios.h>
#endif

namespace tmcl::os {

// Called by every tool first: on Windows the standard streams carry bytes as they are (no "\n"
// to "\r\n"), so output is the same byte for byte as on Linux, and the console shows UTF-8.
void init_console();

// A terminal's mode as it was before raw mode, to put back.
struct SavedTerminal {
#if defined(_WIN32)
  unsigned long mode = 0;
#else
  termios mode{};
#endif
};
// Raw mode on terminal `fd` for a line editor: no echo, no line buffering, Ctrl-C and Enter as
// keys ("\r"), output unchanged. `saved`: the mode before, read on the first call
// (`have_saved`). False when `fd` is not a terminal whose mode can be set.
bool terminal_raw(int fd, SavedTerminal& saved, bool& have_saved);
void terminal_restore(int fd, const SavedTerminal& saved);
// The terminal's width in columns (80 when it cannot be known).
int terminal_width(int fd);

using SignalHandler = void (*)(int);
// A signal's disposition as it was before catch_signal, to put back.
struct SavedSignal {
#if defined(_WIN32)
  SignalHandler handler = nullptr;
#else
  struct sigaction action {};
#endif
};
// Calls `handler` on `sig` (SIGINT or SIGTERM). `restart`: a system call the signal interrupts
// goes on (POSIX SA_RESTART); without it, it fails with EINTR and the caller sees the stop.
void catch_signal(int sig, SignalHandler handler, bool restart, SavedSignal* old = nullptr);
void restore_signal(int sig, const SavedSignal& old);
// The default action again: the next such signal ends the process.
void default_signal(int sig);
// A write to a pipe or socket nobody reads fails (EPIPE) instead of ending the process.
void ignore_broken_pipe();
// Calls `handler` once after `ms` milliseconds of wall time (POSIX: SIGALRM); 0 disarms it.
void arm_timer(int ms, SignalHandler handler);
// Ends the process as `sig`'s default action does (the shell sees 128 + sig).
[[noreturn]] void die_by_signal(int sig);

}  // namespace tmcl::os
