// The parts of the language the full pipeline and the fast path (fast_path.cpp) both read, each
// defined once: which punctuation is a binary operator, its precedence and what it computes, and
// how the file name after #include is delimited. The parser (precedence), the resolver (values,
// expr.cpp), the lexer (include names) and the fast path all call these, so the two paths cannot
// drift apart; tests/asm/fast_path_test checks that they give the same results.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "chars.hpp"
#include "internal.hpp"

namespace tmcl::detail {

// C precedence: | ^ & << >> + - * / % (higher binds tighter); 0 for anything else.
constexpr int binary_precedence(P p) {
  switch (p) {
    case P::Pipe: return 1;
    case P::Caret: return 2;
    case P::Amp: return 3;
    case P::Shl:
    case P::Shr: return 4;
    case P::Plus:
    case P::Minus: return 5;
    case P::Star:
    case P::Slash:
    case P::Percent: return 6;
    default: return 0;
  }
}

// The binary operator that starts with character c ('<' starts <<, '>' starts >>), else P::None.
constexpr P binary_operator_of(char c) {
  switch (c) {
    case '|': return P::Pipe;
    case '^': return P::Caret;
    case '&': return P::Amp;
    case '<': return P::Shl;
    case '>': return P::Shr;
    case '+': return P::Plus;
    case '-': return P::Minus;
    case '*': return P::Star;
    case '/': return P::Slash;
    case '%': return P::Percent;
    default: return P::None;
  }
}

// Why a binary operation has no value (the full pipeline reports it; the fast path gives up).
enum class OpFault : std::uint8_t { None, DivisionByZero, ModuloByZero, ShiftCount, NotBinary };

// a OP b, wrapping like the 64-bit two's complement machine the language models; the result goes
// to `out` only when there is one.
constexpr OpFault apply_binary(P op, std::int64_t a, std::int64_t b, std::int64_t& out) {
  auto ua = static_cast<std::uint64_t>(a), ub = static_cast<std::uint64_t>(b);
  switch (op) {
    case P::Plus: out = static_cast<std::int64_t>(ua + ub); return OpFault::None;
    case P::Minus: out = static_cast<std::int64_t>(ua - ub); return OpFault::None;
    case P::Star: out = static_cast<std::int64_t>(ua * ub); return OpFault::None;
    case P::Slash:
    case P::Percent:
      if (b == 0) return op == P::Slash ? OpFault::DivisionByZero : OpFault::ModuloByZero;
      if (b == -1) out = op == P::Slash ? static_cast<std::int64_t>(0 - ua) : 0;  // INT64_MIN / -1 wraps
      else out = op == P::Slash ? a / b : a % b;
      return OpFault::None;
    case P::Amp: out = static_cast<std::int64_t>(ua & ub); return OpFault::None;
    case P::Pipe: out = static_cast<std::int64_t>(ua | ub); return OpFault::None;
    case P::Caret: out = static_cast<std::int64_t>(ua ^ ub); return OpFault::None;
    case P::Shl:
    case P::Shr:
      if (b < 0 || b > 63) return OpFault::ShiftCount;
      out = op == P::Shl ? static_cast<std::int64_t>(ua << ub) : (a >> b);
      return OpFault::None;
    default: return OpFault::NotBinary;
  }
}

// Where the file name after "#include" lies in `src`, reading from `at` (just after the word):
// blanks, then "quoted" or <angled> up to the closing character on the same line, or a bare
// name up to a comment (//, /*, ;) or the line end, trailing blanks trimmed.
struct IncludeNameSpan {
  std::size_t begin = 0, end = 0;  // the name as the lexer's token: with its quotes or angles
  std::size_t next = 0;            // where reading goes on
  bool unclosed = false;           // a quote or angle with no closing one on its line (at `begin`)
};

// The file name a name token (src[begin, end) above) stands for: without its quotes or angles.
constexpr std::string_view include_file_name(std::string_view token) {
  if (!token.empty() && (token.front() == '"' || token.front() == '<')) return token.substr(1, token.size() - 2);
  return token;
}

constexpr IncludeNameSpan scan_include_name(std::string_view src, std::size_t at) {
  IncludeNameSpan s;
  while (at < src.size() && (src[at] == ' ' || src[at] == '\t')) ++at;
  s.begin = at;
  char open = at < src.size() ? src[at] : '\0';
  if (open == '"' || open == '<') {
    std::size_t close = src.find(open == '"' ? '"' : '>', at + 1);
    std::size_t eol = src.find('\n', at);
    if (close == std::string_view::npos || (eol != std::string_view::npos && close > eol)) {
      s.unclosed = true;
      s.end = s.next = at;
      return s;
    }
    s.end = s.next = close + 1;
    return s;
  }
  std::size_t end = at;
  while (end < src.size() && src[end] != '\n' && src[end] != ';' &&
         !(src[end] == '/' && end + 1 < src.size() && (src[end + 1] == '/' || src[end + 1] == '*')))
    ++end;
  std::size_t trimmed = end;
  while (trimmed > at && char_class(src[trimmed - 1]) == kSpace) --trimmed;
  s.end = trimmed;
  s.next = end;
  return s;
}

}  // namespace tmcl::detail
