// Stable text views of a run: instruction text, --trace lines, the --json state and the summary.
// Every format here is pinned by golden files in tests/vm/golden; change them deliberately.
#include "tmcl/vm_output.hpp"

#include <cinttypes>
#include <set>

#include "tmcl/duration.hpp"

namespace tmcl {

std::string instruction_text(const Instruction& ins) {
  const OpInfo* info = op_info(ins.op);
  if (!info || info->control)
    return "?? " + std::to_string(ins.op) + ", " + std::to_string(ins.type) + ", " + std::to_string(ins.motor) + ", " +
           std::to_string(ins.value);
  std::string s(info->mnemonic);
  bool first = true;
  for (const auto& o : info->operands) {
    s += first ? " " : ", ";
    first = false;
    std::int64_t v = o.field == Field::Type ? ins.type : o.field == Field::Motor ? ins.motor : ins.value;
    if (o.keywords != KwSet::None && v >= 0 && v <= 255) {
      if (auto name = keyword_name(o.keywords, static_cast<std::uint8_t>(v))) {
        s += *name;
        continue;
      }
    }
    s += std::to_string(v);
  }
  return s;
}

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

std::string TextTrace::where(std::int32_t pc) const {
  if (sources_ && pc >= 0 && static_cast<std::size_t>(pc) < sources_->size() && !(*sources_)[static_cast<std::size_t>(pc)].empty())
    return (*sources_)[static_cast<std::size_t>(pc)];
  return "-";
}

void TextTrace::instruction(const Vm& vm, SimTime at, std::int32_t pc, const Instruction& ins) {
  std::fprintf(out_, "%s %5" PRId32 " %-16s %-28s A=%" PRId32 " X=%" PRId32 " F=%s E=%s\n", format_time(at).c_str(), pc,
               where(pc).c_str(), instruction_text(ins).c_str(), vm.acc, vm.x, flags_text(vm.flags).c_str(),
               errors_text(vm.errors).c_str());
}

void TextTrace::interrupt_enter(const Vm& vm, int vector, std::int32_t from_pc) {
  const InterruptVector* v = vm.profile->vector(vector);
  std::fprintf(out_, "%s  --> interrupt %d%s%s%s from %" PRId32 " to %" PRId32 "\n", format_time(vm.now).c_str(), vector,
               v ? " (" : "", v ? std::string(v->name).c_str() : "", v ? ")" : "", from_pc, vm.pc);
}

void TextTrace::interrupt_leave(const Vm& vm, std::int32_t to_pc) {
  std::fprintf(out_, "%s  <-- interrupt done, continue at %" PRId32 "\n", format_time(vm.now).c_str(), to_pc);
}

void TextTrace::motion_event(const Vm& vm, const MotionEvent& ev) {
  (void)vm;
  std::fprintf(out_, "%s  motion: motor %d %s at position %" PRId32 "\n", format_time(ev.at).c_str(), ev.motor,
               std::string(motion_event_name(ev.kind)).c_str(), ev.position);
}

void TextTrace::wait_end(const Vm& vm, std::int32_t pc, bool timeout) {
  std::fprintf(out_, "%s  wait at %" PRId32 " %s\n", format_time(vm.now).c_str(), pc, timeout ? "timed out (ETO set)" : "ended");
}

void TextTrace::input_event(const Vm& vm, const std::string& what) {
  std::fprintf(out_, "%s  input: %s\n", format_time(vm.now).c_str(), what.c_str());
}

// ---------------------------------------------------------------- JSON

namespace {

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

template <typename Range>
std::string json_int_array(const Range& r) {
  std::string s = "[";
  bool first = true;
  for (auto v : r) {
    if (!first) s += ",";
    first = false;
    s += std::to_string(v);
  }
  return s + "]";
}

std::string json_bool(bool b) { return b ? "true" : "false"; }

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
  std::string s = "{";
  auto key = [&](const char* k) {
    if (s.size() > 1) s += ",\n ";
    s += "\"";
    s += k;
    s += "\":";
  };
  key("halt");
  s += json_string(halt_name(result.halt));
  key("message");
  s += json_string(result.message);
  key("profile");
  s += json_string(vm.profile->name);
  key("motion");
  s += json_string(vm.motion->name());
  key("time_us");
  s += std::to_string(vm.now);
  key("time_ms");
  char ms[48];
  std::snprintf(ms, sizeof ms, "%lld.%03lld", static_cast<long long>(vm.now / 1000), static_cast<long long>(vm.now % 1000));
  s += ms;
  key("steps");
  s += std::to_string(vm.steps);
  key("pc");
  s += std::to_string(vm.pc);
  key("acc");
  s += std::to_string(vm.acc);
  key("x");
  s += std::to_string(vm.x);
  key("flags");
  s += "{\"ZE\":" + json_bool(vm.flags & kFlagZero) + ",\"EQ\":" + json_bool(vm.flags & kFlagEqual) +
       ",\"GT\":" + json_bool(vm.flags & kFlagGreater) + ",\"LT\":" + json_bool(vm.flags & kFlagLower) + "}";
  key("errors");
  s += "{\"ETO\":" + json_bool(vm.errors & kErrTimeout) + ",\"EAL\":" + json_bool(vm.errors & kErrAlarm) +
       ",\"EDV\":" + json_bool(vm.errors & kErrDeviation) + ",\"EPO\":" + json_bool(vm.errors & kErrPosition) +
       ",\"ESD\":" + json_bool(vm.errors & kErrShutdown) + "}";
  key("stack");
  s += json_int_array(std::vector<std::int32_t>(vm.stack.begin(), vm.stack.begin() + vm.sp));
  key("vars");
  s += json_int_array(vm.vars);
  key("axis");
  s += "[";
  for (int m = 0; m < vm.profile->motors; ++m) {
    if (m) s += ",";
    s += "{";
    bool first = true;
    for (int p : axis_numbers(vm, m)) {
      if (!first) s += ",";
      first = false;
      s += "\"";
      s += std::to_string(p);
      s += "\":";
      s += std::to_string(vm.axis_param(m, p));
    }
    s += "}";
  }
  s += "]";
  key("coords");
  s += "[";
  for (std::size_t m = 0; m < vm.coords.size(); ++m) {
    if (m) s += ",";
    s += json_int_array(vm.coords[m]);
  }
  s += "]";
  key("inputs");
  s += json_int_array(vm.inputs);
  key("analog");
  s += json_int_array(vm.analog);
  key("outputs");
  s += json_int_array(vm.outputs);
  key("globals");
  {
    std::string g = "{\"0\":{";
    std::set<int> nums;
    for (const auto& p : vm.profile->bank0) nums.insert(p.number);
    for (int p = 0; p < 256; ++p)
      if (vm.bank0[static_cast<std::size_t>(p)] != 0) nums.insert(p);
    nums.insert({128, 129, 130, 132});
    nums.erase(133);  // reading the random number would change it
    bool first = true;
    for (int p : nums) {
      g += first ? "\"" : ",\"";
      g += std::to_string(p);
      g += "\":";
      g += std::to_string(vm.global_param(0, p));
      first = false;
    }
    g += "},\"3\":{";
    nums.clear();
    for (const auto& p : vm.profile->bank3) nums.insert(p.number);
    for (int p = 0; p < 256; ++p)
      if (vm.bank3[static_cast<std::size_t>(p)] != 0) nums.insert(p);
    first = true;
    for (int p : nums) {
      g += first ? "\"" : ",\"";
      g += std::to_string(p);
      g += "\":";
      g += std::to_string(vm.bank3[static_cast<std::size_t>(p)]);
      first = false;
    }
    s += g + "}}";
  }
  key("interrupts");
  {
    std::string e = "[", v = "{";
    for (int n = 0; n < 255; ++n) {
      if (vm.is_enabled(n)) {
        if (e.size() > 1) e += ",";
        e += std::to_string(n);
      }
      if (vm.vectors[static_cast<std::size_t>(n)] >= 0) {
        v += v.size() > 1 ? ",\"" : "\"";
        v += std::to_string(n);
        v += "\":";
        v += std::to_string(vm.vectors[static_cast<std::size_t>(n)]);
      }
    }
    s += "{\"global\":" + json_bool(vm.global_enable) + ",\"enabled\":" + e + "],\"vectors\":" + v +
         "},\"in_handler\":" + json_bool(vm.in_handler) + "}";
  }
  s += "}\n";
  return s;
}

std::string state_summary(Vm& vm, const RunResult& result, const SourceMap* sources) {
  (void)sources;
  std::string s = "halted: " + std::string(halt_name(result.halt));
  if (!result.message.empty()) s += " (" + result.message + ")";
  s += "\nsimulated time: " + format_time(vm.now) + "\nsteps: " + std::to_string(vm.steps) + "\n";
  for (int m = 0; m < vm.profile->motors; ++m) {
    vm.sync_motion();
    s += "motor " + std::to_string(m) + ": position " + std::to_string(vm.motion->position(m)) + "\n";
  }
  return s;
}

}  // namespace tmcl
