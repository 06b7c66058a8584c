// The gdb-like command line of `tmclrun --debug`: command names and abbreviations as gdb's, so
// hands that know gdb know this; output is stable text (golden transcripts pin it). Commands
// come from a file (--debug-commands), a pipe, or a terminal (Enter repeats the last command,
// Ctrl-C pauses a running program). All behaviour is the engine's; this file parses and prints.
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstring>
#include <sstream>

#include "tmcl/asm/disasm.hpp"
#include "tmcl/debug_cli.hpp"
#include "tmcl/duration.hpp"
#include "tmcl/fileio.hpp"
#include "tmcl/program_image.hpp"
#include "source.hpp"
#include "terminal.hpp"

namespace tmcl::debug {
namespace {

Target* g_target = nullptr;
extern "C" void tmcl_debug_on_sigint(int) {
  if (g_target) g_target->pause();
}

}  // namespace

// A named namespace, not an anonymous one: CommandLine::Impl holds a Cli, and in the library's
// unity unit GCC refuses a member of a file-local type in a type with linkage (-Wsubobject-linkage).
namespace gdb {

std::string trim(const std::string& s) {
  std::size_t a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

std::string flags_text(std::uint8_t f) {
  std::string s;
  if (f & kFlagZero) s += " Z";
  if (f & kFlagEqual) s += " EQ";
  if (f & kFlagGreater) s += " GT";
  if (f & kFlagLower) s += " LT";
  return "[" + (s.empty() ? std::string() : s.substr(1)) + "]";
}
std::string errors_text(std::uint8_t f) {
  std::string s;
  if (f & kErrTimeout) s += " ETO";
  if (f & kErrAlarm) s += " EAL";
  if (f & kErrDeviation) s += " EDV";
  if (f & kErrPosition) s += " EPO";
  if (f & kErrShutdown) s += " SHUTDOWN";
  return "[" + (s.empty() ? std::string() : s.substr(1)) + "]";
}
std::string hex(std::int64_t v) {
  char b[32];
  std::snprintf(b, sizeof b, "0x%llx", static_cast<unsigned long long>(static_cast<std::uint32_t>(v)));
  return b;
}

struct Display {
  int id;
  std::string text;
  Expr expr;
};

class Cli {
 public:
  Cli(Target& e, std::FILE* out) : e_(e), m_(e.machine()), out_(out) {
    e_.on_output = [this](const std::string& s) { print(s); };
  }

  // Returns false on quit.
  bool command(const std::string& line);
  std::vector<std::string> completions(const std::string& line, std::size_t start) const;
  int status() const { return status_; }
  void report(const Stop& s);
  void println(const std::string& s) { print(s + "\n"); }

 private:
  void print(const std::string& s) { std::fputs(s.c_str(), out_); }
  void error(const std::string& s) { println(s); }

  std::string frame_line(std::int32_t address) {
    const ProgramInfo& info = e_.info();
    std::string fn = info.function_of(address), place = info.place(address);
    std::string s = fn.empty() ? "address " + std::to_string(address) : fn + " (address " + std::to_string(address) + ")";
    if (!place.empty()) s += " at " + place;
    return s;
  }
  std::string code_line(std::int32_t address) {
    const ProgramInfo& info = e_.info();
    if (const std::string* text = info.source_text(address))
      return std::to_string(info.lines[static_cast<std::size_t>(address)].line) + "\t" + *text;
    if (address >= 0 && address < e_.program_size()) return std::to_string(address) + "\t" + format_instruction(e_.instruction(address));
    return std::to_string(address) + "\t(outside the program)";
  }
  void where_now() {
    const std::int32_t at = e_.pc();
    println(frame_line(at) + e_.when());
    println(code_line(at));
  }
  void show_displays();
  bool need_running() {
    if (e_.running()) return true;
    error("The program is not being run.");
    return false;
  }
  bool parse_count(const std::string& arg, std::uint64_t& n) {
    if (arg.empty()) return n = 1, true;
    Expr x;
    std::int64_t v = 0;
    std::string err;
    if (!parse_expr(arg, e_.info(), x, err) || !e_.eval(x, v, err) || v < 1) {
      error("expected a positive count, not '" + arg + "'");
      return false;
    }
    n = static_cast<std::uint64_t>(v);
    return true;
  }

  void cmd_break(const std::string& arg, bool temporary);
  void cmd_info(const std::string& arg);
  void cmd_backtrace();
  std::string frame_text(const std::vector<Engine::Frame>& frames, std::size_t n);
  void cmd_frame(const std::string& word, const std::string& arg);
  void info_frame();
  std::int32_t selected_pc();
  bool expand_history(std::string& line);
  bool set_switch(const std::string& arg);
  void cmd_list(const std::string& arg);
  void cmd_disassemble(const std::string& arg);
  void cmd_x(const std::string& fmt, const std::string& arg);
  void cmd_print(const std::string& fmt, const std::string& arg);
  void cmd_set(const std::string& arg);
  void info_breakpoints();
  void info_registers();
  void info_interrupts();
  void info_timers();
  void info_motors();
  void module_motors();
  std::string encoder_text(int motor);
  std::string stall_text(int motor);

  Target& e_;
  Engine* m_;  // the virtual machine's engine, for what only it has; nullptr on a module
  std::FILE* out_;
  int status_ = 0;
  std::vector<std::int64_t> values_;  // print's value history: $1 is values_[0]
  std::size_t frame_ = 0;  // the selected frame (up, down, frame N): 0 is the innermost
  std::vector<Display> displays_;
  int next_display_ = 1;
  int list_next_ = -1;  // line after the last `list`, -1: around pc
  int list_file_ = -1;
};

void Cli::report(const Stop& s) {
  switch (s.kind) {
    case StopKind::Entry: break;
    case StopKind::Breakpoint:
      if (s.message.rfind("error in the condition", 0) == 0) {
        println(s.message);
      } else {
        println("");
        print(std::string(s.message == "temporary" ? "Temporary breakpoint " : "Breakpoint ") + std::to_string(s.id) + ", ");
      }
      break;
    case StopKind::Watchpoint: {
      std::string text;
      for (const auto& w : e_.watchpoints())
        if (w.id == s.id) text = w.text;
      println("");
      println("Watchpoint " + std::to_string(s.id) + ": " + text);
      println("");
      println("Old value = " + std::to_string(s.old_value));
      println("New value = " + std::to_string(s.new_value));
      break;
    }
    case StopKind::Step: break;
    case StopKind::Pause: println("\n" + (s.message.empty() ? std::string("Program paused.") : s.message)); break;
    case StopKind::Exited:
      println("[program stopped: " + s.message + e_.when() + "]");
      status_ = 0;
      list_next_ = -1;
      return;
    case StopKind::Fault:
      println("\nProgram faulted: " + s.message);
      status_ = 70;
      break;
    case StopKind::Limit:
      println("\nLimit reached: " + s.message);
      status_ = 3;
      break;
    case StopKind::Blocked:
      println("\nProgram blocked: " + s.message);
      status_ = 3;
      break;
    case StopKind::NotRunning: println(s.message.empty() ? "The program is not being run." : s.message); return;
    case StopKind::HistoryStart: println("\nNo more reverse-execution history."); break;
  }
  list_next_ = -1;
  frame_ = 0;
  where_now();
  show_displays();
}

void Cli::show_displays() {
  for (const auto& d : displays_) {
    std::int64_t v = 0;
    std::string err;
    if (e_.eval(d.expr, v, err))
      println(std::to_string(d.id) + ": " + d.text + " = " + std::to_string(v));
    else
      println(std::to_string(d.id) + ": " + d.text + " = <" + err + ">");
  }
}

void Cli::cmd_break(const std::string& arg, bool temporary) {
  std::string loc = arg, cond;
  // break LOCATION if CONDITION
  auto pos = (" " + arg + " ").find(" if ");
  if (pos != std::string::npos) {
    loc = trim(arg.substr(0, pos));
    cond = trim(arg.substr(std::min(arg.size(), pos + 3)));
  }
  std::int32_t address = 0;
  std::string err;
  if (loc.empty()) {
    if (!e_.running()) return error("No default breakpoint location: the program is not being run.");
    address = e_.pc();
    loc = "*" + std::to_string(address);
  } else if (!e_.resolve(loc, address, err)) {
    return error(err);
  }
  if (!cond.empty()) {
    Expr x;
    if (!parse_expr(cond, e_.info(), x, err)) return error(err);
  }
  int id = e_.add_breakpoint(address, loc, temporary);
  if (!cond.empty()) e_.set_condition(id, cond, err);
  println(std::string(temporary ? "Temporary breakpoint " : "Breakpoint ") + std::to_string(id) + " at " + frame_line(address));
}

void Cli::info_breakpoints() {
  if (e_.breakpoints().empty() && e_.watchpoints().empty()) return println("No breakpoints or watchpoints.");
  println("Num     Type           Disp Enb Address  What");
  struct Row {
    int id;
    std::string text;
  };
  std::vector<Row> rows;
  char buf[512];
  for (const auto& b : e_.breakpoints()) {
    std::string what = e_.info().function_of(b.address);
    std::string place = e_.info().place(b.address);
    if (!place.empty()) what += (what.empty() ? "" : " ") + std::string("at ") + place;
    std::snprintf(buf, sizeof buf, "%-7d %-14s %-4s %-3s %-8d %s\n", b.id, "breakpoint", b.temporary ? "del" : "keep",
                  b.enabled ? "y" : "n", b.address, what.c_str());
    std::string t = buf;
    if (!b.condition.empty()) t += "\tstop only if " + b.condition + "\n";
    if (b.hits) t += "\tbreakpoint already hit " + std::to_string(b.hits) + " time" + (b.hits == 1 ? "" : "s") + "\n";
    if (b.ignore) t += "\tignore next " + std::to_string(b.ignore) + " hits\n";
    rows.push_back({b.id, t});
  }
  for (const auto& w : e_.watchpoints()) {
    std::snprintf(buf, sizeof buf, "%-7d %-14s %-4s %-3s %-8s %s\n", w.id, "watchpoint", "keep", w.enabled ? "y" : "n", "",
                  w.text.c_str());
    std::string t = buf;
    if (w.hits) t += "\tbreakpoint already hit " + std::to_string(w.hits) + " time" + (w.hits == 1 ? "" : "s") + "\n";
    rows.push_back({w.id, t});
  }
  std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.id < b.id; });
  for (const auto& r : rows) print(r.text);
}

void Cli::info_registers() {
  char buf[256];
  auto row = [&](const char* name, std::int64_t v, const std::string& note) {
    std::snprintf(buf, sizeof buf, "%-8s %-12lld %s", name, static_cast<long long>(v), note.c_str());
    println(trim(buf));
  };
  if (!m_) {  // a module: what 135 reads (docs/debugger.md, "Debugging on a module")
    for (const char* r : {"A", "X"}) {
      Expr x;
      std::int64_t v = 0;
      std::string err;
      if (!parse_expr(r, e_.info(), x, err) || !e_.eval(x, v, err)) return error(err);
      row(r, v, hex(v));
    }
    const std::int32_t pc = e_.pc();
    row("pc", pc, frame_line(pc));
    println("status   " + e_.status());
    println("(sp, flags, errors: no command reads them from a module)");
    return;
  }
  Vm& vm = m_->vm();
  row("A", vm.acc, hex(vm.acc));
  row("X", vm.x, hex(vm.x));
  row("pc", vm.pc, frame_line(vm.pc));
  row("sp", vm.sp, "");
  row("flags", vm.flags, flags_text(vm.flags));
  row("errors", vm.errors, errors_text(vm.errors));
  static constexpr const char* kStatus[] = {"stopped", "running", "step", "reset"};
  std::string st = kStatus[static_cast<int>(vm.status) & 3];
  if (vm.wait.active) st += ", in WAIT";
  if (vm.in_handler) st += ", in interrupt " + std::to_string(vm.saved.vector);
  println("status   " + st);
  println("time     " + format_time(vm.now));
  println("steps    " + std::to_string(vm.steps));
}

// One line of backtrace: "#1  loop (address 5) at prog.tmc:9", or the interrupted code's
// frame with what the interrupt saved.
std::string Cli::frame_text(const std::vector<Engine::Frame>& frames, std::size_t n) {
  const Engine::Frame& f = frames[n];
  std::string head = "#" + std::to_string(n) + "  ";
  if (!f.interrupted) return head + frame_line(f.pc);
  if (!m_) {  // a module: what the interrupt saved is not read (no command reads it)
    const InterruptVector* v = e_.profile().vector(f.vector);
    return head + "<interrupt " + std::to_string(f.vector) + (v ? " " + std::string(v->name) : "") + "> resumes " + frame_line(f.pc);
  }
  const auto& s = m_->vm().saved;
  const InterruptVector* v = e_.profile().vector(s.vector);
  std::string name = v ? " " + std::string(v->name) : "";
  return head + "<interrupt " + std::to_string(s.vector) + name + "> saved A=" + std::to_string(s.acc) + " X=" + std::to_string(s.x) +
         " flags=" + flags_text(s.flags) + (s.wait.active ? " (in WAIT)" : "") + ", resumes " + frame_line(f.pc);
}

void Cli::cmd_backtrace() {
  auto frames = e_.frames();
  for (std::size_t n = 0; n < frames.size(); ++n) println(frame_text(frames, n));
  if (e_.frames_unknown_above())
    println("(frames above #" + std::to_string(frames.size() - 1) +
            " unknown: the module cannot read its call stack, and the program ran freely since they were entered)");
}

std::int32_t Cli::selected_pc() {
  auto frames = e_.frames();
  return frames[std::min(frame_, frames.size() - 1)].pc;
}

// up [N], down [N], frame [N] (f): select a frame of the backtrace and show it, as gdb does.
void Cli::cmd_frame(const std::string& word, const std::string& arg) {
  if (!e_.running()) return error("No stack.");
  auto frames = e_.frames();
  frame_ = std::min(frame_, frames.size() - 1);
  std::uint64_t n = 1;
  if (word == "frame" || word == "f") {
    if (!arg.empty()) {
      Expr x;
      std::int64_t level = 0;
      std::string err;
      if (!parse_expr(arg, e_.info(), x, err) || !e_.eval(x, level, err)) return error(err);
      if (level < 0 || static_cast<std::uint64_t>(level) >= frames.size()) return error("No frame at level " + arg + ".");
      frame_ = static_cast<std::size_t>(level);
    }
  } else if (!parse_count(arg, n)) {
    return;
  } else if (word == "up") {
    if (frame_ + 1 >= frames.size()) return error("Initial frame selected; you cannot go up.");
    frame_ = static_cast<std::size_t>(std::min<std::uint64_t>(frame_ + n, frames.size() - 1));
  } else {
    if (frame_ == 0) return error("Bottom (innermost) frame selected; you cannot go down.");
    frame_ = n >= frame_ ? 0 : frame_ - static_cast<std::size_t>(n);
  }
  list_next_ = -1;
  println(frame_text(frames, frame_));
  println(code_line(frames[frame_].pc));
}

// info frame: where the selected frame is, how it was entered and where it goes back to.
void Cli::info_frame() {
  if (!e_.running()) return error("No stack.");
  auto frames = e_.frames();
  const std::size_t n = std::min(frame_, frames.size() - 1);
  const Engine::Frame& f = frames[n];
  println("Stack level " + std::to_string(n) + ", " + frame_line(f.pc) + ":");
  if (f.interrupted && m_) {
    const Vm& vm = m_->vm();
    const InterruptVector* v = vm.profile->vector(vm.saved.vector);
    println(" interrupted by interrupt " + std::to_string(vm.saved.vector) + (v ? " (" + std::string(v->name) + ")" : "") +
            (vm.saved.wait.active ? " in its WAIT" : " before this instruction") + "; RETI resumes here");
    println(" saved A=" + std::to_string(vm.saved.acc) + " X=" + std::to_string(vm.saved.x) + " flags=" + flags_text(vm.saved.flags));
  } else if (f.interrupted) {  // a module: the handler was seen entered by a step
    const InterruptVector* v = e_.profile().vector(f.vector);
    println(" interrupted by interrupt " + std::to_string(f.vector) + (v ? " (" + std::string(v->name) + ")" : "") +
            " before this instruction; RETI resumes here");  // entered by a step, before this instruction ran
  } else if (n == 0) {
    const bool waiting = m_ ? m_->vm().wait.active : e_.status().find("in WAIT") != std::string::npos;
    println(" pc " + std::to_string(f.pc) + (waiting ? ", in its WAIT" : ", the instruction that runs next"));
  } else {
    println(" pc " + std::to_string(f.pc) + ", the call; it returns to " + frame_line(f.pc + 1));
  }
  if (n + 1 < frames.size()) {
    const Engine::Frame& up = frames[n + 1];
    println(up.interrupted ? " an interrupt handler, entered from frame " + std::to_string(n + 1)
                           : " a subroutine, called by frame " + std::to_string(n + 1) + " at " + frame_line(up.pc));
  } else if (e_.frames_unknown_above()) {
    println(" the outermost frame known: the frames above it are unknown (the module cannot read its call stack)");
  } else {
    println(" the outermost frame");
  }
  if (n > 0) println(" caller of frame " + std::to_string(n - 1));
}

void Cli::info_interrupts() {
  if (!m_) return error("info interrupts: not on a module: no command reads a module's interrupt state");
  Vm& vm = m_->vm();
  println(std::string("interrupts globally ") + (vm.global_enable ? "enabled" : "disabled") +
          (vm.in_handler ? ", in the handler of " + std::to_string(vm.saved.vector) : ""));
  bool any = false;
  for (int n = 0; n < 255; ++n) {
    std::int32_t h = vm.vectors[static_cast<std::size_t>(n)];
    bool pending = (vm.pending[static_cast<std::size_t>(n >> 6)] >> (n & 63)) & 1;
    if (h < 0 && !vm.is_enabled(n)) continue;
    any = true;
    const InterruptVector* v = vm.profile->vector(n);
    std::string name = v ? std::string(v->name) : "";
    char buf[256];
    std::snprintf(buf, sizeof buf, "%3d %-16s handler %-28s %s%s", n, name.c_str(),
                  h < 0 ? "(none)" : frame_line(h).c_str(), vm.is_enabled(n) ? "enabled" : "disabled", pending ? ", pending" : "");
    println(buf);
  }
  if (!any) println("no vectors defined and no interrupt enabled");
}

void Cli::info_timers() {
  if (!m_) return error("info timers: not on a module: no command reads a module's timers");
  Vm& vm = m_->vm();
  for (int n = 0; n < Vm::kTimers; ++n) {
    const Timer& t = vm.timers[static_cast<std::size_t>(n)];
    if (t.period_ms == 0)
      println("timer " + std::to_string(n) + ": off");
    else
      println("timer " + std::to_string(n) + ": every " + std::to_string(t.period_ms) + " ms, next at " + format_time(t.next));
  }
}

// ", encoder N (deviation D)" where the core models the module's encoder: 209 and its distance
// from the position counter (axis parameter 1), which 212 bounds (docs/motion.md).
std::string Cli::encoder_text(int m) {
  Vm& vm = m_->vm();
  std::int32_t enc = 0, pos = 0;
  if (!vm.motion->models_encoder(*vm.profile) || vm.get_axis(m, 209, enc) != kStatusOk || vm.get_axis(m, 1, pos) != kStatusOk)
    return {};
  return ", encoder " + std::to_string(enc) + " (deviation " + std::to_string(static_cast<std::int64_t>(pos) - enc) + ")";
}

// ", load value L, actual current C, stall flag F": what stallGuard2 and coolStep give of the
// motor (docs/motion.md, "Loads, stalls and lost steps"), as GAP reads them, each where the
// profile lists it: 206 (0..1023, 0 at the stall), 180 (the current scale 0..31 of the run
// current 6) and 208 bit 0 (stallGuard2 status) where the module has stallGuard2 (174).
std::string Cli::stall_text(int m) {
  Vm& vm = m_->vm();
  const Profile& p = *vm.profile;
  std::string s;
  std::int32_t v = 0;
  if (p.axis_param(206) && vm.get_axis(m, 206, v) == kStatusOk) s += ", load value " + std::to_string(v);
  if (p.axis_param(180) && vm.get_axis(m, 180, v) == kStatusOk) s += ", actual current " + std::to_string(v);
  if (p.axis_param(174) && p.axis_param(208) && vm.get_axis(m, 208, v) == kStatusOk) s += ", stall flag " + std::to_string(v & 1);
  return s;
}

void Cli::info_motors() {
  if (!m_) return module_motors();
  Vm& vm = m_->vm();
  for (int m = 0; m < vm.profile->motors; ++m) {
    MotionSample s = vm.motion->sample_at(m, vm.now);
    std::int32_t target = 0;
    bool has_target = vm.get_axis(m, 0, target) == kStatusOk;
    const char* phase = s.velocity == 0 && s.acceleration == 0 ? "standing"
                        : s.acceleration == 0                  ? "constant velocity"
                        : (s.acceleration > 0) == (s.velocity >= 0) ? "accelerating"
                                                                     : "decelerating";
    char buf[256];
    std::snprintf(buf, sizeof buf, "motor %d: position %lld, velocity %.0f pps, acceleration %.0f pps², %s", m,
                  static_cast<long long>(s.position), s.velocity, s.acceleration, phase);
    std::string line = buf;
    if (has_target) line += ", target " + std::to_string(target);
    if (vm.motion->target_reached(m)) line += ", target reached";
    if (static_cast<std::size_t>(m) < vm.switches.size()) {
      const MotorSwitches& sw = vm.switches[static_cast<std::size_t>(m)];
      std::string on = std::string(sw.left ? " left" : "") + (sw.right ? " right" : "") + (sw.home ? " home" : "");
      if (!on.empty()) line += ", switches on:" + on;
    }
    line += stall_text(m) + encoder_text(m);
    println(line);
  }
  // The lines above are physical; an expression reads the parameters as the module gives them,
  // which on a core in chip units are not pps (the same units as GAP).
  const std::string units = vm.motion->units_note();
  println(units.empty() ? std::string("(expressions read velocity in pps and acceleration in pps² too: velocity M, ap(5, M))")
                        : "(expressions read the module's own units: velocity M, ap(5, M) in " + units + ")");
}

// info motors on a module: what GAP reads, in the module's own units.
void Cli::module_motors() {
  for (int m = 0; m < e_.profile().motors; ++m) {
    std::string line = "motor " + std::to_string(m) + ":";
    const char* sep = " ";
    for (auto [param, name] : {std::pair{1, "position"}, {3, "velocity"}, {0, "target"}, {8, "target reached"}}) {
      if (!e_.profile().axis_param(param)) continue;
      Expr x;
      std::int64_t v = 0;
      std::string err;
      const std::string text = "ap(" + std::to_string(param) + ", " + std::to_string(m) + ")";
      if (!parse_expr(text, e_.info(), x, err) || !e_.eval(x, v, err)) return error(err);
      line += sep + std::string(name) + " " + std::to_string(v);
      sep = ", ";
    }
    println(line);
  }
  println("(as GAP reads them, in the module's own units)");
}

void Cli::cmd_list(const std::string& arg) {
  const ProgramInfo& info = e_.info();
  int file = list_file_, center = 0;
  if (!arg.empty()) {
    std::int32_t a = 0;
    std::string err;
    if (!e_.resolve(arg, a, err)) return error(err);
    if (static_cast<std::size_t>(a) >= info.lines.size() || info.lines[static_cast<std::size_t>(a)].file < 0)
      return error("no source for address " + std::to_string(a));
    file = info.lines[static_cast<std::size_t>(a)].file;
    center = info.lines[static_cast<std::size_t>(a)].line;
    list_next_ = std::max(1, center - 5);
  } else if (list_next_ < 0) {
    std::int32_t a = e_.running() ? selected_pc() : e_.pc();
    if (static_cast<std::size_t>(a) >= info.lines.size() || info.lines[static_cast<std::size_t>(a)].file < 0)
      return cmd_disassemble("");
    file = info.lines[static_cast<std::size_t>(a)].file;
    center = info.lines[static_cast<std::size_t>(a)].line;
    list_next_ = std::max(1, center - 5);
  }
  if (file < 0 || static_cast<std::size_t>(file) >= info.files.size() || info.files[static_cast<std::size_t>(file)].text.empty())
    return error(file >= 0 && static_cast<std::size_t>(file) < info.files.size()
                     ? "no source text for '" + info.files[static_cast<std::size_t>(file)].name + "' (the file was not found)"
                     : "no source text at hand");
  list_file_ = file;
  const auto& text = info.files[static_cast<std::size_t>(file)].text;
  if (static_cast<std::size_t>(list_next_) > text.size())
    return error("Line number " + std::to_string(list_next_) + " out of range; \"" + info.files[static_cast<std::size_t>(file)].name +
                 "\" has " + std::to_string(text.size()) + " lines.");
  int last = std::min<int>(static_cast<int>(text.size()), list_next_ + 9);
  for (int l = list_next_; l <= last; ++l) println(std::to_string(l) + "\t" + text[static_cast<std::size_t>(l - 1)]);
  list_next_ = last + 1;
}

void Cli::cmd_disassemble(const std::string& arg) {
  const ProgramInfo& info = e_.info();
  const std::int32_t size = e_.program_size();
  std::int32_t from = 0, to = size - 1;
  std::string err;
  if (auto comma = arg.find(','); comma != std::string::npos) {
    if (!e_.resolve(arg.substr(0, comma), from, err) || !e_.resolve(arg.substr(comma + 1), to, err)) return error(err);
  } else {
    std::int32_t at = selected_pc();
    if (!arg.empty() && !e_.resolve(arg, at, err)) return error(err);
    // The "function" around `at`: from its label to the next label.
    std::int64_t lo = 0, hi = size;
    for (const auto& l : info.labels) {
      if (l.second <= at && l.second > lo) lo = l.second;
      if (l.second > at && l.second < hi) hi = l.second;
    }
    from = static_cast<std::int32_t>(lo);
    to = static_cast<std::int32_t>(hi - 1);
  }
  std::string fn = info.function_of(from);
  println("Dump of program memory " + std::to_string(from) + ".." + std::to_string(to) + (fn.empty() ? "" : " (" + fn + ")") + ":");
  const std::int32_t mark = e_.running() ? selected_pc() : -1;
  for (std::int32_t a = from; a <= to && a < size; ++a) {
    std::string f = info.function_of(a), place = info.place(a), numbers;
    std::string text = named_instruction(info, e_.instruction(a), a, e_, &numbers);
    char buf[512];
    std::snprintf(buf, sizeof buf, "%s%5d %-16s %-32s %-16s", a == mark ? "=> " : "   ", a, f.empty() ? "" : ("<" + f + ">").c_str(),
                  text.c_str(), place.c_str());
    std::string row = buf;
    if (!numbers.empty()) row += " // " + numbers;  // the numbers behind the names
    row.erase(row.find_last_not_of(' ') + 1);
    println(row);
  }
  println("End of dump.");
}

void Cli::cmd_x(const std::string& fmt, const std::string& arg) {
  std::uint64_t n = 1;
  if (!fmt.empty()) {
    std::string digits;
    for (char c : fmt)
      if (std::isdigit(static_cast<unsigned char>(c))) digits += c;
    if (!digits.empty() && digits.size() < 6) n = std::stoul(digits);
  }
  std::int32_t at = e_.running() ? selected_pc() : e_.pc();
  std::string err;
  if (!arg.empty() && !e_.resolve(arg[0] == '*' ? arg : "*" + arg, at, err)) return error(err);
  // x/Ni: instructions as gdb shows them, `=>` at pc; otherwise their bytes too.
  const bool insns = fmt.find('i') != std::string::npos;
  const std::int32_t mark = e_.running() ? e_.pc() : -1;
  for (std::uint64_t i = 0; i < n && at < e_.program_size(); ++i, ++at) {
    const Instruction ins = e_.instruction(at);
    std::string f = e_.info().function_of(at), numbers;
    std::string text = named_instruction(e_.info(), ins, at, e_, &numbers);
    char buf[256];
    if (insns)
      std::snprintf(buf, sizeof buf, "%s%d%s:\t%s", at == mark ? "=> " : "   ", at, f.empty() ? "" : (" <" + f + ">").c_str(), text.c_str());
    else
      std::snprintf(buf, sizeof buf, "%d%s:\t%02X %02X %02X %08X\t%s", at, f.empty() ? "" : (" <" + f + ">").c_str(), ins.op, ins.type,
                    ins.motor, static_cast<std::uint32_t>(ins.value), text.c_str());
    println(std::string(buf) + (numbers.empty() ? "" : "\t// " + numbers));
  }
}

void Cli::cmd_print(const std::string& fmt, const std::string& arg) {
  Expr x;
  std::string err;
  std::int64_t v = 0;
  if (arg.empty()) return error("print needs an expression");
  // print LV = EXPR assigns, as in gdb.
  auto eq = arg.find('=');
  if (eq != std::string::npos && eq > 0 && arg[eq - 1] != '!' && arg[eq - 1] != '<' && arg[eq - 1] != '>' && arg[eq - 1] != '=' &&
      (eq + 1 >= arg.size() || arg[eq + 1] != '=')) {
    cmd_set("var " + arg);
    if (!parse_expr(trim(arg.substr(0, eq)), e_.info(), x, err)) return;
  } else if (!parse_expr(arg, e_.info(), x, err)) {
    return error(err);
  }
  if (!e_.eval(x, v, err)) return error(err);
  std::string text = fmt == "x" ? hex(v) : fmt == "t" ? "" : std::to_string(v);
  if (fmt == "t") {
    auto u = static_cast<std::uint32_t>(v);
    for (int b = 31; b >= 0; --b)
      if (!text.empty() || ((u >> b) & 1) || b == 0) text += ((u >> b) & 1) ? '1' : '0';
  }
  values_.push_back(v);
  println("$" + std::to_string(values_.size()) + " = " + text);
}

// $, $$, $N and $$N (gdb's value history) become the values they name, in parentheses; $NAME
// (a register: $pc, $sp, $acc, $x) is left to the expression parser.
bool Cli::expand_history(std::string& line) {
  std::string out;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] != '$' || (i + 1 < line.size() && (std::isalpha(static_cast<unsigned char>(line[i + 1])) || line[i + 1] == '_'))) {
      out += line[i];
      continue;
    }
    std::size_t j = i + 1;
    const bool back = j < line.size() && line[j] == '$';
    if (back) ++j;
    const std::size_t digits = j;
    while (j < line.size() && j - digits < 9 && std::isdigit(static_cast<unsigned char>(line[j]))) ++j;
    const std::string num = line.substr(digits, j - digits);
    if (j < line.size() && (std::isalnum(static_cast<unsigned char>(line[j])) || line[j] == '_')) {
      std::size_t end = j;
      while (end < line.size() && std::isalnum(static_cast<unsigned char>(line[end]))) ++end;
      error("'" + line.substr(i, end - i) + "': $N is the value history; hexadecimal is written 0x" + line.substr(i + 1, end - i - 1) + ".");
      return false;
    }
    const std::size_t k = num.empty() ? (back ? 1 : 0) : std::stoul(num);
    const std::string name = line.substr(i, j - i);
    std::size_t index = 0;  // into values_
    if (values_.empty()) {
      error("History is empty: " + name + " names no value yet (print makes $1, $2, ...).");
      return false;
    }
    if (back || num.empty()) {  // counted back from the last value: $ is $$0, $$ is $$1
      if (k >= values_.size()) return error("History has not yet reached " + name + "."), false;
      index = values_.size() - 1 - k;
    } else {
      if (k == 0 || k > values_.size()) return error("History has not yet reached " + name + "."), false;
      index = k - 1;
    }
    out += "(" + std::to_string(values_[index]) + ")";
    i = j - 1;
  }
  line = out;
  return true;
}

