// Unit tests of tmcl::json: every kind of value, every error the parser reports (with where and
// what it expected), \u escapes and surrogate pairs, the depth limit, and stable writer output.
#include "check.hpp"
#include "tmcl/json.hpp"

#include <limits>

using tmcl::json::Error;
using tmcl::json::Value;

namespace {

Value ok(std::string_view text) {
  Value v;
  Error e;
  bool good = tmcl::json::parse(text, v, e);
  if (!good) tmcl_test::fail(__FILE__, __LINE__, "parse failed: " + e.to_string() + " for " + std::string(text));
  return v;
}

std::string err(std::string_view text) {
  Value v;
  Error e;
  if (tmcl::json::parse(text, v, e)) return "(parsed)";
  CHECK(v.is_null());
  return e.to_string();
}

}  // namespace

TEST(scalars) {
  CHECK(ok("null").is_null());
  CHECK_EQ(ok("true").as_bool(), true);
  CHECK_EQ(ok(" false ").as_bool(true), false);
  CHECK_EQ(ok("-42").as_int(), -42);
  CHECK(ok("-42").is_int());
  CHECK_EQ(ok("9223372036854775807").as_int(), 9223372036854775807LL);
  CHECK(!ok("9223372036854775808").is_int());  // too large for int64: a real
  CHECK_EQ(ok("1.5").as_double(), 1.5);
  CHECK_EQ(ok("2e3").as_int(), 2000);
  CHECK_EQ(ok("-0.25E-1").as_double(), -0.025);
  CHECK_EQ(ok("\"a\\\"b\"").as_string(), "a\"b");
  CHECK_EQ(ok("1e999").as_double() > 1e300, true);
}

TEST(readers_fall_back_on_other_kinds) {
  Value v = ok("\"x\"");
  CHECK_EQ(v.as_int(7), 7);
  CHECK_EQ(v.as_bool(true), true);
  CHECK_EQ(ok("3").as_string(), "");
  CHECK(ok("[1]")["key"].is_null());
  CHECK(ok("{}").at(3).is_null());
  CHECK(ok("1.5").as_int(-1) == -1);
}

TEST(objects_keep_key_order_and_replace_repeated_keys) {
  Value v = ok(R"({"b":1,"a":[true,null],"c":{"d":"e"},"b":2})");
  CHECK_EQ(v.size(), 3u);
  CHECK_EQ(v.key(0), "b");
  CHECK_EQ(v.key(1), "a");
  CHECK_EQ(v["b"].as_int(), 2);
  CHECK_EQ(v["c"]["d"].as_string(), "e");
  CHECK(v["a"].at(1).is_null());
  CHECK_EQ(tmcl::json::write(v), R"({"b":2,"a":[true,null],"c":{"d":"e"}})");
}

TEST(escapes_and_unicode) {
  CHECK_EQ(ok(R"("\/\b\f\n\r\t\\")").as_string(), "/\b\f\n\r\t\\");
  CHECK_EQ(ok(R"("\u0041\u00e9\u20AC")").as_string(), "A\xC3\xA9\xE2\x82\xAC");
  CHECK_EQ(ok(R"("\ud83d\ude00")").as_string(), "\xF0\x9F\x98\x80");  // U+1F600 from a pair
  CHECK_EQ(ok("\"\xF0\x9F\x98\x80\"").as_string(), "\xF0\x9F\x98\x80");
  CHECK_EQ(ok(R"("\u0000")").as_string(), std::string(1, '\0'));
}

TEST(errors_say_where_and_what) {
  CHECK_EQ(err(""), "1:1: expected a value, found the end of the input");
  CHECK_EQ(err("{\"a\":1,}"), "1:8: expected a member name in double quotes, found '}'");
  CHECK_EQ(err("{\"a\" 1}"), "1:6: expected ':' after the member name, found '1'");
  CHECK_EQ(err("{\"a\":1\n \"b\":2}"), "2:2: expected ',' or '}' after an object member, found '\"'");
  CHECK_EQ(err("[1 2]"), "1:4: expected ',' or ']' after an array element, found '2'");
  CHECK_EQ(err("[1,]"), "1:4: expected a value, found ']'");
  CHECK_EQ(err("tru"), "1:1: expected a value, found 't'");
  CHECK_EQ(err("1 2"), "1:3: expected the end of the input after the value");
  CHECK_EQ(err("\"abc"), "1:5: unterminated string: expected '\"' before the end of the input");
  CHECK_EQ(err("\"a\nb\""), "1:3: control character byte 0x0A in a string: expected it escaped");
  CHECK_EQ(err(R"("\x")"), "1:3: invalid escape: expected one of \\\" \\\\ \\/ \\b \\f \\n \\r \\t \\u after '\\', found 'x'");
  CHECK_EQ(err(R"("\u12G4")"), "1:6: expected four hex digits after \\u, found 'G'");
  CHECK_EQ(err(R"("\ud83d")"), "1:2: high surrogate \\ud83d not followed by a \\u low surrogate");
  CHECK_EQ(err(R"("\ud83d\u0041")"), "1:8: expected a low surrogate \\uDC00..\\uDFFF after a high surrogate");
  CHECK_EQ(err(R"("\ude00")"), "1:2: unpaired low surrogate \\ude00 in a string");
  CHECK_EQ(err("\"\xC3\x28\""), "1:2: invalid UTF-8 byte 0xC3 in a string");
  CHECK_EQ(err("\"\xED\xA0\x80\""), "1:2: invalid UTF-8 byte 0xED in a string");  // encoded surrogate
  CHECK_EQ(err("\"\xC0\xAF\""), "1:2: invalid UTF-8 byte 0xC0 in a string");      // overlong
  CHECK_EQ(err("01"), "1:2: leading zero in a number: expected '.', 'e' or the number's end");
  CHECK_EQ(err("-x"), "1:2: expected a digit after '-', found 'x'");
  CHECK_EQ(err("1."), "1:3: expected a digit after the decimal point, found the end of the input");
  CHECK_EQ(err("1e+"), "1:4: expected a digit in the exponent, found the end of the input");
  CHECK_EQ(err("+1"), "1:1: expected a value, found '+'");
  CHECK_EQ(err("\x01"), "1:1: expected a value, found byte 0x01");
}

