// tmclrun: runs a TMCL program on the virtual machine without hardware. Parses arguments, loads
// the program (assembling .tmc in-process), scenario and EEPROM, runs the VM library, prints the
// summary, trace, JSON, CSV or plot. Serving (--serve) and debugging are tmclrun_modes.cpp's, in
// tmclrun-full only (cli/tmclrun_modes.hpp). All semantics live in vm/; see docs/tmclrun.md. Exit
// status: 0 STOP, 3 limit reached or blocked, 70 runtime fault, 65 bad input, 64 usage, 71
// --serve transport failed or tmclrun-full missing, 74 an output file or standard output not
// written. With --json every outcome is one JSON object on standard output.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "tmcl/analysis.hpp"
#include "tmcl/asm/assembler.hpp"
#include "tmcl/diag_text.hpp"
#include "tmcl/duration.hpp"
#include "tmcl/eeprom.hpp"
#include "tmcl/fileio.hpp"
#include "tmcl/motion_recording.hpp"
#include "tmcl/numbers.hpp"
#include "tmcl/program_image.hpp"
#include "tmcl/scenario.hpp"
#include "tmcl/version.hpp"
#include "tmcl/vm.hpp"
#include "tmcl/vm_output.hpp"
#include "tmclrun.hpp"

using namespace tmclrun;

