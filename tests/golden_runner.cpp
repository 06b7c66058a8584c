// The one golden-file test runner for every tool's stable text: assembler, linker, disassembler,
// VM traces and JSON, motion CSVs and server transcripts. A case is a file NAME.tmc or NAME.run
// whose comment lines ("// ..." or "; ...") hold directives:
//   RUN: TOOL ARGS... [< FILE]   run a command; TOOL is a name given with --tool
//   CWD: DIR                     run the following commands in DIR (relative to the case's folder)
//   NOT-ON-WINDOWS: REASON       with --emulator (the Windows tools): skip the case, saying REASON
// In a RUN line
//   %s  the case file's name        %S  the case's folder (absolute)
//   %t  a fresh temporary file      %T  a temporary folder shared by the case's commands
//   %{TOOL}  the path of a tool (for a command run through `sh -c "..."`)
// Arguments split at blanks; '...' and "..." quote (nothing is escaped inside either). Standard
// input is FILE (relative to the command's folder) or /dev/null.
// For each command the runner records the exit status, standard output, standard error and the
// contents of %t (as hex when not text), with the %t and %T paths shown as "%t" and "%T", and
// compares the whole record with NAME.golden. --update rewrites the .golden files instead, for
// review in git diff. CTest runs one case per test (tests/CMakeLists.txt), so a failure names it.
//
// --emulator PROGRAM runs the tools that are Windows programs (NAME.exe) through PROGRAM (Wine:
// docs/install.md, "Windows"), %{TOOL} included; the %T and %S folders are then also recognised
// in the tools' text in their Windows spelling (Z:\tmp\..., and doubled backslashes in JSON).
//
// usage: golden_runner --tool NAME=PATH... [--emulator PROGRAM] [--update] [--filter SUBSTR]
//        (SUITE_DIR | CASE_FILE)...
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "text_file.hpp"

namespace fs = std::filesystem;

namespace {

using tmcl_test::read_text;

bool is_text(const std::string& s) {
  for (unsigned char c : s)
    if ((c < 0x20 && c != '\n' && c != '\t' && c != '\r') || c == 0x7f) return false;
  return true;
}

std::string hex(const std::string& s) {
  std::string out;
  char buf[4];
  for (std::size_t i = 0; i < s.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%02X", static_cast<unsigned char>(s[i]));
    out += buf;
    out += (i % 16 == 15 || i + 1 == s.size()) ? '\n' : ' ';
  }
  return out;
}

// Blanks separate arguments; a quote ('...' or "...") keeps its text, blanks and the other quote
// character included, as one argument or part of one.
std::vector<std::string> split_args(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  bool in = false;
  char quote = 0;
  for (char c : line) {
    if (quote) {
      if (c == quote) quote = 0;
      else cur += c;
    } else if (c == '\'' || c == '"') {
      quote = c;
      in = true;
    } else if (c == ' ' || c == '\t') {
      if (in) out.push_back(cur);
      cur.clear();
      in = false;
    } else {
      cur += c;
      in = true;
    }
  }
  if (in) out.push_back(cur);
  return out;
}

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  if (from.empty()) return;
  for (std::size_t p = 0; (p = s.find(from, p)) != std::string::npos; p += to.size()) s.replace(p, from.size(), to);
}

struct Run {
  int status = 0;
  std::string out, err;
};

// Runs argv in `dir` with stdin from `stdin_file` (or /dev/null), capturing stdout and stderr.
Run run(const std::vector<std::string>& argv, const fs::path& dir, const std::string& stdin_file) {
  Run r;
  fs::path tmp = fs::temp_directory_path() / ("golden." + std::to_string(::getpid()));
  std::string o = tmp.string() + ".out", e = tmp.string() + ".err";
  pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(dir.c_str()) != 0) _exit(126);
    std::FILE* in = std::fopen(stdin_file.empty() ? "/dev/null" : stdin_file.c_str(), "rb");
    std::FILE* fo = std::fopen(o.c_str(), "wb");
    std::FILE* fe = std::fopen(e.c_str(), "wb");
    if (!in || !fo || !fe) _exit(126);
    ::dup2(fileno(in), 0);
    ::dup2(fileno(fo), 1);
    ::dup2(fileno(fe), 2);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execv(args[0], args.data());
    _exit(127);
  }
  int st = 0;
  ::waitpid(pid, &st, 0);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
  r.out = read_text(o);
  r.err = read_text(e);
  fs::remove(o);
  fs::remove(e);
  return r;
}

