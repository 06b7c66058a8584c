// Unit tests of the assembler library: expressions, symbols, includes, linking of units,
// line information and diagnostics counts. CLI behaviour and messages are pinned by the golden
// suite in tests/golden/asm/.
#include "check.hpp"
#include "tmcl/asm/assembler.hpp"

namespace {

struct Asm {
  tmcl::MemoryReader reader;
  tmcl::AsmOptions opts;
  tmcl::AsmResult run(const std::vector<std::string>& roots = {"main.tmc"}) {
    return tmcl::assemble(roots, opts, reader);
  }
  tmcl::AsmResult src(const std::string& text) {
    reader.files["main.tmc"] = text;
    return run();
  }
};

std::int32_t value_of(const std::string& expr) {
  Asm a;
  a.opts.append_stop = false;
  auto r = a.src("COMP " + expr + "\n");
  CHECK(r.ok());
  if (!r.ok()) std::fprintf(stderr, "%s", r.diags.render(r.sources).c_str());
  return r.program.empty() ? 0 : r.program[0].value;
}

}  // namespace

TEST(expression_precedence_and_literals) {
  CHECK_EQ(value_of("1 + 2 * 3"), 7);
  CHECK_EQ(value_of("(1 + 2) * 3"), 9);
  CHECK_EQ(value_of("1 << 4 | 1"), 17);
  CHECK_EQ(value_of("0x1F + $10 + 0b11 + %11"), 31 + 16 + 3 + 3);
  CHECK_EQ(value_of("7 % 4"), 3);
  CHECK_EQ(value_of("10 %11"), 10 % 11);  // % after an operand is modulo, not a binary prefix
  CHECK_EQ(value_of("-7 / 2"), -3);       // truncates toward zero, like C
  CHECK_EQ(value_of("~0"), -1);
  CHECK_EQ(value_of("6 ^ 3 & 1"), 6 ^ (3 & 1));
  CHECK_EQ(value_of("-(-2147483647 - 1)"), INT32_MIN);  // wraps into the 32-bit field as 0x80000000
  CHECK_EQ(value_of("0xFFFFFFFF"), -1);
  CHECK_EQ(value_of("-16 >> 2"), -4);
}

TEST(forward_references_and_case_insensitive_names) {
  Asm a;
  auto r = a.src("JA later\nSpeed = BASE * 2\nBase = 100\nlater: ROR 0, speed\n");
  CHECK(r.ok());
  CHECK_EQ(r.program.size(), std::size_t{3});
  CHECK_EQ(r.program[0].value, 1);
  CHECK_EQ(r.program[1].value, 200);
}

TEST(keywords_and_expressions_in_keyword_positions) {
  Asm a;
  auto r = a.src("Op = 2\nCALC Op, 5\ncalc mul, 5\nCALCV COMP, 3, 4\nWAIT rfs, 0, 0\n");
  CHECK(r.ok());
  CHECK_EQ(r.program[0].type, 2);
  CHECK_EQ(r.program[1].type, 2);
  CHECK_EQ(r.program[2].type, 11);
  CHECK_EQ(r.program[3].type, 4);
}

TEST(includes_relative_to_the_including_file_and_once_only) {
  Asm a;
  a.reader.files["src/main.tmc"] = "#include \"lib/a.inc\"\n#include lib/a.inc\n#include <TMCLParam.tmc>\nSAP APMaxAcceleration, 0, X\n";
  a.reader.files["src/lib/a.inc"] = "X = 5\n#include b.inc\n";
  a.reader.files["src/lib/b.inc"] = "Y = 6\n";
  auto r = a.run({"src/main.tmc"});
  CHECK(r.ok());
  CHECK_EQ(r.program[0].type, 5);
  CHECK_EQ(r.program[0].value, 5);
  CHECK_EQ(r.sources.files.size(), std::size_t{4});  // main, a.inc, b.inc, TMCLParam.tmc
}

TEST(include_search_order_local_then_I_then_bundled) {
  Asm a;
  a.reader.files["main.tmc"] = "#include TMCLParam.tmc\nCOMP Motor1\n";
  a.reader.files["inc/TMCLParam.tmc"] = "Motor1 = 42\n";
  a.opts.include_dirs = {"inc"};
  auto r = a.run();
  CHECK(r.ok());
  CHECK_EQ(r.program[0].value, 42);  // -I wins over the bundled file
}

TEST(include_cycle_is_one_error) {
  Asm a;
  a.reader.files["main.tmc"] = "#include a.inc\nSTOP\n";
  a.reader.files["a.inc"] = "#include b.inc\n";
  a.reader.files["b.inc"] = "#include a.inc\n";
  auto r = a.run();
  CHECK_EQ(r.diags.error_count(), 1);
  CHECK(r.diags.all()[0].message.find("include cycle: a.inc -> b.inc -> a.inc") != std::string::npos);
}

