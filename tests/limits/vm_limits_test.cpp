// The input-file limits of tmclrun (docs/limits.md), through tmclrun itself: a file at its limit
// is read (its content may still be rejected for other reasons, never for its size), one byte
// more is rejected with a message naming the limit, exit status 65, and nothing crashes.
#define TMCL_TEST_MAIN
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
  std::string path = std::string(TMCL_TMP_DIR) + "/" + name;
  std::string text = head;
  std::string line = comment + std::string(1000, 'x') + "\n";
  while (text.size() + line.size() <= size) text += line;
  text += std::string(size - text.size(), '\n');
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

bool says(const Out& o, const std::string& s) { return o.text.find(s) != std::string::npos; }

}  // namespace

TEST(program_file_64_MiB) {
  std::string at = make_file("at.tmc", tmcl::kMaxInputBytes, "STOP\n", "//");
  Out ok = tmclrun("--motion ideal " + at);
  CHECK_EQ(ok.status, 0);
  CHECK(!says(ok, "larger than the limit"));
  std::string past = make_file("past.tmc", tmcl::kMaxInputBytes + 1, "STOP\n", "//");
  Out bad = tmclrun("--motion ideal " + past);
  CHECK_EQ(bad.status, 65);
  CHECK(says(bad, "is larger than the limit of 64 MiB"));
  std::remove(at.c_str());
  std::remove(past.c_str());
}

TEST(scenario_file_16_MiB) {
  std::string prog = make_file("prog.tmc", 5, "STOP\n", "//");
  std::string at = make_file("at.scn", tmcl::kMaxScenarioBytes, "at 1ms input 0 = 1\n", "#");
  Out ok = tmclrun("--motion ideal --scenario " + at + " " + prog);
  CHECK_EQ(ok.status, 0);
  CHECK(!says(ok, "larger than the limit"));
  std::string past = make_file("past.scn", tmcl::kMaxScenarioBytes + 1, "at 1ms input 0 = 1\n", "#");
  Out bad = tmclrun("--motion ideal --scenario " + past + " " + prog);
  CHECK_EQ(bad.status, 65);
  CHECK(says(bad, "is larger than the limit of 16 MiB"));
  std::remove(at.c_str());
  std::remove(past.c_str());
}

TEST(eeprom_file_1_MiB) {
  std::string prog = make_file("prog2.tmc", 5, "STOP\n", "//");
  std::string at = make_file("at.eeprom", tmcl::kMaxEepromBytes, "", "#");
  Out big = tmclrun("--motion ideal --eeprom " + at + " " + prog);
  CHECK_EQ(big.status, 65);  // not an EEPROM file, but read: the message is about its content
  CHECK(!says(big, "larger than the limit"));
  std::string past = make_file("past.eeprom", tmcl::kMaxEepromBytes + 1, "", "#");
  Out bad = tmclrun("--motion ideal --eeprom " + past + " " + prog);
  CHECK_EQ(bad.status, 65);
  CHECK(says(bad, "is larger than the limit of 1 MiB"));
  std::remove(at.c_str());
  std::remove(past.c_str());
}