// set var switch left|right|home MOTOR = VALUE: a stop or home switch, as a scenario line.
bool Cli::set_switch(const std::string& arg) {
  static const char* kUsage = "usage: set var switch left|right|home MOTOR = VALUE";
  if (!m_) return error("set var switch: not on a module: its switches are real ones"), false;
  const std::string which = arg.substr(0, arg.find_first_of(" \t"));
  const std::string rest = trim(arg.substr(which.size()));
  const auto eq = rest.find('=');
  InputEvent ev;
  if (which == "left") ev.kind = InputEvent::StopLeft;
  else if (which == "right") ev.kind = InputEvent::StopRight;
  else if (which == "home") ev.kind = InputEvent::Home;
  else return error(kUsage), false;
  if (eq == std::string::npos || trim(rest.substr(0, eq)).empty()) return error(kUsage), false;
  Expr m, v;
  std::string err;
  std::int64_t motor = 0, value = 0;
  if (!parse_expr(trim(rest.substr(0, eq)), e_.info(), m, err) || !e_.eval(m, motor, err) ||
      !parse_expr(trim(rest.substr(eq + 1)), e_.info(), v, err) || !e_.eval(v, value, err))
    return error(err), false;
  const int motors = e_.profile().motors;
  if (motor < 0 || motor >= motors)
    return error("motor " + std::to_string(motor) + " is out of range (0.." + std::to_string(motors - 1) + ")"), false;
  ev.index = static_cast<int>(motor);
  ev.value = value != 0;
  if (!m_->set_input(ev, err)) return error(err), false;
  return true;
}

