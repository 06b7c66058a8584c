// Stable text views of a run: instruction text, --trace lines, the --json state and the summary.
// Every format here is pinned by golden files in tests/golden/vm; change them deliberately.
#include "tmcl/vm_output.hpp"

#include <algorithm>
#include <cinttypes>
#include <optional>
#include <set>

#include "tmcl/duration.hpp"
#include "tmcl/json.hpp"
#include "tmcl/params.hpp"

namespace tmcl {

std::string instruction_text(const Instruction& ins) { return named_instruction_text(ins, 0, nullptr); }

std::string flags_text(std::uint8_t flags) {
  std::string s;
  auto add = [&](bool on, const char* name) {
    if (!on) return;
    if (!s.empty()) s += '|';
    s += name;
  };
  add(flags & kFlagZero, "ZE");
  add(flags & kFlagEqual, "EQ");
  add(flags & kFlagGreater, "GT");
  add(flags & kFlagLower, "LT");
  return s.empty() ? "-" : s;
}

std::string errors_text(std::uint8_t errors) {
  std::string s;
  auto add = [&](bool on, const char* name) {
    if (!on) return;
    if (!s.empty()) s += '|';
    s += name;
  };
  add(errors & kErrTimeout, "ETO");
  add(errors & kErrAlarm, "EAL");
  add(errors & kErrDeviation, "EDV");
  add(errors & kErrPosition, "EPO");
  add(errors & kErrShutdown, "ESD");
  return s.empty() ? "-" : s;
}

// ---------------------------------------------------------------- trace

void TextTrace::written() {
  if (failed_ || !std::ferror(out_)) return;
  failed_ = true;
  if (write_failed) write_failed();
}

std::string TextTrace::where(std::int32_t pc) const {
  if (sources_ && pc >= 0 && static_cast<std::size_t>(pc) < sources_->size() && !(*sources_)[static_cast<std::size_t>(pc)].empty())
    return (*sources_)[static_cast<std::size_t>(pc)];
  return "-";
}

namespace {
// A core in chip units (tmc429): the physical value of the velocity or acceleration an instruction
// wrote or read, e.g. "motor 0, parameter 4: 1000 = 30517.578 pps"; nullopt otherwise.
std::optional<std::string> units_text(const Vm& vm, const Instruction& ins) {
  int param = ins.type;
  std::int32_t raw = ins.value;
  switch (static_cast<Op>(ins.op)) {
    case Op::ROR: case Op::ROL: param = kApTargetSpeed; raw = ins.op == static_cast<std::uint8_t>(Op::ROL) ? -ins.value : ins.value; break;
    case Op::RORA: case Op::ROLA: param = kApTargetSpeed; raw = vm.acc; break;
    case Op::SAP: break;
    case Op::GAP: case Op::AAP: raw = vm.acc; break;
    default: return std::nullopt;
  }
  if (!vm.motor_ok(ins.motor)) return std::nullopt;
  auto phys = vm.motion->physical(ins.motor, param, raw);
  if (!phys) return std::nullopt;
  char buf[128];
  std::snprintf(buf, sizeof buf, "motor %d, parameter %d: %" PRId32 " = %.3f %s", ins.motor, param, raw, phys->value,
                std::string(phys->unit).c_str());
  return std::string(buf);
}
}  // namespace

// The widths of the source and instruction columns, from the whole program, once.
void TextTrace::measure(const Vm& vm) {
  std::size_t source = 16, text = 28;
  if (sources_)
    for (const auto& s : *sources_) source = std::max(source, s.size());
  for (std::int32_t a = 0; a < vm.program_size; ++a)
    text = std::max(text, named_instruction_text(vm.program[static_cast<std::size_t>(a)], a, names_).size());
  source_width_ = static_cast<int>(source);
  text_width_ = static_cast<int>(text);
}

void TextTrace::instruction(const Vm& vm, SimTime at, std::int32_t pc, const Instruction& ins) {
  if (source_width_ == 0) measure(vm);
  const std::string plain = instruction_text(ins);
  const std::string named = names_ ? named_instruction_text(ins, pc, names_) : plain;
  std::fprintf(out_, "%s %5" PRId32 " %-*s %-*s A=%" PRId32 " X=%" PRId32 " F=%s E=%s%s%s\n", format_time(at).c_str(), pc,
               source_width_, where(pc).c_str(), text_width_, named.c_str(), vm.acc, vm.x, flags_text(vm.flags).c_str(),
               errors_text(vm.errors).c_str(), named == plain ? "" : "  // ", named == plain ? "" : plain.c_str());
  if (auto u = units_text(vm, ins)) std::fprintf(out_, "%s  units: %s\n", format_time(at).c_str(), u->c_str());
  // New units hold from the instruction's end (vm.now here), the instant the CSV and the plot
  // give them too (docs/tmclrun.md).
  if (std::string note = vm.motion->units_note(); !note.empty() && note != units_) {
    std::fprintf(out_, "%s  units: %s\n", format_time(vm.now).c_str(), note.c_str());
    units_ = std::move(note);
  }
  written();
}

void TextTrace::interrupt_enter(const Vm& vm, int vector, std::int32_t from_pc) {
  const InterruptVector* v = vm.profile->vector(vector);
  std::fprintf(out_, "%s  --> interrupt %d%s%s%s from %" PRId32 " to %" PRId32 "\n", format_time(vm.now).c_str(), vector,
               v ? " (" : "", v ? std::string(v->name).c_str() : "", v ? ")" : "", from_pc, vm.pc);
  written();
}

void TextTrace::interrupt_leave(const Vm& vm, std::int32_t to_pc) {
  std::fprintf(out_, "%s  <-- interrupt done, continue at %" PRId32 "\n", format_time(vm.now).c_str(), to_pc);
  written();
}

void TextTrace::motion_event(const Vm& vm, const MotionEvent& ev) {
  (void)vm;
  std::fprintf(out_, "%s  motion: motor %d %s at position %" PRId32 "\n", format_time(ev.at).c_str(), ev.motor,
               motion_event_text(ev).c_str(), ev.position);
  written();
}

void TextTrace::wait_end(const Vm& vm, std::int32_t pc, bool timeout) {
  std::fprintf(out_, "%s  wait at %" PRId32 " %s\n", format_time(vm.now).c_str(), pc, timeout ? "timed out (ETO set)" : "ended");
  written();
}

void TextTrace::input_event(const Vm& vm, const std::string& what) {
  std::fprintf(out_, "%s  input: %s\n", format_time(vm.now).c_str(), what.c_str());
  written();
}

// Same form as a wait line: the instant, then the address (and source line) it happened at.
void TextTrace::warning(const Vm& vm, const RuntimeWarning& w) {
  (void)vm;
  std::fprintf(out_, "%s  %s at %" PRId32 " %s: %s\n", format_time(w.at).c_str(), w.note ? "note" : "warning", w.pc,
               where(w.pc).c_str(), w.message.c_str());
  written();
}

// ---------------------------------------------------------------- JSON

namespace {

// Every JSON text of tmclrun is written by the project's JSON library (tmcl/json.hpp).
// The run-time warnings (or notes) of a run as a JSON list under `key`.
void set_warnings(json::Value& s, const char* key, const std::vector<RuntimeWarning>& list) {
  json::Value& out = s.set(key, json::Value::array());
  for (const auto& w : list) {
    json::Value& o = out.push(json::Value::object());
    o.set("time_us", static_cast<long long>(w.at));
    o.set("pc", static_cast<long long>(w.pc));
    o.set("kind", warning_kind_name(w.kind));
    o.set("message", w.message);
  }
}

template <typename Range>
json::Value int_array(const Range& r) {
  json::Value a = json::Value::array();
  for (auto v : r) a.push(static_cast<long long>(v));
  return a;
}

// A motor still turning after STOP (errata E50): STOP ends the program, not the motion, so a
// ROR/ROL goes on as on the module. `speed` is what axis parameter 3 reads (the core's units),
// `pps` the physical speed.
struct Moving {
  int motor;
  std::int32_t speed;
  double pps;
};
std::vector<Moving> moving_after_stop(Vm& vm, const RunResult& result) {
  std::vector<Moving> list;
  if (result.halt != Halt::Stop) return list;
  vm.sync_motion();
  for (int m = 0; m < vm.profile->motors; ++m) {
    // A core without a recorder's view (sample_at) still reports parameter 3.
    double pps = vm.motion->sample_at(m, vm.now).velocity;
    const std::int32_t raw = vm.motion->owns(kApActualSpeed) ? vm.motion->get_param(m, kApActualSpeed) : 0;
    if (pps == 0.0 && raw != 0) {
      auto phys = vm.motion->physical(m, kApTargetSpeed, raw);
      pps = phys ? phys->value : raw;
    }
    if (pps == 0.0) continue;
    list.push_back({m, raw != 0 ? raw : static_cast<std::int32_t>(pps), pps});
  }
  return list;
}

std::string pps_text(double pps) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3f", pps);
  std::string s = buf;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

// Axis parameter numbers worth reporting for a motor: the profile's, the core's, any written.
std::set<int> axis_numbers(const Vm& vm, int motor) {
  std::set<int> n;
  for (const auto& p : vm.profile->axis_params) n.insert(p.number);
  for (int p = 0; p < 256; ++p) {
    if (vm.motion->owns(p) || vm.axis_written[static_cast<std::size_t>(motor)][static_cast<std::size_t>(p)]) n.insert(p);
  }
  return n;
}

}  // namespace

std::string state_json(Vm& vm, const RunResult& result) {
  json::Value s = json::Value::object();
  s.set("halt", halt_name(result.halt));
  s.set("message", result.message);
  if (auto moving = moving_after_stop(vm, result); !moving.empty()) {  // only then: no key more otherwise
    json::Value& list = s.set("moving", json::Value::array());
    for (const auto& mv : moving) {
      json::Value& o = list.push(json::Value::object());
      o.set("motor", mv.motor);
      o.set("speed", static_cast<long long>(mv.speed));
      o.set("pps", json::Value::number_text(pps_text(mv.pps)));
    }
  }
  s.set("profile", vm.profile->name);
  s.set("motion", vm.motion->name());
  s.set("time_us", static_cast<long long>(vm.now));
  char ms[48];
  std::snprintf(ms, sizeof ms, "%lld.%03lld", static_cast<long long>(vm.now / 1000), static_cast<long long>(vm.now % 1000));
  s.set("time_ms", json::Value::number_text(ms));  // always three decimals
  s.set("steps", static_cast<long long>(vm.steps));
  s.set("pc", static_cast<long long>(vm.pc));
  s.set("acc", static_cast<long long>(vm.acc));
  s.set("x", static_cast<long long>(vm.x));
  json::Value& flags = s.set("flags", json::Value::object());
  flags.set("ZE", (vm.flags & kFlagZero) != 0);
  flags.set("EQ", (vm.flags & kFlagEqual) != 0);
  flags.set("GT", (vm.flags & kFlagGreater) != 0);
  flags.set("LT", (vm.flags & kFlagLower) != 0);
  json::Value& errors = s.set("errors", json::Value::object());
  errors.set("ETO", (vm.errors & kErrTimeout) != 0);
  errors.set("EAL", (vm.errors & kErrAlarm) != 0);
  errors.set("EDV", (vm.errors & kErrDeviation) != 0);
  errors.set("EPO", (vm.errors & kErrPosition) != 0);
  errors.set("ESD", (vm.errors & kErrShutdown) != 0);
  s.set("stack", int_array(std::vector<std::int32_t>(vm.stack.begin(), vm.stack.begin() + vm.sp)));
  s.set("vars", int_array(vm.vars));
  json::Value& axis = s.set("axis", json::Value::array());
  for (int m = 0; m < vm.profile->motors; ++m) {
    json::Value& motor = axis.push(json::Value::object());
    for (int p : axis_numbers(vm, m)) motor.set(std::to_string(p), static_cast<long long>(vm.axis_param(m, p)));
  }
  json::Value& coords = s.set("coords", json::Value::array());
  for (const auto& c : vm.coords) coords.push(int_array(c));
  // Ports 0 up to the highest the profile lists in that bank, at least 0 … 7 (E53).
  auto ports = [&](const std::array<std::int32_t, Vm::kPorts>& a, int bank) {
    const int n = std::max(8, vm.profile->last_port(bank) + 1);
    return int_array(std::vector<std::int32_t>(a.begin(), a.begin() + n));
  };
  s.set("inputs", ports(vm.inputs, 0));
  s.set("analog", ports(vm.analog, 1));
  s.set("outputs", ports(vm.outputs, 2));
  json::Value& globals = s.set("globals", json::Value::object());
  {
    json::Value& g0 = globals.set("0", json::Value::object());
    std::set<int> nums;
    for (const auto& p : vm.profile->bank0) nums.insert(p.number);
    for (int p = 0; p < 256; ++p)
      if (vm.bank0[static_cast<std::size_t>(p)] != 0) nums.insert(p);
    nums.insert({kGpApplicationStatus, kGpDownloadMode, kGpProgramCounter, kGpTickTimer});
    nums.erase(kGpRandomNumber);  // reading it would change it
    for (int p : nums) g0.set(std::to_string(p), static_cast<long long>(vm.global_param(0, p)));
    json::Value& g3 = globals.set("3", json::Value::object());
    nums.clear();
    for (const auto& p : vm.profile->bank3) nums.insert(p.number);
    for (int p = 0; p < 256; ++p)
      if (vm.bank3[static_cast<std::size_t>(p)] != 0) nums.insert(p);
    for (int p : nums) g3.set(std::to_string(p), static_cast<long long>(vm.bank3[static_cast<std::size_t>(p)]));
  }
  json::Value enabled = json::Value::array(), vectors = json::Value::object();
  for (int n = 0; n < 255; ++n) {
    if (vm.is_enabled(n)) enabled.push(n);
    if (vm.vectors[static_cast<std::size_t>(n)] >= 0)
      vectors.set(std::to_string(n), static_cast<long long>(vm.vectors[static_cast<std::size_t>(n)]));
  }
  json::Value& interrupts = s.set("interrupts", json::Value::object());
  interrupts.set("global", vm.global_enable);
  interrupts.set("enabled", std::move(enabled));
  interrupts.set("vectors", std::move(vectors));
  interrupts.set("in_handler", vm.in_handler);
  // Only when there are any, so that a clean run's JSON has no key more.
  if (vm.warnings_total != 0) {
    set_warnings(s, "warnings", vm.warnings);
    s.set("warnings_omitted", static_cast<long long>(vm.warnings_total - vm.warnings.size()));
  }
  if (!vm.notes.empty()) {  // E52: what the run does not simulate though the program enabled it
    set_warnings(s, "notes", vm.notes);
  }
  return json::write_lines(s) + "\n";
}

std::string status_text(int status) {
  switch (status) {
    case kStatusWrongChecksum: return "wrong checksum";
    case kStatusInvalidCommand: return "invalid command";
    case kStatusWrongType: return "wrong type";
    case kStatusInvalidValue: return "invalid value";
    case kStatusEepromLocked: return "EEPROM locked";
    case kStatusNotAvailable: return "command not available";
    case kStatusOk: return "ok";
    case kStatusLoaded: return "loaded into program memory";
    case kStatusPositionReached: return "position reached";
    default: return "status " + std::to_string(status);
  }
}

namespace {

// Opcode 0 is no instruction: hosts send it at the end of a download (TMCL-IDE, go-tmcl's "NOP
// sentinel"), and program memory past the program reads as it (errata S7).
std::string word_text(const Instruction& ins) {
  if (ins.op != 0) return instruction_text(ins);
  std::string s = "end marker (NOP)";
  if (ins.type != 0 || ins.motor != 0 || ins.value != 0)
    s += ", type " + std::to_string(ins.type) + ", motor " + std::to_string(ins.motor) + ", value " + std::to_string(ins.value);
  return s;
}

// The reply in words: a special reply (134 or 136 type 0) as what it carries, decoded with the
// codec; any other as its status and value.
std::string reply_text(const Instruction& request, const Frame& reply, bool special) {
  if (special && request.op == static_cast<std::uint8_t>(Op::ReadProgramMemory)) return word_text(decode7(reply.data() + 1));
  if (special) {  // 136 type 0: eight characters; anything unprintable as \xNN
    std::string s = "\"";
    for (std::size_t i = 1; i < reply.size(); ++i) {
      const unsigned char c = reply[i];
      if (c >= 0x20 && c < 0x7F && c != '"' && c != '\\') {
        s += static_cast<char>(c);
      } else {
        char hex[8];
        std::snprintf(hex, sizeof hex, "\\x%02X", c);
        s += hex;
      }
    }
    return s + "\"";
  }
  const Reply r = decode_reply(reply.data());
  return std::to_string(r.status) + " " + status_text(r.status) + ", value " + std::to_string(r.value);
}

}  // namespace

std::string exchange_text(SimTime at, int module, const Instruction& request, const Frame& reply, bool special, bool sent) {
  // A control command (128..138, 255) has no source form: its number, name and fields.
  const OpInfo* info = op_info(request.op);
  std::string what = info && info->control
                         ? std::to_string(request.op) + " " + std::string(info->id) + ", type " + std::to_string(request.type) +
                               ", motor " + std::to_string(request.motor) + ", value " + std::to_string(request.value)
                         : word_text(request);
  return format_time(at) + " module " + std::to_string(module) + ": " + what + " -> " + reply_text(request, reply, special) +
         (sent ? "" : " (reply suppressed)") + "\n";
}

std::string error_json(std::string_view kind, int exit_status, const std::vector<JsonDiagnostic>& diags,
                       long long more) {
  json::Value s = json::Value::object();
  s.set("error", kind);
  s.set("exit", exit_status);
  s.set("message", diags.empty() ? std::string_view() : std::string_view(diags.front().message));
  json::Value& list = s.set("diagnostics", json::Value::array());
  for (const auto& d : diags) {
    json::Value& o = list.push(json::Value::object());
    o.set("file", d.file);
    o.set("line", d.line);
    o.set("column", d.column);
    o.set("severity", d.severity);
    o.set("name", d.name.empty() ? json::Value(nullptr) : json::Value(d.name));
    o.set("message", d.message);
  }
  s.set("more", more);
  return json::write_lines(s) + "\n";
}

std::vector<int> shown_motors(Vm& vm) {
  vm.sync_motion();
  std::vector<int> motors;
  if (!vm.profile->any_parameter) {
    for (int m = 0; m < vm.profile->motors; ++m) motors.push_back(m);
    return motors;
  }
  std::vector<bool> named(static_cast<std::size_t>(vm.profile->motors), false);
  for (std::int32_t a = 0; a < vm.program_size; ++a) {
    const Instruction& ins = vm.program[static_cast<std::size_t>(a)];
    const OpInfo* info = op_info(ins.op);
    if (!info || (ins.op == static_cast<std::uint8_t>(Op::WAIT) && ins.type == 0)) continue;  // WAIT TICKS: no motor
    for (const auto& o : info->operands)
      if (o.role == Role::Motor && ins.motor < named.size()) named[ins.motor] = true;
  }
  for (int m = 0; m < vm.profile->motors; ++m)
    if (named[static_cast<std::size_t>(m)] || vm.motion->position(m) != 0) motors.push_back(m);
  return motors;
}

std::string state_summary(Vm& vm, const RunResult& result, const std::array<std::int32_t, 256>* vars_at_start) {
  std::string s = "halted: " + std::string(halt_name(result.halt));
  if (result.halt == Halt::Fault)
    s += " at " + vm.where(vm.halt_pc >= 0 ? vm.halt_pc : vm.pc);  // the message is tmclrun's error line
  else if (!result.message.empty())
    s += " (" + result.message + ")";
  s += "\nsimulated time: " + format_time(vm.now) + "\nsteps: " + std::to_string(vm.steps) + "\n";
  const std::vector<Moving> moving = moving_after_stop(vm, result);
  for (int m : shown_motors(vm)) {
    s += "motor " + std::to_string(m) + ": position " + std::to_string(vm.motion->position(m));
    for (const auto& mv : moving)
      if (mv.motor == m) {
        const std::string pps = pps_text(mv.pps);
        s += ", still moving at " + pps + " pps";
        if (std::to_string(mv.speed) != pps) s += " (actual speed " + std::to_string(mv.speed) + ")";
      }
    s += "\n";
  }
  if (!moving.empty()) s += "note: STOP ends the program, not the motion: the motors above still move, as on the module\n";
  for (std::size_t v = 0; v < vm.vars.size(); ++v) {
    const std::int32_t start = vars_at_start ? (*vars_at_start)[v] : 0;
    if (vm.vars[v] == start) continue;
    s += "variable " + std::to_string(v) + ": " + std::to_string(vm.vars[v]);
    s += start != 0 ? " (at start " + std::to_string(start) + ")\n" : "\n";
  }
  for (const auto& w : vm.warnings) s += "warning: " + format_time(w.at) + " at " + vm.where(w.pc) + ": " + w.message + "\n";
  for (const auto& w : vm.notes) s += "note: " + format_time(w.at) + " at " + vm.where(w.pc) + ": " + w.message + "\n";
  if (vm.warnings_total > vm.warnings.size())
    s += "warning: " + std::to_string(vm.warnings_total - vm.warnings.size()) + " more run-time warnings not shown\n";
  return s;
}

}  // namespace tmcl
