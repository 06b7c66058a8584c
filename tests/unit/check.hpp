// Our small unit-test harness: TEST(name) { CHECK(...); CHECK_EQ(a, b); }. Prints a failure with
// file:line and both values, and a closing "N passed, N failed" line; exits non-zero on any
// failure. `EXE [--file STEM] [--jobs N] [CASE]` runs only the cases of source file STEM (a suite
// of several test files, tmcl_unit_suite in tests/CMakeLists.txt), only the case named CASE, and
// N cases at a time, each in a process of its own (for cases that mostly wait; see main()).
// The harness is check_core.hpp; this file adds main() where TMCL_TEST_MAIN is defined, which is
// tests/unit/test_main.cpp alone: tmcl_test_main in tests/CMakeLists.txt links it into every
// unit-test executable.
#include "check_core.hpp"

#ifdef TMCL_TEST_MAIN
#ifndef _WIN32
#include <sys/wait.h>
#include <unistd.h>
#endif

#include <cstdlib>
#include <optional>

namespace tmcl_test {

// Counts a finished case and names it when it failed: the one tally of a serial and a --jobs run.
inline void tally(const Case& c, bool ok, int& passed, int& failed) {
  if (ok) {
    ++passed;
  } else {
    ++failed;
    std::fprintf(stderr, "FAILED: %s\n", c.name);
  }
}

#ifndef _WIN32
// --jobs N: the cases of a suite that mostly waits (on ports, timeouts, other processes) run N
// at a time, each in a child process of its own (fork) with its output in a temporary file.
// The outputs are printed in the cases' order, so the log reads as that of a serial run; a case
// that crashes is a failed case, not a lost run. Windows has no fork: there (the cross build,
// tests/windows/run.sh) the cases run one after another, as without --jobs.
struct Outcome {
  bool passed;
  std::string output;
};

inline Outcome finish_child(pid_t pid, int status, std::FILE* out) {
  std::string text;
  std::rewind(out);
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, out)) > 0;) text.append(buf, n);
  std::fclose(out);
  const bool passed = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (WIFSIGNALED(status))
    text += "case process " + std::to_string(pid) + " killed by signal " + std::to_string(WTERMSIG(status)) + "\n";
  return {passed, text};
}

inline int run_in_children(const std::vector<const Case*>& cases, int jobs, int& passed, int& failed) {
  struct Running {
    pid_t pid;
    std::size_t index;
    std::FILE* out;
  };
  std::vector<Running> running;
  std::vector<std::optional<Outcome>> outcomes(cases.size());
  std::size_t next = 0, shown = 0;
  while (shown < cases.size()) {
    while (running.size() < static_cast<std::size_t>(jobs) && next < cases.size()) {
      std::FILE* out = std::tmpfile();
      if (!out) {
        std::perror("tmpfile");
        return 1;
      }
      std::fflush(stdout);
      std::fflush(stderr);
      const pid_t pid = ::fork();
      if (pid < 0) {
        std::perror("fork");
        return 1;
      }
      if (pid == 0) {
        ::dup2(::fileno(out), 1);
        ::dup2(::fileno(out), 2);
        cases[next]->fn();
        std::fflush(stdout);
        std::fflush(stderr);
        ::_exit(failures() == 0 ? 0 : 1);
      }
      running.push_back({pid, next++, out});
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      std::perror("waitpid");
      return 1;
    }
    for (std::size_t r = 0; r < running.size(); ++r) {
      if (running[r].pid != pid) continue;
      outcomes[running[r].index] = finish_child(pid, status, running[r].out);
      running.erase(running.begin() + static_cast<std::ptrdiff_t>(r));
      break;
    }
    for (; shown < cases.size() && outcomes[shown]; ++shown) {
      std::fputs(outcomes[shown]->output.c_str(), stderr);
      tally(*cases[shown], outcomes[shown]->passed, passed, failed);
    }
  }
  return 0;
}
#endif

}  // namespace tmcl_test

int main(int argc, char** argv) {
  std::string file, only;
  int jobs = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--file" && i + 1 < argc) {
      file = argv[++i];
    } else if (a == "--jobs" && i + 1 < argc) {
      char* end = nullptr;
      const long n = std::strtol(argv[++i], &end, 10);
      jobs = *argv[i] && !*end && n >= 1 && n <= 256 ? static_cast<int>(n) : 0;
      if (jobs < 1) {
        std::fprintf(stderr, "--jobs needs a number from 1 to 256, not '%s'\n", argv[i]);
        return 2;
      }
    } else {
      only = a;
    }
  }
  std::vector<const ::tmcl_test::Case*> selected;
  for (auto& c : ::tmcl_test::registry()) {
    if (!file.empty() && !::tmcl_test::from_file(c.file, file)) continue;
    if (!only.empty() && only != c.name) continue;
    selected.push_back(&c);
  }
  int passed = 0, failed = 0;
#ifdef _WIN32
  jobs = 1;
#endif
  if (jobs > 1) {
#ifndef _WIN32
    if (::tmcl_test::run_in_children(selected, jobs, passed, failed) != 0) return 1;
#endif
  } else {
    for (const auto* c : selected) {
      int before = ::tmcl_test::failures();
      c->fn();
      ::tmcl_test::tally(*c, ::tmcl_test::failures() == before, passed, failed);
    }
  }
  std::printf("%d passed, %d failed\n", passed, failed);
  return failed == 0 && passed > 0 ? 0 : 1;
}
#endif
