// Every limit of the assembler (docs/limits.md), tested at the limit (works) and one past it (a
// clear error, never a crash): include depth, expression nesting, evaluation depth, line length,
// file size, names per unit, program size per profile. Also the inputs the fuzzer found that
// exhausted the native stack (kept as regression tests; they run under the sanitizers in CI).
#include <string>

#include "check.hpp"
#include "tmcl/asm/assembler.hpp"

namespace {

struct Run {
  tmcl::AsmResult r;
  std::string messages;
};

Run assemble(tmcl::MemoryReader& reader, const tmcl::Profile* profile = nullptr) {
  tmcl::AsmOptions opts;
  opts.profile = profile;
  Run run{tmcl::assemble({"main.tmc"}, opts, reader), ""};
  run.messages = run.r.diags.render(run.r.sources);
  return run;
}

Run source(const std::string& text, const tmcl::Profile* profile = nullptr) {
  tmcl::MemoryReader reader;
  reader.files["main.tmc"] = text;
  return assemble(reader, profile);
}

bool says(const Run& run, const std::string& text) { return run.messages.find(text) != std::string::npos; }

// A chain of `depth` includes: main.tmc includes i1.inc, which includes i2.inc, ...
Run include_chain(int depth) {
  tmcl::MemoryReader reader;
  reader.files["main.tmc"] = "#include i1.inc\nSTOP\n";
  for (int i = 1; i <= depth; ++i)
    reader.files["i" + std::to_string(i) + ".inc"] =
        i < depth ? "#include i" + std::to_string(i + 1) + ".inc\n" : "X = 1\n";
  return assemble(reader);
}

}  // namespace

TEST(include_depth_64) {
  CHECK(include_chain(64).r.ok());
  Run past = include_chain(65);
  CHECK(!past.r.ok());
  CHECK(says(past, "includes nested more than 64 deep"));
}

TEST(expression_nesting_256) {
  auto nested = [](int n) { return "COMP " + std::string(static_cast<std::size_t>(n), '(') + "1" +
                                   std::string(static_cast<std::size_t>(n), ')') + "\n"; };
  CHECK(source(nested(255)).r.ok());
  Run past = source(nested(300));
  CHECK(!past.r.ok());
  CHECK(says(past, "expression nested more than 256 levels deep"));
  CHECK(!source("COMP " + std::string(100000, '-') + "1\n").r.ok());  // unary chain
}

TEST(evaluation_depth_and_the_fuzzer_inputs) {
  auto chain = [](int n) {
    std::string s = "COMP a0\n";
    for (int i = 0; i < n; ++i) s += "a" + std::to_string(i) + " = a" + std::to_string(i + 1) + " + 1\n";
    return s + "a" + std::to_string(n) + " = 0\n";
  };
  Run ok = source(chain(1000));
  CHECK(ok.r.ok());
  CHECK_EQ(ok.r.program[0].value, 1000);
  Run past = source(chain(5000));  // found by fuzz_asm: overflowed the stack under ASan
  CHECK(says(past, "nested more than 3000 levels deep"));
  CHECK_EQ(past.r.diags.error_count(), 1);
  // Depth multiplied: constants each wrapping the next in 200 unary minus signs (fuzz_asm).
  std::string wide = "COMP c0\n";
  for (int i = 0; i < 1500; ++i) wide += "c" + std::to_string(i) + " = " + std::string(200, '-') + "c" + std::to_string(i + 1) + "\n";
  wide += "c1500 = 1\n";
  Run multiplied = source(wide);
  CHECK(!multiplied.r.ok());
  CHECK_EQ(multiplied.r.diags.error_count(), 1);
  // A long flat expression is no nesting at all.
  std::string flat = "COMP 0";
  for (int i = 0; i < 30000; ++i) flat += "+1";
  Run sum = source(flat + "\n");
  CHECK(sum.r.ok());
  CHECK_EQ(sum.r.program[0].value, 30000);
}

TEST(line_length_65536) {
  std::string comment = "//";
  Run at = source(comment + std::string(65536 - 3, 'x') + "\nSTOP\n");  // 65536 bytes with its newline
  CHECK(at.r.ok());
  Run past = source(comment + std::string(65536, 'x') + "\nSTOP\n");
  CHECK(!past.r.ok());
  CHECK(says(past, "line is longer than 65536 bytes"));
}

TEST(file_size_64_MiB) {
  std::string line = "//" + std::string(65533, 'x') + "\n";  // 65536 bytes
  std::string big;
  big.reserve(64u << 20);
  for (int i = 0; i < 1024; ++i) big += line;
  CHECK_EQ(big.size(), std::size_t{64u << 20});
  CHECK(source(big).r.ok());
  Run past = source(big + "\n");
  CHECK(!past.r.ok());
  CHECK(says(past, "larger than the limit of 64 MiB"));
}

TEST(names_per_unit_1048576) {
  auto names = [](int n) {
    std::string s;
    s.reserve(static_cast<std::size_t>(n) * 12);
    for (int i = 0; i < n; ++i) s += "n" + std::to_string(i) + "=0\n";
    return s;
  };
  CHECK(source(names(1 << 20)).r.ok());
  Run past = source(names((1 << 20) + 2));
  CHECK(!past.r.ok());
  CHECK_EQ(past.r.diags.error_count(), 1);
  CHECK(says(past, "more than 1048576 labels and constants in one unit"));
}

TEST(program_size_per_profile) {
  auto program = [](int n) {
    std::string s;
    for (int i = 0; i < n; ++i) s += "MST 0\n";
    return s + "STOP\n";
  };
  CHECK(source(program(576), tmcl::find_profile("usb-2-sd")).r.ok());  // 577 instructions
  CHECK(says(source(program(577), tmcl::find_profile("usb-2-sd")), "has room for 577"));
  CHECK(source(program(2047), tmcl::find_profile("tmc2300-eval")).r.ok());  // 2048 instructions
  CHECK(says(source(program(2048), tmcl::find_profile("tmc2300-eval")), "has room for 2048"));
  CHECK(source(program(100000)).r.ok());  // generic: no limit
}
