// Generated programs the benchmarks share (asm_bench, profile_bench, analysis_bench): `lines` lines in the
// style of real programs, with every construct the assembler has to handle on its hot path
// (comments, constants with expressions, labels, instructions with operand expressions). The
// speeds are i % speed_range * 16 + (Base & base_mask) + 1: a small range keeps them inside
// every module's parameter 4 (no warnings against any profile).
#pragma once

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <string>
#include <vector>

#include "tmcl/codec.hpp"
#include "tmcl/isa.hpp"

namespace tmcl::bench {

// One instruction of a program given as a list (vm_bench, debug_bench: the assembler is not on
// their measured path).
inline Instruction I(Op op, int type = 0, int motor = 0, std::int32_t value = 0) {
  return Instruction{static_cast<std::uint8_t>(op), static_cast<std::uint8_t>(type), static_cast<std::uint8_t>(motor), value};
}

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

// The x86 peer of a TMCL program: the file GNU as reads in the "vs GNU as" rows (asm_bench,
// analysis_bench). A ratio to GNU as depends on what GNU as reads, so its file is made from the
// TMCL program itself, line for line, each line an x86 line of the same kind: both assemblers read
// the same lines, comments, constant definitions (with the same expressions and forward
// references), labels, label references and operand expressions (docs/performance.md, "The x86
// peer"):
//   // TEXT                      ->  # TEXT
//   NAME = EXPR                  ->  .set NAME, EXPR            ($1F -> 0x1F, %101 -> 0b101)
//   LABEL: (alone or in front)   ->  LABEL:
//   JA / JC c / CSUB / DJNZ n, L ->  jmp / jge / call / loop L  (a label reference)
//   RSUB / RETI / STOP           ->  ret / iret / hlt
//   any other instruction        ->  movl $EXPR, D(%rbx): EXPR its last number or expression,
//                                    D = 256 * type + motor from the numbers before it (none:
//                                    movl $EXPR, %ebx); keywords (ABS, POS, ADD, GE) are x86's
//                                    opcode bits and read as nothing; no number at all: cmpl %eax, %ebx
inline std::string x86_expression(std::string e) {
  std::string out;
  for (std::size_t k = 0; k < e.size(); ++k) {
    const bool starts = k == 0 || !(std::isalnum(static_cast<unsigned char>(e[k - 1])) || e[k - 1] == '_');
    if (starts && e[k] == '$' && k + 1 < e.size() && std::isxdigit(static_cast<unsigned char>(e[k + 1]))) {
      out += "0x";
    } else if (starts && e[k] == '%' && k + 1 < e.size() && (e[k + 1] == '0' || e[k + 1] == '1')) {
      out += "0b";
    } else {
      out += e[k];
    }
  }
  return out;
}

inline std::string x86_trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

inline std::string x86_line(std::string line) {
  std::string comment;
  if (auto c = line.find("//"); c != std::string::npos) {
    comment = "# " + x86_trim(line.substr(c + 2));
    line = line.substr(0, c);
  }
  std::string out = line.substr(0, line.find_first_not_of(" \t") == std::string::npos ? line.size() : line.find_first_not_of(" \t"));
  line = x86_trim(line);
  if (auto eq = line.find(" = "); eq != std::string::npos && line.find(':') == std::string::npos) {
    out += ".set " + x86_trim(line.substr(0, eq)) + ", " + x86_expression(x86_trim(line.substr(eq + 3)));
  } else {
    if (auto colon = line.find(':'); colon != std::string::npos) {
      out += line.substr(0, colon + 1);
      line = x86_trim(line.substr(colon + 1));
      if (!line.empty()) out += " ";
    }
    if (!line.empty()) {
      const auto sp = line.find(' ');
      const std::string m = line.substr(0, sp);
      std::vector<std::string> ops;
      for (std::string rest = sp == std::string::npos ? "" : line.substr(sp + 1); !rest.empty();) {
        const auto comma = rest.find(',');
        ops.push_back(x86_trim(rest.substr(0, comma)));
        rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
      }
      auto keyword = [](const std::string& o) {
        return !o.empty() && std::all_of(o.begin(), o.end(), [](char c) { return c >= 'A' && c <= 'Z'; });
      };
      if (m == "JA" || m == "JC" || m == "CSUB" || m == "DJNZ") {
        out += std::string(m == "JA" ? "jmp " : m == "JC" ? "jge " : m == "CSUB" ? "call " : "loop ") + ops.back();
      } else if (m == "RSUB" || m == "RETI" || m == "STOP") {
        out += m == "RSUB" ? "ret" : m == "RETI" ? "iret" : "hlt";
      } else {
        std::vector<std::string> numbers;
        for (const auto& o : ops)
          if (!keyword(o)) numbers.push_back(o);
        if (numbers.empty()) {
          out += "cmpl %eax, %ebx";
        } else {
          long d = 0;
          for (std::size_t k = 0; k + 1 < numbers.size(); ++k) d = d * 256 + std::strtol(numbers[k].c_str(), nullptr, 0);
          out += "movl $" + x86_expression(numbers.back()) +
                 (numbers.size() > 1 ? ", " + std::to_string(d) + "(%rbx)" : std::string(", %ebx"));
        }
      }
    }
  }
  if (!comment.empty()) out += (x86_trim(out).empty() ? "" : "   ") + comment;
  return out;
}

inline std::string x86_peer(const std::string& tmcl) {
  std::string s;
  s.reserve(tmcl.size() + tmcl.size() / 2);
  std::size_t at = 0;
  while (at < tmcl.size()) {
    auto nl = tmcl.find('\n', at);
    if (nl == std::string::npos) nl = tmcl.size();
    s += x86_line(tmcl.substr(at, nl - at));
    s += '\n';
    at = nl + 1;
  }
  return s;
}

}  // namespace tmcl::bench
