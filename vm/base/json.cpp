// The JSON library: Value access, a recursive-descent parser with a depth limit that reports
// line:column and what it expected, and the three writers. Number text is stable: integers in
// decimal, reals in the shortest form that reads back to the same double (std::to_chars).
#include "tmcl/json.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>

#include "tmcl/diag_text.hpp"  // utf8_length

namespace tmcl::json {

namespace {

const Value& null_value() {
  static const Value v;
  return v;
}
const std::string& empty_string() {
  static const std::string s;
  return s;
}

// True when `t` is a complete JSON number: -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?
bool is_number_text(std::string_view t) {
  std::size_t i = 0;
  auto digit = [&](std::size_t k) { return k < t.size() && t[k] >= '0' && t[k] <= '9'; };
  if (i < t.size() && t[i] == '-') ++i;
  if (!digit(i)) return false;
  if (t[i] == '0') {
    ++i;
  } else {
    while (digit(i)) ++i;
  }
  if (i < t.size() && t[i] == '.') {
    ++i;
    if (!digit(i)) return false;
    while (digit(i)) ++i;
  }
  if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
    ++i;
    if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
    if (!digit(i)) return false;
    while (digit(i)) ++i;
  }
  return i == t.size();
}

void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

class Parser {
 public:
  Parser(std::string_view text, const ParseOptions& options) : s_(text), options_(options) {}

  bool run(Value& out, Error& error) {
    skip_space();
    if (!value(out, 0)) {
      fill(error);
      return false;
    }
    skip_space();
    if (pos_ != s_.size()) {
      fail("expected the end of the input after the value");
      fill(error);
      return false;
    }
    return true;
  }

 private:
  std::string_view s_;
  const ParseOptions& options_;
  std::size_t pos_ = 0;
  std::size_t error_pos_ = 0;
  std::string message_;

  bool fail(std::string message) {
    if (message_.empty()) {
      message_ = std::move(message);
      error_pos_ = pos_;
    }
    return false;
  }

  void fill(Error& e) const {
    e.offset = error_pos_;
    e.line = 1;
    e.column = 1;
    for (std::size_t i = 0; i < error_pos_ && i < s_.size(); ++i) {
      if (s_[i] == '\n') {
        ++e.line;
        e.column = 1;
      } else {
        ++e.column;
      }
    }
    e.message = message_;
  }

  bool at_end() const { return pos_ >= s_.size(); }
  char peek() const { return at_end() ? '\0' : s_[pos_]; }

  // What the input holds at the error position, for messages: "'x'" or "the end of the input".
  std::string found() const {
    if (at_end()) return "the end of the input";
    unsigned char c = static_cast<unsigned char>(s_[pos_]);
    if (c < 0x20 || c >= 0x7F) {
      char buf[16];
      std::snprintf(buf, sizeof buf, "byte 0x%02X", c);
      return buf;
    }
    return std::string("'") + static_cast<char>(c) + "'";
  }