namespace {

const char* kUsage = R"(usage: tmclrun [options] PROGRAM        PROGRAM: .tmc source, .bin, .dgm, or - (stdin)
       tmclrun --test [options] FILE.tmctest|DIR...

Runs a TMCL program on a deterministic virtual module. Simulated time: nothing waits for real.

options:
  -t, --target NAME      usb-2-sd | tmc2300-eval | generic (default, as for tmclasm)
  --motion NAME          motion core (default: the module's; available: %s)
  --instr-time DURATION  simulated time per instruction (default 20us)
  --max-time DURATION    stop when simulated time reaches DURATION
  --max-steps N          stop after N instructions
  --scenario FILE        timed inputs, switches and encoder slip (docs/tmclrun.md)
  --eeprom FILE          load the EEPROM from FILE at start, save it there at exit
  --eeprom-seal FILE     after editing an EEPROM file by hand: check it, write a new checksum
  --trace                print a line per instruction, interrupt, wait and motion event
                         (to standard error when --json is given); with --serve, a line per
                         request and reply, decoded, to standard error or --log FILE
  --log FILE             with --serve --trace: write the request log to FILE
  --json                 print the final state as one JSON object instead of the summary;
                         when there is no run (bad option or input), the errors as one object
  --strict               a run-time warning (full call stack, RSUB or RETI with nothing to
                         return to, a handler left without RETI) is a runtime fault (70)
  --error-limit N        show at most N errors of the source or scenario (default 20, 0 = all)
  --serve SPEC           act as a virtual module: tcp:HOST:PORT (loopback unless told
                         otherwise; [::1]:PORT for IPv6), pty, or stdio (docs/virtual-module.md).
                         PROGRAM is then optional (a host can download one)
  --autostart            with --serve: start the program at once (also: global 77 = 1)
  --time-scale X         with --serve: simulated seconds per real second (default 1)
  --module-address N     with --serve: answer requests to address N (default: global 66, 1)
  --host-address N       with --serve: address replies to N (default: global 76, 2)
  --eeprom-locked        with --serve: refuse commands that write the EEPROM (status 5)
  --max-wall-time DURATION  with --serve: stop by itself after this much real time
  --faults SPEC          with --serve: drop, corrupt, delay, split, silence or stale replies, by
                         count, command or seeded chance (docs/virtual-module.md, "Faults")
  --module ADDR[/TARGET][:FILE]  with --serve, repeatable: modules on one bus, each its own VM,
                         EEPROM and address (the first replaces PROGRAM and --module-address)
  --csv FILE             write time, position, velocity, acceleration of every motor to FILE
                         at each --sample period, plus one row per event
  --sample DURATION      the sampling period of --csv and --plot (default 10ms)
  --plot FILE.svg        draw position, velocity and acceleration against time as an SVG
  --debug                debug PROGRAM with gdb's commands (docs/debugger.md), read from
                         standard input: a terminal, or a pipe or file for scripts; with
                         --serve tcp:... or pty, while the module keeps answering its host
  --debug-commands FILE  debug PROGRAM with the commands in FILE, then quit (gdb -batch -x)
  --symbols FILE         with --debug: the labels and source lines of a .bin (tmclasm -f symbols)
  --source-dir DIR       with --debug or --dap: look for the sources of a .bin in DIR too
  --checkpoint-memory MIB  with --debug: memory for reverse execution (default 64)
  --dap                  the debugger over the Debug Adapter Protocol on stdin/stdout
  --test                 run test files (*.tmctest; a folder: every one under it) and print
                         PASS or FAIL for each, then 'N passed, N failed' (docs/testing.md)
  -j, --jobs N           with --test: run N tests at a time (default: one per core)
  --junit FILE           with --test: write a JUnit XML report to FILE
  --coverage FILE        with --test: write line and branch coverage to FILE (lcov tracefile)
  --coverage-summary     with --test: print lines and branches covered per file
  --update               with --test: rewrite the values of failing expectations from the run
  -I DIR                 search DIR for #include files
  -D NAME=VALUE          define an assembler constant
  -Werror, -Werror=NAME  assembler warnings (all, or the one named) are errors
  -Wno-NAME              do not report the assembler warning NAME
  --help                 show this help
  --version              show the version
DURATION: a number with us, ms, s, min or h (50us, 0.25ms, 1.5s, 2min, 1h); 0 needs no unit.

examples:
  tmclrun prog.tmc                              run until STOP, print a summary
  tmclrun --trace --max-time 10s prog.tmc       trace the first 10 simulated seconds
  tmclrun --scenario switches.txt --json prog.bin
  tmclrun --eeprom module.eeprom prog.tmc       run twice: the EEPROM persists
  tmclrun --plot motion.svg --csv motion.csv prog.tmc   what the motors did, as a picture and data
  tmclrun --serve tcp:127.0.0.1:2001 prog.tmc   a virtual module for PyTrinamic (Ctrl-C stops it)
  tmclrun --test --junit report.xml --coverage coverage.info tests/

exit status: 0 STOP, 3 limit reached or blocked forever, 70 runtime fault, 65 bad input,
             64 usage error, 71 --serve transport failed or tmclrun-full missing, 74 an output
             file (EEPROM, --csv, --plot, a report) or standard output could not be written;
             with --test: 0 every test passed, 1 a test failed, 65 a bad test file or program
)";

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// --json: what went wrong when there is no run to report, printed as one object at exit.
struct Failure {
  bool json = false;
  int error_limit = tmcl::kDefaultErrorLimit;
  std::string kind;  // usage, input, io; empty: nothing failed before the run
  std::vector<tmcl::JsonDiagnostic> diags;
  long long more = 0;
} g_failure;

int fail(const char* kind, int status, tmcl::JsonDiagnostic d) {
  if (g_failure.kind.empty()) g_failure.kind = kind;
  g_failure.diags.push_back(std::move(d));
  return status;
}

}  // namespace

int tmclrun::usage_error(const std::string& msg) {
  std::fprintf(stderr, "tmclrun: %s\n(see tmclrun --help)\n", msg.c_str());
  return fail("usage", kExitUsage, {"", 0, 0, "error", "", msg});
}

// An error that has no line to point at: "tmclrun: error: ..." or "FILE: error: ...".
int tmclrun::input_error(const std::string& file, const std::string& msg, int status) {
  std::fprintf(stderr, "%s: error: %s\n", file.empty() ? "tmclrun" : file.c_str(), msg.c_str());
  return fail(status == kExitIo ? "io" : "input", status, {file, 0, 0, "error", "", msg});
}

