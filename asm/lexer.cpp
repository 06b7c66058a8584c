// The lexer: bytes of one source file to tokens. Comments (//, ;, /* */) vanish; bytes that are
// not ASCII are allowed only inside comments (real TMCL files carry ISO-8859-1 text there).
#include <cctype>
#include <string>

#include "internal.hpp"

namespace tmcl::detail {

std::string upper(std::string_view s) {
  std::string u(s);
  for (auto& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return u;
}

namespace {

bool ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

class Lexer {
 public:
  Lexer(const SourceFile& f, int index, Diagnostics& d) : src_(f.text), file_(index), diags_(d) {}

  std::vector<Token> run() {
    while (pos_ < src_.size()) step();
    push(Tok::Newline, pos_, 0);
    push(Tok::End, pos_, 0);
    return std::move(out_);
  }

 private:
  SourceLoc loc_at(std::size_t p, int len) const {
    return SourceLoc{file_, line_, static_cast<int>(p - line_start_) + 1, len};
  }
  void push(Tok k, std::size_t p, std::size_t len, P punct = P::None, std::int64_t num = 0) {
    Token t{k, punct, src_.substr(p, len), num, line_, static_cast<int>(p - line_start_) + 1};
    out_.push_back(t);
  }
  void newline() {
    push(Tok::Newline, pos_, 0);
    ++pos_;
    ++line_;
    line_start_ = pos_;
  }
  // True when the previous token ends an operand, so '%' is modulo rather than a binary prefix.
  bool after_operand() const {
    if (out_.empty()) return false;
    const Token& t = out_.back();
    return t.kind == Tok::Ident || t.kind == Tok::Number || (t.kind == Tok::Punct && t.punct == P::RParen);
  }
  void skip_to_eol() {
    while (pos_ < src_.size() && src_[pos_] != '\n') ++pos_;
  }

  void step() {
    char c = src_[pos_];
    if (c == '\n') return newline();
    if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++pos_;
      return;
    }
    if (c == '/' && peek(1) == '/') return skip_to_eol();
    if (c == ';') return skip_to_eol();
    if (c == '/' && peek(1) == '*') return block_comment();
    if (ident_start(c)) return ident();
    if (c == '.' && ident_start(peek(1))) return ident();
    if (std::isdigit(static_cast<unsigned char>(c))) return number();
    if (c == '$' && std::isxdigit(static_cast<unsigned char>(peek(1)))) return prefixed_number(1, 16);
    if (c == '%' && !after_operand() && (peek(1) == '0' || peek(1) == '1')) return prefixed_number(1, 2);
    if (c == '#') return directive();
    if (punct()) return;
    auto u = static_cast<unsigned char>(c);
    if (u >= 0x80)
      diags_.error(loc_at(pos_, 1), "non-ASCII byte 0x" + hex(u) + " outside a comment");
    else
      diags_.error(loc_at(pos_, 1), std::string("unexpected character '") + (u < 0x20 ? '?' : c) + "'");
    push(Tok::Bad, pos_, 1);
    ++pos_;
  }

  static std::string hex(unsigned v) {
    const char* d = "0123456789ABCDEF";
    return {d[(v >> 4) & 15], d[v & 15]};
  }
  char peek(std::size_t k) const { return pos_ + k < src_.size() ? src_[pos_ + k] : '\0'; }

  void block_comment() {
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

  void ident() {
    std::size_t start = pos_++;
    while (pos_ < src_.size() && ident_char(src_[pos_])) ++pos_;
    push(Tok::Ident, start, pos_ - start);
  }

  void directive() {
    std::size_t start = pos_++;
    while (pos_ < src_.size() && ident_char(src_[pos_])) ++pos_;
    push(Tok::Directive, start, pos_ - start);
    std::string name = upper(src_.substr(start, pos_ - start));
    if (name == "#INCLUDE") include_name();
  }

  // The file name after #include: "quoted", <angled> or bare up to a comment or the line end.
  void include_name() {
    while (pos_ < src_.size() && (src_[pos_] == ' ' || src_[pos_] == '\t')) ++pos_;
    std::size_t start = pos_;
    char open = peek(0);
    if (open == '"' || open == '<') {
      char close = open == '"' ? '"' : '>';
      std::size_t end = src_.find(close, pos_ + 1);
      std::size_t eol = src_.find('\n', pos_);
      if (end == std::string_view::npos || (eol != std::string_view::npos && end > eol)) {
        diags_.error(loc_at(start, 1), std::string("missing closing ") + close + " in #include");
        push(Tok::Bad, start, 1);
        skip_to_eol();
        return;
      }
      push(Tok::IncludeName, start, end + 1 - start);
      pos_ = end + 1;
      return;
    }
    std::size_t end = pos_;
    while (end < src_.size() && src_[end] != '\n' && src_[end] != ';' &&
           !(src_[end] == '/' && end + 1 < src_.size() && (src_[end + 1] == '/' || src_[end + 1] == '*')))
      ++end;
    std::size_t trimmed = end;
    while (trimmed > start && std::isspace(static_cast<unsigned char>(src_[trimmed - 1]))) --trimmed;
    push(Tok::IncludeName, start, trimmed - start);
    pos_ = end;
  }

  void number() {
    if (src_[pos_] == '0' && (peek(1) == 'x' || peek(1) == 'X')) return prefixed_number(2, 16);
    if (src_[pos_] == '0' && (peek(1) == 'b' || peek(1) == 'B') && (peek(2) == '0' || peek(2) == '1'))
      return prefixed_number(2, 2);
    digits(pos_, 0, 10);
  }
  void prefixed_number(std::size_t prefix, int base) { digits(pos_, prefix, base); }

  void digits(std::size_t start, std::size_t prefix, int base) {
    pos_ = start + prefix;
    std::uint64_t v = 0;
    bool overflow = false, any = false;
    while (pos_ < src_.size() && ident_char(src_[pos_])) {
      char c = src_[pos_];
      int d = std::isdigit(static_cast<unsigned char>(c)) ? c - '0'
              : std::isxdigit(static_cast<unsigned char>(c))
                  ? std::tolower(static_cast<unsigned char>(c)) - 'a' + 10
                  : 99;
      if (d >= base) {
        while (pos_ < src_.size() && ident_char(src_[pos_])) ++pos_;
        diags_.error(loc_at(start, static_cast<int>(pos_ - start)),
                     "invalid digit '" + std::string(1, c) + "' in " +
                         (base == 16 ? "hexadecimal" : base == 2 ? "binary" : "decimal") + " number");
        push(Tok::Bad, start, pos_ - start);
        return;
      }
      any = true;
      if (v > (UINT64_MAX >> 1) / static_cast<std::uint64_t>(base)) overflow = true;
      v = v * static_cast<std::uint64_t>(base) + static_cast<std::uint64_t>(d);
      if (v > static_cast<std::uint64_t>(INT64_MAX)) overflow = true;
      ++pos_;
    }
    if (!any) {
      diags_.error(loc_at(start, static_cast<int>(pos_ - start)), "number has no digits after its prefix");
      push(Tok::Bad, start, pos_ - start);
      return;
    }
    if (overflow) {
      diags_.error(loc_at(start, static_cast<int>(pos_ - start)), "number is too large (more than 63 bits)");
      push(Tok::Bad, start, pos_ - start);
      return;
    }
    push(Tok::Number, start, pos_ - start, P::None, static_cast<std::int64_t>(v));
  }

  bool punct() {
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

  std::string_view src_;
  int file_;
  Diagnostics& diags_;
  std::vector<Token> out_;
  std::size_t pos_ = 0;
  std::size_t line_start_ = 0;
  int line_ = 1;
};

}  // namespace

std::vector<Token> lex(const SourceFile& file, int file_index, Diagnostics& diags) {
  return Lexer(file, file_index, diags).run();
}

}  // namespace tmcl::detail
