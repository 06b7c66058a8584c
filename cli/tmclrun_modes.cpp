// tmclrun-full's part of tmclrun (cli/tmclrun_modes.hpp): the options of serving (--serve and its
// companions, --module, --faults), debugging (--debug, --dap) and testing (--test and its
// reports), their checks, and the runs that serve a host with the virtual module (vm/module),
// debug with the debugger (vm/debug) or run test files (vm/testrun).
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "tmcl/debug_cli.hpp"
#include "tmcl/numbers.hpp"
#include "tmcl/server.hpp"
#include "tmcl/testrun.hpp"
#include "tmcl/vm_output.hpp"
#include "tmclrun.hpp"

using namespace tmclrun;

namespace {

// The options only this part reads.
struct ModeOptions {
  std::string serve;  // --serve SPEC
  tmcl::ServeOptions serve_opts;
  std::vector<std::string> modules;  // --module ADDR[/TARGET][:FILE], in order
  tmcl::debug::FrontEnd debug;       // --debug, --debug-commands, --symbols, --checkpoint-memory, --dap
  tmcl::testrun::SuiteOptions test;  // --test, -j, --junit, --coverage, --coverage-summary, --update
};
// One command line per process: main() parses it once, and the run reads it back.
ModeOptions g_modes;

// --module ADDR[/TARGET][:FILE]: one module of a bus.
struct BusSpec {
  std::uint8_t address = 1;
  std::string target, file;
};
bool parse_bus_spec(const std::string& spec, BusSpec& out, std::string& error) {
  const std::size_t colon = spec.find(':');
  std::string head = spec.substr(0, colon);
  out.file = colon == std::string::npos ? "" : spec.substr(colon + 1);
  if (const std::size_t slash = head.find('/'); slash != std::string::npos) {
    out.target = head.substr(slash + 1);
    head = head.substr(0, slash);
  }
  char* end = nullptr;
  const long n = std::strtol(head.c_str(), &end, 0);
  if (head.empty() || *end || n < 1 || n > 255 || (colon != std::string::npos && out.file.empty())) {
    error = "--module needs ADDR[/TARGET][:FILE] with ADDR from 1 to 255, not '" + spec + "'";
    return false;
  }
  out.address = static_cast<std::uint8_t>(n);
  return true;
}

// The second and later --module: each its own profile, motion core, VM (program, EEPROM image
// in memory) and address on the primary's line. Returns -1 on success, else an exit status.
int build_bus(Options& o, ModeOptions& m, std::vector<std::unique_ptr<tmcl::MotionCore>>& cores,
              std::vector<std::unique_ptr<tmcl::Vm>>& vms) {
  std::vector<int> seen{m.serve_opts.protocol.module_address.value_or(1)};
  for (std::size_t i = 1; i < m.modules.size(); ++i) {
    BusSpec b;
    if (std::string err; !parse_bus_spec(m.modules[i], b, err)) return usage_error(err);
    for (int a : seen)
      if (a == b.address) return usage_error("--module: two modules with address " + std::to_string(a));
    seen.push_back(b.address);
    const tmcl::Profile* profile = tmcl::find_profile(b.target.empty() ? o.target : b.target);
    if (!profile) return usage_error("--module " + m.modules[i] + ": unknown module '" + b.target + "'");
    auto core = tmcl::make_motion_core(std::string(profile->default_motion));
    if (!core) core = tmcl::make_ideal_motion_core();
    std::vector<tmcl::Instruction> program;
    tmcl::SourceMap sources;
    if (!b.file.empty()) {
      Options each = o;
      each.program = b.file;
      each.target = std::string(profile->name);
      if (int r = load_program(each, profile, program, sources); r >= 0) return r;
    }
    auto vm = std::make_unique<tmcl::Vm>(*profile, *core);
    set_up_vm(*vm, o, program, sources, nullptr, {});
    tmcl::BusModule member{vm.get(), {}};
    member.protocol.module_address = b.address;
    member.protocol.host_address = m.serve_opts.protocol.host_address;
    member.protocol.eeprom_locked = m.serve_opts.protocol.eeprom_locked;
    m.serve_opts.bus.push_back(member);
    cores.push_back(std::move(core));
    vms.push_back(std::move(vm));
  }
  return -1;
}

}  // namespace

