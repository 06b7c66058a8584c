// `tmclrun --dap`: the engine over the Debug Adapter Protocol on standard input and output
// (Content-Length framed JSON, tmcl::json), so any DAP client (VS Code, nvim-dap, dape, Helix)
// debugs TMCL source. One thread: a request that runs the program answers at once and the
// program then runs in slices (Engine::on_slice), between which the adapter reads the requests
// that came meanwhile: `pause` stops it at the next instruction, `threads`, `disconnect`,
// `terminate` and the breakpoint setters are answered while it runs, anything else gets an
// error response until it stops. Every request it does not support gets an error response.
// docs/debugger.md, "Debug Adapter Protocol".

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <map>
#include <sstream>

#include "tmcl/debug_cli.hpp"
#include "tmcl/debug_module.hpp"
#include "tmcl/duration.hpp"
#include "tmcl/json.hpp"
#include "tmcl/os_files.hpp"
#include "tmcl/os_net.hpp"
#include "tmcl/targets.hpp"

namespace tmcl::debug {
namespace {

using json::Value;

class Dap {
 public:
  Dap(const DapSetup& setup, std::FILE* in, std::FILE* out)
      : setup_(setup), file_fd_(::fileno(in)), in_fd_(os::pollable_input(file_fd_)), out_(out) {}
  // tmclctl PORT debug --dap: the module is attached already; `attach` confirms it (taking the
  // program as it is), `launch` too (then configurationDone resets and runs it, as `run`).
  Dap(const DapSetup& setup, Target& attached, std::FILE* in, std::FILE* out) : Dap(setup, in, out) { use(attached); }
  ~Dap() {
    os::release_pollable_input(in_fd_, file_fd_);
    if (target_) {  // a target attached from outside outlives the adapter
      target_->on_output = nullptr;
      target_->on_wait = nullptr;
    }
  }
  Dap(const Dap&) = delete;
  Dap& operator=(const Dap&) = delete;

  int serve() {
    for (;;) {
      std::string body;
      if (!read_frame(body)) break;
      Value req;
      if (!parse_request(body, req)) continue;
      if (!handle(req)) break;
    }
    end_module();
    return exit_code_;
  }

 private:
  static Value obj(std::initializer_list<std::pair<const char*, Value>> members) {
    Value v = Value::object();
    for (const auto& [k, m] : members) v.set(k, m);
    return v;
  }

  // Input is read from the descriptor into our own buffer (no stdio buffering), so that poll()
  // tells the truth about whether a request is waiting while the program runs.
  // Reads what is there; with `wait`, blocks until something is. False: nothing was read.
  bool fill(bool wait) {
    if (eof_) return false;
    if (!wait) {
      pollfd p = os::poll_entry(in_fd_, POLLIN);
      if (os::poll(&p, 1, 0) <= 0) return false;
    }
    char buf[1 << 16];
    long n = os::read_some(in_fd_, buf, sizeof buf);
    if (n > 0) return inbuf_.append(buf, static_cast<std::size_t>(n)), true;
    if (setup_.quit && *setup_.quit) n = 0;  // a signal ends the session as the client's going would
    if (n < 0 && errno == EINTR) return true;
    eof_ = true;  // end of input, or an error reading it: the client is gone
    return false;
  }
  // One whole frame from the buffer: headers up to an empty line (a Content-Length among
  // them; a header block without one is skipped), then that many bytes.
  enum class Frame { Whole, Partial, Bad };
  Frame take_frame(std::string& body) {
    for (;;) {
      std::size_t end = inbuf_.find("\r\n\r\n"), skip = 4;
      if (std::size_t lf = inbuf_.find("\n\n"); lf != std::string::npos && (end == std::string::npos || lf < end)) end = lf, skip = 2;
      if (end == std::string::npos) return Frame::Partial;
      long length = -1;
      for (std::size_t at = 0; at < end;) {
        std::size_t nl = inbuf_.find('\n', at);
        std::string l = inbuf_.substr(at, std::min(nl, end) - at);
        if (l.rfind("Content-Length:", 0) == 0) length = std::strtol(l.c_str() + 15, nullptr, 10);
        if (nl == std::string::npos) break;
        at = nl + 1;
      }
      if (length < 0) {
        inbuf_.erase(0, end + skip);
        continue;
      }
      if (length > (64 << 20)) return Frame::Bad;
      if (inbuf_.size() < end + skip + static_cast<std::size_t>(length)) return Frame::Partial;
      body = inbuf_.substr(end + skip, static_cast<std::size_t>(length));
      inbuf_.erase(0, end + skip + static_cast<std::size_t>(length));
      return Frame::Whole;
    }
  }
  bool read_frame(std::string& body) {
    for (;;) {
      Frame f = take_frame(body);
      if (f == Frame::Whole) return true;
      if (f == Frame::Bad || !fill(true)) return false;
    }
  }
  bool parse_request(const std::string& body, Value& req) {
    json::Error err;
    if (!json::parse(body, req, err) || !req.is_object()) {
      event("output", obj({{"category", "stderr"}, {"output", "tmclrun --dap: bad message: " + err.to_string() + "\n"}}));
      return false;
    }
    return req["type"].as_string() == "request";
  }