  void skip_space() {
    while (!at_end() && (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\n' || s_[pos_] == '\r')) ++pos_;
  }

  bool literal(std::string_view word) {
    if (s_.substr(pos_, word.size()) != word) return fail("expected a value, found " + found());
    pos_ += word.size();
    return true;
  }

  bool value(Value& out, int depth) {
    switch (peek()) {
      case '{': return object(out, depth + 1);
      case '[': return array(out, depth + 1);
      case '"': {
        std::string text;
        if (!string(text)) return false;
        out = Value(std::move(text));
        return true;
      }
      case 't': if (!literal("true")) return false; out = Value(true); return true;
      case 'f': if (!literal("false")) return false; out = Value(false); return true;
      case 'n': if (!literal("null")) return false; out = Value(); return true;
      default:
        if (peek() == '-' || (peek() >= '0' && peek() <= '9')) return number(out);
        return fail("expected a value, found " + found());
    }
  }

  bool deep(int depth) {
    if (depth > options_.max_depth)
      return fail("nesting deeper than " + std::to_string(options_.max_depth) + " arrays and objects");
    return true;
  }

  bool object(Value& out, int depth) {
    if (!deep(depth)) return false;
    ++pos_;
    out = Value::object();
    skip_space();
    if (peek() == '}') {
      ++pos_;
      return true;
    }
    for (;;) {
      if (peek() != '"') return fail("expected a member name in double quotes, found " + found());
      std::string key;
      if (!string(key)) return false;
      skip_space();
      if (peek() != ':') return fail("expected ':' after the member name, found " + found());
      ++pos_;
      skip_space();
      Value v;
      if (!value(v, depth)) return false;
      out.set(std::move(key), std::move(v));
      skip_space();
      if (peek() == ',') {
        ++pos_;
        skip_space();
        continue;
      }
      if (peek() == '}') {
        ++pos_;
        return true;
      }
      return fail("expected ',' or '}' after an object member, found " + found());
    }
  }

  bool array(Value& out, int depth) {
    if (!deep(depth)) return false;
    ++pos_;
    out = Value::array();
    skip_space();
    if (peek() == ']') {
      ++pos_;
      return true;
    }
    for (;;) {
      Value v;
      if (!value(v, depth)) return false;
      out.push(std::move(v));
      skip_space();
      if (peek() == ',') {
        ++pos_;
        skip_space();
        continue;
      }
      if (peek() == ']') {
        ++pos_;
        return true;
      }
      return fail("expected ',' or ']' after an array element, found " + found());
    }
  }

  bool hex4(std::uint32_t& v) {
    v = 0;
    for (int k = 0; k < 4; ++k, ++pos_) {
      char c = peek();
      int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
      if (d < 0) return fail("expected four hex digits after \\u, found " + found());
      v = v * 16 + static_cast<std::uint32_t>(d);
    }
    return true;
  }

  bool string(std::string& out) {
    ++pos_;  // opening quote
    for (;;) {
      if (at_end()) return fail("unterminated string: expected '\"' before the end of the input");
      unsigned char c = static_cast<unsigned char>(s_[pos_]);
      if (c == '"') {
        ++pos_;
        return true;
      }
      if (c < 0x20) return fail("control character " + found() + " in a string: expected it escaped");
      if (c >= 0x80) {
        std::size_t n = utf8_length(s_, pos_);
        if (n == 0) return fail("invalid UTF-8 " + found() + " in a string");
        out.append(s_.substr(pos_, n));
        pos_ += n;
        continue;
      }
      if (c != '\\') {
        out += static_cast<char>(c);
        ++pos_;
        continue;
      }
      ++pos_;
      char e = peek();
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          ++pos_;
          std::size_t start = pos_ - 2;
          std::uint32_t cp;
          if (!hex4(cp)) return false;
          if (cp >= 0xDC00 && cp <= 0xDFFF) {
            pos_ = start;
            return fail("unpaired low surrogate \\u" + std::string(s_.substr(start + 2, 4)) + " in a string");
          }
          if (cp >= 0xD800 && cp <= 0xDBFF) {
            if (s_.substr(pos_, 2) != "\\u") {
              pos_ = start;
              return fail("high surrogate \\u" + std::string(s_.substr(start + 2, 4)) + " not followed by a \\u low surrogate");
            }
            pos_ += 2;
            std::uint32_t lo;
            if (!hex4(lo)) return false;
            if (lo < 0xDC00 || lo > 0xDFFF) {
              pos_ -= 6;
              return fail("expected a low surrogate \\uDC00..\\uDFFF after a high surrogate");
            }
            cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
          }
          append_utf8(out, cp);
          continue;  // hex4 already moved past the digits
        }
        default:
          return fail("invalid escape: expected one of \\\" \\\\ \\/ \\b \\f \\n \\r \\t \\u after '\\', found " + found());
      }
      ++pos_;
    }
  }

  bool number(Value& out) {
    std::size_t start = pos_;
    if (peek() == '-') ++pos_;
    auto digits = [&] {
      std::size_t n = 0;
      while (peek() >= '0' && peek() <= '9') ++pos_, ++n;
      return n;
    };
    bool integral = true;
    if (peek() == '0') {
      ++pos_;
      if (peek() >= '0' && peek() <= '9') return fail("leading zero in a number: expected '.', 'e' or the number's end");
    } else if (digits() == 0) {
      return fail("expected a digit after '-', found " + found());
    }
    if (peek() == '.') {
      integral = false;
      ++pos_;
      if (digits() == 0) return fail("expected a digit after the decimal point, found " + found());
    }
    if (peek() == 'e' || peek() == 'E') {
      integral = false;
      ++pos_;
      if (peek() == '+' || peek() == '-') ++pos_;
      if (digits() == 0) return fail("expected a digit in the exponent, found " + found());
    }
    const char* b = s_.data() + start;
    const char* e = s_.data() + pos_;
    if (integral) {
      std::int64_t v = 0;
      auto r = std::from_chars(b, e, v);
      if (r.ec == std::errc() && r.ptr == e) {
        out = Value(static_cast<long long>(v));
        return true;
      }
    }
    double d = 0;
    auto r = std::from_chars(b, e, d);
    if (r.ec == std::errc::result_out_of_range) {
      // Too large or too small for a double: keep the sign, saturate like strtod does.
      bool negative = *b == '-';
      bool tiny = false;
      for (const char* p = b; p != e; ++p)
        if ((*p == 'e' || *p == 'E') && p + 1 != e && p[1] == '-') tiny = true;
      d = tiny ? (negative ? -0.0 : 0.0) : (negative ? -std::numeric_limits<double>::max() : std::numeric_limits<double>::max());
    } else if (r.ec != std::errc() || r.ptr != e) {
      pos_ = start;
      return fail("malformed number");
    }
    out = Value(d);
    return true;
  }
};

void write_number(std::string& out, const Value& v) {
  if (v.kind() == Kind::integer) {
    out += std::to_string(v.as_int());
    return;
  }
  if (!v.text().empty()) {
    out += v.text();
    return;
  }
  double d = v.as_double();
  if (!std::isfinite(d)) {
    out += "null";  // JSON has no infinities or NaN
    return;
  }
  if (d == 0 && std::signbit(d)) {
    out += "-0.0";  // "-0" would read back as the integer 0
    return;
  }
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, d);
  out.append(buf, r.ptr);
}

