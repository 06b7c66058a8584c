// The project's one JSON library: a Value (null, bool, integer, real, string, array, object with
// its keys in insertion order), a parser that never throws on bad input and says where and what
// it expected, and writers with stable output (compact, pretty, and the "lines" layout of
// tmclrun --json). Every JSON need of the tools (--json, the language server, the debugger)
// goes through here, so escaping and number text are the same everywhere.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tmcl::json {

enum class Kind { null, boolean, integer, real, string, array, object };

class Value {
 public:
  Value() = default;
  Value(std::nullptr_t) {}
  Value(bool b) : kind_(Kind::boolean), int_(b ? 1 : 0) {}
  Value(int v) : kind_(Kind::integer), int_(v) {}
  Value(long v) : kind_(Kind::integer), int_(v) {}
  Value(long long v) : kind_(Kind::integer), int_(v) {}
  Value(unsigned v) : kind_(Kind::integer), int_(v) {}
  Value(unsigned long v) : kind_(Kind::integer), int_(static_cast<std::int64_t>(v)) {}
  Value(unsigned long long v) : kind_(Kind::integer), int_(static_cast<std::int64_t>(v)) {}
  Value(double v) : kind_(Kind::real), real_(v) {}
  Value(std::string s) : kind_(Kind::string), text_(std::move(s)) {}
  Value(std::string_view s) : kind_(Kind::string), text_(s) {}
  Value(const char* s) : kind_(Kind::string), text_(s) {}

  static Value array() { Value v; v.kind_ = Kind::array; return v; }
  static Value object() { Value v; v.kind_ = Kind::object; return v; }
  // A real number written exactly as `text` (e.g. "12.500" for a fixed number of decimals).
  // `text` must be a JSON number; anything else is written as null.
  static Value number_text(std::string text);

  Kind kind() const { return kind_; }
  bool is_null() const { return kind_ == Kind::null; }
  bool is_bool() const { return kind_ == Kind::boolean; }
  bool is_int() const { return kind_ == Kind::integer; }
  bool is_number() const { return kind_ == Kind::integer || kind_ == Kind::real; }
  bool is_string() const { return kind_ == Kind::string; }
  bool is_array() const { return kind_ == Kind::array; }
  bool is_object() const { return kind_ == Kind::object; }

  // Readers answer `fallback` when the value is of another kind (no exceptions).
  bool as_bool(bool fallback = false) const { return kind_ == Kind::boolean ? int_ != 0 : fallback; }
  std::int64_t as_int(std::int64_t fallback = 0) const;  // reals with an integral value count
  double as_double(double fallback = 0) const;
  const std::string& as_string() const;  // "" unless a string
  std::string_view text() const { return text_; }  // string contents, or a number_text's text

  // Arrays and objects: element count (0 for scalars), elements by index, members by key.
  std::size_t size() const { return items_.size(); }
  const Value& at(std::size_t i) const;  // a null value when out of range
  const std::string& key(std::size_t i) const { return keys_[i]; }  // objects only
  const std::vector<Value>& items() const { return items_; }
  const Value* find(std::string_view key) const;  // null when absent or not an object
  Value* find(std::string_view key);
  const Value& operator[](std::string_view key) const;  // a null value when absent
  const Value& operator[](const char* key) const { return (*this)[std::string_view(key)]; }
  bool contains(std::string_view key) const { return find(key) != nullptr; }

  // Building: set() turns a null into an object and replaces an existing key in place;
  // push() turns a null into an array. Both return the stored value.
  Value& set(std::string key, Value v);
  Value& push(Value v);

  friend bool operator==(const Value& a, const Value& b);

 private:
  Kind kind_ = Kind::null;
  std::int64_t int_ = 0;
  double real_ = 0;
  std::string text_;               // string, or the text of a number_text real
  std::vector<Value> items_;       // array elements or object values
  std::vector<std::string> keys_;  // object keys, parallel to items_
};

// Where and why parsing failed: 1-based line and column (in bytes), byte offset, and a message
// saying what was expected ("expected ',' or '}' after an object member").
struct Error {
  int line = 0;
  int column = 0;
  std::size_t offset = 0;
  std::string message;
  std::string to_string() const;  // "LINE:COL: MESSAGE"
};

struct ParseOptions {
  int max_depth = 256;  // arrays and objects nested deeper are an error, not a stack overflow
};

// Parses exactly one JSON text (RFC 8259; whitespace around it allowed). On failure returns
// false and fills `error`; `out` is then null. Strings must be valid UTF-8; \u escapes
// (surrogate pairs joined) become UTF-8. Integers that fit int64 are integers, other numbers
// reals. A repeated object key replaces the earlier value.
bool parse(std::string_view text, Value& out, Error& error, const ParseOptions& options = {});

// Compact: no spaces at all. Pretty: two-space indent, "key": value, one member per line,
// empty containers as [] and {}. Lines: an object's members one per line (",\n "), everything
// inside them compact (tmclrun --json). All end without a newline.
std::string write(const Value& v);
std::string write_pretty(const Value& v);
std::string write_lines(const Value& v);

// Appends `s` as a quoted JSON string: \" \\ \n \t, other control bytes as \u00XX, the rest as is.
void write_string(std::string& out, std::string_view s);
std::string quote(std::string_view s);

}  // namespace tmcl::json