  // Engine::on_slice while the program runs: the requests that came meanwhile.
  SimTime slice() {
    if (setup_.quit && *setup_.quit) ending_ = disconnect_ = true;
    while (!ending_) {
      std::string body;
      Frame f = take_frame(body);
      if (f == Frame::Bad) ending_ = disconnect_ = true;
      if (f != Frame::Whole) {
        if (ending_ || fill(false)) continue;
        if (eof_) ending_ = disconnect_ = true;  // the client went away: stop and end
        break;
      }
      Value req;
      // After a pause, the requests behind it are for the stopped program: they wait.
      if (parse_request(body, req) && handle_running(req)) break;
    }
    if (ending_) target_->pause();
    return kNever;
  }
  bool handle_running(const Value& req);  // true: the program is to stop

  void send(Value msg) {
    msg.set("seq", ++seq_);
    std::string text = json::write(msg);
    std::fprintf(out_, "Content-Length: %zu\r\n\r\n%s", text.size(), text.c_str());
    std::fflush(out_);
  }
  void respond(const Value& req, bool ok, Value body = Value::object(), const std::string& message = "") {
    Value r = obj({{"type", "response"}, {"request_seq", req["seq"].as_int()}, {"success", ok}, {"command", req["command"].as_string()}});
    if (!message.empty()) r.set("message", message);
    r.set("body", std::move(body));
    send(std::move(r));
  }
  void fail(const Value& req, const std::string& message) { respond(req, false, obj({{"error", obj({{"id", 1}, {"format", message}})}}), message); }
  void event(const char* name, Value body = Value::object()) { send(obj({{"type", "event"}, {"event", name}, {"body", std::move(body)}})); }

  // After a run: the stopped event, or exited and terminated.
  void stopped(const Stop& s, const char* step_reason = "step") {
    const char* reason = step_reason;
    Value body = Value::object();
    switch (s.kind) {
      case StopKind::Entry: reason = "entry"; break;
      case StopKind::Breakpoint: reason = "breakpoint"; break;
      case StopKind::Watchpoint: reason = "data breakpoint"; break;
      case StopKind::Pause: reason = "pause"; break;
      case StopKind::Fault: reason = "exception"; break;
      case StopKind::Limit:
      case StopKind::Blocked: reason = "pause"; break;
      case StopKind::HistoryStart: reason = "step"; break;
      case StopKind::Exited:
      case StopKind::NotRunning:
        exit_code_ = s.kind == StopKind::Exited ? 0 : exit_code_;
        event("exited", obj({{"exitCode", exit_code_}}));
        event("terminated");
        return;
      default: break;
    }
    if (s.kind == StopKind::Fault) exit_code_ = 70;
    body.set("reason", reason);
    body.set("threadId", 1);
    body.set("allThreadsStopped", true);
    if (!s.message.empty()) body.set("text", s.message);
    if (s.kind == StopKind::Fault) body.set("description", "runtime fault: " + s.message);
    if (s.kind == StopKind::Breakpoint || s.kind == StopKind::Watchpoint) {
      Value ids = Value::array();
      ids.push(s.id);
      body.set("hitBreakpointIds", ids);
    }
    event("stopped", std::move(body));
  }

