// The formatter (asm/format.cpp) on every source in the repository — examples/, the manuals'
// example programs, include_files/, every golden case: formatting twice gives what formatting
// once gave, and the formatted source assembles to exactly the same bytes for every target.
// Plus the layout rules on small inputs, and sources the formatter must refuse.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "check.hpp"
#include "text_file.hpp"
#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/format.hpp"
#include "tmcl/asm/output.hpp"

namespace {

using tmcl_test::read_text;

namespace fs = std::filesystem;

// Reads from disk, except that one path is served formatted.
class FormattedReader final : public tmcl::FileReader {
 public:
  std::string path, text;
  bool read(const std::string& p, std::string& out) override {
    if (p == path) {
      out = text;
      return true;
    }
    return disk_.read(p, out);
  }
  std::string last_error() const override { return disk_.last_error(); }

 private:
  tmcl::DiskReader disk_;
};

std::string fmt(std::string_view s) {
  tmcl::FormatResult r = tmcl::format_source(s);
  if (!r.ok) return "error: " + r.error;
  return r.text;
}

}  // namespace

TEST(every_repository_source_is_idempotent_and_assembles_identically) {
  std::vector<fs::path> files;
  for (const char* dir : {"examples", "include_files", "tests"})
    for (const auto& e : fs::recursive_directory_iterator(fs::path(TMCL_SOURCE_DIR) / dir))
      if (e.is_regular_file() && (e.path().extension() == ".tmc" || e.path().extension() == ".inc"))
        files.push_back(e.path());
  std::sort(files.begin(), files.end());
  int formatted = 0, assembled = 0;
  for (const auto& f : files) {
    std::string text = read_text(f.string());
    tmcl::FormatResult once = tmcl::format_source(text);
    if (!once.ok) continue;  // sources with lexical errors (golden error cases) are refused
    ++formatted;
    tmcl::FormatResult twice = tmcl::format_source(once.text);
    if (!twice.ok || twice.text != once.text) tmcl_test::fail(__FILE__, __LINE__, "not idempotent: " + f.string());
    for (const char* target : {"generic", "usb-2-sd", "tmc2300-eval"}) {
      tmcl::AsmOptions opts;
      opts.profile = tmcl::find_profile(target);
      tmcl::DiskReader disk;
      tmcl::AsmResult before = tmcl::assemble({f.string()}, opts, disk);
      if (!before.ok()) continue;
      FormattedReader reader;
      reader.path = f.string();
      reader.text = once.text;
      tmcl::AsmResult after = tmcl::assemble({f.string()}, opts, reader);
      ++assembled;
      if (!after.ok() || tmcl::format_output(tmcl::OutputFormat::Bin, before, *opts.profile, 1) !=
                             tmcl::format_output(tmcl::OutputFormat::Bin, after, *opts.profile, 1))
        tmcl_test::fail(__FILE__, __LINE__, std::string("different bytes after formatting: ") + f.string() + " " + target);
    }
  }
  CHECK(formatted > 100);
  CHECK(assembled > 150);
}

TEST(layout) {
  CHECK_EQ(fmt("loop:  mvp abs,0 ,  x+1*(2-3)  ; go\n  stop// end\n"),
           "loop:\n  MVP abs, 0, x + 1 * (2 - 3)  ; go\n  STOP                         // end\n");
  CHECK_EQ(fmt("A:B: sap 4,0,-5\n"), "A:\nB:\n  SAP 4, 0, -5\n");
  CHECK_EQ(fmt("Speed=1000 // fast\nX   =  -(~Speed)\n"), "Speed = 1000  // fast\nX = -(~Speed)\n");
  CHECK_EQ(fmt("\n\n#include   TMCLParam.tmc\n\n\n\n   // indented note\n// note\nstop\n\n\n"),
           "#include TMCLParam.tmc\n\n  // indented note\n// note\n  STOP\n");
  CHECK_EQ(fmt("Here: // a label's comment\n"), "Here:  // a label's comment\n");
  CHECK_EQ(fmt("sap 4, 0, 1 /* inline */ + 2\r\nstop\r\n"), "  SAP 4, 0, 1 /* inline */ + 2\n  STOP\n");
  CHECK_EQ(fmt("/* two\n   lines */ stop\n"), "/* two\n   lines */ stop\n");  // a leading comment keeps the line as it is
  CHECK_EQ(fmt(".raw 5,4,0,1\n"), "  .raw 5, 4, 0, 1\n");
  CHECK_EQ(fmt("calc add,10 % 3\ncalc load,%101\n"), "  CALC add, 10 % 3\n  CALC load, %101\n");
  CHECK_EQ(fmt("\xEF\xBB\xBFstop\n"), "\xEF\xBB\xBF  STOP\n");
  CHECK_EQ(fmt(""), "");
  CHECK_EQ(fmt("stop"), "  STOP\n");
}

TEST(refuses_what_the_lexer_rejects) {
  CHECK_EQ(fmt("sap 4, 0, 12x\n"), "error: 1:11: error: invalid digit 'x' in decimal number");
  CHECK_EQ(fmt("stop\n/* open\n"), "error: 2:1: error: unterminated /* comment");
  CHECK_EQ(fmt("sap 4, 0, @\n"), "error: 1:11: error: unexpected character '@'");
}

TEST(long_lines_stay_within_the_assemblers_limit) {
  std::string expr = "1";
  for (int i = 0; i < 25000; ++i) expr += "+1";
  std::string once = fmt("sap 4, 0, " + expr + "\n");
  CHECK_EQ(once, "  SAP 4, 0, " + expr + "\n");  // spacing it would pass 64 KiB: kept tight
  CHECK_EQ(fmt(once), once);
}

TEST(tokens_include_comments_in_order) {
  auto toks = tmcl::tokenize("L: sap 4 ; c\n/* b */ stop");
  std::string kinds;
  for (const auto& t : toks) kinds += std::to_string(static_cast<int>(t.kind));
  // Name Punct Name Number Comment Newline Comment Name Newline
  CHECK_EQ(kinds, "020156506");
  CHECK_EQ(toks[4].text, "; c");
  CHECK_EQ(toks[6].line, 2);
  CHECK_EQ(toks[7].col, 9);
  CHECK_EQ(toks[7].offset, 21u);
}
