// Running a tool as a whole process from a benchmark (the process start, the kernel's first touch
// of fresh pages and the exit are part of what a user waits for), shared by the benchmarks.
#pragma once

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <vector>

namespace tmcl::bench {

// Wall time in seconds of running argv to completion (output discarded); negative when it could
// not run or did not exit with 0. posix_spawn, not fork: the benchmark holds a million-line
// program, and fork would copy its page tables into every child, which is the benchmark's cost,
// not the tool's. `cpu_seconds`, when given, receives the child's user + system time (steadier
// than wall time on a loaded machine).
inline double run_process(const std::vector<std::string>& argv, double* cpu_seconds = nullptr) {
  using Clock = std::chrono::steady_clock;
  auto t = Clock::now();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) return -1;
  int st = 0;
  rusage ru{};
  ::wait4(pid, &st, 0, &ru);
  if (cpu_seconds)
    *cpu_seconds = static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
                   static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) / 1e6;
  if (!WIFEXITED(st) || WEXITSTATUS(st) != 0) return -1;
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Starts a server (`tmclrun --serve ...`) in the background with standard error discarded and
// reads the line it announces on standard output (a pty's path, "listening on HOST:PORT") into
// `first_line`. The process id, or -1 when it could not start.
inline pid_t start_server(const std::vector<std::string>& argv, std::string& first_line) {
  int out[2];
  if (::pipe(out) != 0) return -1;
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out[1], 1);
  posix_spawn_file_actions_addclose(&actions, out[0]);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(out[1]);
  if (rc != 0) {
    ::close(out[0]);
    return -1;
  }
  char c;
  while (::read(out[0], &c, 1) == 1 && c != '\n') first_line += c;
  ::close(out[0]);
  return pid;
}

}  // namespace tmcl::bench