  Value source_of(std::int32_t address) const {
    const ProgramInfo& info = target_->info();
    if (address < 0 || static_cast<std::size_t>(address) >= info.lines.size()) return Value();
    int f = info.lines[static_cast<std::size_t>(address)].file;
    if (f < 0) return Value();
    const auto& file = info.files[static_cast<std::size_t>(f)];
    const std::string& name = file.path.empty() ? file.name : file.path;  // a .bin's source as found
    std::string base = name.substr(os::last_separator(name) + 1);
    return obj({{"name", base}, {"path", name}});
  }
  int line_of(std::int32_t address) const {
    const ProgramInfo& info = target_->info();
    if (address < 0 || static_cast<std::size_t>(address) >= info.lines.size()) return 0;
    return info.lines[static_cast<std::size_t>(address)].line;
  }

  bool launch(const Value& req, std::string& error);
  bool attach(const Value& req, std::string& error);
  void use(Target& t) {
    target_ = &t;
    t.on_output = [this](const std::string& text) { event("output", obj({{"category", "console"}, {"output", text}})); };
    t.on_wait = [this] { slice(); };
  }
  // A module this adapter attached (tmclrun --dap, `attach`): its patches removed at the end.
  void end_module() {
    if (!module_) return;
    std::string left;
    if (!module_->restore(left)) std::fprintf(stderr, "tmclrun: error: %s\n", left.c_str());
    if (target_ == module_.get()) target_ = nullptr;  // gone: the destructor must not touch it
    module_.reset();
  }
  bool after_run(const Stop& s);
  // A module left running by itself at attach: its breakpoints are written by running it on as
  // `continue` does (128, the patches, 129 from where it was), never by a reset. (While a
  // command runs the program, the module's mode is the debugger's stop, so this does nothing.)
  bool run_on() {
    ModuleTarget* mt = module_target();
    if (!configured_ || !mt || !mt->running_by_itself() || !mt->running()) return true;
    const auto& points = mt->breakpoints();
    if (std::none_of(points.begin(), points.end(), [](const Breakpoint& b) { return b.enabled; })) return true;
    return after_run(mt->cont());
  }
  void set_breakpoints(const Value& req);
  Value variables(std::int64_t ref);
  bool handle(const Value& req);