std::string section(const std::string& title, const std::string& body) {
  if (body.empty()) return "";
  std::string s = "--- " + title + (is_text(body) ? "" : " (hex)") + "\n" + (is_text(body) ? body : hex(body));
  if (s.back() != '\n') s += "\n--- (no newline at end)\n";
  return s;
}

// The directive on a comment line ("// KEY: rest" or "; KEY: rest"): rest, or false. RUN: may
// follow other words on the line (as it always could); CWD: must come first.
bool directive(const std::string& line, const char* key, std::string& rest) {
  if (!(line.rfind("//", 0) == 0 || line.rfind(";", 0) == 0)) return false;
  std::size_t at = line.find(key);
  if (at == std::string::npos) return false;
  if (std::strcmp(key, "RUN:") != 0 && line.find_first_not_of("/; \t") != at) return false;
  rest = line.substr(at + std::strlen(key));
  return true;
}

struct Runner {
  std::map<std::string, std::string> tools;
  std::string emulator;  // run the Windows tools through it
  bool emulated(const std::string& path) const {
    return !emulator.empty() && path.size() > 4 && path.compare(path.size() - 4, 4, ".exe") == 0;
  }
  bool update = false;
  int passed = 0, failed = 0, updated = 0, skipped = 0;

  // A temporary folder for the case's commands (%T), made on first use.
  struct CaseDir {
    std::string path;
    const std::string& get() {
      if (path.empty()) {
        std::string tmpl = (fs::temp_directory_path() / "golden.XXXXXX").string();
        if (::mkdtemp(tmpl.data())) path = tmpl;
      }
      return path;
    }
    ~CaseDir() {
      std::error_code ec;
      if (!path.empty()) fs::remove_all(path, ec);
    }
  };

  // Runs one case and compares (or rewrites) its record; false when it has no RUN line.
  bool run_case(const fs::path& c) {
    std::string text = read_text(c);
    std::istringstream lines(text);
    std::string line, record, rest;
    fs::path folder = fs::absolute(c.parent_path()), cwd = folder;
    CaseDir shared;
    int runs = 0;
    bool broken = false;
    while (std::getline(lines, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();  // CRLF case files
      if (directive(line, "CWD:", rest)) {
        auto dir = split_args(rest);
        if (dir.size() == 1) cwd = fs::weakly_canonical(folder / dir[0]);
        else broken = true;
        continue;
      }
      if (!emulator.empty() && directive(line, "NOT-ON-WINDOWS:", rest)) {
        std::printf("SKIP %s: not on Windows:%s\n", c.string().c_str(), rest.c_str());
        ++skipped;
        return true;
      }
      if (!directive(line, "RUN:", rest)) continue;
      std::string cmd = rest;
      fs::path tmpout = fs::temp_directory_path() / ("golden_t." + std::to_string(::getpid()));
      fs::remove(tmpout);
      for (const auto& [name, path] : tools)
        replace_all(cmd, "%{" + name + "}", emulated(path) ? emulator + " " + path : path);
      replace_all(cmd, "%s", c.filename().string());
      replace_all(cmd, "%t", tmpout.string());
      replace_all(cmd, "%S", folder.string());
      if (cmd.find("%T") != std::string::npos) replace_all(cmd, "%T", shared.get());
      std::string stdin_file;
      auto lt = cmd.find(" < ");
      if (lt != std::string::npos) {
        auto in = split_args(cmd.substr(lt + 3));
        stdin_file = in.empty() ? std::string("/nonexistent") : fs::absolute(cwd / in[0]).string();
        cmd = cmd.substr(0, lt);
      }
      auto args = split_args(cmd);
      if (args.empty() || !tools.count(args[0])) {
        std::fprintf(stderr, "%s: unknown tool in '%s'\n", c.string().c_str(), line.c_str());
        broken = true;
        continue;
      }
      args[0] = tools[args[0]];
      if (emulated(args[0])) args.insert(args.begin(), emulator);
      Run r = run(args, cwd, stdin_file);
      ++runs;
      std::string output;
      bool has_output = fs::exists(tmpout);
      if (has_output) {
        output = read_text(tmpout);
        fs::remove(tmpout);
      }
      for (std::string* s : {&r.out, &r.err, &output}) {  // temporary paths are not the tools' text
        if (!emulator.empty()) {
          for (const auto& [unix_path, name] : {std::pair{shared.path, "%T"}, {tmpout.string(), "%t"}}) {
            if (unix_path.empty()) continue;
            std::string win = "Z:" + unix_path;
            std::replace(win.begin(), win.end(), '/', '\\');
            std::string json;
            for (char ch : win) json += ch == '\\' ? std::string("\\\\") : std::string(1, ch);
            replace_all(*s, json, name);
            replace_all(*s, win, name);
          }
        }
        replace_all(*s, shared.path, "%T");
        replace_all(*s, tmpout.string(), "%t");
      }
      record += "=== RUN:" + rest + "\nexit: " + std::to_string(r.status) + "\n";
      record += section("stdout", r.out);
      record += section("stderr", r.err);
      if (has_output) record += section("output", output.empty() ? std::string("(empty)\n") : output);
    }
    if (runs == 0 && !broken) return false;
    fs::path golden = c;
    golden.replace_extension(".golden");
    if (broken) {
      ++failed;
      return true;
    }
    if (update) {
      if (!fs::exists(golden) || read_text(golden) != record) {
        std::ofstream(golden, std::ios::binary) << record;
        ++updated;
      }
      ++passed;
      return true;
    }
    std::string want = fs::exists(golden) ? read_text(golden) : "";
    if (want == record) {
      ++passed;
      return true;
    }
    ++failed;
    std::fprintf(stderr, "FAIL %s (expected %s; --update or the golden-update target rewrites it)\n",
                 c.string().c_str(), golden.string().c_str());
    fs::path got = fs::temp_directory_path() / (c.filename().string() + "." + std::to_string(::getpid()) + ".actual");
    std::ofstream(got, std::ios::binary) << record;
    std::string diff = "diff -u '" + golden.string() + "' '" + got.string() + "' | head -60 1>&2";
    if (std::system(diff.c_str()) != 0) {
    }
    fs::remove(got);
    return true;
  }
};

}  // namespace