void Cli::cmd_set(const std::string& arg) {
  std::string a = trim(arg);
  if (a.rfind("var ", 0) == 0 || a.rfind("variable ", 0) == 0) a = trim(a.substr(a.find(' ')));
  if (a.rfind("switch ", 0) == 0) return static_cast<void>(set_switch(trim(a.substr(7))));
  if (Engine::is_machine_line(a)) {  // set var hardstop ..., set var load ...: the scenario's lines
    std::string err;
    if (!m_) return error("set var " + a.substr(0, a.find(' ')) + ": not on a module: its stops and loads are real ones");
    if (!m_->set_machine(a, err)) error(err);
    return;
  }
  auto eq = a.find('=');
  if (eq == std::string::npos) return error("usage: set var LVALUE = EXPRESSION");
  Expr lhs, rhs;
  std::string err;
  std::int64_t v = 0;
  if (!parse_expr(trim(a.substr(0, eq)), e_.info(), lhs, err)) return error(err);
  if (!parse_expr(trim(a.substr(eq + 1)), e_.info(), rhs, err)) return error(err);
  if (!e_.eval(rhs, v, err)) return error(err);
  if (!e_.assign(lhs, v, err)) return error(err);
}

void Cli::cmd_info(const std::string& arg) {
  std::string what = trim(arg);
  auto is = [&](std::initializer_list<const char*> names) {
    for (const char* n : names)
      if (what == n) return true;
    return false;
  };
  if (is({"breakpoints", "break", "b", "br", "watchpoints", "watch"})) return info_breakpoints();
  if (is({"registers", "reg", "r", "all-registers"})) return info_registers();
  if (is({"interrupts", "int"})) return info_interrupts();
  if (is({"timers"})) return info_timers();
  if (is({"motors", "motor"})) return info_motors();
  if (is({"frame", "f"})) return info_frame();
  if (is({"stack", "s"})) return cmd_backtrace();
  if (is({"display"})) {
    if (displays_.empty()) return println("There are no auto-display expressions now.");
    for (const auto& d : displays_) println(std::to_string(d.id) + ":   " + d.text);
    return;
  }
  if (is({"checkpoints"})) {
    if (!m_) return error("info checkpoints: not on a module: the module keeps no history");
    const Engine& e = *m_;
    return println(std::to_string(e.checkpoint_count()) + " checkpoints, " + std::to_string(e.checkpoint_memory() / 1024) +
                   " KiB of at most " + std::to_string(e.setup().checkpoint_bytes / 1024) + " KiB");
  }
  error("Undefined info command: \"" + what +
        "\".  Try breakpoints, registers, frame, stack, interrupts, timers, motors, display or checkpoints.");
}

