// tmclrun's modes beside a plain run: the checks of the options of serving (--serve and its
// companions, --module, --faults), debugging (--debug, --dap) and testing (--test and its
// reports), and the runs that serve a host with the virtual module (vm/module), debug with the
// debugger (cli/debug) or run test files (cli/testrun).
#include <algorithm>
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
#include "tmcl/targets.hpp"
#include "tmclrun.hpp"

using namespace tmclrun;

namespace {

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
int build_bus(Options& o, std::vector<std::unique_ptr<tmcl::MotionCore>>& cores,
              std::vector<std::unique_ptr<tmcl::Vm>>& vms) {
  std::vector<int> seen{o.serve_opts.protocol.module_address.value_or(1)};
  for (std::size_t i = 1; i < o.modules.size(); ++i) {
    BusSpec b;
    if (std::string err; !parse_bus_spec(o.modules[i], b, err)) return usage_error(err);
    for (int a : seen)
      if (a == b.address) return usage_error("--module: two modules with address " + std::to_string(a));
    seen.push_back(b.address);
    const tmcl::TargetResult t = tmcl::resolve_target(b.target.empty() ? o.target : b.target);
    if (!t.profile) return usage_error("--module " + o.modules[i] + ": " + t.message());
    const tmcl::Profile* profile = t.profile;
    auto core = tmcl::make_profile_motion_core(*profile);
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
    member.protocol.host_address = o.serve_opts.protocol.host_address;
    member.protocol.eeprom_locked = o.serve_opts.protocol.eeprom_locked;
    member.protocol.variants = o.serve_opts.protocol.variants;
    o.serve_opts.bus.push_back(member);
    cores.push_back(std::move(core));
    vms.push_back(std::move(vm));
  }
  return -1;
}

}  // namespace

int tmclrun::check_mode_options(Options& o, bool have_program) {
  auto given = [&o](const char* opt) { return std::find(o.given.begin(), o.given.end(), opt) != o.given.end(); };
  for (const char* opt : {"--jobs", "--junit", "--coverage", "--coverage-summary", "--update"})
    if (!o.testing && given(opt)) return usage_error(std::string(opt) + " goes with --test");
  if (o.testing && (o.serving || o.debug.enabled || o.trace || o.json || !o.csv.empty() || !o.plot.empty() ||
                    !o.scenario.empty() || !o.eeprom.empty() || !o.eeprom_seal.empty()))
    return usage_error("--test runs test files (each holds its own scenario): it goes with -t, --motion, --instr-time, "
                       "--max-time, --strict, -I, -D and -W, not with --serve, --debug, --dap, --trace, --json, --csv, "
                       "--plot, --scenario or --eeprom");
  if (o.testing && !have_program) return usage_error("--test needs test files or folders (FILE.tmctest or DIR)");
  if (!o.serving) {
    for (const char* opt : {"--autostart", "--time-scale", "--module-address", "--host-address", "--eeprom-locked",
                            "--variant", "--max-wall-time", "--faults", "--module"})
      if (std::find(o.given.begin(), o.given.end(), opt) != o.given.end())
        return usage_error(std::string(opt) + " goes with --serve");
  } else if (o.json || !o.csv.empty() || !o.plot.empty() || o.limits.until != tmcl::kNever ||
             o.limits.max_steps != UINT64_MAX) {
    return usage_error("--serve runs until stopped: --json, --csv, --plot, --max-time and --max-steps do not go with it");
  }
  if (!o.modules.empty() && o.eeprom_seal.empty()) {  // the first --module is the primary module: its program and address
    if (have_program) return usage_error("with --module, give each module's program there, not as PROGRAM");
    BusSpec first;
    if (std::string err; !parse_bus_spec(o.modules.front(), first, err)) return usage_error(err);
    if (!first.target.empty()) o.target = first.target, o.target_given = true;
    o.program = first.file;
    o.serve_opts.protocol.module_address = first.address;
  }
  return -1;
}

int tmclrun::run_tests(Options& o) {
  tmcl::testrun::RunOptions& r = o.test.run;
  std::tie(r.target, r.motion, r.instr_time, r.asm_options, r.strict) = std::tie(o.target, o.motion, o.instr_time, o.asm_opts, o.strict);
  r.target_given = o.target_given;  // else a program's first line names its test's module, as for a plain run
  r.max_time_given = o.limits.until != tmcl::kNever;
  r.max_time = o.limits.until;
  r.error_limit = o.asm_opts.error_limit;  // --error-limit
  return tmcl::testrun::run_command(o.inputs, o.test, stdout, stderr);
}

int tmclrun::run_mode(Options& o, const tmcl::Profile& profile, std::unique_ptr<tmcl::MotionCore> core,
                      const std::vector<tmcl::Instruction>& program, const tmcl::SourceMap& sources,
                      std::vector<tmcl::InputEvent> inputs, tmcl::EepromImage* image) {
  if (o.debug.enabled && o.serving) {  // debugging while serving: tcp or pty, one module
    if (o.debug.dap || o.serve_opts.transport == tmcl::Transport::Stdio || !o.modules.empty() || o.trace)
      return usage_error("--serve with --debug takes tcp:HOST:PORT or pty, one module, no --dap and no --trace");
    o.serve_opts.eeprom_path = o.eeprom;
  }
  o.debug.target_given = o.target_given;
  if (o.debug.enabled)  // the debugger loads and runs the program (cli/debug, docs/debugger.md)
    return tmcl::debug::main(o.debug, profile, std::move(core), o.program, o.asm_opts, o.instr_time, o.limits,
                             std::move(inputs), image, o.serving ? &o.serve_opts : nullptr);

  // The virtual module runs until SIGINT/SIGTERM (or --max-wall-time) and saves the EEPROM.
  tmcl::Vm vm(profile, *core);
  set_up_vm(vm, o, program, sources, image, std::move(inputs));
  o.serve_opts.eeprom_path = o.eeprom;
  // --trace: every request and its reply, decoded, as it is answered (flushed: a user watches
  // the traffic live, and a killed server loses nothing).
  std::FILE* log = stderr;
  if (o.trace && !o.log.empty()) {
    log = std::fopen(o.log.c_str(), "wb");
    if (!log) return input_error("", "cannot open log file '" + o.log + "': " + std::strerror(errno), kExitIo);
  }
  if (o.trace)
    o.serve_opts.on_exchange = [log](const tmcl::TmclModule::Exchange& e) {
      std::fputs(tmcl::exchange_text(e.at, e.module, e.request, e.reply, e.special, e.sent).c_str(), log);
      std::fflush(log);
    };
  std::vector<std::unique_ptr<tmcl::MotionCore>> bus_cores;
  std::vector<std::unique_ptr<tmcl::Vm>> bus_vms;
  if (int r = build_bus(o, bus_cores, bus_vms); r >= 0) return r;
  int served = tmcl::serve(vm, o.serve_opts);
  if (log != stderr && std::fclose(log) != 0)
    return input_error("", "cannot write log file '" + o.log + "': " + std::strerror(errno), kExitIo);
  return served;
}
