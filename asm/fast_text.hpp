// Reading source text for the fast path (fast_path.cpp): a cursor is a plain pointer into the
// text, which ends in the '\0' every std::string has, so no step needs a bounds check. A '\0'
// inside the text is never accepted as anything (the full lexer reports it), so the scanner
// stops on it and the fast path gives up.
#pragma once

#include <cstring>
#include <string_view>

#include "chars.hpp"

namespace tmcl::detail {

// Where pass 1 counts lines (block comments may span several); pass 2 does not need to.
struct LineCount {
  int line = 1;
  const char* start = nullptr;  // where the current line starts
};

class FastText {
 public:
  // `text` must be followed by a '\0' (std::string's data() is).
  explicit FastText(std::string_view text) : begin_(text.data()), end_(text.data() + text.size()) {}

  const char* begin() const { return begin_; }
  const char* end() const { return end_; }

  // Skips spaces and /* */ comments, which do not end a statement; false on an unterminated one.
  bool skip_space(const char*& p, LineCount* lines = nullptr) const {
    for (;;) {
      while (char_class(*p) == kSpace) ++p;
      if (p[0] != '/' || p[1] != '*') return true;
      if (!block_comment(p, lines)) return false;
    }
  }

  // The end of a statement: a newline, a comment running to it, or the end of the text.
  bool at_end(const char* p) const {
    char c = *p;
    return c == '\n' || c == ';' || (c == '/' && p[1] == '/') || (c == '\0' && p == end_);
  }

  // From the end of a statement to its newline (or the end of the text).
  const char* newline(const char* p) const {
    const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(end_ - p));
    return nl ? static_cast<const char*>(nl) : end_;
  }

  // An identifier at p; false when there is none or a byte outside ASCII touches it (an error
  // to the full lexer).
  static bool ident(const char*& p, std::string_view& name) {
    const char* start = p;
    if (!ident_start(*p)) return false;
    do ++p;
    while (ident_char(*p));
    if (non_ascii(*p)) return false;
    name = std::string_view(start, static_cast<std::size_t>(p - start));
    return true;
  }

  // Skips the rest of a statement, leaving p at its newline (or the end of the text).
  bool skip_statement(const char*& p, LineCount* lines) const {
    for (;;) {
      while (!kStatementStop[static_cast<unsigned char>(*p)]) ++p;
      if (p[0] == '/' && p[1] == '*') {
        if (!block_comment(p, lines)) return false;
      } else if (p[0] == '/' && p[1] != '/') {
        ++p;  // division
      } else if (p[0] == '\0' && p != end_) {
        ++p;  // a stray '\0': pass 2 or the constant's evaluation rejects it
      } else {
        break;
      }
    }
    p = newline(p);
    return true;
  }

 private:
  static constexpr auto kStatementStop = [] {
    std::array<bool, 256> t{};
    t['\n'] = t[';'] = t['/'] = t[0] = true;
    return t;
  }();

  bool block_comment(const char*& p, LineCount* lines) const {
    const char* close = nullptr;
    for (const char* q = p + 2; q + 1 < end_; ++q)
      if (q[0] == '*' && q[1] == '/') {
        close = q;
        break;
      }
    if (!close) return false;
    if (lines)
      for (const char* q = p + 2; q < close; ++q)
        if (*q == '\n') {
          ++lines->line;
          lines->start = q + 1;
        }
    p = close + 2;
    return true;
  }

  const char* begin_;
  const char* end_;
};

}  // namespace tmcl::detail