bool Cli::command(const std::string& raw) {
  std::string line = trim(raw);
  if (line.empty() || line[0] == '#') return true;
  if (line.find('$') != std::string::npos && !expand_history(line)) return true;
  std::string word = line.substr(0, line.find_first_of(" \t/"));
  std::string fmt;
  std::string rest = trim(line.substr(word.size()));
  if (!rest.empty() && rest[0] == '/') {
    auto sp = rest.find_first_of(" \t");
    fmt = rest.substr(1, sp == std::string::npos ? std::string::npos : sp - 1);
    rest = sp == std::string::npos ? "" : trim(rest.substr(sp));
  }
  auto is = [&](std::initializer_list<const char*> names) {
    for (const char* n : names)
      if (word == n) return true;
    return false;
  };
  std::uint64_t n = 1;
  std::string err;
  if (is({"quit", "q", "exit"})) return false;
  if (is({"break", "b", "br", "bre", "brea"})) return cmd_break(rest, false), true;
  if (is({"tbreak", "tb", "tbr"})) return cmd_break(rest, true), true;
  if (is({"delete", "d", "del"})) {
    if (rest.empty()) return e_.delete_all(), true;
    std::istringstream ids(rest);
    for (std::string id; ids >> id;)
      if (!e_.delete_point(std::atoi(id.c_str()))) error("No breakpoint number " + id + ".");
    return true;
  }
  if (is({"disable", "disa", "dis", "enable", "en"})) {
    bool on = word[0] == 'e';
    std::istringstream ids(rest);
    if (rest.empty()) {
      for (auto& b : e_.breakpoints()) e_.enable_point(b.id, on);
      for (auto& w : e_.watchpoints()) e_.enable_point(w.id, on);
    }
    for (std::string id; ids >> id;)
      if (!e_.enable_point(std::atoi(id.c_str()), on)) error("No breakpoint number " + id + ".");
    return true;
  }
  if (is({"condition", "cond"})) {
    std::string id = rest.substr(0, rest.find(' '));
    std::string cond = rest.size() > id.size() ? trim(rest.substr(id.size())) : "";
    if (!e_.set_condition(std::atoi(id.c_str()), cond, err)) error(err);
    else if (cond.empty()) println("Breakpoint " + id + " now unconditional.");
    return true;
  }
  if (is({"ignore"})) {
    std::istringstream a(rest);
    int id = 0, count = 0;
    if (!(a >> id >> count)) return error("usage: ignore N COUNT"), true;
    if (!e_.set_ignore(id, count)) return error("No breakpoint number " + std::to_string(id) + "."), true;
    println("Will ignore next " + std::to_string(count) + " crossings of breakpoint " + std::to_string(id) + ".");
    return true;
  }
  if (is({"watch", "wa"})) {
    int id = e_.add_watchpoint(rest, err);
    if (!id) return error(err), true;
    println("Watchpoint " + std::to_string(id) + ": " + rest);
    return true;
  }
  if (is({"run", "r", "start"})) {
    Stop s = e_.start(word == "start");
    if (word == "start" && s.kind != StopKind::NotRunning) println("Program started at " + frame_line(0) + ".");
    report(s);
    return true;
  }
  if (is({"continue", "c", "cont", "fg"})) {
    if (!need_running()) return true;
    // continue N: ignore this breakpoint N-1 more times, as in gdb.
    if (!rest.empty() && parse_count(rest, n))
      for (auto& b : e_.breakpoints())
        if (b.address == e_.pc() && b.enabled) {
          e_.set_ignore(b.id, static_cast<int>(n - 1));
          println("Will ignore next " + std::to_string(n - 1) + " crossings of breakpoint " + std::to_string(b.id) + ".  Continuing.");
        }
    report(e_.cont());
    return true;
  }
  if (is({"step", "s", "stepi", "si"})) {
    if (!need_running() || !parse_count(rest, n)) return true;
    return report(e_.step(n)), true;
  }
  if (is({"next", "n", "nexti", "ni"})) {
    if (!need_running() || !parse_count(rest, n)) return true;
    Stop s;
    for (std::uint64_t i = 0; i < n; ++i) {
      s = e_.next();
      if (s.kind != StopKind::Step) break;
    }
    return report(s), true;
  }
  if (is({"finish", "fin"})) {
    if (!need_running()) return true;
    std::string from = frame_line(e_.pc());
    if (e_.depth() == 0) return error("\"finish\" not meaningful in the outermost frame."), true;
    if (!m_) {  // a module may not know the caller: then it refuses, and nothing ran
      Stop s = e_.finish();
      if (s.kind != StopKind::NotRunning) println("Run till exit from " + from);
      return report(s), true;
    }
    println("Run till exit from " + from);
    return report(e_.finish()), true;
  }
  if (is({"until", "u", "advance"})) {
    if (!need_running()) return true;
    if (rest.empty()) return report(word == "advance" ? Stop{StopKind::NotRunning, 0, "advance needs a duration or a location", 0, 0} : e_.next()), true;
    if (word == "advance")
      if (auto d = parse_duration(rest))
        return report(m_ ? m_->advance(*d) : e_.cannot("advance", "a module's time cannot be bounded from outside (until LOCATION, or Ctrl-C)")), true;
    std::int32_t a = 0;
    if (!e_.resolve(rest, a, err)) return error(err), true;
    return report(e_.until(a)), true;
  }
  if (is({"load"})) {
    if (!rest.empty()) return error("load takes no arguments: it downloads the program being debugged"), true;
    if (!e_.load(err)) return error(err), true;
    println("Loaded " + std::to_string(e_.info().program.size()) + " instructions, verified.");
    return true;
  }
  if (is({"jump", "j"})) {
    if (!need_running()) return true;
    if (!m_) return error("jump: not on a module: no command moves its pc without running it"), true;
    std::int32_t a = 0;
    if (!e_.resolve(rest, a, err)) return error(err), true;
    e_.set_pc(a);
    return where_now(), true;
  }
  if (is({"kill", "k"})) {
    if (!need_running()) return true;
    e_.kill();
    println("[program killed]");
    return true;
  }
  if (is({"reverse-step", "rs", "reverse-stepi", "rsi", "reverse-next", "rn", "reverse-nexti", "rni", "reverse-finish",
          "reverse-continue", "rc"})) {
    if (!parse_count(rest, n)) return true;
    Stop s;
    if (!m_) {  // only the virtual machine keeps history
      std::string why;
      e_.can_reverse(why);
      const std::string name = word == "rs" || word == "reverse-stepi" || word == "rsi" ? "reverse-step"
                               : word == "rn" || word == "reverse-nexti" || word == "rni" ? "reverse-next"
                               : word == "rc"                                          ? "reverse-continue"
                                                                                       : word;
      return error(e_.cannot(name, why).message), true;
    }
    if (word == "reverse-finish") {
      Vm& vm = m_->vm();
      const bool handler = vm.in_handler && vm.sp == vm.saved.stack_depth;
      const int vector = vm.saved.vector;
      s = e_.reverse_finish();
      if (s.kind == StopKind::Step)
        println(handler ? "Run back to before interrupt " + std::to_string(vector) + " was entered"
                        : "Run back to call of " + frame_line(m_->vm().pc));
    } else if (word == "reverse-continue" || word == "rc") {
      s = e_.reverse_continue();
    } else if (word.find("next") != std::string::npos || word == "rn" || word == "rni") {
      for (std::uint64_t i = 0; i < n; ++i)
        if ((s = e_.reverse_next()).kind != StopKind::Step) break;
    } else {
      s = e_.reverse_step(n);
    }
    if (s.kind == StopKind::NotRunning) return error(s.message), true;
    return report(s), true;
  }
  if (is({"backtrace", "bt", "where"})) return cmd_backtrace(), true;
  if (is({"up", "down", "frame", "f"})) return cmd_frame(word, rest), true;
  if (is({"info", "i"})) return cmd_info(rest), true;
  if (is({"list", "l"})) return cmd_list(rest), true;
  if (is({"disassemble", "disas"})) return cmd_disassemble(rest), true;
  if (is({"x"})) return cmd_x(fmt, rest), true;
  if (is({"print", "p", "inspect", "call"})) return cmd_print(fmt, rest), true;
  if (is({"display", "disp"})) {
    if (rest.empty()) return show_displays(), true;
    Display d{next_display_, rest, {}};
    if (!parse_expr(rest, e_.info(), d.expr, err)) return error(err), true;
    ++next_display_;
    displays_.push_back(d);
    std::int64_t v = 0;
    if (e_.eval(d.expr, v, err)) println(std::to_string(d.id) + ": " + d.text + " = " + std::to_string(v));
    return true;
  }
  if (is({"undisplay"})) {
    int id = std::atoi(rest.c_str());
    std::erase_if(displays_, [&](const Display& d) { return rest.empty() || d.id == id; });
    return true;
  }
  if (is({"set"})) return cmd_set(rest), true;
  if (is({"help", "h"})) {
    println("Breakpoints: break/b, tbreak, delete/d, disable, enable, condition, ignore, watch, info breakpoints");
    println("Running: run/r, start, continue/c [N], step/s [N], next/n [N], finish, until/u LOC, advance DURATION|LOC,");
    println("         jump LOC, kill, quit/q; on a module: load");
    println("Reverse: reverse-step/rs [N], reverse-next/rn, reverse-finish, reverse-continue/rc");
    println("Looking: info registers|frame|interrupts|timers|motors|display|checkpoints, backtrace/bt, up, down,");
    println("         frame N, list/l, disassemble, x/N[i] ADDRESS, print/p[/x] EXPR, display EXPR, undisplay");
    println("Changing: set var LV = EXPR (in(n) and ain(n) too), set var switch left|right|home MOTOR = VALUE,");
    println("         set var hardstop left|right MOTOR at POS, set var load MOTOR = P%, set var load MOTOR from A to B = P%");
    println("Locations: LABEL, LINE, FILE:LINE, *ADDRESS.  Expressions: A X flags errors pc sp time steps v[n]");
    println("         ap(param, motor) gp(bank, n) in(n) ain(n) out(n) labels constants, C operators, 2s = 2000000,");
    println("         $pc $sp $acc $x, the value history $ $$ $N $$N, hexadecimal 0x1F.");
    return true;
  }
  error("Undefined command: \"" + word + "\".  Try \"help\".");
  return true;
}

