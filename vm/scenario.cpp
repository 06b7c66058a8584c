// Scenario files (format in scenario.hpp): timed input changes, parsed with FILE:LINE errors.
#include "tmcl/scenario.hpp"

#include <sstream>

#include "tmcl/duration.hpp"

namespace tmcl {
namespace {

bool parse_value(const std::string& s, std::int32_t& out) {
  if (s.empty()) return false;
  std::size_t i = (s[0] == '-' || s[0] == '+') ? 1 : 0;
  if (i == s.size()) return false;
  long long v = 0;
  for (; i < s.size(); ++i) {
    if (s[i] < '0' || s[i] > '9') return false;
    v = v * 10 + (s[i] - '0');
    if (v > 2147483648LL) return false;
  }
  if (s[0] == '-') v = -v;
  if (v > INT32_MAX) return false;
  out = static_cast<std::int32_t>(v);
  return true;
}

struct KindName {
  const char* name;
  InputEvent::Kind kind;
  int max_index;  // inclusive
};
constexpr KindName kKinds[] = {
    {"input", InputEvent::Digital, Vm::kPorts - 1}, {"analog", InputEvent::Analog, Vm::kPorts - 1},
    {"left", InputEvent::StopLeft, 255},            {"right", InputEvent::StopRight, 255},
    {"home", InputEvent::Home, 255},                {"slip", InputEvent::Slip, 255},
};

}  // namespace

bool parse_scenario(const std::string& text, const std::string& file, std::vector<InputEvent>& out, std::string& error) {
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  auto fail = [&](const std::string& msg) {
    error = file + ":" + std::to_string(line_no) + ": error: " + msg;
    return false;
  };
  while (std::getline(in, line)) {
    ++line_no;
    if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream ls(line);
    std::vector<std::string> w;
    for (std::string t; ls >> t;) w.push_back(t);
    if (w.empty()) continue;
    if (w[0] != "at") return fail("expected 'at TIME WHAT INDEX = VALUE', found '" + w[0] + "'");
    if (w.size() != 6 || w[4] != "=") return fail("expected 'at TIME WHAT INDEX = VALUE'");
    auto t = parse_duration(w[1]);
    if (!t) return fail("bad time '" + w[1] + "' (use e.g. 0, 250us, 10ms, 2s, 1min)");
    const KindName* kind = nullptr;
    for (const auto& k : kKinds)
      if (w[2] == k.name) kind = &k;
    if (!kind) return fail("unknown input '" + w[2] + "' (input, analog, left, right, home, slip)");
    std::int32_t index = 0, value = 0;
    if (!parse_value(w[3], index) || index < 0 || index > kind->max_index)
      return fail("bad " + w[2] + " number '" + w[3] + "' (0.." + std::to_string(kind->max_index) + ")");
    if (!parse_value(w[5], value)) return fail("bad value '" + w[5] + "' (a 32-bit integer)");
    InputEvent ev;
    ev.at = *t;
    ev.kind = kind->kind;
    ev.index = index;
    ev.value = value;
    ev.line = line_no;
    out.push_back(ev);
  }
  return true;
}

}  // namespace tmcl
