// The names of a program's source (asm/names.cpp, tmcl/source_names.hpp) for tmclrun --trace and
// the debugger's disassembly: an operand written as a name or an expression over names is shown
// as written, a program address by its label, keywords and numbers as the plain form shows them;
// a line read again finds its mnemonic after labels and comments, on the fast path and the full
// pipeline alike (issue 26, section 2).
#include "check.hpp"
#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/names.hpp"
#include "tmcl/isa.hpp"

namespace {

tmcl::Instruction ins(tmcl::Op op, int type, int motor, std::int32_t value) {
  return {static_cast<std::uint8_t>(op), static_cast<std::uint8_t>(type), static_cast<std::uint8_t>(motor), value};
}

std::string field(const std::array<std::string, 3>& a, tmcl::Field f) { return a[static_cast<std::size_t>(f)]; }

}  // namespace

TEST(named_operands_read_a_line_again) {
  using tmcl::Field;
  using tmcl::Op;
  auto a = tmcl::named_operands("Loop: Again :  jc lt, Loop  // back", ins(Op::JC, 6, 0, 3));
  CHECK_EQ(field(a, Field::Type), std::string());  // a keyword
  CHECK_EQ(field(a, Field::Value), std::string("Loop"));
  a = tmcl::named_operands("  SAP APMaxSpeed ,Motor0, 2*Speed+1 ; speed", ins(Op::SAP, 4, 0, 102401));
  CHECK_EQ(field(a, Field::Type), std::string("APMaxSpeed"));
  CHECK_EQ(field(a, Field::Motor), std::string("Motor0"));
  CHECK_EQ(field(a, Field::Value), std::string("2*Speed+1"));
  a = tmcl::named_operands("SAP 4, 0, 0x1F /* hex */", ins(Op::SAP, 4, 0, 31));
  CHECK(a == (std::array<std::string, 3>{}));  // numbers, also $1F, %101 and 2*3
  a = tmcl::named_operands("SAP $1F, %101, 2*3", ins(Op::SAP, 31, 5, 6));
  CHECK(a == (std::array<std::string, 3>{}));
  a = tmcl::named_operands("CALC MyOp, -Step", ins(Op::CALC, 2, 0, -4));
  CHECK_EQ(field(a, Field::Type), std::string("MyOp"));
  CHECK_EQ(field(a, Field::Value), std::string("-Step"));
  // Not this instruction's line: nothing (the line table pointed elsewhere, a .raw, a comment).
  CHECK(tmcl::named_operands("MVP ABS, 0, Far", ins(Op::SAP, 4, 0, 1)) == (std::array<std::string, 3>{}));
  CHECK(tmcl::named_operands(".raw 5, 4, 0, Speed", ins(Op::SAP, 4, 0, 1)) == (std::array<std::string, 3>{}));
  a = tmcl::named_operands("end of a comment */ CSUB Home", ins(Op::CSUB, 0, 0, 9));
  CHECK_EQ(field(a, Field::Value), std::string("Home"));
}

// A /* */ comment in the operand list is the lexer's, not the end of the line: the operands
// after it are still read, and one inside an expression stands as a blank.
TEST(named_operands_past_an_inline_comment) {
  using tmcl::Field;
  using tmcl::Op;
  auto a = tmcl::named_operands("SAP 4, 0, /* max */ Speed", ins(Op::SAP, 4, 0, 100));
  CHECK_EQ(field(a, Field::Value), std::string("Speed"));
  a = tmcl::named_operands("/* a */ Go: SAP /* b */ APMax, /* c */ Motor0 /* d */, 2*/* e */Speed ; f", ins(Op::SAP, 4, 0, 200));
  CHECK_EQ(field(a, Field::Type), std::string("APMax"));
  CHECK_EQ(field(a, Field::Motor), std::string("Motor0"));
  CHECK_EQ(field(a, Field::Value), std::string("2* Speed"));
  a = tmcl::named_operands("JC /* when */ LT, Loop /* back */", ins(Op::JC, 6, 0, 3));
  CHECK_EQ(field(a, Field::Type), std::string());  // still a keyword
  CHECK_EQ(field(a, Field::Value), std::string("Loop"));
}

TEST(named_instruction_text_with_and_without_names) {
  tmcl::SourceNames names;
  names.labels[3] = "Loop";
  names.operands.resize(2);
  names.operands[1][static_cast<std::size_t>(tmcl::Field::Value)] = "MaxSpeed";
  const auto jc = ins(tmcl::Op::JC, 6, 0, 3), sap = ins(tmcl::Op::SAP, 4, 0, 51200);
  CHECK_EQ(tmcl::named_instruction_text(jc, 0, &names), std::string("JC LT, Loop"));  // a label, though written 3
  CHECK_EQ(tmcl::named_instruction_text(jc, 0, nullptr), std::string("JC LT, 3"));
  CHECK_EQ(tmcl::named_instruction_text(sap, 1, &names), std::string("SAP 4, 0, MaxSpeed"));
  CHECK_EQ(tmcl::named_instruction_text(sap, 7, &names), std::string("SAP 4, 0, 51200"));  // past the table
  CHECK_EQ(tmcl::named_instruction_text(ins(tmcl::Op::JA, 0, 0, 4), 0, &names), std::string("JA 4"));  // no label at 4
  CHECK_EQ(tmcl::named_instruction_text({200, 1, 2, 3}, 0, &names), std::string("?? 200, 1, 2, 3"));
}

TEST(source_names_of_an_assembly_on_both_paths) {
  tmcl::MemoryReader reader;
  reader.files["main.tmc"] = "Speed = 51200\n#include part.inc\nLoop:\n  SAP 4, 0, Speed\n  CSUB Home\n  JA Loop\n";
  reader.files["part.inc"] = "  JA Start\nHome: RSUB\nStart:\n";
  for (bool fast : {true, false}) {
    tmcl::AsmOptions o;
    o.fast_path = fast;
    auto r = tmcl::assemble({"main.tmc"}, o, reader);
    CHECK(r.ok());
    tmcl::SourceNames n = tmcl::source_names(r);
    CHECK_EQ(tmcl::named_instruction_text(r.program[0], 0, &n), std::string("JA Start"));
    CHECK_EQ(tmcl::named_instruction_text(r.program[2], 2, &n), std::string("SAP 4, 0, Speed"));
    CHECK_EQ(tmcl::named_instruction_text(r.program[3], 3, &n), std::string("CSUB Home"));
    CHECK_EQ(tmcl::named_instruction_text(r.program[4], 4, &n), std::string("JA Loop"));
    CHECK_EQ(tmcl::named_instruction_text(r.program[5], 5, &n), std::string("STOP"));  // appended
  }
}