enum class Layout { compact, pretty, lines };

void write_value(std::string& out, const Value& v, Layout layout, int depth) {
  switch (v.kind()) {
    case Kind::null: out += "null"; return;
    case Kind::boolean: out += v.as_bool() ? "true" : "false"; return;
    case Kind::integer:
    case Kind::real: write_number(out, v); return;
    case Kind::string: write_string(out, v.as_string()); return;
    case Kind::array:
    case Kind::object: break;
  }
  bool obj = v.is_object();
  out += obj ? '{' : '[';
  if (v.size() == 0) {
    out += obj ? '}' : ']';
    return;
  }
  bool pretty = layout == Layout::pretty;
  Layout inner = layout == Layout::lines ? Layout::compact : layout;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i) out += ',';
    if (pretty) {
      out += '\n';
      out.append(static_cast<std::size_t>(depth + 1) * 2, ' ');
    } else if (layout == Layout::lines && i) {
      out += "\n ";
    }
    if (obj) {
      write_string(out, v.key(i));
      out += pretty ? ": " : ":";
    }
    write_value(out, v.at(i), inner, depth + 1);
  }
  if (pretty) {
    out += '\n';
    out.append(static_cast<std::size_t>(depth) * 2, ' ');
  }
  out += obj ? '}' : ']';
}

}  // namespace

Value Value::number_text(std::string text) {
  if (!is_number_text(text)) return Value();
  Value v;
  v.kind_ = Kind::real;
  std::from_chars(text.data(), text.data() + text.size(), v.real_);
  v.text_ = std::move(text);
  return v;
}

std::int64_t Value::as_int(std::int64_t fallback) const {
  if (kind_ == Kind::integer) return int_;
  if (kind_ == Kind::real && std::isfinite(real_) && std::trunc(real_) == real_ && std::fabs(real_) < 9.2e18)
    return static_cast<std::int64_t>(real_);
  return fallback;
}

double Value::as_double(double fallback) const {
  if (kind_ == Kind::integer) return static_cast<double>(int_);
  if (kind_ == Kind::real) return real_;
  return fallback;
}

const std::string& Value::as_string() const { return kind_ == Kind::string ? text_ : empty_string(); }

const Value& Value::at(std::size_t i) const { return i < items_.size() ? items_[i] : null_value(); }

const Value* Value::find(std::string_view key) const {
  if (kind_ != Kind::object) return nullptr;
  for (std::size_t i = 0; i < keys_.size(); ++i)
    if (keys_[i] == key) return &items_[i];
  return nullptr;
}

Value* Value::find(std::string_view key) {
  return const_cast<Value*>(static_cast<const Value*>(this)->find(key));
}

const Value& Value::operator[](std::string_view key) const {
  const Value* v = find(key);
  return v ? *v : null_value();
}

Value& Value::set(std::string key, Value v) {
  if (kind_ == Kind::null) kind_ = Kind::object;
  if (Value* old = find(key)) {
    *old = std::move(v);
    return *old;
  }
  keys_.push_back(std::move(key));
  items_.push_back(std::move(v));
  return items_.back();
}

Value& Value::push(Value v) {
  if (kind_ == Kind::null) kind_ = Kind::array;
  items_.push_back(std::move(v));
  return items_.back();
}

bool operator==(const Value& a, const Value& b) {
  if (a.is_number() && b.is_number()) {
    if (a.kind_ == Kind::integer && b.kind_ == Kind::integer) return a.int_ == b.int_;
    return a.as_double() == b.as_double();
  }
  if (a.kind_ != b.kind_) return false;
  switch (a.kind_) {
    case Kind::null: return true;
    case Kind::boolean: return a.int_ == b.int_;
    case Kind::string: return a.text_ == b.text_;
    case Kind::array: return a.items_ == b.items_;
    case Kind::object: return a.keys_ == b.keys_ && a.items_ == b.items_;
    default: return false;
  }
}

std::string Error::to_string() const {
  return std::to_string(line) + ":" + std::to_string(column) + ": " + message;
}

bool parse(std::string_view text, Value& out, Error& error, const ParseOptions& options) {
  out = Value();
  Parser p(text, options);
  Value v;
  if (!p.run(v, error)) return false;
  out = std::move(v);
  return true;
}

void write_string(std::string& out, std::string_view s) {
  out += '"';
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
          out += buf;
        } else {
          out += c;
        }
    }
  }
  out += '"';
}

std::string quote(std::string_view s) {
  std::string out;
  write_string(out, s);
  return out;
}

std::string write(const Value& v) {
  std::string out;
  write_value(out, v, Layout::compact, 0);
  return out;
}

std::string write_pretty(const Value& v) {
  std::string out;
  write_value(out, v, Layout::pretty, 0);
  return out;
}

std::string write_lines(const Value& v) {
  std::string out;
  write_value(out, v, Layout::lines, 0);
  return out;
}

}  // namespace tmcl::json