bool tmclrun::mode_option(const std::string& a, bool has_inline, const ValueFn& value, char**, Options& o, int& status) {
  ModeOptions& m = g_modes;
  std::string v;
  status = -1;
  if (a == "--serve") {
    if (!value(m.serve)) {
      status = usage_error("--serve needs tcp:HOST:PORT, pty or stdio");
      return true;
    }
    std::string err;
    if (!tmcl::parse_serve_spec(m.serve, m.serve_opts, err)) status = usage_error(err);
    o.serving = true;
  } else if (a == "--autostart" && !has_inline) {
    m.serve_opts.autostart = true;
  } else if (a == "--eeprom-locked" && !has_inline) {
    m.serve_opts.protocol.eeprom_locked = true;
  } else if (a == "--time-scale") {
    if (!value(v)) {
      status = usage_error("--time-scale needs a number");
      return true;
    }
    char* end = nullptr;
    errno = 0;
    double x = std::strtod(v.c_str(), &end);
    if (v.empty() || *end || errno || !(x > 0) || x > 1e9)
      status = usage_error("--time-scale needs a number greater than 0");
    else
      m.serve_opts.time_scale = x;
  } else if (a == "--module-address" || a == "--host-address") {
    if (!value(v)) {
      status = usage_error(a + " needs a number from 0 to 255");
      return true;
    }
    char* end = nullptr;
    long n = std::strtol(v.c_str(), &end, 0);
    if (v.empty() || *end || n < 0 || n > 255)
      status = usage_error(a + " needs a number from 0 to 255");
    else
      (a == "--module-address" ? m.serve_opts.protocol.module_address : m.serve_opts.protocol.host_address) =
          static_cast<std::uint8_t>(n);
  } else if (a == "--faults") {
    std::string err;
    if (!value(v))
      status = usage_error("--faults needs a SPEC (e.g. drop@3,corrupt@p=0.1,seed=7)");
    else if (!tmcl::parse_faults(v, m.serve_opts.faults, err))
      status = usage_error(err);
  } else if (a == "--module") {
    if (!value(v))
      status = usage_error("--module needs ADDR[/TARGET][:FILE]");
    else
      m.modules.push_back(v);
  } else if (a == "--max-wall-time") {
    tmcl::SimTime wall = 0;
    status = duration_option("--max-wall-time", value, wall);
    if (status < 0) m.serve_opts.max_wall_ms = wall / tmcl::kUsPerMs + (wall % tmcl::kUsPerMs ? 1 : 0);
  } else if (a == "--test" || a == "--coverage-summary" || a == "--update") {
    (a == "--test" ? o.testing : a == "--update" ? m.test.update : m.test.coverage_summary) = true;
  } else if (a == "-j" || a == "--jobs") {
    std::int64_t n = 0;
    if (!value(v) || !tmcl::parse_int(v, 1, 256, n)) status = usage_error(a + " needs a number of tests at a time, 1 to 256");
    m.test.jobs = static_cast<int>(n);
  } else if (a == "--junit" || a == "--coverage") {
    if (!value(a == "--junit" ? m.test.junit : m.test.coverage)) status = usage_error(a + " needs a file");
  } else if (int r = tmcl::debug::parse_option(a, has_inline, value, m.debug); r != 0) {
    if (r < 0) status = usage_error(m.debug.error);
    o.debugging = m.debug.enabled;
    o.dap = m.debug.dap;
  } else {
    return false;
  }
  return true;
}