// Tab completion: a command's name as the first word; after `info` what it shows, after `set`
// `var`, after `set var` the machine's inputs (switch, hardstop, load), after `set var switch`
// the switches, after `set var hardstop` the sides, and the keywords of those lines; anywhere
// else labels, constants (the parameter names the program defines, e.g. AP_ActualPosition of
// USB-2-SD.inc), source files, registers ($pc too) and the expression functions.
std::vector<std::string> Cli::completions(const std::string& line, std::size_t start) const {
  static const char* kCommands[] = {
      "advance", "backtrace", "break", "condition", "continue", "delete", "disable", "disassemble", "display", "down",
      "enable", "finish", "frame", "help", "ignore", "info", "jump", "kill", "list", "load", "next", "nexti", "print", "quit",
      "reverse-continue", "reverse-finish", "reverse-next", "reverse-step", "run", "set", "start", "step", "stepi",
      "tbreak", "undisplay", "until", "up", "watch", "where", "x"};
  static const char* kInfo[] = {"breakpoints", "checkpoints", "display", "frame", "interrupts", "motors", "registers", "stack",
                                "timers", "watchpoints"};
  static const char* kWords[] = {"A", "X", "acc", "flags", "errors", "pc", "sp", "time", "steps", "v[", "ap(", "gp(", "in(", "ain(", "out("};
  static const char* kRegisters[] = {"$pc", "$sp", "$acc", "$x", "$a", "$flags", "$errors", "$time", "$steps"};
  const std::string word = line.substr(start);
  std::istringstream before(line.substr(0, start));
  std::vector<std::string> words;
  for (std::string w; before >> w;) words.push_back(w);
  std::vector<std::string> out;
  auto offer = [&](const std::string& name) {
    if (name.size() < word.size()) return;
    for (std::size_t i = 0; i < word.size(); ++i)
      if (std::tolower(static_cast<unsigned char>(name[i])) != std::tolower(static_cast<unsigned char>(word[i]))) return;
    out.push_back(name);
  };
  if (words.empty()) {
    for (const char* c : kCommands) offer(c);
    return out;
  }
  if (words.size() == 1 && (words[0] == "info" || words[0] == "i")) {
    for (const char* c : kInfo) offer(c);
    return out;
  }
  if (words.size() == 1 && words[0] == "set") {
    offer("var");
    offer("variable");
    return out;
  }
  if (words.size() == 2 && words[0] == "set" && words[1].rfind("var", 0) == 0)
    for (const char* c : {"switch", "hardstop", "load"}) offer(c);
  if (words.size() == 3 && words[0] == "set" && words[2] == "switch") {
    for (const char* c : {"left", "right", "home"}) offer(c);
    return out;
  }
  if (words.size() == 3 && words[0] == "set" && words[2] == "hardstop") {
    for (const char* c : {"left", "right"}) offer(c);
    return out;
  }
  // set var hardstop SIDE MOTOR |at, set var load MOTOR |from (or '='), ... |to
  if (words.size() == 5 && words[0] == "set" && words[2] == "hardstop") return offer("at"), out;
  if (words.size() == 4 && words[0] == "set" && words[2] == "load") return offer("from"), out;
  if (words.size() == 6 && words[0] == "set" && words[2] == "load" && words[4] == "from") return offer("to"), out;
  if (!word.empty() && word[0] == '$') {
    for (const char* r : kRegisters) offer(r);
    return out;
  }
  const ProgramInfo& info = e_.info();
  for (const auto& l : info.labels) offer(l.first);
  for (const auto& c : info.constants) offer(c.first);
  for (const auto& f : info.files) offer(f.name + ":");
  for (const char* w : kWords) offer(w);
  return out;
}

}  // namespace gdb

