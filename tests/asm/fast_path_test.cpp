// The fast path (asm/fast_path.cpp) must give exactly the full assembler's result whenever it
// accepts a program, and give up on everything else. Checked on every source in the repository,
// on targeted edge cases, and on thousands of seeded mutations of those sources (a mutation the
// fast path accepts must assemble cleanly and identically through the full assembler).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "check.hpp"
#include "text_file.hpp"
#include "internal.hpp"
#include "same_result.hpp"

namespace {

using tmcl_test::read_text;

namespace fs = std::filesystem;

std::vector<fs::path> repository_sources() {
  std::vector<fs::path> out;
  for (const char* dir : {"examples", "tests"})
    for (const auto& e : fs::recursive_directory_iterator(fs::path(TMCL_SOURCE_DIR) / dir))
      if (e.is_regular_file() && e.path().extension() == ".tmc") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<const tmcl::Profile*> targets() {
  return {nullptr, tmcl::find_profile("usb-2-sd"), tmcl::find_profile("tmc2300-eval")};
}

struct Input {
  std::string path = "main.tmc";
  tmcl::MemoryReader memory;  // main.tmc and what it includes (unless `disk`)
  bool disk = false;
  std::vector<std::pair<std::string, std::string>> defines;
};

tmcl::AsmOptions options_for(const Input& in, const tmcl::Profile* target) {
  tmcl::AsmOptions o;
  o.profile = target;
  o.defines = in.defines;
  return o;
}

// The fast path alone; accepted tells whether it handled the program.
tmcl::AsmResult fast(Input& in, const tmcl::Profile* target, bool& accepted) {
  tmcl::DiskReader disk;
  tmcl::FileReader& reader = in.disk ? static_cast<tmcl::FileReader&>(disk) : in.memory;
  std::string text, copy;
  reader.read(in.path, text);
  copy = text;
  tmcl::AsmResult r;
  accepted = tmcl::detail::fast_assemble(in.path, options_for(in, target), reader, copy, r);
  if (!accepted) CHECK(copy == text);  // given back unchanged for the full assembler
  return r;
}

tmcl::AsmResult full(Input& in, const tmcl::Profile* target) {
  tmcl::DiskReader disk;
  tmcl::FileReader& reader = in.disk ? static_cast<tmcl::FileReader&>(disk) : in.memory;
  tmcl::AsmOptions o = options_for(in, target);
  o.fast_path = false;
  return tmcl::assemble({in.path}, o, reader);
}

// Whenever the fast path accepts a program, the full assembler must succeed silently with the
// same result.
bool agrees(Input& in, const tmcl::Profile* target, bool& accepted) {
  tmcl::AsmResult f = fast(in, target, accepted);
  if (!accepted) return true;
  tmcl::AsmResult r = full(in, target);
  std::string diff = tmcl_test::result_difference(f, r);
  if (diff.empty()) return true;
  std::fprintf(stderr, "fast path differs (%s) on %s:\n%s\n--- full assembler says:\n%s\n", diff.c_str(), in.path.c_str(),
               in.disk ? "" : in.memory.files[in.path].c_str(), r.diags.render(r.sources).c_str());
  return false;
}

bool agrees(const std::string& text, const tmcl::Profile* target, bool& accepted) {
  Input in;
  in.memory.files[in.path] = text;
  return agrees(in, target, accepted);
}

TEST(every_repository_source_agrees_through_the_public_interface) {
  int files = 0;
  for (const auto& path : repository_sources()) {
    for (const auto* target : targets()) {
      tmcl::DiskReader reader;
      tmcl::AsmOptions on, off;
      on.profile = off.profile = target;
      on.append_stop = off.append_stop = target != nullptr;  // both ways over the targets
      off.fast_path = false;
      auto a = tmcl::assemble({path.string()}, on, reader);
      auto b = tmcl::assemble({path.string()}, off, reader);
      std::string diff = tmcl_test::result_difference(a, b);
      if (!diff.empty()) std::fprintf(stderr, "%s: %s\n", path.string().c_str(), diff.c_str());
      CHECK(diff.empty());
    }
    ++files;
  }
  CHECK(files > 100);
}

TEST(the_fast_path_takes_most_plain_programs) {
  int accepted_count = 0, total = 0;
  for (const auto& path : repository_sources()) {
    bool accepted = false;
    Input in;
    in.path = path.string();
    in.disk = true;
    CHECK(agrees(in, nullptr, accepted));
    accepted_count += accepted;
    ++total;
  }
  std::printf("fast path accepted %d of %d repository sources (generic target)\n", accepted_count, total);
  CHECK(accepted_count >= 70);  // the rest are golden error cases or use #export, #import, .raw
}

TEST(edge_cases) {
  struct Case {
    const char* text;
    bool accepted;
  };
  const Case cases[] = {
      {"SAP 4, 0, %101\n", true},                      // '%' after a comma: a binary number
      {"SAP %1, 0, 0\n", false},                       // after the mnemonic: the modulo operator
      {"X = %101 % %11\nSAP X, 0, 0\n", true},
      {"JA Later\nLater: STOP\n", true},                // forward label
      {"A = B + 1\nB = 2\nSAP A, 0, B\n", true},        // forward constant
      {"A = B\nB = A\n", false},                        // a cycle
      {"/* two\nlines */ SAP 1, /* x\n */ 2, 3\nSTOP\n", true},
      {"SAP 1, 2, 3 ; /* not a block comment\nSTOP\n", true},
      {"SAP 1, 2, 3 // x /* y\nSTOP\n", true},
      {"SAP 1, 2, 3 /* unterminated\n", false},
      {"L1: L2: L3: STOP\n", true},
      {"WAIT TICKS, 0, 100\nJC GE, 0\nCALC MUL, 3\nMVP REL, 0, -(1 << 10)\n", true},
      {"ABS = 3\n", false},                              // a keyword's name: warned about
      {"JC 99, 0\n", false},                             // not a condition: warned about
      {"JA 5\n", false},                                 // outside the program: warned about
      {"SAP 1, 256, 0\n", false},                        // does not fit
      {"SAP 1, 0, 4294967295\nSAP 1, 0, -2147483648\n", true},
      {"SAP 1, 0, 4294967296\n", false},
      {"X = 1 / 0\n", false},
      {"X = 1 << 64\n", false},
      {"X = 9223372036854775807\nSAP 1, 0, X & 1\n", true},
      {"X = 9223372036854775808\n", false},
      {"L: X = 3\nSAP X, 0, L\n", true},
      {"L:\nL:\n", false},                               // duplicate label
      {"X = 1\nX = 1\nSAP X, 0, 0\n", true},           // the same value again: harmless
      {"X = 1\nX = 2\n", false},                         // another value: an error
      {"X = 1\nX = 2 / 0\n", false},
      {"X = 1\nX: STOP\n", false},
      {"X: STOP\nX = 1\n", false},
      {"#include \"a.tmc\"\n", false},
      {".raw 1, 2, 3, 4\n", false},
      {"SAP 1, 2\n", false},
      {"SAP 1, 2, 3, 4\n", false},
      {"STOP 1\n", false},
      {"caf\xC3\xA9: STOP\n", false},
      {"// caf\xC3\xA9 in a comment\r\nSTOP\r\n", true},
      {"\xEF\xBB\xBFSTOP\n", true},                      // a byte-order mark
      {"SAP 1, 2, 0x1G\n", false},
      {"SAP 1, 2, $\n", false},
      {"SAP 1, 2, 0b\n", false},
      {"SAP 1, 2, 12abc\n", false},
      {"SAP 1, 2, 3 4\n", false},
      {"SAP 1, 2, (3\n", false},
      {"SAP 1, 2, 3)\n", false},
      {"SAP 1, 2, 3 < 4\n", false},
      {"SAP 1, 2, ~-+3\n", true},
      {"", false},  // no instructions: the full assembler warns, so the fast path gives up
      {"STOP", true},
      {"FOO 1\n", false},
      {"Loop\n", false},
  };
  for (const auto& c : cases) {
    for (const auto* target : targets()) {
      bool accepted = false;
      CHECK(agrees(c.text, target, accepted));
      if (target == nullptr && accepted != c.accepted)
        std::fprintf(stderr, "expected the fast path to %s: %s\n", c.accepted ? "accept" : "give up", c.text);
      if (target == nullptr) CHECK(accepted == c.accepted);
    }
  }
}

// A control byte anywhere, a comment included, makes the full assembler take the file for binary
// data ("is not TMCL source"): the fast path, which skips a comment unread, gives up on it too
// (fuzz_asm found a NUL in a comment that only the fast path accepted). White space does not.
TEST(binary_bytes_in_comments_send_the_file_to_the_full_assembler) {
  for (const char byte : {'\0', '\x01', '\x08', '\x0E', '\x19', '\x1F', '\x7F'}) {
    const std::string text = std::string("// a comment with a ") + byte + " byte\nSTOP\n";
    bool accepted = true;
    CHECK(agrees(text, nullptr, accepted));
    CHECK(!accepted);
    Input in;
    in.memory.files[in.path] = text;
    const tmcl::AsmResult r = full(in, nullptr);
    CHECK(!r.ok());
    CHECK(r.diags.render(r.sources).find("is not TMCL source") != std::string::npos);
  }
  bool accepted = false;
  CHECK(agrees("// tab\there, form feed\f, vertical tab\v\r\nSTOP\r\n", nullptr, accepted));
  CHECK(accepted);
}

TEST(includes) {
  struct Case {
    std::vector<std::pair<std::string, std::string>> files;  // the first is main.tmc
    bool accepted;
  };
  const Case cases[] = {
      {{{"main.tmc", "#include \"inc.tmc\"\nSAP X, 0, L\n"}, {"inc.tmc", "X = 4\nL: STOP\n"}}, true},
      {{{"main.tmc", "#include inc.tmc ; bare, with a comment\nSAP X, 0, 0\n"}, {"inc.tmc", "X = 4\n"}}, true},
      {{{"main.tmc", "L: #include <inc.tmc> /* c\n */\nJA L\n"}, {"inc.tmc", "X = 4\n"}}, true},
      {{{"main.tmc", "#INCLUDE \"inc.tmc\"\n#include \"inc.tmc\"\nSAP X, 0, 0\n"}, {"inc.tmc", "X = 4\n"}}, true},
      {{{"main.tmc", "#include \"TMCLParam.tmc\"\nSAP APMaxPositioningSpeed, 0, 100\n"}}, true},  // bundled
      {{{"main.tmc", "#include \"a.tmc\"\n"}, {"a.tmc", "#include \"b.tmc\"\n"}, {"b.tmc", "#include \"a.tmc\"\n"}}, false},
      {{{"main.tmc", "#include \"inc.tmc\" junk\n"}, {"inc.tmc", "X = 4\n"}}, false},
      {{{"main.tmc", "#include \"inc.tmc\n"}, {"inc.tmc", "X = 4\n"}}, false},
      {{{"main.tmc", "#include\n"}}, false},
      {{{"main.tmc", "#include \"missing.tmc\"\n"}}, false},
      {{{"main.tmc", "#include \"inc.tmc\"\n"}, {"inc.tmc", "X = 4\nX = 5\n"}}, false},
      {{{"main.tmc", "#include \"inc.tmc\"\nX: STOP\n"}, {"inc.tmc", "X = 4\n"}}, false},
      {{{"main.tmc", "#include \"inc.tmc\"\nX = 4\nSTOP\n"}, {"inc.tmc", "X = 4\n"}}, true},  // the same value again
      {{{"main.tmc", "#include \"inc.tmc\"\nX = 4\n"}, {"inc.tmc", "X = 4\n"}}, false},  // no instructions: a warning
      {{{"main.tmc", "#include \"inc.tmc\"\n"}, {"inc.tmc", "\xEF\xBB\xBFX = 4\nSTOP\n"}}, true},
      {{{"main.tmc", "#export X\nX = 1\n"}}, false},
      {{{"main.tmc", "#no_append_stop\nSTOP\n"}}, false},
  };
  for (const auto& c : cases) {
    Input in;
    for (const auto& [name, text] : c.files) in.memory.files[name] = text;
    bool accepted = false;
    CHECK(agrees(in, nullptr, accepted));
    if (accepted != c.accepted)
      std::fprintf(stderr, "expected the fast path to %s: %s\n", c.accepted ? "accept" : "give up", c.files[0].second.c_str());
    CHECK(accepted == c.accepted);
  }
}

TEST(command_line_definitions) {
  struct Case {
    std::vector<std::pair<std::string, std::string>> defines;
    const char* text;
    bool accepted;
  };
  const Case cases[] = {
      {{{"SPEED", "1000"}, {"Axis", "1 + 1"}}, "SAP 4, AXIS, Speed\n", true},
      {{{"UNUSED", "1 / 0"}}, "STOP\n", false},            // still evaluated, still an error
      {{{"X", "1"}, {"X", "1"}}, "STOP\n", true},           // twice, the same value
      {{{"X", "1"}, {"X", "2"}}, "STOP\n", false},
      {{{"X", "1"}}, "X = 1\nSTOP\n", true},               // again in the source, the same value
      {{{"X", "1"}}, "X = 2\nSTOP\n", false},              // another value
      {{{"X\x11", "1"}}, "SAP 1, 0, X1\n", false},          // not a name
      {{{"X", "2 3"}}, "SAP 1, 0, X\n", false},
      {{{"X", "Y * 2"}}, "Y = 3\nSAP 1, 0, X\n", true},    // a -D value may use the program's names
  };
  for (const auto& c : cases) {
    Input in;
    in.memory.files["main.tmc"] = c.text;
    in.defines = c.defines;
    bool accepted = false;
    CHECK(agrees(in, nullptr, accepted));
    if (accepted != c.accepted)
      std::fprintf(stderr, "expected the fast path to %s: %s\n", c.accepted ? "accept" : "give up", c.text);
    CHECK(accepted == c.accepted);
  }
}

TEST(a_byte_order_mark_survives_giving_up) {
  std::string text = "\xEF\xBB\xBF#bogus\nSTOP\n";
  tmcl::MemoryReader reader;
  reader.files["main.tmc"] = text;
  tmcl::AsmOptions on, off;
  off.fast_path = false;
  auto a = tmcl::assemble({"main.tmc"}, on, reader);
  auto b = tmcl::assemble({"main.tmc"}, off, reader);
  CHECK(!a.ok());
  CHECK(tmcl_test::result_difference(a, b).empty());
}

// Small edits of real programs: whatever the fast path accepts must be right.
TEST(seeded_mutations_never_fool_the_fast_path) {
  std::mt19937 rng(20261122);
  const std::string alphabet = "\n;/*%$#.,:=()+-~<>&|^019abfxXLqZ_ \t\r\xE9\"";
  int tried = 0, accepted_count = 0;
  for (const auto& path : repository_sources()) {
    std::string base = read_text(path.string());
    bool accepted = false;
    Input plain;
    plain.memory.files[plain.path] = base;
    (void)fast(plain, nullptr, accepted);
    if (!accepted || base.size() > 20000 || base.empty()) continue;
    for (int m = 0; m < 60; ++m) {
      std::string t = base;
      int edits = 1 + static_cast<int>(rng() % 3);
      for (int e = 0; e < edits && !t.empty(); ++e) {
        std::size_t at = rng() % t.size();
        switch (rng() % 4) {
          case 0: t.erase(at, 1); break;
          case 1: t.insert(at, 1, alphabet[rng() % alphabet.size()]); break;
          case 2: t[at] = alphabet[rng() % alphabet.size()]; break;
          case 3: {  // repeat a line elsewhere
            std::size_t s = t.rfind('\n', at);
            s = s == std::string::npos ? 0 : s + 1;
            std::size_t n = t.find('\n', at);
            std::string line = t.substr(s, n == std::string::npos ? std::string::npos : n - s + 1);
            t.insert(rng() % t.size(), line);
            break;
          }
        }
      }
      const auto* target = targets()[rng() % 3];
      bool ok = false;
      CHECK(agrees(t, target, ok));
      accepted_count += ok;
      ++tried;
    }
  }
  std::printf("%d mutations, %d accepted by the fast path\n", tried, accepted_count);
  CHECK(tried > 1000);
  CHECK(accepted_count > 100);
}

}  // namespace
