// Golden-file test runner. A case is a file NAME.tmc or NAME.run in a suite folder whose lines
// "// RUN: TOOL ARGS..." (also "; RUN:") give commands to run from the case's folder, with
//   %s  the case file's name        %t  a fresh temporary output file
//   %S  the case's folder            %{TOOL}  is replaced by the tool's path from --tool
// For each command the runner records the exit status, standard error, standard output and the
// contents of %t (as hex when not text) and compares the whole record with NAME.golden.
// --update rewrites the .golden files instead, for review in git diff.
//
// usage: golden_runner --tool NAME=PATH... [--update] [--filter SUBSTR] SUITE_DIR...
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

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

std::vector<std::string> split_args(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  bool in = false, quoted = false;
  for (char c : line) {
    if (c == '\'') {
      quoted = !quoted;
      in = true;
    } else if ((c == ' ' || c == '\t') && !quoted) {
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

struct Run {
  int status = 0;
  std::string out, err;
};

// Runs argv in `dir` with stdin from `input` (or /dev/null), capturing stdout and stderr.
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
  r.out = slurp(o);
  r.err = slurp(e);
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

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  for (std::size_t p = 0; (p = s.find(from, p)) != std::string::npos; p += to.size()) s.replace(p, from.size(), to);
}

}  // namespace

int main(int argc, char** argv) {
  std::map<std::string, std::string> tools;
  bool update = false;
  std::string filter;
  std::vector<fs::path> suites;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--update") update = true;
    else if (a == "--filter" && i + 1 < argc) filter = argv[++i];
    else if (a == "--tool" && i + 1 < argc) {
      std::string t = argv[++i];
      auto eq = t.find('=');
      tools[t.substr(0, eq)] = fs::absolute(t.substr(eq + 1)).string();
    } else suites.emplace_back(a);
  }
  int passed = 0, failed = 0, updated = 0;
  for (const auto& suite : suites) {
    std::vector<fs::path> cases;
    for (const auto& entry : fs::recursive_directory_iterator(suite)) {
      auto ext = entry.path().extension();
      if (ext == ".tmc" || ext == ".run") cases.push_back(entry.path());
    }
    std::sort(cases.begin(), cases.end());
    for (const auto& c : cases) {
      if (!filter.empty() && c.string().find(filter) == std::string::npos) continue;
      std::string text = slurp(c);
      std::istringstream lines(text);
      std::string line, record;
      int runs = 0;
      while (std::getline(lines, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();  // CRLF case files
        std::size_t at = line.find("RUN:");
        if (at == std::string::npos || !(line.rfind("//", 0) == 0 || line.rfind(";", 0) == 0)) continue;
        std::string cmd = line.substr(at + 4);
        fs::path tmpout = fs::temp_directory_path() / ("golden_t." + std::to_string(::getpid()));
        fs::remove(tmpout);
        replace_all(cmd, "%s", c.filename().string());
        replace_all(cmd, "%t", tmpout.string());
        replace_all(cmd, "%S", fs::absolute(c.parent_path()).string());
        std::string stdin_file;
        auto lt = cmd.find(" < ");
        if (lt != std::string::npos) {
          stdin_file = fs::absolute(c.parent_path() / split_args(cmd.substr(lt + 3))[0]).string();
          cmd = cmd.substr(0, lt);
        }
        auto args = split_args(cmd);
        if (args.empty() || !tools.count(args[0])) {
          std::fprintf(stderr, "%s: unknown tool in '%s'\n", c.string().c_str(), line.c_str());
          ++failed;
          continue;
        }
        args[0] = tools[args[0]];
        Run r = run(args, c.parent_path(), stdin_file);
        ++runs;
        record += "=== RUN:" + line.substr(at + 4) + "\nexit: " + std::to_string(r.status) + "\n";
        record += section("stdout", r.out);
        record += section("stderr", r.err);
        if (fs::exists(tmpout)) {
          std::string body = slurp(tmpout);
          record += section("output", body.empty() ? std::string("(empty)\n") : body);
          fs::remove(tmpout);
        }
      }
      if (runs == 0) continue;
      fs::path golden = c;
      golden.replace_extension(".golden");
      if (update) {
        if (!fs::exists(golden) || slurp(golden) != record) {
          std::ofstream(golden, std::ios::binary) << record;
          ++updated;
        }
        ++passed;
        continue;
      }
      std::string want = fs::exists(golden) ? slurp(golden) : "";
      if (want == record) {
        ++passed;
      } else {
        ++failed;
        std::fprintf(stderr, "FAIL %s (expected %s)\n", c.string().c_str(), golden.string().c_str());
        fs::path got = fs::temp_directory_path() / (c.filename().string() + ".actual");
        std::ofstream(got, std::ios::binary) << record;
        std::string diff = "diff -u '" + golden.string() + "' '" + got.string() + "' | head -40 1>&2";
        if (std::system(diff.c_str()) != 0) {
        }
      }
    }
  }
  if (update) std::printf("%d golden file%s rewritten\n", updated, updated == 1 ? "" : "s");
  std::printf("%d passed, %d failed\n", passed, failed);
  return failed == 0 && passed > 0 ? 0 : 1;
}