TEST(depth_limit) {
  std::string deep(300, '[');
  CHECK_EQ(err(deep), "1:257: nesting deeper than 256 arrays and objects");
  std::string fine = std::string(256, '[') + std::string(256, ']');
  CHECK(ok(fine).is_array());
  Value v;
  Error e;
  tmcl::json::ParseOptions shallow;
  shallow.max_depth = 2;
  CHECK(!tmcl::json::parse("[[[]]]", v, e, shallow));
  CHECK(tmcl::json::parse("[[{}]]", v, e, shallow) == false);
  CHECK(tmcl::json::parse("[{}]", v, e, shallow));
  // A million brackets: an error, not a stack overflow.
  CHECK(!tmcl::json::parse(std::string(1000000, '['), v, e));
}

TEST(writers_are_stable) {
  Value v = Value::object();
  v.set("name", "a\"b\\c\nd\te\x01");
  v.set("n", -5);
  v.set("r", 0.1);
  v.set("big", 1e300);
  v.set("ms", Value::number_text("12.500"));
  v.set("list", Value::array()).push(1);
  v["list"];  // const access does not create
  v.set("empty", Value::array());
  v.set("obj", Value::object()).set("k", nullptr);
  CHECK_EQ(tmcl::json::write(v),
           R"({"name":"a\"b\\c\nd\te\u0001","n":-5,"r":0.1,"big":1e+300,"ms":12.500,"list":[1],"empty":[],"obj":{"k":null}})");
  CHECK_EQ(tmcl::json::write_pretty(v),
           "{\n  \"name\": \"a\\\"b\\\\c\\nd\\te\\u0001\",\n  \"n\": -5,\n  \"r\": 0.1,\n  \"big\": 1e+300,\n"
           "  \"ms\": 12.500,\n  \"list\": [\n    1\n  ],\n  \"empty\": [],\n  \"obj\": {\n    \"k\": null\n  }\n}");
  Value small = Value::object();
  small.set("a", 1);
  small.set("b", Value::array()).push(Value::object()).set("c", true);
  CHECK_EQ(tmcl::json::write_lines(small), "{\"a\":1,\n \"b\":[{\"c\":true}]}");
  CHECK_EQ(tmcl::json::write(Value::number_text("1.")), "null");  // not a JSON number
  CHECK_EQ(tmcl::json::write(Value(std::numeric_limits<double>::infinity())), "null");
  CHECK_EQ(tmcl::json::quote("\xE2\x82\xAC"), "\"\xE2\x82\xAC\"");
}

TEST(set_replaces_in_place) {
  Value v;
  v.set("a", 1);
  v.set("b", 2);
  v.set("a", 3);
  CHECK_EQ(tmcl::json::write(v), R"({"a":3,"b":2})");
  Value a;
  a.push("x");
  CHECK_EQ(tmcl::json::write(a), R"(["x"])");
}

TEST(round_trip) {
  const char* texts[] = {
      R"({"jsonrpc":"2.0","id":1,"method":"initialize","params":{"rootUri":null,"capabilities":{}}})",
      R"([0,-1,1.25,-3.5e-7,"\u00e9",[],{},[[[]]],{"":""}])",
      R"("\ud834\udd1e")",
  };
  for (const char* t : texts) {
    Value v = ok(t);
    std::string once = tmcl::json::write(v);
    Value back = ok(once);
    CHECK(back == v);
    CHECK_EQ(tmcl::json::write(back), once);
    CHECK(ok(tmcl::json::write_pretty(v)) == v);
  }
  CHECK_EQ(tmcl::json::write(ok("-0.0e5")), "-0.0");  // found by fuzz_json: "-0" read back as 0
  CHECK_EQ(tmcl::json::write(ok("-0")), "0");
  CHECK(ok("1") == ok("1.0"));
  CHECK(!(ok("[1]") == ok("[2]")));
  CHECK(!(ok(R"({"a":1,"b":2})") == ok(R"({"b":2,"a":1})")));  // key order is part of the value
}