int tmclrun::check_mode_options(Options& o, const std::vector<std::string>& args, bool have_program) {
  ModeOptions& m = g_modes;
  for (const char* opt : {"-j", "--jobs", "--junit", "--coverage", "--coverage-summary", "--update"})
    for (const auto& arg : args)
      if (!o.testing && (arg == opt || arg.rfind(std::string(opt) + "=", 0) == 0)) return usage_error(std::string(opt) + " goes with --test");
  if (o.testing && (o.serving || o.debugging || o.trace || o.json || !o.csv.empty() || !o.plot.empty() || !o.scenario.empty() ||
                    !o.eeprom.empty() || !o.eeprom_seal.empty()))
    return usage_error("--test runs test files (each holds its own scenario): it goes with -t, --motion, --instr-time, "
                       "--max-time, --strict, -I, -D and -W, not with --serve, --debug, --dap, --trace, --json, --csv, "
                       "--plot, --scenario or --eeprom");
  if (o.testing && !have_program) return usage_error("--test needs test files or folders (FILE.tmctest or DIR)");
  if (!o.serving) {
    for (const char* opt : {"--autostart", "--time-scale", "--module-address", "--host-address", "--eeprom-locked",
                            "--max-wall-time", "--faults", "--module"})
      for (const auto& arg : args)
        if (arg == opt || arg.rfind(std::string(opt) + "=", 0) == 0)
          return usage_error(std::string(opt) + " goes with --serve");
  } else if (o.json || !o.csv.empty() || !o.plot.empty() || o.limits.until != tmcl::kNever ||
             o.limits.max_steps != UINT64_MAX) {
    return usage_error("--serve runs until stopped: --json, --csv, --plot, --max-time and --max-steps do not go with it");
  }
  if (!m.modules.empty() && o.eeprom_seal.empty()) {  // the first --module is the primary module: its program and address
    if (have_program) return usage_error("with --module, give each module's program there, not as PROGRAM");
    BusSpec first;
    if (std::string err; !parse_bus_spec(m.modules.front(), first, err)) return usage_error(err);
    if (!first.target.empty()) o.target = first.target;
    o.program = first.file;
    m.serve_opts.protocol.module_address = first.address;
  }
  return -1;
}

int tmclrun::run_mode(Options& o, const tmcl::Profile& profile, std::unique_ptr<tmcl::MotionCore> core,
                      const std::vector<tmcl::Instruction>& program, const tmcl::SourceMap& sources,
                      std::vector<tmcl::InputEvent> inputs, tmcl::EepromImage* image) {
  ModeOptions& m = g_modes;
  if (o.testing) {  // the test files of o.inputs (vm/testrun, docs/testing.md)
    tmcl::testrun::RunOptions& r = m.test.run;
    std::tie(r.target, r.motion, r.instr_time, r.asm_options, r.strict) = std::tie(o.target, o.motion, o.instr_time, o.asm_opts, o.strict);
    r.max_time_given = o.limits.until != tmcl::kNever;
    r.max_time = o.limits.until;
    r.error_limit = o.asm_opts.error_limit;  // --error-limit
    return tmcl::testrun::run_command(o.inputs, m.test, stdout, stderr);
  }
  if (o.debugging && o.serving) {  // debugging while serving: tcp or pty, one module
    if (o.dap || m.serve_opts.transport == tmcl::Transport::Stdio || !m.modules.empty() || o.trace)
      return usage_error("--serve with --debug takes tcp:HOST:PORT or pty, one module, no --dap and no --trace");
    m.serve_opts.eeprom_path = o.eeprom;
  }
  if (o.debugging)  // the debugger loads and runs the program (vm/debug, docs/debugger.md)
    return tmcl::debug::main(m.debug, profile, std::move(core), o.program, o.asm_opts, o.instr_time, o.limits,
                             std::move(inputs), image, o.serving ? &m.serve_opts : nullptr);

  // The virtual module runs until SIGINT/SIGTERM (or --max-wall-time) and saves the EEPROM.
  tmcl::Vm vm(profile, *core);
  set_up_vm(vm, o, program, sources, image, std::move(inputs));
  m.serve_opts.eeprom_path = o.eeprom;
  // --trace: every request and its reply, decoded, as it is answered (flushed: a user watches
  // the traffic live, and a killed server loses nothing).
  std::FILE* log = stderr;
  if (o.trace && !o.log.empty()) {
    log = std::fopen(o.log.c_str(), "w");
    if (!log) return input_error("", "cannot open log file '" + o.log + "': " + std::strerror(errno), kExitIo);
  }
  if (o.trace)
    m.serve_opts.on_exchange = [log](const tmcl::TmclModule::Exchange& e) {
      std::fputs(tmcl::exchange_text(e.at, e.module, e.request, e.status, e.value, e.sent).c_str(), log);
      std::fflush(log);
    };
  std::vector<std::unique_ptr<tmcl::MotionCore>> bus_cores;
  std::vector<std::unique_ptr<tmcl::Vm>> bus_vms;
  if (int r = build_bus(o, m, bus_cores, bus_vms); r >= 0) return r;
  int served = tmcl::serve(vm, m.serve_opts);
  if (log != stderr && std::fclose(log) != 0)
    return input_error("", "cannot write log file '" + o.log + "': " + std::strerror(errno), kExitIo);
  return served;
}
