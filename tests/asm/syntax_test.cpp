// The language pieces the full pipeline and the fast path share (asm/syntax.hpp): operator
// precedence and values at their edges, and where an #include file name starts and ends. The
// equality of the two paths on whole programs is fast_path_test's job; this pins the one
// definition both read.
#include "check.hpp"
#include "syntax.hpp"

using namespace tmcl::detail;

namespace {

std::int64_t value(P op, std::int64_t a, std::int64_t b, OpFault want = OpFault::None) {
  std::int64_t v = 12345;
  CHECK(apply_binary(op, a, b, v) == want);
  return v;
}

std::string name_of(std::string_view src) {
  IncludeNameSpan s = scan_include_name(src, 0);
  if (s.unclosed) return "<unclosed>";
  return std::string(include_file_name(src.substr(s.begin, s.end - s.begin)));
}

}  // namespace

TEST(precedence_is_c) {
  CHECK(binary_precedence(P::Pipe) < binary_precedence(P::Caret));
  CHECK(binary_precedence(P::Caret) < binary_precedence(P::Amp));
  CHECK(binary_precedence(P::Amp) < binary_precedence(P::Shl));
  CHECK_EQ(binary_precedence(P::Shl), binary_precedence(P::Shr));
  CHECK(binary_precedence(P::Shr) < binary_precedence(P::Plus));
  CHECK_EQ(binary_precedence(P::Plus), binary_precedence(P::Minus));
  CHECK(binary_precedence(P::Minus) < binary_precedence(P::Star));
  CHECK_EQ(binary_precedence(P::Star), binary_precedence(P::Percent));
  CHECK_EQ(binary_precedence(P::Tilde), 0);
  CHECK_EQ(binary_precedence(P::Comma), 0);
  for (char c : std::string_view("|^&<>+-*/%")) CHECK(binary_precedence(binary_operator_of(c)) > 0);
  CHECK(binary_operator_of('~') == P::None);
  CHECK(binary_operator_of('(') == P::None);
}

TEST(values_wrap_like_64_bit_twos_complement) {
  constexpr std::int64_t kMin = INT64_MIN, kMax = INT64_MAX;
  CHECK_EQ(value(P::Plus, kMax, 1), kMin);
  CHECK_EQ(value(P::Minus, kMin, 1), kMax);
  CHECK_EQ(value(P::Slash, kMin, -1), kMin);
  CHECK_EQ(value(P::Percent, kMin, -1), 0);
  CHECK_EQ(value(P::Slash, -7, 2), -3);
  CHECK_EQ(value(P::Percent, -7, 2), -1);
  CHECK_EQ(value(P::Shr, -8, 1), -4);
  CHECK_EQ(value(P::Shl, 1, 63), kMin);
  CHECK_EQ(value(P::Caret, 6, 3), 5);
  value(P::Slash, 1, 0, OpFault::DivisionByZero);
  value(P::Percent, 1, 0, OpFault::ModuloByZero);
  value(P::Shl, 1, 64, OpFault::ShiftCount);
  value(P::Shr, 1, -1, OpFault::ShiftCount);
  value(P::Tilde, 1, 1, OpFault::NotBinary);
  CHECK_EQ(value(P::Shl, 1, 64, OpFault::ShiftCount), 12345);  // no value on a fault
}

TEST(include_names) {
  CHECK_EQ(name_of("  \"a b.tmc\" // why"), std::string("a b.tmc"));
  CHECK_EQ(name_of("\t<USB-2-SD.inc>"), std::string("USB-2-SD.inc"));
  CHECK_EQ(name_of(" lib.inc   ; comment"), std::string("lib.inc"));
  CHECK_EQ(name_of("lib.inc/* c */"), std::string("lib.inc"));
  CHECK_EQ(name_of("dir/lib.inc // c"), std::string("dir/lib.inc"));
  CHECK_EQ(name_of("lib.inc \r\nNEXT"), std::string("lib.inc"));
  CHECK_EQ(name_of("\"open\n\"later\""), std::string("<unclosed>"));
  CHECK_EQ(name_of("<open"), std::string("<unclosed>"));
  CHECK_EQ(name_of("\"\""), std::string(""));
  IncludeNameSpan s = scan_include_name("\"x.tmc\" ; after", 0);
  CHECK_EQ(s.next, std::size_t{7});  // reading goes on after the closing quote
  s = scan_include_name(" x.tmc  // c", 0);
  CHECK_EQ(s.end, std::size_t{6});   // trailing blanks trimmed
  CHECK_EQ(s.next, std::size_t{8});  // at the comment
}