struct CommandLine::Impl {
  gdb::Cli cli;
  bool echo, repeat;
  std::string last;
  Impl(Target& e, std::FILE* out, bool echo_lines, bool repeat_empty) : cli(e, out), echo(echo_lines), repeat(repeat_empty) {}
};

CommandLine::CommandLine(Target& engine, std::FILE* out, bool echo, bool repeat)
    : impl_(std::make_unique<Impl>(engine, out, echo, repeat)), out_(out) {}
CommandLine::~CommandLine() = default;

bool CommandLine::line(std::string text) {
  if (!text.empty() && text.back() == '\n') text.pop_back();
  if (!text.empty() && text.back() == '\r') text.pop_back();
  if (impl_->echo) {
    std::fprintf(out_, "(tmdb) %s\n", text.c_str());
    std::fflush(out_);  // seen before a command that runs for long
  }
  if (gdb::trim(text).empty() && impl_->repeat) text = impl_->last;  // Enter repeats the last command
  else if (!gdb::trim(text).empty()) impl_->last = text;
  bool more = impl_->cli.command(text);
  std::fflush(out_);
  return more;
}

void CommandLine::report(const Stop& stop) {
  impl_->cli.report(stop);
  std::fflush(out_);
}

void CommandLine::note(const std::string& text) {
  impl_->cli.println(text);
  std::fflush(out_);
}