int tmclrun::duration_option(const char* opt, const ValueFn& value, tmcl::SimTime& out) {
  std::string v;
  if (!value(v)) return usage_error(std::string(opt) + " needs a duration");
  std::string why;
  auto d = tmcl::parse_duration(v, why);
  if (!d) return usage_error("bad duration for " + std::string(opt) + ": " + why);
  out = *d;
  return -1;
}

namespace {

// Errors of a scenario or EEPROM file, collected with places, shown like the assembler's.
int file_errors(const std::vector<tmcl::FileDiag>& diags) {
  std::fputs(tmcl::render_file_diags(diags, g_failure.error_limit).c_str(), stderr);
  for (const auto& d : diags) {
    if (g_failure.error_limit > 0 && g_failure.diags.size() >= static_cast<std::size_t>(g_failure.error_limit)) {
      ++g_failure.more;
      continue;
    }
    fail("input", kExitInput, {d.file, d.line, d.col, "error", "", d.message});
  }
  return kExitInput;
}

// "FILE:LINE: error: MESSAGE" (as the EEPROM reader words it) into a JSON diagnostic.
int located_error(const std::string& text) {
  std::fprintf(stderr, "%s\n", text.c_str());
  tmcl::JsonDiagnostic d;
  d.message = text;
  auto marker = text.find(": error: ");
  if (marker != std::string::npos) {
    d.message = text.substr(marker + 9);
    std::string where = text.substr(0, marker);
    auto colon = where.rfind(':');
    if (colon != std::string::npos && colon + 1 < where.size() &&
        where.find_first_not_of("0123456789", colon + 1) == std::string::npos) {
      d.line = std::atoi(where.c_str() + colon + 1);
      where.resize(colon);
    }
    d.file = where;
  }
  return fail("input", kExitInput, d);
}

bool ends_with_ci(const std::string& s, const char* suffix) {
  std::string suf = suffix;
  if (s.size() < suf.size()) return false;
  for (std::size_t i = 0; i < suf.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - suf.size() + i])) != suf[i]) return false;
  return true;
}

// Serves "-" from memory (standard input was already read to sniff its kind), the rest from disk.
class StdinFirstReader final : public tmcl::FileReader {
 public:
  explicit StdinFirstReader(std::string text) : text_(std::move(text)) {}
  bool read(const std::string& path, std::string& out) override {
    if (path == "-") {
      out = text_;
      return true;
    }
    return disk_.read(path, out);
  }

 private:
  std::string text_;
  tmcl::DiskReader disk_;
};