  DapSetup setup_;
  int file_fd_;  // the input as given
  int in_fd_;    // what os::poll waits on for it (pollable_input)
  std::string inbuf_;
  bool eof_ = false;
  std::FILE* out_;
  bool ending_ = false;      // disconnect or terminate came while the program ran
  bool disconnect_ = false;  // ... and it was disconnect (or the client went away)
  std::int64_t seq_ = 0;
  int exit_code_ = 0;
  std::unique_ptr<Engine> engine_;
  Target* target_ = nullptr;  // the engine, or a module
  // A module attached by this adapter (tmclrun --dap): its port and client.
  std::unique_ptr<host::Port> port_;
  std::unique_ptr<host::Client> client_;
  std::unique_ptr<ModuleTarget> module_;
  bool stop_on_entry_ = false;
  bool attached_ = false;  // `attach` on a module: configurationDone takes the program as it is
  bool configured_ = false;  // configurationDone came: breakpoints set now apply at once
  ModuleTarget* module_target() { return module_ ? module_.get() : dynamic_cast<ModuleTarget*>(target_); }
  std::map<std::string, std::vector<int>> source_breaks_;  // source path -> breakpoint ids
  std::vector<int> function_breaks_, instruction_breaks_;
};

bool Dap::launch(const Value& req, std::string& error) {
  const Value& a = req["arguments"];
  std::string program = a["program"].as_string();
  if (program.empty()) return error = "launch needs \"program\": a .tmc, .bin or .dgm file", false;
  std::string target = a["target"].as_string().empty() ? setup_.target : a["target"].as_string();
  if (a["target"].as_string().empty() && !setup_.target_given) target = target_named_by_file(program, target);
  const Profile* profile = setup_.profile && target == setup_.target ? setup_.profile : nullptr;
  if (!profile) {
    const TargetResult t = resolve_target(target);
    if (!t.profile) return error = t.message(), false;
    profile = t.profile;
  }
  std::string core_name = a["motion"].as_string();
  auto core = core_name.empty() ? make_profile_motion_core(*profile) : make_motion_core(core_name);
  if (!core) return error = "unknown motion core '" + core_name + "'", false;
  if (core_name.empty()) core_name = std::string(core->name());
  Setup s;
  s.profile = profile;
  s.core_name = core_name;
  s.instr_time = setup_.instr_time;
  s.limits = setup_.limits;
  s.inputs = setup_.inputs;
  s.eeprom = setup_.eeprom;
  if (a.contains("instructionTime")) {
    auto d = parse_duration(a["instructionTime"].as_string());
    if (!d) return error = "bad instructionTime '" + a["instructionTime"].as_string() + "' (e.g. 20us)", false;
    s.instr_time = *d;
  }
  ProgramInfo info;
  std::string messages;
  if (!load_program_info(program, *profile, setup_.asm_options, a["symbols"].as_string(), info, messages, setup_.source_dirs))
    return error = messages.empty() ? "cannot load " + program : messages, false;
  if (!messages.empty()) event("output", obj({{"category", "stderr"}, {"output", messages}}));
  engine_ = std::make_unique<Engine>(std::move(s), std::move(info), std::move(core));
  use(*engine_);
  engine_->on_slice = [this] { return slice(); };
  stop_on_entry_ = a["stopOnEntry"].as_bool();
  return true;
}

// attach {port, program, target?, baud?, symbols?, noPatch?}: the program on a module (serial
// port or tcp:HOST:PORT), as tmclctl PORT debug; the module's program memory is compared with
// the program and a killed session's patches put back (said as output events).
bool Dap::attach(const Value& req, std::string& error) {
  const Value& a = req["arguments"];
  stop_on_entry_ = a["stopOnEntry"].as_bool();
  if (target_) {  // tmclctl PORT debug --dap: attached already
    if (!setup_.attach_notes.empty()) event("output", obj({{"category", "console"}, {"output", setup_.attach_notes}}));
    setup_.attach_notes.clear();
    return true;
  }
  const std::string port = a["port"].as_string(), program = a["program"].as_string();
  if (port.empty() || program.empty())
    return error = "attach needs \"port\" (a serial device or tcp:HOST:PORT) and \"program\" (.tmc, or .bin with symbols)", false;
  std::string target = a["target"].as_string().empty() ? setup_.target : a["target"].as_string();
  const TargetResult t = resolve_target(target);
  if (!t.profile) return error = t.message(), false;
  ProgramInfo info;
  std::string messages;
  if (!load_program_info(program, *t.profile, setup_.asm_options, a["symbols"].as_string(), info, messages, setup_.source_dirs))
    return error = messages.empty() ? "cannot load " + program : messages, false;
  if (!messages.empty()) event("output", obj({{"category", "stderr"}, {"output", messages}}));
  const long baud = a.contains("baud") ? static_cast<long>(a["baud"].as_int()) : 9600;
  port_ = host::Port::open(port, baud, 1000, error);
  if (!port_) return false;
  client_ = std::make_unique<host::Client>(*port_, host::ClientOptions{});
  ModuleSetup ms;
  ms.program_name = program;
  ms.patch = !a["noPatch"].as_bool();
  module_ = std::make_unique<ModuleTarget>(*client_, *t.profile, std::move(info), ms);
  std::string notes;
  if (!module_->attach(notes, error)) {
    module_.reset();
    return false;
  }
  use(*module_);
  if (!notes.empty()) event("output", obj({{"category", "console"}, {"output", notes}}));
  return true;
}

void Dap::set_breakpoints(const Value& req) {
  const Value& a = req["arguments"];
  std::string path = a["source"]["path"].as_string();
  for (int id : source_breaks_[path]) target_->delete_point(id);
  source_breaks_[path].clear();
  Value out = Value::array();
  for (const auto& bp : a["breakpoints"].items()) {
    std::int64_t line = bp["line"].as_int();
    std::int32_t address = 0;
    std::string err;
    if (!target_->resolve(path + ":" + std::to_string(line), address, err) && !target_->resolve(std::to_string(line), address, err)) {
      out.push(obj({{"verified", false}, {"line", line}, {"message", err}}));
      continue;
    }
    int id = target_->add_breakpoint(address, path + ":" + std::to_string(line), false);
    source_breaks_[path].push_back(id);
    std::string cond = bp["condition"].as_string();
    if (!cond.empty() && !target_->set_condition(id, cond, err)) {
      out.push(obj({{"id", id}, {"verified", false}, {"line", line}, {"message", err}}));
      continue;
    }
    // hitCondition: a number N stops at the Nth hit (gdb's ignore count N-1).
    std::string hit = bp["hitCondition"].as_string();
    if (!hit.empty()) target_->set_ignore(id, std::max(0, std::atoi(hit.c_str()) - 1));
    for (auto& b : target_->breakpoints())
      if (b.id == id) b.log_message = bp["logMessage"].as_string();
    out.push(obj({{"id", id}, {"verified", true}, {"line", line_of(address)}, {"instructionReference", std::to_string(address)}}));
  }
  respond(req, true, obj({{"breakpoints", out}}));
}

Value Dap::variables(std::int64_t ref) {
  Value out = Value::array();
  auto add = [&](std::string name, std::int64_t v, const char* eval = nullptr) {
    Value item = obj({{"name", name}, {"value", std::to_string(v)}, {"variablesReference", 0}});
    if (eval) item.set("evaluateName", eval);
    out.push(std::move(item));
  };
  if (!target_->machine()) {
    // A module: what 135 and GGP/GAP read; a value that cannot be read says why.
    auto read = [&](const std::string& text) {
      Expr x;
      std::int64_t v = 0;
      std::string err;
      if (parse_expr(text, target_->info(), x, err) && target_->eval(x, v, err)) return add(text, v, text.c_str());
      out.push(obj({{"name", text}, {"value", err}, {"variablesReference", 0}}));
    };
    if (ref == 1) {
      for (const char* r : {"A", "X", "pc"}) read(r);
      out.push(obj({{"name", "status"}, {"value", target_->status()}, {"variablesReference", 0}}));
    } else if (ref == 2) {
      for (int n = 0; n < target_->profile().user_vars; ++n) read("v[" + std::to_string(n) + "]");
    } else if (ref == 3) {
      for (int m = 0; m < target_->profile().motors; ++m)
        for (int p : {0, 1, 2, 3, 4, 5})
          if (target_->profile().axis_param(p)) read("ap(" + std::to_string(p) + ", " + std::to_string(m) + ")");
    }
    return out;
  }
  Vm& vm = engine_->vm();
  if (ref == 1) {
    add("A", vm.acc, "A");
    add("X", vm.x, "X");
    add("pc", vm.pc, "pc");
    add("sp", vm.sp, "sp");
    add("flags", vm.flags, "flags");
    add("errors", vm.errors, "errors");
    out.push(obj({{"name", "time"}, {"value", format_time(vm.now)}, {"variablesReference", 0}}));
    add("steps", static_cast<std::int64_t>(vm.steps), "steps");
  } else if (ref == 2) {
    for (int n = 0; n < 256; ++n) {
      std::string e = "v[" + std::to_string(n) + "]";
      add(e, vm.vars[static_cast<std::size_t>(n)], e.c_str());
    }
  } else if (ref == 3) {
    // The ramp's parameters, then what `info motors` adds where the profile lists it: the load
    // value, the actual current, the driver flags (bit 0: stallGuard2 status) and the encoder.
    const Profile& profile = *vm.profile;
    for (int m = 0; m < profile.motors; ++m) {
      for (int p : {0, 1, 2, 3, 4, 5, 206, 180, 208, 209}) {
        std::int32_t v = 0;
        if (p > 5 && !profile.axis_param(p)) continue;
        if (vm.get_axis(m, p, v) != kStatusOk) continue;
        std::string e = "ap(" + std::to_string(p) + ", " + std::to_string(m) + ")";
        add(e, v, e.c_str());
      }
    }
  } else if (ref == 4) {
    for (const auto& g : vm.profile->bank0) {
      std::int32_t v = 0;
      if (vm.get_global(0, g.number, v) != kStatusOk) continue;
      std::string e = "gp(0, " + std::to_string(g.number) + ")";
      add(e, v, e.c_str());
    }
  } else if (ref == 5) {
    for (int t = 0; t < Vm::kTimers; ++t)
      out.push(obj({{"name", "timer " + std::to_string(t)}, {"value", vm.timers[static_cast<std::size_t>(t)].period_ms ? std::to_string(vm.timers[static_cast<std::size_t>(t)].period_ms) + " ms" : "off"}, {"variablesReference", 0}}));
    out.push(obj({{"name", "interrupts"}, {"value", vm.global_enable ? "enabled" : "disabled"}, {"variablesReference", 0}}));
    for (int n = 0; n < 255; ++n)
      if (vm.vectors[static_cast<std::size_t>(n)] >= 0)
        out.push(obj({{"name", "vector " + std::to_string(n)}, {"value", "handler " + std::to_string(vm.vectors[static_cast<std::size_t>(n)]) + (vm.is_enabled(n) ? ", enabled" : ", disabled")}, {"variablesReference", 0}}));
  }
  return out;
}

bool Dap::handle_running(const Value& req) {
  const std::string cmd = req["command"].as_string();
  if (cmd == "pause") {
    respond(req, true);  // the stopped event (reason "pause") follows when the program stops
    target_->pause();
    return true;
  }
  if (cmd == "disconnect" || cmd == "terminate") {
    respond(req, true);
    ending_ = true;
    disconnect_ = cmd == "disconnect";
    return true;
  }
  if (cmd == "threads" || cmd == "setBreakpoints" || cmd == "setFunctionBreakpoints" || cmd == "setInstructionBreakpoints" ||
      cmd == "setExceptionBreakpoints") {
    handle(req);  // these read nothing the run changes; new breakpoints count from the next instruction
    return false;
  }
  fail(req, "the program is running: '" + cmd + "' needs it stopped (send pause first)");
  return false;
}

// After a request that ran the program: disconnect or terminate may have come meanwhile.
// Returns false when the adapter ends.
bool Dap::after_run(const Stop& s) {
  if (!ending_) {
    stopped(s);
    return true;
  }
  ending_ = false;
  if (disconnect_) return false;
  target_->kill();
  event("terminated");
  return true;
}

bool Dap::handle(const Value& req) {
  const std::string cmd = req["command"].as_string();
  const Value& a = req["arguments"];
  std::string err;
  if (cmd == "initialize") {
    Value caps = obj({{"supportsConfigurationDoneRequest", true}, {"supportsFunctionBreakpoints", true},
                      {"supportsConditionalBreakpoints", true}, {"supportsHitConditionalBreakpoints", true},
                      {"supportsLogPoints", true}, {"supportsStepBack", !target_ || target_->machine()}, {"supportsSetVariable", true},
                      {"supportsEvaluateForHovers", true}, {"supportsInstructionBreakpoints", true},
                      {"supportsDisassembleRequest", true}, {"supportsDataBreakpoints", true},
                      {"supportsGotoTargetsRequest", true}, {"supportsRestartRequest", true},
                      {"supportsTerminateRequest", true}, {"supportsSteppingGranularity", false},
                      {"supportsExceptionInfoRequest", false}});
    Value filters = Value::array();
    filters.push(obj({{"filter", "fault"}, {"label", "Runtime faults"}, {"default", true}}));
    caps.set("exceptionBreakpointFilters", filters);
    respond(req, true, caps);
    event("initialized");
    return true;
  }
  if (cmd == "disconnect" || cmd == "terminate") {
    respond(req, true);
    if (cmd == "terminate") event("terminated");
    return cmd != "disconnect";
  }
  if (cmd == "launch" || cmd == "attach") {
    if (module_ || (target_ && !target_->machine())) {  // a module: launch means attach
      if (!attach(req, err)) return fail(req, err), true;
    } else if (cmd == "attach") {
      if (!attach(req, err)) return fail(req, err), true;
    } else if (!launch(req, err)) {
      return fail(req, err), true;
    }
    // Only `attach` takes a module as it is; `launch` resets and runs it at configurationDone.
    attached_ = cmd == "attach" && module_target();
    respond(req, true);
    return true;
  }
  if (!target_) return fail(req, "'" + cmd + "' before launch or attach"), true;
  Target& e = *target_;
  Engine* m = e.machine();
  if (cmd == "setBreakpoints") return set_breakpoints(req), run_on();
  if (cmd == "setFunctionBreakpoints" || cmd == "setInstructionBreakpoints") {
    auto& ids = cmd == "setFunctionBreakpoints" ? function_breaks_ : instruction_breaks_;
    for (int id : ids) e.delete_point(id);
    ids.clear();
    Value out = Value::array();
    for (const auto& bp : a["breakpoints"].items()) {
      std::string loc = cmd == "setFunctionBreakpoints" ? bp["name"].as_string()
                                                         : "*" + bp["instructionReference"].as_string() + "+" + std::to_string(bp["offset"].as_int());
      std::int32_t address = 0;
      if (!e.resolve(loc, address, err)) {
        out.push(obj({{"verified", false}, {"message", err}}));
        continue;
      }
      int id = e.add_breakpoint(address, loc, false);
      ids.push_back(id);
      if (!bp["condition"].as_string().empty()) e.set_condition(id, bp["condition"].as_string(), err);
      Value b = obj({{"id", id}, {"verified", true}, {"instructionReference", std::to_string(address)}});
      if (int l = line_of(address)) b.set("line", l);
      out.push(std::move(b));
    }
    return respond(req, true, obj({{"breakpoints", out}})), run_on();
  }
  if (cmd == "setExceptionBreakpoints") return respond(req, true, obj({{"breakpoints", Value::array()}})), true;
  if (cmd == "dataBreakpointInfo") {
    std::string name = a["name"].as_string();
    Expr x;
    if (!parse_expr(name, e.info(), x, err)) return respond(req, true, obj({{"dataId", nullptr}, {"description", err}})), true;
    Value types = Value::array();
    types.push("write");
    return respond(req, true, obj({{"dataId", name}, {"description", name}, {"accessTypes", types}})), true;
  }
  if (cmd == "setDataBreakpoints") {
    for (auto& w : std::vector<Watchpoint>(e.watchpoints())) e.delete_point(w.id);
    Value out = Value::array();
    for (const auto& bp : a["breakpoints"].items()) {
      int id = e.add_watchpoint(bp["dataId"].as_string(), err);
      out.push(id ? obj({{"id", id}, {"verified", true}}) : obj({{"verified", false}, {"message", err}}));
    }
    return respond(req, true, obj({{"breakpoints", out}})), true;
  }
  if (cmd == "configurationDone" && attached_) {
    // The program as it is on the module: stopped where it is with stopOnEntry, else left as it
    // was (a running program runs on: the attach notes said where; `pause` stops it).
    respond(req, true);
    configured_ = true;
    const std::optional<Stop> s = module_target()->attached(stop_on_entry_);
    if (!s) return run_on();
    if (s->kind == StopKind::Entry) return stopped(*s), true;
    return after_run(*s);
  }
  if (cmd == "configurationDone" || cmd == "restart") {
    respond(req, true);
    return after_run(e.start(stop_on_entry_));
  }
  if (cmd == "threads") {
    Value threads = Value::array();
    threads.push(obj({{"id", 1}, {"name", "TMCL program"}}));
    return respond(req, true, obj({{"threads", threads}})), true;
  }
  if (cmd == "stackTrace") {
    Value frames = Value::array();
    auto frame = [&](std::int32_t at, std::string name) {
      std::string fn = e.info().function_of(at);
      Value f = obj({{"id", static_cast<std::int64_t>(frames.size())}, {"name", name.empty() ? (fn.empty() ? "address " + std::to_string(at) : fn) : name},
                     {"line", line_of(at)}, {"column", 1}, {"instructionPointerReference", std::to_string(at)}});
      if (Value s = source_of(at); !s.is_null()) f.set("source", s);
      frames.push(std::move(f));
    };
    for (const auto& f : e.frames()) frame(f.pc, f.interrupted ? "<interrupt " + std::to_string(m ? m->vm().saved.vector : f.vector) + ">" : "");
    if (e.frames_unknown_above()) frame(-1, "<frames above unknown: the module cannot read its call stack>");
    return respond(req, true, obj({{"stackFrames", frames}, {"totalFrames", static_cast<std::int64_t>(frames.size())}})), true;
  }
  if (cmd == "scopes") {
    Value scopes = Value::array();
    const char* names[] = {"Registers and flags", "User variables", "Motors", "Global parameters", "Timers and interrupts"};
    // On a module every value is a request: the client asks for the scopes it shows.
    for (int i = 0; i < (m ? 5 : 3); ++i) scopes.push(obj({{"name", names[i]}, {"variablesReference", i + 1}, {"expensive", !m && i > 0}}));
    return respond(req, true, obj({{"scopes", scopes}})), true;
  }
  if (cmd == "variables") return respond(req, true, obj({{"variables", variables(a["variablesReference"].as_int())}})), true;
  if (cmd == "evaluate" && a["context"].as_string() == "repl" && Engine::is_machine_line(a["expression"].as_string())) {
    // In the debug console, a hard stop or a load as the CLI's `set var` takes it.
    if (!m) return fail(req, "set var: not on a module: its stops and loads are real ones"), true;
    if (!m->set_machine(a["expression"].as_string(), err)) return fail(req, err), true;
    return respond(req, true, obj({{"result", "ok"}, {"variablesReference", 0}})), true;
  }
  if (cmd == "setVariable" || cmd == "evaluate") {
    bool set = cmd == "setVariable";
    std::string lhs = set ? a["name"].as_string() : a["expression"].as_string();
    Expr x, rhs;
    std::int64_t v = 0;
    if (!parse_expr(lhs, e.info(), x, err)) return fail(req, err), true;
    if (set) {
      if (!parse_expr(a["value"].as_string(), e.info(), rhs, err) || !e.eval(rhs, v, err) || !e.assign(x, v, err))
        return fail(req, err), true;
    }
    if (!e.eval(x, v, err)) return fail(req, err), true;
    return respond(req, true, obj({{set ? "value" : "result", std::to_string(v)}, {"variablesReference", 0}})), true;
  }
  if (cmd == "pause") {
    // A module left running at attach runs with no command under way: stopped (128) where it is.
    if (ModuleTarget* mt = module_target(); mt && mt->running_by_itself()) return respond(req, true), after_run(mt->halt());
    return respond(req, true), true;  // stopped already (a running program is paused in slice())
  }
  if (cmd == "continue" || cmd == "next" || cmd == "stepIn" || cmd == "stepOut" || cmd == "stepBack" || cmd == "reverseContinue") {
    if (cmd == "continue") respond(req, true, obj({{"allThreadsContinued", true}}));
    else respond(req, true);
    Stop s = cmd == "continue" ? e.cont() : cmd == "next" ? e.next() : cmd == "stepIn" ? e.step(1) : cmd == "stepOut" ? e.finish()
           : cmd == "stepBack" ? e.reverse_step(1) : e.reverse_continue();
    if (s.kind == StopKind::NotRunning && e.running()) {
      event("output", obj({{"category", "console"}, {"output", s.message + "\n"}}));
      s = Stop{StopKind::Step, 0, "", 0, 0};
    }
    return after_run(s);
  }
  if (cmd == "gotoTargets") {
    std::int32_t address = 0;
    Value targets = Value::array();
    if (e.resolve(a["source"]["path"].as_string() + ":" + std::to_string(a["line"].as_int()), address, err))
      targets.push(obj({{"id", address}, {"label", "address " + std::to_string(address)}, {"line", line_of(address)}}));
    return respond(req, true, obj({{"targets", targets}})), true;
  }
  if (cmd == "goto") {
    std::int64_t t = a["targetId"].as_int(-1);
    if (!m) return fail(req, "goto: not on a module: no command moves its pc without running it"), true;
    if (t < 0 || t >= e.program_size()) return fail(req, "no goto target " + std::to_string(t)), true;
    e.set_pc(static_cast<std::int32_t>(t));
    respond(req, true);
    stopped(Stop{StopKind::Step, 0, "", 0, 0}, "goto");
    return true;
  }
  if (cmd == "disassemble") {
    std::int64_t start = std::atoll(a["memoryReference"].as_string().c_str()) + a["instructionOffset"].as_int();
    std::int64_t count = a["instructionCount"].as_int();
    Value list = Value::array();
    for (std::int64_t i = 0; i < count && i < 100000; ++i) {
      std::int64_t at = start + i;
      Value ins = obj({{"address", std::to_string(at)}});
      if (at < 0 || at >= e.program_size()) {
        ins.set("instruction", "");
        ins.set("presentationHint", "invalid");
      } else {
        // Targets by label and the constants the source named, as disassemble shows them.
        ins.set("instruction", named_instruction(e.info(), e.instruction(static_cast<std::int32_t>(at)), static_cast<std::int32_t>(at), e));
        std::string fn = e.info().function_of(static_cast<std::int32_t>(at));
        if (!fn.empty()) ins.set("symbol", fn);
        if (int l = line_of(static_cast<std::int32_t>(at))) {
          ins.set("line", l);
          ins.set("location", source_of(static_cast<std::int32_t>(at)));
        }
      }
      list.push(std::move(ins));
    }
    return respond(req, true, obj({{"instructions", list}})), true;
  }
  fail(req, "tmclrun --dap does not support the request '" + cmd + "'");
  return true;
}

}  // namespace

int run_dap(const DapSetup& setup, std::FILE* in, std::FILE* out) { return Dap(setup, in, out).serve(); }

int run_dap(const DapSetup& setup, Target& target, std::FILE* in, std::FILE* out) { return Dap(setup, target, in, out).serve(); }

}  // namespace tmcl::debug
