// Scenario files (format in scenario.hpp): timed input changes and loads, and the machine's
// switches, hard stops and loads placed at positions.
// Every line is checked and every
// error collected with its column, so a user mends the whole file in one go, as with the
// assembler. Numbers and times go through the one decimal reader (numbers.hpp, duration.hpp).
#include "tmcl/scenario.hpp"

#include <algorithm>

#include "tmcl/duration.hpp"
#include "tmcl/numbers.hpp"

namespace tmcl {
namespace {

struct KindName {
  const char* name;
  InputEvent::Kind kind;
  int max_index;  // inclusive
  bool motor;     // the index is a motor
  bool percent = false;  // the value is a load: P%
};
constexpr KindName kKinds[] = {
    {"input", InputEvent::Digital, Vm::kPorts - 1, false}, {"analog", InputEvent::Analog, Vm::kPorts - 1, false},
    {"left", InputEvent::StopLeft, 255, true},            {"right", InputEvent::StopRight, 255, true},
    {"home", InputEvent::Home, 255, true},                {"slip", InputEvent::Slip, 255, true},
    {"load", InputEvent::Load, 255, true, true},
};

// The largest load a line may give: 100 % and above all stall the motor alike (docs/motion.md).
constexpr std::int64_t kMaxLoad = 1000;

// `P%`: a load in whole percent of the motor's holding torque, 0%..1000%.
bool parse_percent(const std::string& text, std::int64_t& out) {
  if (text.size() < 2 || text.back() != '%') return false;
  return parse_int(text.substr(0, text.size() - 1), 0, kMaxLoad, out) && text[0] != '+' && text[0] != '-';
}
std::string percent_error(const std::string& text) {
  std::string why = text.empty() || text.back() != '%' ? " (a percentage needs its '%': 50%)" : " (0%..1000%)";
  return "bad load '" + text + "'" + why;
}

// The motor word of a machine line: a number the module has, or an error at it.
template <class AtWord>
bool parse_motor(const LineWord& x, const ScenarioOptions& options, AtWord at_word, std::int64_t& motor) {
  const int max = std::min(255, options.motors - 1);
  if (!parse_int(x.text, 0, 255, motor)) {
    at_word(x, "bad motor number '" + x.text + "' (0.." + std::to_string(max) + ")");
    return false;
  }
  if (motor > max) {
    at_word(x, (options.module.empty() ? std::string("the module") : options.module) + " has no motor " +
                   std::to_string(motor) + " (0.." + std::to_string(max) + ")");
    return false;
  }
  return true;
}

template <class AtWord>
bool parse_position(const LineWord& x, AtWord at_word, std::int64_t& v) {
  if (parse_int(x.text, INT32_MIN, INT32_MAX, v)) return true;
  at_word(x, "bad position '" + x.text + "' (microsteps, a 32-bit integer)");
  return false;
}

// Where each motor's hard stops are, as the file places them: the line that placed one (0: none
// yet) and its position, by motor * 2 + side.
struct HardStops {
  std::vector<int> line = std::vector<int>(256 * 2, 0);
  std::vector<std::int64_t> at = std::vector<std::int64_t>(256 * 2, 0);
};

// `hardstop left|right MOTOR at POS`: a mechanical end the shaft cannot pass (below POS: left,
// above: right). It may lie inside a switch's range (a switch that closes before the end). The
// carriage starts at position 0, so a left end lies at or below 0 and a right end at or above it,
// and a motor's left end lies left of its right end (docs/tmclrun.md).
template <class Error, class AtWord>
void parse_hardstop(const std::vector<LineWord>& w, const ScenarioOptions& options, std::vector<InputEvent>& out,
                    HardStops& stops, int line_no, Error error, AtWord at_word, const std::string& line) {
  static const char* kShape = "expected 'hardstop left|right MOTOR at POSITION'";
  if (w.size() < 5) {
    error(static_cast<int>(line.find_last_not_of(" \t")) + 2, 1, std::string(kShape) + ": the line ends early");
    return;
  }
  int side = w[1].text == "left" ? 0 : w[1].text == "right" ? 1 : -1;
  if (side < 0) {
    std::string hint = closest_match(w[1].text, {"left", "right"});
    at_word(w[1], "unknown hard stop '" + w[1].text + "' (left, right)" + (hint.empty() ? "" : "; did you mean '" + hint + "'?"));
    return;
  }
  std::int64_t motor = 0, p = 0;
  bool ok = parse_motor(w[2], options, at_word, motor);
  if (w[3].text != "at") {
    at_word(w[3], std::string(kShape) + ": 'at' expected here");
    return;
  }
  if (w.size() > 5) {
    at_word(w[5], "unexpected '" + w[5].text + "' after the position (a comment starts with '#')");
    return;
  }
  if (!parse_position(w[4], at_word, p) || !ok) return;
  const auto k = static_cast<std::size_t>(motor * 2 + side);
  int& first = stops.line[k];
  if (first != 0) {
    at_word(w[1], "hardstop " + w[1].text + " " + w[2].text + " is already placed at line " + std::to_string(first));
    return;
  }
  const std::size_t other = k ^ 1;
  if (stops.line[other] != 0 && (side == 0 ? p > stops.at[other] : p < stops.at[other])) {
    at_word(w[4], std::string("the ") + (side == 0 ? "left" : "right") + " end lies " + (side == 0 ? "right" : "left") +
                      " of the " + (side == 0 ? "right" : "left") + " end at " + std::to_string(stops.at[other]) +
                      " (line " + std::to_string(stops.line[other]) + ")");
    return;
  }
  if (options.from_start && (side == 0 ? p > 0 : p < 0)) {
    at_word(w[4], std::string("the carriage starts at position 0, beyond this ") + (side == 0 ? "left" : "right") +
                      " end (a " + (side == 0 ? "left end lies at or below 0" : "right end lies at or above 0") + ")");
    return;
  }
  first = line_no;
  stops.at[k] = p;
  InputEvent ev;
  ev.kind = InputEvent::HardStop;
  ev.index = static_cast<int>(motor);
  ev.input = side == 0 ? SwitchInput::StopLeft : SwitchInput::StopRight;
  ev.from = ev.to = p;
  ev.line = line_no;
  out.push_back(ev);
}

// `load MOTOR from A to B = P%`: a load while the shaft is between A and B (a tight spot, a clamp).
template <class Error, class AtWord>
void parse_load_zone(const std::vector<LineWord>& w, const ScenarioOptions& options, std::vector<InputEvent>& out,
                     int line_no, Error error, AtWord at_word, const std::string& line) {
  static const char* kShape = "expected 'load MOTOR from POSITION to POSITION = P%' (or 'at TIME load MOTOR = P%')";
  if (w.size() < 8) {
    error(static_cast<int>(line.find_last_not_of(" \t")) + 2, 1, std::string(kShape) + ": the line ends early");
    return;
  }
  std::int64_t motor = 0, lo = 0, hi = 0, percent = 0;
  bool ok = parse_motor(w[1], options, at_word, motor);
  if (w[2].text != "from") return at_word(w[2], std::string(kShape) + ": 'from' expected here");
  if (w[4].text != "to") return at_word(w[4], "'to' expected here");
  if (w[6].text != "=") return at_word(w[6], "'=' expected here");
  if (w.size() > 8) return at_word(w[8], "unexpected '" + w[8].text + "' after the load (a comment starts with '#')");
  ok = parse_position(w[3], at_word, lo) && ok;
  ok = parse_position(w[5], at_word, hi) && ok;
  if (!parse_percent(w[7].text, percent)) {
    at_word(w[7], percent_error(w[7].text));
    ok = false;
  }
  if (!ok) return;
  if (lo > hi) return at_word(w[5], "the range ends below its start (" + w[3].text + " > " + w[5].text + ")");
  InputEvent ev;
  ev.kind = InputEvent::LoadZone;
  ev.index = static_cast<int>(motor);
  ev.from = lo;
  ev.to = hi;
  ev.value = static_cast<std::int32_t>(percent);
  ev.line = line_no;
  out.push_back(ev);
}

constexpr KindName kPlaced[] = {
    {"left", InputEvent::Placed, 255, true}, {"right", InputEvent::Placed, 255, true}, {"home", InputEvent::Placed, 255, true}};

// `switch left|right|home MOTOR at POS` or `... from LO to HI`: a switch that belongs to the
// machine, closed while the motor's physical position is <= POS (left), >= POS (right) or in
// [LO, HI]. Appends the event, or reports what is wrong with the line.
// `first_line[motor * 3 + input]`: the line that placed that switch (0: none yet).
template <class Error, class AtWord>
void parse_placed(const std::vector<LineWord>& w, const ScenarioOptions& options, std::vector<InputEvent>& out,
                  std::vector<int>& first_line, int line_no, Error error, AtWord at_word, const std::string& line) {
  static const char* kShape = "expected 'switch left|right MOTOR at POSITION' or 'switch left|right|home MOTOR from POSITION to POSITION'";
  if (w.size() < 5) {
    error(static_cast<int>(line.find_last_not_of(" \t")) + 2, 1, std::string(kShape) + ": the line ends early");
    return;
  }
  int input = -1;
  for (int k = 0; k < 3; ++k)
    if (w[1].text == kPlaced[k].name) input = k;
  if (input < 0) {
    std::string hint = closest_match(w[1].text, {"left", "right", "home"});
    at_word(w[1], "unknown switch '" + w[1].text + "' (left, right, home)" + (hint.empty() ? "" : "; did you mean '" + hint + "'?"));
    return;
  }
  std::int64_t motor = 0;
  const bool ok = parse_motor(w[2], options, at_word, motor);
  auto position = [&](const LineWord& x, std::int64_t& v) { return parse_position(x, at_word, v); };
  InputEvent ev;
  ev.kind = InputEvent::Placed;
  ev.index = static_cast<int>(motor);
  ev.input = static_cast<SwitchInput>(input);
  ev.line = line_no;
  if (w[3].text == "at") {
    if (input == 2) {
      at_word(w[3], "a home switch closes over a range: 'switch home MOTOR from POSITION to POSITION'");
      return;
    }
    if (w.size() > 5) {
      at_word(w[5], "unexpected '" + w[5].text + "' after the position (a comment starts with '#')");
      return;
    }
    std::int64_t p = 0;
    if (!position(w[4], p) || !ok) return;
    ev.from = input == 0 ? INT64_MIN : p;
    ev.to = input == 0 ? p : INT64_MAX;
  } else if (w[3].text == "from") {
    if (w.size() < 7 || w[5].text != "to") {
      if (w.size() < 6)
        error(static_cast<int>(line.find_last_not_of(" \t")) + 2, 1, "'to POSITION' is missing");
      else
        at_word(w[5], "'to' expected here");
      return;
    }
    if (w.size() > 7) {
      at_word(w[7], "unexpected '" + w[7].text + "' after the range (a comment starts with '#')");
      return;
    }
    std::int64_t lo = 0, hi = 0;
    bool good = position(w[4], lo);
    good = position(w[6], hi) && good;
    if (!good || !ok) return;
    if (lo > hi) {
      at_word(w[6], "the range ends below its start (" + w[4].text + " > " + w[6].text + ")");
      return;
    }
    ev.from = lo;
    ev.to = hi;
  } else {
    at_word(w[3], std::string(kShape) + ": 'at' or 'from' expected here");
    return;
  }
  int& first = first_line[static_cast<std::size_t>(ev.index * 3 + input)];
  if (first != 0) {
    at_word(w[1], "switch " + w[1].text + " " + w[2].text + " is already placed at line " + std::to_string(first));
    return;
  }
  first = line_no;
  out.push_back(ev);
}

// `input N` / `analog N`: a port the profile lists (E53), a value in its range; without a profile
// (or under `ports any`) ports 0..7, as before there were port tables.
template <class AtWord>
bool port_ok(const ScenarioOptions& options, const KindName& kind, const std::vector<LineWord>& w, std::int64_t value,
             AtWord at_word) {
  std::int64_t index = 0;
  (void)parse_int(w[3].text, 0, 255, index);
  const bool digital = kind.kind == InputEvent::Digital;
  const Profile* p = options.profile;
  const std::string module = options.module.empty() ? std::string("the module") : options.module;
  if (!p || p->any_port) {
    if (index <= 7) return true;
    at_word(w[3], "bad " + w[2].text + " number '" + w[3].text + "' (0..7)");
    return false;
  }
  const IoPort* port = p->read_port(digital ? 0 : 1, static_cast<int>(index));
  if (!port || port->output || port->kind == PortKind::Bits) {
    std::string list;
    for (const auto& q : p->ports)
      if (q.bank == (digital ? 0 : 1) && !q.output && q.kind != PortKind::Bits)
        list += (list.empty() ? "" : ", ") + std::to_string(q.number);
    at_word(w[3], module + " has no " + (digital ? "digital input " : "analog input ") + w[3].text + " (" +
                      (list.empty() ? std::string("it has none") : w[2].text + " " + list) + ")");
    return false;
  }
  if (!digital && (value < port->min || value > port->max)) {  // a digital input reads any non-zero as 1
    at_word(w[5], "value " + w[5].text + " is outside the range of " + w[2].text + " " + w[3].text + " (" +
                      std::string(port->name) + "): " + std::to_string(port->min) + " to " + std::to_string(port->max) +
                      (port->unit.empty() ? "" : " " + std::string(port->unit)));
    return false;
  }
  return true;
}

}  // namespace

bool parse_scenario(const std::string& text, const std::string& file, std::vector<InputEvent>& out,
                    std::vector<FileDiag>& diags, const ScenarioOptions& options) {
  const std::size_t errors_before = diags.size();
  std::vector<int> placed_at(256 * 3, 0);  // per motor and switch: the line that placed it
  HardStops stop_at;                       // per motor and side: the hard stops placed
  int line_no = 0;
  for (std::size_t pos = 0; pos < text.size();) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(pos, end - pos);
    pos = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::string source = line;
    if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::vector<LineWord> w = split_words(line);
    if (w.empty()) continue;
    auto error = [&](int col, int len, const std::string& msg) {
      diags.push_back({file, line_no, col, len, msg, source});
    };
    auto at_word = [&](const LineWord& x, const std::string& msg) { error(x.col, static_cast<int>(x.text.size()), msg); };
    static const char* kShape = "expected 'at TIME WHAT INDEX = VALUE'";  // (or a switch, hardstop or load line)
    if (w[0].text == "switch") {
      parse_placed(w, options, out, placed_at, line_no, error, at_word, line);
      continue;
    }
    if (w[0].text == "hardstop") {
      parse_hardstop(w, options, out, stop_at, line_no, error, at_word, line);
      continue;
    }
    if (w[0].text == "load") {
      parse_load_zone(w, options, out, line_no, error, at_word, line);
      continue;
    }
    if (w[0].text != "at") {
      at_word(w[0], std::string(kShape) + ", found '" + w[0].text + "'");
      continue;
    }
    if (w.size() < 6) {
      static const char* kParts[] = {"at", "TIME", "WHAT", "INDEX", "'='", "VALUE"};
      error(static_cast<int>(line.find_last_not_of(" \t")) + 2, 1,
            std::string(kShape) + ": " + kParts[w.size()] + " is missing");
      continue;
    }
    if (w[4].text != "=") {
      at_word(w[4], std::string(kShape) + ": '=' expected here");
      continue;
    }
    if (w.size() > 6) {
      at_word(w[6], "unexpected '" + w[6].text + "' after the value (a comment starts with '#')");
      continue;
    }
    InputEvent ev;
    bool ok = true;
    std::string why;
    if (auto t = parse_duration(w[1].text, why)) {
      ev.at = *t;
    } else {
      at_word(w[1], "bad time: " + why);
      ok = false;
    }
    const KindName* kind = nullptr;
    for (const auto& k : kKinds)
      if (w[2].text == k.name) kind = &k;
    if (!kind) {
      std::vector<std::string_view> names;
      for (const auto& k : kKinds) names.emplace_back(k.name);
      std::string hint = closest_match(w[2].text, names);
      at_word(w[2], "unknown input '" + w[2].text + "' (input, analog, left, right, home, slip, load)" +
                        (hint.empty() ? "" : "; did you mean '" + hint + "'?"));
      ok = false;
    } else {
      std::int64_t index = 0;
      int max = kind->motor ? std::min(kind->max_index, options.motors - 1) : kind->max_index;
      if (!parse_int(w[3].text, 0, kind->max_index, index)) {
        at_word(w[3], "bad " + w[2].text + " number '" + w[3].text + "' (0.." + std::to_string(max) + ")");
        ok = false;
      } else if (index > max) {
        at_word(w[3], (options.module.empty() ? std::string("the module") : options.module) + " has no motor " +
                          std::to_string(index) + " (0.." + std::to_string(max) + ")");
        ok = false;
      } else {
        ev.kind = kind->kind;
        ev.index = static_cast<int>(index);
      }
      if (kind->kind == InputEvent::Slip && !options.no_encoder.empty()) {
        at_word(w[2], "'slip' needs an encoder: the motion core '" + options.no_encoder + "' models none on " +
                          (options.module.empty() ? std::string("this module") : options.module));
        ok = false;
      }
    }
    std::int64_t value = 0;
    if (kind && kind->percent) {
      if (!parse_percent(w[5].text, value)) {
        at_word(w[5], percent_error(w[5].text));
        ok = false;
      }
    } else if (!parse_int(w[5].text, INT32_MIN, INT32_MAX, value)) {
      at_word(w[5], "bad value '" + w[5].text + "' (a 32-bit integer)");
      ok = false;
    }
    if (ok && kind && !kind->motor && !port_ok(options, *kind, w, value, at_word)) ok = false;
    if (!ok) continue;
    ev.value = static_cast<std::int32_t>(value);
    ev.line = line_no;
    out.push_back(ev);
  }
  return diags.size() == errors_before;
}

bool parse_scenario(const std::string& text, const std::string& file, std::vector<InputEvent>& out,
                    std::string& error, const ScenarioOptions& options) {
  std::vector<FileDiag> diags;
  if (parse_scenario(text, file, out, diags, options)) return true;
  error = render_file_diags(diags, options.error_limit);
  return false;
}

}  // namespace tmcl
