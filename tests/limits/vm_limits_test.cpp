// The input-file limits of tmclrun (docs/limits.md), through tmclrun itself: a file at its limit
// is read (its content may still be rejected for other reasons, never for its size), one byte
// more is rejected with a message naming the limit, exit status 65, and nothing crashes.
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "check.hpp"
#include "tmcl/fileio.hpp"

namespace {

struct Out {
  int status;
  std::string text;
};

Out tmclrun(const std::string& args) {
  std::string cmd = std::string(TMCL_TMCLRUN) + " " + args + " 2>&1";
  Out out{-1, ""};
  std::FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return out;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.text.append(buf, n);
  int st = ::pclose(p);
  out.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return out;
}

// A file of exactly `size` bytes: `head`, then comment lines ('#' for scenarios, '//' for .tmc).
std::string make_file(const std::string& name, std::size_t size, const std::string& head, const std::string& comment) {
  // Written line by line: a 64 MiB string built first cost a second of copying.
  std::string path = std::string(TMCL_TMP_DIR) + "/" + name;
  std::ofstream out(path, std::ios::binary);
  std::string line = comment + std::string(1000, 'x') + "\n";
  std::size_t written = head.size();
  out << head;
  for (; written + line.size() <= size; written += line.size()) out << line;
  out << std::string(size - written, '\n');
  return path;
}

bool says(const Out& o, const std::string& s) { return o.text.find(s) != std::string::npos; }

// A file of `limit` bytes is read (the run ends with `at_status`, never with a size message); one
// of limit + 1 bytes is rejected with exit 65 and "is larger than the limit of <limit_text>".
void check_limit(const std::string& name, std::size_t limit, const std::string& head, const std::string& comment,
                 const std::string& option, const std::string& program, int at_status, const std::string& limit_text) {
  std::string at = make_file("at-" + name, limit, head, comment);
  Out ok = tmclrun("--motion ideal " + option + at + " " + program);
  CHECK_EQ(ok.status, at_status);
  CHECK(!says(ok, "larger than the limit"));
  std::string past = make_file("past-" + name, limit + 1, head, comment);
  Out bad = tmclrun("--motion ideal " + option + past + " " + program);
  CHECK_EQ(bad.status, 65);
  CHECK(says(bad, "is larger than the limit of " + limit_text));
  std::remove(at.c_str());
  std::remove(past.c_str());
}

}  // namespace

TEST(program_file_64_MiB) { check_limit("prog.tmc", tmcl::kMaxInputBytes, "STOP\n", "//", "", "", 0, "64 MiB"); }

TEST(scenario_file_16_MiB) {
  std::string prog = make_file("prog.tmc", 5, "STOP\n", "//");
  check_limit("s.scn", tmcl::kMaxScenarioBytes, "at 1ms input 0 = 1\n", "#", "--scenario ", prog, 0, "16 MiB");
}

TEST(eeprom_file_1_MiB) {
  // Not an EEPROM file, so exit 65 at the limit too, but for its content, not its size.
  std::string prog = make_file("prog2.tmc", 5, "STOP\n", "//");
  check_limit("e.eeprom", tmcl::kMaxEepromBytes, "", "#", "--eeprom ", prog, 65, "1 MiB");
}