int main(int argc, char** argv) {
  // The tools look for profiles in the user's folders (TMCL_PROFILE_PATH, ~/.config/tmcl/profiles;
  // vm/isa/targets.hpp): a case sees the bundled ones only, unless its RUN line sets its own.
  ::unsetenv("TMCL_PROFILE_PATH");
  ::unsetenv("XDG_CONFIG_HOME");
  ::setenv("HOME", "/nonexistent/tmcl-golden-home", 1);
  Runner runner;
  std::string filter;
  std::vector<fs::path> paths;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--update") runner.update = true;
    else if (a == "--filter" && i + 1 < argc) filter = argv[++i];
    else if (a == "--emulator" && i + 1 < argc) runner.emulator = argv[++i];
    else if (a == "--tool" && i + 1 < argc) {
      std::string t = argv[++i];
      auto eq = t.find('=');
      if (eq == std::string::npos) {
        std::fprintf(stderr, "golden_runner: --tool wants NAME=PATH, not '%s'\n", t.c_str());
        return 64;
      }
      runner.tools[t.substr(0, eq)] = fs::absolute(t.substr(eq + 1)).string();
    } else paths.emplace_back(a);
  }
  for (const auto& path : paths) {
    if (!fs::is_directory(path)) {  // one case, named on the command line: it must have a RUN line
      if (!fs::exists(path) || !runner.run_case(path)) {
        std::fprintf(stderr, "%s: not a golden case (no file, or no RUN: line)\n", path.string().c_str());
        ++runner.failed;
      }
      continue;
    }
    std::vector<fs::path> cases;
    for (const auto& entry : fs::recursive_directory_iterator(path)) {
      auto ext = entry.path().extension();
      if (ext == ".tmc" || ext == ".run") cases.push_back(entry.path());
    }
    std::sort(cases.begin(), cases.end());
    for (const auto& c : cases)
      if (filter.empty() || c.string().find(filter) != std::string::npos) runner.run_case(c);
  }
  if (runner.update) std::printf("%d golden file%s rewritten\n", runner.updated, runner.updated == 1 ? "" : "s");
  std::printf("%d passed, %d failed%s\n", runner.passed, runner.failed,
              runner.skipped ? (", " + std::to_string(runner.skipped) + " skipped").c_str() : "");
  if (runner.failed == 0 && runner.passed == 0 && runner.skipped > 0) return 77;  // CTest: skipped
  return runner.failed == 0 && runner.passed > 0 ? 0 : 1;
}
