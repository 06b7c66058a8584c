// The control-flow analysis at scale (docs/limits.md, docs/analysis.md): warnings of one kind
// past --error-limit are counted, kept no longer and summed up in one line; a call chain as deep
// as the program is long costs a list of its calls once, not once per subroutine. Speed itself is
// measured by tests/bench/analysis_bench.cpp, never here.
#include <string>

#include "check.hpp"
#include "tmcl/analysis.hpp"
#include "tmcl/asm/assembler.hpp"

namespace {

struct Checked {
  tmcl::AsmResult r;
  tmcl::Analysis a;
  std::string messages;
};

// Assembles and analyses `text` as tmclasm does: at most `limit` warnings of each kind kept.
Checked check(const std::string& text, int limit, const tmcl::Profile* profile = nullptr) {
  tmcl::MemoryReader reader;
  reader.files["main.tmc"] = text;
  tmcl::AsmOptions opts;
  opts.profile = profile;
  Checked c{tmcl::assemble({"main.tmc"}, opts, reader), {}, ""};
  c.r.diags.set_kind_limit(limit);
  if (c.r.ok()) c.a = tmcl::analyze(tmcl::analysis_input(c.r), c.r.diags);
  c.messages = c.r.diags.render(c.r.sources, limit);
  return c;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

}  // namespace

TEST(warnings_of_one_kind_past_the_limit_are_one_line) {
  // 50 subroutines, each with two instructions after its RSUB that nothing reaches.
  std::string s;
  for (int k = 0; k < 50; ++k) s += "CSUB S" + std::to_string(k) + "\n";
  s += "STOP\n";
  for (int k = 0; k < 50; ++k) s += "S" + std::to_string(k) + ": RSUB\nMST 0\nMST 1\n";
  Checked c = check(s, 20);
  CHECK_EQ(c.r.diags.warning_count(), 50);
  CHECK_EQ(c.r.diags.all().size(), std::size_t{20});  // the other 30 only counted
  CHECK_EQ(count(c.messages, "[-Wunreachable]"), std::size_t{20});
  CHECK(c.messages.find("note: 30 more -Wunreachable warnings not shown (--error-limit N changes the limit, 0 shows all)\n") !=
        std::string::npos);
  // The first 20 in source order are the ones shown (subroutine k's MST 0 is on line 53 + 3k).
  CHECK(c.messages.find("main.tmc:53:") != std::string::npos);
  CHECK(c.messages.find("main.tmc:110:") != std::string::npos);
  CHECK(c.messages.find("main.tmc:113:") == std::string::npos);
  // No limit: all kept and shown.
  Checked all = check(s, 0);
  CHECK_EQ(all.r.diags.all().size(), std::size_t{50});
  CHECK_EQ(count(all.messages, "[-Wunreachable]"), std::size_t{50});
  CHECK(all.messages.find("more -Wunreachable") == std::string::npos);
}

TEST(each_kind_is_summed_up_on_its_own) {
  // 25 parameters USB-2-SD does not have (-Wtarget) and 25 unreachable stretches: 20 of each.
  std::string s;
  for (int k = 0; k < 25; ++k) s += "SAP 200, 0, " + std::to_string(k) + "\nCSUB S" + std::to_string(k) + "\n";
  s += "STOP\n";
  for (int k = 0; k < 25; ++k) s += "S" + std::to_string(k) + ": RSUB\nMST 0\n";
  Checked c = check(s, 20, tmcl::find_profile("usb-2-sd"));
  CHECK_EQ(c.r.diags.warning_count(), 50);
  CHECK_EQ(count(c.messages, "[-Wtarget]"), std::size_t{20});
  CHECK_EQ(count(c.messages, "[-Wunreachable]"), std::size_t{20});
  CHECK(c.messages.find("note: 5 more -Wtarget warnings not shown") != std::string::npos);
  CHECK(c.messages.find("note: 5 more -Wunreachable warnings not shown") != std::string::npos);
  // -Wno-NAME: not counted at all.
  tmcl::MemoryReader reader;
  reader.files["main.tmc"] = s;
  tmcl::AsmOptions opts;
  opts.profile = tmcl::find_profile("usb-2-sd");
  auto r = tmcl::assemble({"main.tmc"}, opts, reader);
  tmcl::WarningOptions w;
  std::string err;
  CHECK(w.parse("-Wno-unreachable", err));
  r.diags.set_warning_options(w);
  r.diags.set_kind_limit(20);
  tmcl::analyze(tmcl::analysis_input(r), r.diags);
  CHECK_EQ(r.diags.warning_count(), 25);
}

TEST(a_call_chain_10000_deep) {
  // Main calls S0, S0 calls S1, ... S9999: each subroutine's deepest chain is the rest of it.
  const int depth = 10000;
  std::string s = "CSUB S0\nSTOP\n";
  for (int k = 0; k < depth; ++k)
    s += "S" + std::to_string(k) + ": " + (k + 1 < depth ? "CSUB S" + std::to_string(k + 1) + "\n" : "MST 0\n") + "RSUB\n";
  Checked c = check(s, 20);
  CHECK_EQ(c.a.main_depth, depth);
  CHECK_EQ(c.r.diags.warning_count(), 1);  // the 9th nested call
  CHECK(c.messages.find("the chain is 10000 calls deep") != std::string::npos);
  CHECK_EQ(tmcl::deepest_chain(c.a, 0).size(), std::size_t{depth});
  CHECK_EQ(tmcl::deepest_chain(c.a, 1, 9).size(), std::size_t{9});
  // The stack report names each region's first 9 calls and how many more there are, and its
  // columns make room for a depth of five digits.
  std::string report = tmcl::stack_usage_report(c.a, tmcl::analysis_input(c.r));
  CHECK(report.find("main    main        address 0     depth 10000 main > S0 > S1 > S2 > S3 > S4 > S5 > S6 > S7 > S8 > ... "
                    "(9991 more calls)\n") != std::string::npos);
  CHECK(report.size() < std::size_t{depth} * 200);
}