// Returns -1 when the run should go on, otherwise an exit status.
int parse_args(int argc, char** argv, Options& o) {
  std::vector<std::string> args(argv + 1, argv + argc);
  bool have_program = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string a = args[i];
    std::string inline_value;
    bool has_inline = false;
    if (a.rfind("--", 0) == 0 && a.find('=') != std::string::npos) {
      inline_value = a.substr(a.find('=') + 1);
      a = a.substr(0, a.find('='));
      has_inline = true;
    } else if (a.size() > 2 && a[0] == '-' && a[1] != '-' && (a[1] == 't' || a[1] == 'I' || a[1] == 'D')) {
      inline_value = a.substr(2);
      a = a.substr(0, 2);
      has_inline = true;
    }
    auto value = [&](std::string& out) -> bool {
      if (has_inline) {
        out = inline_value;
        return true;
      }
      if (i + 1 >= args.size()) return false;
      out = args[++i];
      return true;
    };
    auto duration = [&](const char* opt, tmcl::SimTime& out) { return duration_option(opt, value, out); };
    std::string v;
    if (a == "--help" || a == "-h") {
      std::printf(kUsage, joined(tmcl::motion_core_names()).c_str());
      return kExitOk;
    } else if (a == "--version") {
      std::puts(tmcl::version_line("tmclrun").c_str());
      return kExitOk;
    } else if (a == "-t" || a == "--target") {
      if (!value(o.target)) return usage_error("-t needs a module name");
    } else if (a == "--motion") {
      if (!value(o.motion)) return usage_error("--motion needs a core name");
    } else if (a == "--instr-time") {
      if (int r = duration("--instr-time", o.instr_time); r >= 0) return r;
    } else if (a == "--max-time") {
      if (int r = duration("--max-time", o.limits.until); r >= 0) return r;
    } else if (a == "--max-steps") {
      if (!value(v)) return usage_error("--max-steps needs a number");
      char* end = nullptr;
      errno = 0;
      unsigned long long n = std::strtoull(v.c_str(), &end, 10);
      if (v.empty() || *end || v[0] == '-' || errno) return usage_error("bad step count '" + v + "' for --max-steps");
      o.limits.max_steps = n;
    } else if (a == "--scenario") {
      if (!value(o.scenario)) return usage_error("--scenario needs a file");
    } else if (a == "--eeprom") {
      if (!value(o.eeprom)) return usage_error("--eeprom needs a file");
    } else if (a == "--eeprom-seal") {
      if (!value(o.eeprom_seal)) return usage_error("--eeprom-seal needs a file");
    } else if (a == "--error-limit") {
      if (!value(v)) return usage_error("--error-limit needs a number");
      std::int64_t n = 0;
      if (!tmcl::parse_int(v, 0, 1'000'000'000, n))
        return usage_error("bad error limit '" + v + "' for --error-limit (a number, 0 for no limit)");
      g_failure.error_limit = o.asm_opts.error_limit = static_cast<int>(n);
    } else if (a == "--csv") {
      if (!value(o.csv)) return usage_error("--csv needs a file");
    } else if (a == "--plot") {
      if (!value(o.plot)) return usage_error("--plot needs a file");
    } else if (a == "--log") {
      if (!value(o.log)) return usage_error("--log needs a file");
    } else if (a == "--sample") {
      if (int r = duration("--sample", o.sample); r >= 0) return r;
      if (o.sample <= 0) return usage_error("--sample needs a duration greater than 0");
    } else if (a == "--trace" && !has_inline) {
      o.trace = true;
    } else if (a == "--json" && !has_inline) {
      o.json = true;
    } else if (a == "--strict" && !has_inline) {
      o.strict = true;
    } else if (a == "-I") {
      if (!value(v)) return usage_error("-I needs a directory");
      o.asm_opts.include_dirs.push_back(v);
    } else if (a == "-D") {
      if (!value(v)) return usage_error("-D needs NAME=VALUE");
      auto eq = v.find('=');
      if (eq == std::string::npos || eq == 0) return usage_error("bad -D '" + v + "' (expected NAME=VALUE)");
      o.asm_opts.defines.emplace_back(v.substr(0, eq), v.substr(eq + 1));
    } else if (a.rfind("-W", 0) == 0 && a.size() > 2) {
      std::string error;
      if (!o.asm_opts.warnings.parse(a, error)) return usage_error(error.empty() ? "unknown option '" + a + "'" : error);
    } else if (int status = -1; mode_option(a, has_inline, value, argv, o, status)) {
      if (status >= 0) return status;
    } else if (a != "-" && a.size() > 1 && a[0] == '-') {
      return usage_error("unknown option '" + args[i] + "'");
    } else {
      if (!have_program) o.program = a;
      o.inputs.push_back(a);
      have_program = true;
    }
  }
  if (o.inputs.size() > 1 && !o.testing)
    return usage_error("only one PROGRAM can be run (got '" + o.inputs[0] + "' and '" + o.inputs[1] + "')");
  if (int r = check_mode_options(o, args, have_program); r >= 0) return r;
  if (!o.log.empty() && (!o.serving || !o.trace)) return usage_error("--log FILE goes with --serve --trace");
  if (!o.eeprom_seal.empty()) {
    if (have_program || o.serving || !o.eeprom.empty())
      return usage_error("--eeprom-seal FILE goes alone (it seals FILE and runs nothing)");
    return -1;
  }
  if (!have_program && !o.serving && !o.dap) return usage_error("no PROGRAM given");
  return -1;
}

// Per address, 1 where the control-flow analysis puts the instruction in an interrupt handler's
// own code: the VM then reports a handler that goes on elsewhere without RETI, as tmclasm's
// -Wreti does before the run (errata E43). Empty when the program sets no vector.
std::vector<std::uint8_t> handler_code(const std::vector<tmcl::Instruction>& program) {
  bool vect = std::any_of(program.begin(), program.end(),
                          [](const tmcl::Instruction& i) { return i.op == static_cast<std::uint8_t>(tmcl::Op::VECT); });
  if (!vect) return {};
  tmcl::AnalysisInput in;
  in.program = program;
  tmcl::Diagnostics ignored;  // tmclasm reports them; tmclrun only needs the regions
  tmcl::Analysis a = tmcl::analyze(in, ignored);
  std::vector<std::uint8_t> code(program.size(), 0);
  for (std::size_t i = 0; i < program.size(); ++i) {
    int r = a.owner[i];
    code[i] = r >= 0 && a.regions[static_cast<std::size_t>(r)].kind == tmcl::RegionKind::Handler;
  }
  return code;
}

}  // namespace

