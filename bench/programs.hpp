// Generated programs the benchmarks share (asm_bench, profile_bench, analysis_bench): `lines` lines in the
// style of real programs, with every construct the assembler has to handle on its hot path
// (comments, constants with expressions, labels, instructions with operand expressions). The
// speeds are i % speed_range * 16 + (Base & base_mask) + 1: a small range keeps them inside
// every module's parameter 4 (no warnings against any profile).
#pragma once

#include <string>

namespace tmcl::bench {

inline std::string tmcl_program(int lines, int speed_range = 5000, const char* base_mask = "0xFF") {
  std::string s;
  s.reserve(static_cast<std::size_t>(lines) * 40);
  int n = 0;
  for (int i = 0; n < lines; ++i) {
    s += "// block " + std::to_string(i) + ": move and wait\n";
    s += "Speed" + std::to_string(i) + " = " + std::to_string(i % speed_range) + " * 16 + (Base & " + base_mask + ")\n";
    s += "L" + std::to_string(i) + ":\n";
    s += "  SAP 4, 0, Speed" + std::to_string(i) + " + 1   // maximum speed\n";
    s += "  MVP ABS, 0, -" + std::to_string(i * 7) + "\n";
    s += "  WAIT POS, 0, 0\n";
    s += "  CALC MUL, (1 << 4) | %101\n";
    s += "  JC GE, L" + std::to_string(i) + "\n";
    n += 8;
  }
  s += "Base = $1F\n";
  return s;
}

// An x86 file of tmcl_program's shape for GNU as, the reference run of assembly speed.
inline std::string x86_program(int lines) {
  std::string s;
  s.reserve(static_cast<std::size_t>(lines) * 40);
  int n = 0;
  for (int i = 0; n < lines; ++i) {
    s += "# block " + std::to_string(i) + ": move and wait\n";
    s += ".set Speed" + std::to_string(i) + ", " + std::to_string(i % 5000) + " * 16 + (Base & 0xFF)\n";
    s += "L" + std::to_string(i) + ":\n";
    s += "  movl $Speed" + std::to_string(i) + " + 1, %eax   # maximum speed\n";
    s += "  movl $-" + std::to_string(i * 7) + ", %ebx\n";
    s += "  cmpl %eax, %ebx\n";
    s += "  orl $((1 << 4) | 5), %ecx\n";
    s += "  jge L" + std::to_string(i) + "\n";
    n += 8;
  }
  s += ".set Base, 0x1F\n";
  return s;
}

}  // namespace tmcl::bench
