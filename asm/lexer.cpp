// The lexer: bytes of one source file to tokens. Comments (//, ;, /* */) vanish; bytes that are
// not ASCII are allowed only inside comments (real TMCL files carry ISO-8859-1 text there).
#include <array>
#include <cctype>
#include <cstring>
#include <string>

#include "chars.hpp"
#include "internal.hpp"
#include "syntax.hpp"

namespace tmcl {
bool is_valid_name(std::string_view name) {
  auto letter = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_'; };
  if (name.empty() || name.size() > 255 || !letter(name[0])) return false;
  for (char c : name)
    if (!letter(c) && !(c >= '0' && c <= '9')) return false;
  return true;
}
}  // namespace tmcl

namespace tmcl::detail {

std::string upper(std::string_view s) {
  std::string u(s);
  for (auto& c : u)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');  // ASCII only, no locale
  return u;
}

namespace {

std::string hex(unsigned v) {
  const char* d = "0123456789ABCDEF";
  return {d[(v >> 4) & 15], d[v & 15]};
}

}  // namespace

Token Lexer::next_token() {
  while (pending_head_ == pending_count_) {
    pending_head_ = pending_count_ = 0;
    if (pos_ >= src_.size()) {
      // Every file ends with a newline and then End, however it ends.
      Token t{finished_ == 0 ? Tok::Newline : Tok::End, P::None, src_.substr(src_.size(), 0), 0, line_,
              static_cast<int>(pos_ - line_start_) + 1};
      if (finished_ < 2) ++finished_;
      last_ = t;
      return t;
    }
    step();
  }
  last_ = pending_[pending_head_++];
  return last_;
}

SourceLoc Lexer::loc_at(std::size_t p, int len) const {
  return SourceLoc{file_, line_, static_cast<int>(p - line_start_) + 1, len};
}

void Lexer::push(Tok k, std::size_t p, std::size_t len, P punct, std::int64_t num) {
  pending_[pending_count_++] = Token{k, punct, src_.substr(p, len), num, line_, static_cast<int>(p - line_start_) + 1};
}

// True when the previous token ends an operand, so '%' is modulo rather than a binary prefix.
bool Lexer::after_operand() const {
  const Token& t = pending_count_ > 0 ? pending_[pending_count_ - 1] : last_;
  return t.kind == Tok::Ident || t.kind == Tok::Number || (t.kind == Tok::Punct && t.punct == P::RParen);
}

void Lexer::skip_to_eol() {
  const void* nl = std::memchr(src_.data() + pos_, '\n', src_.size() - pos_);
  pos_ = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - src_.data()) : src_.size();
}

void Lexer::step() {
  char c = src_[pos_];
  switch (char_class(c)) {
    case kLetter: return ident();
    case kDigit: return number();
    case kSpace:
      do ++pos_;
      while (pos_ < src_.size() && char_class(src_[pos_]) == kSpace);
      return;
    default: break;
  }
  if (c == '\n') {
    push(Tok::Newline, pos_, 0);
    ++pos_;
    ++line_;
    line_start_ = pos_;
    return;
  }
  if ((c == '/' && peek(1) == '/') || c == ';') {
    std::size_t start = pos_;
    skip_to_eol();
    if (comments_) comments_->push_back(Token{Tok::Bad, P::None, src_.substr(start, pos_ - start), 0, line_, static_cast<int>(start - line_start_) + 1});
    return;
  }
  if (c == '/' && peek(1) == '*') {
    std::size_t start = pos_, start_line_start = line_start_;
    int start_line = line_;
    block_comment();
    if (comments_) comments_->push_back(Token{Tok::Bad, P::None, src_.substr(start, pos_ - start), 0, start_line, static_cast<int>(start - start_line_start) + 1});
    return;
  }
  if (c == '.' && ident_start(peek(1))) return ident();
  if (c == '$') return digits(pos_, 1, 16);
  if (c == '%' && !after_operand() && (peek(1) == '0' || peek(1) == '1')) return digits(pos_, 1, 2);
  if (c == '#') return directive();
  if (punct()) return;
  auto u = static_cast<unsigned char>(c);
  if (u >= 0x80) return ident();  // reported there, with the whole word it belongs to
  else
    diags_.error(loc_at(pos_, 1), std::string("unexpected character '") + (u < 0x20 ? '?' : c) + "'");
  push(Tok::Bad, pos_, 1);
  ++pos_;
}


void Lexer::block_comment() {
  std::size_t start = pos_;
  int start_line = line_;
  std::size_t start_line_start = line_start_;
  pos_ += 2;
  while (pos_ < src_.size()) {
    if (src_[pos_] == '*' && peek(1) == '/') {
      pos_ += 2;
      return;
    }
    if (src_[pos_] == '\n') {
      // Keep line numbers right; a comment does not end a statement.
      ++line_;
      line_start_ = pos_ + 1;
    }
    ++pos_;
  }
  diags_.error(SourceLoc{file_, start_line, static_cast<int>(start - start_line_start) + 1, 2},
               "unterminated /* comment");
}