TEST(units_are_linked_in_order_with_exports) {
  Asm a;
  a.reader.files["main.tmc"] = "#import Home\nCSUB Home\nJA 0\n";
  a.reader.files["lib.tmc"] = "#export Home\nLocal: MST 0\nHome: JA Local\n";
  auto r = a.run({"main.tmc", "lib.tmc"});
  CHECK(r.ok());
  CHECK_EQ(r.program.size(), std::size_t{5});  // 2 + 2 + appended STOP
  CHECK_EQ(r.program[0].value, 3);             // Home is lib's second instruction, after main's 2
  CHECK_EQ(r.program[3].value, 2);             // lib's own label, relocated by main's size
}

TEST(labels_are_local_to_their_unit) {
  Asm a;
  a.reader.files["main.tmc"] = "Same: JA Same\n";
  a.reader.files["lib.tmc"] = "Same: JA Same\n";
  auto r = a.run({"main.tmc", "lib.tmc"});
  CHECK(r.ok());
  CHECK_EQ(r.program[0].value, 0);
  CHECK_EQ(r.program[1].value, 1);
}

TEST(command_line_defines) {
  Asm a;
  a.opts.defines = {{"SPEED", "1000 * 2"}};
  auto r = a.src("ROR 0, Speed\nSPEED = 2000\n");  // same value again: harmless
  CHECK(r.ok());
  CHECK_EQ(r.program[0].value, 2000);
  a.opts.defines = {{"SPEED", "1"}};
  CHECK_EQ(a.src("ROR 0, SPEED\nSpeed = 2\n").diags.error_count(), 1);
}

TEST(line_info_and_appended_stop) {
  Asm a;
  auto r = a.src("\n\nROR 0, 1\n");
  CHECK_EQ(r.lines.size(), std::size_t{2});
  CHECK_EQ(r.lines[0].line, 3);
  CHECK_EQ(r.lines[1].file, -1);
  a.opts.append_stop = false;
  CHECK_EQ(a.src("ROR 0, 1\n").program.size(), std::size_t{1});
  CHECK_EQ(a.src("").program.size(), std::size_t{0});
}

TEST(one_mistake_one_error) {
  Asm a;
  // A broken constant must not produce errors at its uses; a bad mnemonic keeps its address.
  auto r = a.src("X = (1 +\nROR 0, X\nROR 0, X\nBAD 1, 2\nL: JA L\n");
  CHECK_EQ(r.diags.error_count(), 2);
  bool found = false;
  for (const auto& s : r.symbols)
    if (s.name == "L") found = s.value == 3;
  CHECK(found);
}

TEST(program_memory_limit) {
  Asm a;
  a.opts.profile = tmcl::find_profile("usb-2-sd");
  std::string big;
  for (int i = 0; i < 576; ++i) big += "MST 0\n";
  CHECK(a.src(big).ok());  // 576 + appended STOP = 577 fits exactly
  CHECK(!a.src(big + "MST 0\n").ok());
}

TEST(raw_instructions) {
  Asm a;
  a.opts.append_stop = false;
  auto r = a.src(".raw 200, 1, 2, -1\n");
  CHECK(r.ok());
  CHECK(r.program[0] == (tmcl::Instruction{200, 1, 2, -1}));
}

TEST(deep_input_is_an_error_not_a_crash) {
  Asm a;
  std::string deep(100000, '(');
  CHECK(!a.src("COMP " + deep + "1\n").ok());
  std::string chain;
  for (int i = 0; i < 20000; ++i) chain += "c" + std::to_string(i) + " = c" + std::to_string(i + 1) + " + 1\n";
  chain += "c20000 = 0\nCOMP c0\n";
  auto r = a.src(chain);
  CHECK(!r.ok());
}

// Without AsmOptions::symbols the symbol list stays empty, on both paths, and nothing else
// changes: unused constants are still evaluated and their errors reported.
TEST(symbols_can_be_left_out) {
  for (bool fast : {true, false}) {
    for (const char* text : {"X = 3\nL: SAP X, 0, L\n", "#include \"none.tmc\"\n", "X = 3\nY = 1 / 0\nSTOP\n"}) {
      Asm with, without;
      with.opts.fast_path = without.opts.fast_path = fast;
      without.opts.symbols = false;
      auto a = with.src(text);
      auto b = without.src(text);
      CHECK(b.symbols.empty());
      CHECK_EQ(a.ok(), b.ok());
      CHECK_EQ(a.diags.render(a.sources), b.diags.render(b.sources));
      CHECK(a.program == b.program);
    }
  }
  Asm a;
  a.opts.symbols = false;
  CHECK(!a.src("X = 3\nY = 1 / 0\nSTOP\n").ok());
}

// An include named "-" is a file of that name, never standard input (which a DiskReader reads
// for "-"): reading stdin there would consume it behind the user's back.
TEST(an_include_never_reads_standard_input) {
  for (bool fast : {true, false}) {
    Asm a;
    a.opts.fast_path = fast;
    a.reader.files["-"] = "X = 1\n";
    auto r = a.src("#include -\nSAP 1, 0, X\n");
    CHECK(!r.ok());
    CHECK(r.diags.render(r.sources).find("cannot find include file '-'") != std::string::npos);
  }
}