int tmclrun::load_program(Options& o, const tmcl::Profile* profile, std::vector<tmcl::Instruction>& program,
                 tmcl::SourceMap& sources) {
  std::vector<std::uint8_t> bytes;
  std::string err;
  if (!tmcl::read_file(o.program, bytes, err)) return input_error("", err);
  bool is_image = ends_with_ci(o.program, ".bin") || ends_with_ci(o.program, ".dgm");
  if (o.program == "-") {
    for (auto b : bytes) is_image = is_image || b == 0;  // a binary image always has zero bytes
  }
  if (is_image) {
    std::string messages;
    std::string name = o.program == "-" ? "<stdin>" : o.program;
    bool ok = tmcl::read_program_image(name, bytes, program, messages);
    if (!ok) {
      // The image reader words its messages itself; the JSON diagnostic carries them whole.
      while (!messages.empty() && messages.back() == '\n') messages.pop_back();
      std::fprintf(stderr, "%s\n", messages.c_str());
      return fail("input", kExitInput, {name, 0, 0, "error", "", messages});
    }
    std::fputs(messages.c_str(), stderr);
  } else {
    StdinFirstReader reader(o.program == "-" ? std::string(bytes.begin(), bytes.end()) : std::string());
    o.asm_opts.profile = profile;
    tmcl::AsmResult res = tmcl::assemble({o.program}, o.asm_opts, reader);
    if (!res.diags.all().empty()) std::fputs(res.diags.render(res.sources, g_failure.error_limit).c_str(), stderr);
    if (!res.ok()) {
      // The same diagnostics as standard error shows, cut at the same --error-limit.
      int shown = 0;
      for (const tmcl::Diagnostic* d : res.diags.sorted(res.sources)) {
        if (g_failure.error_limit > 0 && shown >= g_failure.error_limit) {
          ++g_failure.more;
          continue;
        }
        if (d->severity == tmcl::Severity::Error) ++shown;
        auto file_of = [&res](const tmcl::SourceLoc& loc) {
          bool known = loc.file >= 0 && static_cast<std::size_t>(loc.file) < res.sources.files.size();
          return known ? res.sources.files[static_cast<std::size_t>(loc.file)].name : std::string();
        };
        fail("input", kExitInput,
             {file_of(d->loc), d->loc.line, d->loc.col, d->severity == tmcl::Severity::Error ? "error" : "warning",
              d->name, d->message});
        for (const auto& n : d->notes) fail("input", kExitInput, {file_of(n.loc), n.loc.line, n.loc.col, "note", "", n.message});
      }
      return kExitInput;
    }
    program = res.program;
    for (const auto& li : res.lines) {
      if (li.file >= 0 && static_cast<std::size_t>(li.file) < res.sources.files.size())
        sources.push_back(res.sources.files[static_cast<std::size_t>(li.file)].name + ":" + std::to_string(li.line));
      else
        sources.emplace_back();
    }
  }
  if (program.empty()) return input_error(o.program, "the program is empty");
  if (profile->program_memory > 0 && program.size() > static_cast<std::size_t>(profile->program_memory))
    return input_error(o.program, std::to_string(program.size()) + " instructions do not fit the " +
                                      std::to_string(profile->program_memory) + " of " + o.target + " program memory");

  return -1;
}