int CommandLine::status() const { return impl_->cli.status(); }

std::vector<std::string> CommandLine::completions(const std::string& line, std::size_t start) const {
  return impl_->cli.completions(line, start);
}

int run_cli(Target& engine, const CliOptions& options, std::FILE* in, std::FILE* out) {
  std::FILE* src = in;
  bool from_file = !options.commands_file.empty();
  std::vector<std::string> script;
  if (from_file) {
    std::vector<std::uint8_t> bytes;
    std::string err;
    if (!read_file(options.commands_file, bytes, err)) {
      std::fprintf(stderr, "%s: error: %s\n", options.tool.c_str(), err.c_str());
      return 65;
    }
    std::string text(bytes.begin(), bytes.end());
    std::istringstream lines(text);
    for (std::string l; std::getline(lines, l);) script.push_back(l);
  }
  const bool tty = !from_file && ::isatty(::fileno(src));
  CommandLine cli(engine, out, !tty, !from_file);
  // On a terminal (both ways) the line editor reads the commands: history, keys, completion.
  std::unique_ptr<TerminalPrompt> editor;
  if (tty && TerminalPrompt::usable(::fileno(src), ::fileno(out)))
    editor = std::make_unique<TerminalPrompt>(::fileno(src), ::fileno(out), "(tmdb) ",
                                              [&cli](const std::string& l, std::size_t at) { return cli.completions(l, at); });
  g_target = &engine;
  os::SavedSignal old;
  os::catch_signal(SIGINT, tmcl_debug_on_sigint, false, &old);
  // The note of an unbounded run, as a plain run gives it (docs/tmclrun.md): when neither
  // --max-time nor --max-steps bounds the program and standard error is a terminal, a command
  // that has run for 2 s of wall time says so once, whether the commands come from a terminal,
  // a pipe or a file. The wall clock times the note only; the engine asks between slices.
  using Clock = std::chrono::steady_clock;
  Clock::time_point command_start = Clock::now();
  bool noted = false;
  Engine* machine = engine.machine();
  const Limits* bounds = machine ? &machine->setup().limits : nullptr;
  if (bounds && bounds->until == kNever && bounds->max_steps == UINT64_MAX && ::isatty(2) && !machine->on_slice)
    machine->on_slice = [machine, &command_start, &noted] {
      if (!noted && Clock::now() - command_start >= std::chrono::seconds(2)) {
        noted = true;
        std::fprintf(stderr,
                     "tmclrun: note: still running after 2 s, at simulated time %s (no --max-time or --max-steps): "
                     "--max-time DURATION bounds a run; Ctrl-C pauses it\n",
                     format_time(machine->vm().now).c_str());
        std::fflush(stderr);
      }
      return kNever;
    };
  std::size_t next_line = 0;
  for (;;) {
    std::string line;
    if (from_file) {
      if (next_line >= script.size()) break;
      line = script[next_line++];
    } else if (editor) {
      std::fflush(out);
      std::optional<std::string> typed = editor->read_line();
      if (!typed) {
        std::fputs("quit\n", out);  // Ctrl-D, as gdb
        break;
      }
      line = *typed;
    } else {
      if (tty) {
        std::fputs("(tmdb) ", out);
        std::fflush(out);
      }
      char buf[4096];
      if (!std::fgets(buf, sizeof buf, src)) break;
      line = buf;
    }
    command_start = Clock::now();
    noted = false;
    if (options.quit && *options.quit) break;
    if (!cli.line(line)) break;
    if (options.quit && *options.quit) break;  // SIGTERM, SIGHUP: the command was paused; the session ends
  }
  if (machine) machine->on_slice = nullptr;
  os::restore_signal(SIGINT, old);
  g_target = nullptr;
  std::fflush(out);
  return cli.status();
}

