// Fuzzes the JSON parser: any bytes are parsed or rejected with a position inside the input and
// a message, never a crash or hang. A text that parses must round-trip: the compact and pretty
// writings parse back to an equal value, and writing that value again gives the same text.
#include <cstdint>
#include <string_view>

#include "tmcl/json.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  tmcl::json::Value v;
  tmcl::json::Error e;
  if (!tmcl::json::parse(text, v, e)) {
    if (e.message.empty() || e.line < 1 || e.column < 1 || e.offset > size || !v.is_null()) __builtin_trap();
    return 0;
  }
  for (const std::string& once : {tmcl::json::write(v), tmcl::json::write_pretty(v), tmcl::json::write_lines(v)}) {
    tmcl::json::Value back;
    if (!tmcl::json::parse(once, back, e)) __builtin_trap();
    if (!(back == v)) __builtin_trap();
  }
  tmcl::json::Value back;
  std::string compact = tmcl::json::write(v);
  tmcl::json::parse(compact, back, e);
  if (tmcl::json::write(back) != compact) __builtin_trap();
  return 0;
}
