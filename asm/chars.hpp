// How source bytes are classified and how number literals are read: shared by the lexer and
// the fast path (fast_path.cpp), so that both read every byte of a source the same way.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace tmcl::detail {

enum : std::uint8_t { kOther, kSpace, kLetter, kDigit };
constexpr std::array<std::uint8_t, 256> make_char_classes() {
  std::array<std::uint8_t, 256> t{};
  for (int c = 'a'; c <= 'z'; ++c) t[static_cast<std::size_t>(c)] = kLetter;
  for (int c = 'A'; c <= 'Z'; ++c) t[static_cast<std::size_t>(c)] = kLetter;
  t['_'] = kLetter;
  for (int c = '0'; c <= '9'; ++c) t[static_cast<std::size_t>(c)] = kDigit;
  for (char c : {' ', '\t', '\r', '\f', '\v'}) t[static_cast<unsigned char>(c)] = kSpace;
  return t;
}
inline constexpr auto kCharClass = make_char_classes();
inline std::uint8_t char_class(char c) { return kCharClass[static_cast<unsigned char>(c)]; }
inline bool ident_start(char c) { return char_class(c) == kLetter; }
inline bool ident_char(char c) { return char_class(c) == kLetter || char_class(c) == kDigit; }
inline bool non_ascii(char c) { return static_cast<unsigned char>(c) >= 0x80; }

// A number literal's digits: every identifier character after the prefix belongs to it.
struct DigitsRead {
  enum Status : std::uint8_t { Ok, BadDigit, NoDigits, Overflow };
  Status status = Ok;
  std::size_t end = 0;     // one past the last identifier character
  std::int64_t value = 0;  // Ok only
  char bad = 0;            // BadDigit: the first digit outside the base
};

// Reads the digits of a number in `base` (2, 10 or 16) starting at src[pos]; values above
// INT64_MAX overflow.
inline DigitsRead read_digits(std::string_view src, std::size_t pos, int base) {
  DigitsRead r;
  if (base == 10) {
    // Plain decimal digits that end the number (at most 18, so no overflow).
    std::size_t p = pos;
    std::int64_t v = 0;
    while (p < src.size() && p - pos < 18 && char_class(src[p]) == kDigit) v = v * 10 + (src[p++] - '0');
    if (p > pos && (p == src.size() || !ident_char(src[p]))) {
      r.end = p;
      r.value = v;
      return r;
    }
  }
  std::uint64_t v = 0;
  bool overflow = false, any = false;
  std::size_t p = pos;
  for (; p < src.size() && ident_char(src[p]); ++p) {
    char c = src[p];
    int d = c >= '0' && c <= '9' ? c - '0'
            : c >= 'a' && c <= 'f' ? c - 'a' + 10
            : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                   : 99;
    if (d >= base) {
      if (r.status == DigitsRead::Ok) {
        r.status = DigitsRead::BadDigit;
        r.bad = c;
      }
      continue;
    }
    any = true;
    if (v > (UINT64_MAX >> 1) / static_cast<std::uint64_t>(base)) overflow = true;
    v = v * static_cast<std::uint64_t>(base) + static_cast<std::uint64_t>(d);
    if (v > static_cast<std::uint64_t>(INT64_MAX)) overflow = true;
  }
  r.end = p;
  if (r.status == DigitsRead::Ok) {
    if (!any) r.status = DigitsRead::NoDigits;
    else if (overflow) r.status = DigitsRead::Overflow;
    else r.value = static_cast<std::int64_t>(v);
  }
  return r;
}

}  // namespace tmcl::detail