// A name; bytes outside ASCII inside or next to it make the whole word one bad token with one
// error, so that "café = 1" is one mistake, not four.
void Lexer::ident() {
  std::size_t start = pos_++;
  bool foreign = static_cast<unsigned char>(src_[start]) >= 0x80;
  while (pos_ < src_.size() && (ident_char(src_[pos_]) || static_cast<unsigned char>(src_[pos_]) >= 0x80)) {
    foreign = foreign || static_cast<unsigned char>(src_[pos_]) >= 0x80;
    ++pos_;
  }
  if (!foreign) return push(Tok::Ident, start, pos_ - start);
  std::size_t first = start;
  while (static_cast<unsigned char>(src_[first]) < 0x80) ++first;
  std::string shown;
  for (std::size_t i = start; i < pos_; ++i)
    shown += static_cast<unsigned char>(src_[i]) < 0x80 ? src_[i] : '?';
  bool word = shown.find_first_not_of('?') != std::string::npos;
  diags_.error(loc_at(start, static_cast<int>(pos_ - start)),
               "non-ASCII byte 0x" + hex(static_cast<unsigned char>(src_[first])) +
                   (word ? " in '" + shown + "'" : std::string()) + " outside a comment (sources must be ASCII)");
  push(Tok::Bad, start, pos_ - start);
}

void Lexer::directive() {
  std::size_t start = pos_++;
  while (pos_ < src_.size() && ident_char(src_[pos_])) ++pos_;
  push(Tok::Directive, start, pos_ - start);
  std::string name = upper(src_.substr(start, pos_ - start));
  if (name == "#INCLUDE") include_name();
}

// The file name after #include: "quoted", <angled> or bare up to a comment or the line end
// (scan_include_name, syntax.hpp, which the fast path reads it with too).
void Lexer::include_name() {
  IncludeNameSpan s = scan_include_name(src_, pos_);
  if (s.unclosed) {
    diags_.error(loc_at(s.begin, 1), std::string("missing closing ") + (src_[s.begin] == '"' ? '"' : '>') +
                                         " in #include");
    pos_ = s.begin;
    push(Tok::Bad, s.begin, 1);
    skip_to_eol();
    return;
  }
  push(Tok::IncludeName, s.begin, s.end - s.begin);
  pos_ = s.next;
}

void Lexer::number() {
  if (src_[pos_] == '0' && (peek(1) == 'x' || peek(1) == 'X')) return digits(pos_, 2, 16);
  if (src_[pos_] == '0' && (peek(1) == 'b' || peek(1) == 'B')) return digits(pos_, 2, 2);
  digits(pos_, 0, 10);
}

void Lexer::digits(std::size_t start, std::size_t prefix, int base) {
  DigitsRead r = read_digits(src_, start + prefix, base);
  pos_ = r.end;
  int len = static_cast<int>(pos_ - start);
  switch (r.status) {
    case DigitsRead::Ok: return push(Tok::Number, start, pos_ - start, P::None, r.value);
    case DigitsRead::BadDigit:
      diags_.error(loc_at(start, len), "invalid digit '" + std::string(1, r.bad) + "' in " +
                                           (base == 16 ? "hexadecimal" : base == 2 ? "binary" : "decimal") + " number");
      break;
    case DigitsRead::NoDigits: diags_.error(loc_at(start, len), "number has no digits after its prefix"); break;
    case DigitsRead::Overflow: diags_.error(loc_at(start, len), "number is too large (more than 63 bits)"); break;
  }
  push(Tok::Bad, start, pos_ - start);
}

bool Lexer::punct() {
  struct Two { char a, b; P p; };
  static constexpr Two two[] = {{'<', '<', P::Shl}, {'>', '>', P::Shr}};
  for (auto t : two)
    if (src_[pos_] == t.a && peek(1) == t.b) {
      push(Tok::Punct, pos_, 2, t.p);
      pos_ += 2;
      return true;
    }
  P p = P::None;
  switch (src_[pos_]) {
    case ',': p = P::Comma; break;
    case ':': p = P::Colon; break;
    case '=': p = P::Assign; break;
    case '(': p = P::LParen; break;
    case ')': p = P::RParen; break;
    case '+': p = P::Plus; break;
    case '-': p = P::Minus; break;
    case '*': p = P::Star; break;
    case '/': p = P::Slash; break;
    case '%': p = P::Percent; break;
    case '&': p = P::Amp; break;
    case '|': p = P::Pipe; break;
    case '^': p = P::Caret; break;
    case '~': p = P::Tilde; break;
    default: return false;
  }
  push(Tok::Punct, pos_, 1, p);
  ++pos_;
  return true;
}


}  // namespace tmcl::detail