void tmclrun::set_up_vm(tmcl::Vm& vm, const Options& o, const std::vector<tmcl::Instruction>& program,
                        const tmcl::SourceMap& sources, const tmcl::EepromImage* image,
                        std::vector<tmcl::InputEvent> inputs) {
  vm.instr_time = o.instr_time;
  vm.strict = o.strict;
  vm.load(program);
  vm.source_of = sources;
  vm.power_on(image);
  vm.add_inputs(std::move(inputs));
}

int run(int argc, char** argv) {
  Options o;
  if (int r = parse_args(argc, argv, o); r >= 0) return r;
  if (!o.eeprom_seal.empty()) {
    std::string why;
    std::vector<tmcl::FileDiag> ediags;
    if (tmcl::seal_eeprom_file(o.eeprom_seal, ediags, why)) return kExitOk;
    if (!ediags.empty()) return file_errors(ediags);
    // A file that cannot be written is an I/O error; one that cannot be read or parsed, bad input.
    if (why.find(": error: cannot write") != std::string::npos) {
      std::fprintf(stderr, "%s\n", why.c_str());
      return fail("io", kExitIo, {o.eeprom_seal, 0, 0, "error", "", why.substr(why.find(": error: ") + 9)});
    }
    return located_error(why);
  }

  const tmcl::Profile* profile = tmcl::find_profile(o.target);
  if (!profile) {
    std::vector<std::string> names;
    for (const auto* p : tmcl::all_profiles()) names.emplace_back(p->name);
    return usage_error("unknown module '" + o.target + "' (available: " + joined(names) + ")");
  }
  std::string core_name = o.motion.empty() ? std::string(profile->default_motion) : o.motion;
  auto core = tmcl::make_motion_core(core_name);
  if (!core && !o.motion.empty())
    return usage_error("unknown motion core '" + o.motion + "' (available: " + joined(tmcl::motion_core_names()) + ")");
  if (!core) {
    std::fprintf(stderr, "tmclrun: note: motion core '%s' (the default for %s) is not built in; using 'ideal'\n",
                 core_name.c_str(), o.target.c_str());
    core = tmcl::make_ideal_motion_core();
  }

  if (o.testing) return run_mode(o, *profile, std::move(core), {}, {}, {}, nullptr);  // --test: tmclrun_modes.cpp

  // ---- the program (optional with --serve: a host may download one) ----
  std::vector<tmcl::Instruction> program;
  tmcl::SourceMap sources;
  std::string err;
  if (!o.program.empty() && !o.debugging)
    if (int r = load_program(o, profile, program, sources); r >= 0) return r;

  // ---- scenario and EEPROM ----
  std::vector<tmcl::InputEvent> inputs;
  if (!o.scenario.empty()) {
    std::vector<std::uint8_t> sb;
    if (!tmcl::read_file(o.scenario, sb, err, tmcl::kMaxScenarioBytes)) return input_error("", err);
    tmcl::ScenarioOptions sopts;
    sopts.motors = profile->motors;
    sopts.module = o.target;
    sopts.error_limit = g_failure.error_limit;
    std::vector<tmcl::FileDiag> sdiags;
    if (!tmcl::parse_scenario(std::string(sb.begin(), sb.end()), o.scenario, inputs, sdiags, sopts))
      return file_errors(sdiags);
  }
  tmcl::EepromImage image;
  if (!o.eeprom.empty()) {
    bool existed = false;
    std::vector<tmcl::FileDiag> ediags;
    if (!tmcl::load_eeprom_file(o.eeprom, image, existed, ediags, err)) return ediags.empty() ? located_error(err) : file_errors(ediags);
    if (existed && image.profile != profile->name)
      return located_error(o.eeprom + ":2: error: EEPROM written for module '" + image.profile + "', not '" + o.target + "'");
  }

  // --serve, --debug, --dap: tmclrun_modes.cpp (in tmclrun-full only).
  if (o.serving || o.debugging)
    return run_mode(o, *profile, std::move(core), program, sources, std::move(inputs), o.eeprom.empty() ? nullptr : &image);

  // ---- run ----
  // --csv/--plot: the VM drives a recording decorator around the real core.
  bool recording = !o.csv.empty() || !o.plot.empty();
  tmcl::MotionRecorder recorder(profile->motors, o.sample);
  tmcl::RecordingCore recording_core(*core, recorder);
  tmcl::Vm vm(*profile, recording ? static_cast<tmcl::MotionCore&>(recording_core) : *core);
  tmcl::TextTrace trace(o.json ? stderr : stdout, &sources);
  if (o.trace) vm.trace = &trace;
  tmcl::RecordingTrace recording_trace(vm.trace, recorder);
  if (recording) vm.trace = &recording_trace;
  vm.handler_code = handler_code(program);
  set_up_vm(vm, o, program, sources, o.eeprom.empty() ? nullptr : &image, std::move(inputs));
  vm.start(0);
  tmcl::RunResult result = vm.run(o.limits);

  int status = kExitOk;
  switch (result.halt) {
    case tmcl::Halt::Stop:
    case tmcl::Halt::NotRunning: status = kExitOk; break;
    case tmcl::Halt::Fault: status = kExitFault; break;
    default: status = kExitLimit; break;
  }
  if (result.halt == tmcl::Halt::Fault) {
    std::int32_t at = vm.halt_pc;
    std::string where = at >= 0 && static_cast<std::size_t>(at) < sources.size() ? sources[static_cast<std::size_t>(at)] : "";
    std::fprintf(stderr, "%s: error: runtime fault: %s\n", where.empty() ? "tmclrun" : where.c_str(), result.message.c_str());
  } else if (status == kExitLimit) {
    std::fprintf(stderr, "tmclrun: %s: %s\n", std::string(tmcl::halt_name(result.halt)).c_str(), result.message.c_str());
  }

  if (recording) {
    recording_core.finish(vm.now);
    std::ostringstream csv, svg;
    if (!o.csv.empty()) tmcl::write_csv(csv, recorder);
    if (!o.plot.empty()) {
      tmcl::PlotOptions plot;
      plot.title = (o.program == "-" ? std::string("<stdin>") : o.program) + " on " + o.target + " (" +
                   std::string(core->name()) + " motion)";
      tmcl::write_svg(svg, recorder, plot);
    }
    for (const auto& [file, text] : {std::pair{o.csv, csv.str()}, std::pair{o.plot, svg.str()}}) {
      if (file.empty()) continue;
      if (!tmcl::write_file_atomic(file, std::vector<std::uint8_t>(text.begin(), text.end()), err)) {
        std::fprintf(stderr, "tmclrun: %s\n", err.c_str());
        status = kExitIo;
      }
    }
  }
  if (!o.eeprom.empty() && !tmcl::save_eeprom_file(o.eeprom, vm.eeprom, err)) {
    std::fprintf(stderr, "%s\n", err.c_str());
    status = kExitIo;
  }
  if (o.json)
    std::fputs(tmcl::state_json(vm, result).c_str(), stdout);
  else
    std::fputs(tmcl::state_summary(vm, result, &sources).c_str(), stdout);
  return status;
}


int main(int argc, char** argv) {
  // --json is known before any other option is read, so even a bad option is reported as JSON.
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--json") == 0) g_failure.json = true;
  int status = run(argc, argv);
  if (g_failure.json && !g_failure.kind.empty())
    std::fputs(tmcl::error_json(g_failure.kind, status, g_failure.diags, g_failure.more).c_str(), stdout);
  // Every write is checked, standard output included: a full disk or a closed pipe is exit 74,
  // never a silent success.
  if (std::string err; !tmcl::flush_stdout(err)) {
    std::fprintf(stderr, "tmclrun: error: %s\n", err.c_str());
    return kExitIo;
  }
  return status;
}