// ---- loading ----

bool load_program_info(const std::string& path, const Profile& profile, AsmOptions asm_options, const std::string& symbols,
                       ProgramInfo& info, std::string& messages, const std::vector<std::string>& source_dirs) {
  std::vector<std::uint8_t> bytes;
  std::string err;
  if (!read_file(path, bytes, err)) {
    messages += "tmclrun: error: " + err + "\n";
    return false;
  }
  auto ends = [&](const char* suf) {
    std::string s = path, f = suf;
    if (s.size() < f.size()) return false;
    for (std::size_t i = 0; i < f.size(); ++i)
      if (std::tolower(static_cast<unsigned char>(s[s.size() - f.size() + i])) != f[i]) return false;
    return true;
  };
  info = ProgramInfo{};
  if (ends(".bin") || ends(".dgm")) {
    if (!read_program_image(path, bytes, info.program, messages)) return false;
    if (!symbols.empty() && !apply_symbols(symbols, source_dirs, info, messages)) return false;
  } else {
    DiskReader reader;
    asm_options.profile = &profile;
    asm_options.symbols = true;
    AsmResult res = assemble({path}, asm_options, reader);
    if (!res.diags.all().empty()) messages += res.diags.render(res.sources);
    if (!res.ok()) return false;
    info.program = res.program;
    for (const auto& f : res.sources.files) {
      ProgramInfo::File pf;
      pf.name = f.name;
      pf.text = split_lines(f.text);
      info.files.push_back(std::move(pf));
    }
    for (const auto& li : res.lines) info.lines.push_back({li.file, li.line});
    for (const auto& s : res.symbols)
      (s.kind == SymbolKind::Label ? info.labels : info.constants).emplace_back(s.name, s.value);
  }
  if (info.program.empty()) {
    messages += path + ": error: the program is empty\n";
    return false;
  }
  return true;
}

}  // namespace tmcl::debug
