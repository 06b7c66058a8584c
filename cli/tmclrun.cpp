// tmclrun: runs a TMCL program on the virtual machine without hardware. Parses arguments, loads
// the program (assembling .tmc in-process), scenario and EEPROM, runs the VM library, prints the
// summary, trace, JSON, CSV or plot. Serving (--serve) and debugging are tmclrun_modes.cpp's. All
// semantics live in vm/; see docs/tmclrun.md. Exit status: 0 STOP, 3 limit reached or blocked, 70
// runtime fault, 65 bad input, 64 usage, 71 --serve transport failed, 74 an output file or
// standard output not written, 130/143 ended by SIGINT/SIGTERM (run_control.hpp). With --json
// every outcome is one JSON object on standard output.
#include <unistd.h>

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
#include "tmcl/asm/names.hpp"
#include "tmcl/diag_text.hpp"
#include "tmcl/duration.hpp"
#include "tmcl/eeprom.hpp"
#include "tmcl/fileio.hpp"
#include "tmcl/motion_recording.hpp"
#include "tmcl/numbers.hpp"
#include "tmcl/options.hpp"
#include "tmcl/os_console.hpp"
#include "tmcl/program_image.hpp"
#include "tmcl/run_control.hpp"
#include "tmcl/scenario.hpp"
#include "tmcl/targets.hpp"
#include "tmcl/vm.hpp"
#include "tmcl/vm_output.hpp"
#include "tmclrun.hpp"

using namespace tmclrun;

namespace {

const char* kUsage = R"(usage: tmclrun [options] PROGRAM        PROGRAM: .tmc source, .bin, .dgm, or - (stdin)
       tmclrun --test [options] FILE.tmctest|DIR...

Runs a TMCL program on a deterministic virtual module. Simulated time: nothing waits for real.

options:
)";

const char* kEpilogue = R"(DURATION: a number with us, ms, s, min or h (50us, 0.25ms, 1.5s, 2min, 1h); 0 needs no unit.

examples:
  tmclrun prog.tmc                              run until STOP, print a summary
  tmclrun --trace --max-time 10s prog.tmc       trace the first 10 simulated seconds
  tmclrun --scenario switches.txt --json prog.bin
  tmclrun --eeprom module.eeprom prog.tmc       run twice: the EEPROM persists
  tmclrun --plot motion.svg --csv motion.csv prog.tmc   what the motors did, as a picture and data
  tmclrun --serve tcp:127.0.0.1:2001 prog.tmc   a virtual module for PyTrinamic (Ctrl-C stops it)
  tmclrun --test --junit report.xml --coverage coverage.info tests/

exit status: 0 STOP, 3 limit reached or blocked forever, 70 runtime fault, 65 bad input,
             64 usage error, 71 --serve transport failed, 74 an output file (EEPROM, --csv,
             --plot, a report) or standard output could not be written (a --trace into a closed
             pipe ends the run so), 130/143 ended by SIGINT (Ctrl-C)/SIGTERM after writing the
             summary, --json, --csv, --plot and EEPROM; with --test: 0 every test passed, 1 a
             test failed, 65 a bad test file or program

documentation: the .md files named above are in share/doc/tmcl/ of the installation
               (/usr/share/doc/tmcl/ from the Debian package); also man tmclrun
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
class StdinFirstReader final : public tmcl::FileOverlay {
 public:
  explicit StdinFirstReader(std::string text) : text_(std::move(text)) {}

 private:
  bool serve(const std::string& path, std::string& out) override {
    if (path != "-") return false;
    out = text_;
    return true;
  }
  std::string text_;
};

// DURATION for OPT into `out`: "" when it parsed, else the usage error.
std::string duration_value(const char* opt, const std::string& v, tmcl::SimTime& out) {
  std::string why;
  auto d = tmcl::parse_duration(v, why);
  if (!d) return "bad duration for " + std::string(opt) + ": " + why;
  out = *d;
  return {};
}

// A number from 0 to 255 (--module-address, --host-address): "" when it parsed.
std::string address_value(const char* opt, const std::string& v, std::optional<std::uint8_t>& out) {
  char* end = nullptr;
  const long n = std::strtol(v.c_str(), &end, 0);
  if (v.empty() || *end || n < 0 || n > 255) return std::string(opt) + " needs a number from 0 to 255";
  out = static_cast<std::uint8_t>(n);
  return {};
}

// --plot-series PARAMS (206,180): the axis parameters the plot can draw (plot_series_name), each
// once, appended in order: "" when they parsed.
std::string plot_series_value(const std::string& v, std::vector<int>& out) {
  std::size_t at = 0;
  do {
    const std::size_t comma = std::min(v.find(',', at), v.size());
    const std::string word = v.substr(at, comma - at);
    char* end = nullptr;
    const long n = std::strtol(word.c_str(), &end, 10);
    if (word.empty() || *end || tmcl::plot_series_name(static_cast<int>(n)).empty() || n != static_cast<int>(n))
      return "--plot-series draws axis parameters 206 (load value) and 180 (actual current), not '" + word + "'";
    if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(static_cast<int>(n));
    at = comma + 1;
  } while (at <= v.size());
  return {};
}

// The options, each declared once: --help, the errors, the man-page check and bash completion
// follow from this table (tmcl/options.hpp).
// --variant: the names and meanings of the virtual module's firmware variants, from their table.
std::vector<std::string> variant_names() {
  std::vector<std::string> names;
  for (const tmcl::VariantInfo& v : tmcl::firmware_variant_table()) names.emplace_back(v.name);
  return names;
}
std::string variant_names_text() {
  std::string text;
  for (const std::string& n : variant_names()) text += (text.empty() ? "" : ", ") + n;
  return text;
}
std::string variant_help() {
  std::string text;
  for (const tmcl::VariantInfo& v : tmcl::firmware_variant_table())
    text += (text.empty() ? "" : "\n") + std::string("  ") + std::string(v.name) + ": " + std::string(v.meaning);
  return text;
}

tmcl::cli::Tool command_line(Options& o) {
  using tmcl::cli::flag, tmcl::cli::set, tmcl::cli::Values;
  auto duration = [](const char* opt, tmcl::SimTime& field) {
    return [opt, &field](const std::string& v) { return duration_value(opt, v, field); };
  };
  auto warning = [&o](const char* prefix) {
    return [&o, prefix](const std::string& v) {
      std::string error, arg = prefix + v;
      if (!o.asm_opts.warnings.parse(arg, error)) return error.empty() ? "unknown option '" + arg + "'" : error;
      return std::string();
    };
  };
  const std::vector<std::string> durations{"20us", "10ms", "1s", "1min"};
  const Values warnings = Values::words(tmcl::warning_names());
  tmcl::cli::Tool t;
  t.name = "tmclrun";
  t.usage = kUsage;
  t.epilogue = kEpilogue;
  t.column = 25;
  t.options = {
      {"-t, --target", "NAME",
       "the module: a target name or a profile file, as for tmclasm (default:\n"
       "what the program's first line names, // tmcl-target: NAME, else generic)",
       [&o](const std::string& v) {
         o.target = v;
         o.target_given = true;
         return std::string();
       },
       Values::words([] { return tmcl::target_names(); }, {"profile"}), "a target name or a profile file"},
      {"--motion", "NAME", "motion core (default: the module's; available: " + joined(tmcl::motion_core_names()) + ")",
       set(o.motion), Values::words(tmcl::motion_core_names()), "a core name"},
      {"--instr-time", "DURATION", "simulated time per instruction (default 20us)", duration("--instr-time", o.instr_time),
       Values::words(durations)},
      {"--max-time", "DURATION", "stop when simulated time reaches DURATION", duration("--max-time", o.limits.until),
       Values::words(durations)},
      {"--max-steps", "N", "stop after N instructions",
       [&o](const std::string& v) {
         char* end = nullptr;
         errno = 0;
         const unsigned long long n = std::strtoull(v.c_str(), &end, 10);
         if (v.empty() || *end || v[0] == '-' || errno) return "bad step count '" + v + "' for --max-steps";
         o.limits.max_steps = n;
         return std::string();
       }},
      {"--scenario", "FILE",
       "the machine and its inputs (tmclrun.md): timed inputs, switches,\n"
       "hard stops, loads (timed and at positions) and encoder slip",
       set(o.scenario), Values::files()},
      {"--eeprom", "FILE", "load the EEPROM from FILE at start, save it there at exit", set(o.eeprom),
       Values::files({"eeprom"})},
      {"--eeprom-seal", "FILE", "after editing an EEPROM file by hand: check it, write a new checksum",
       set(o.eeprom_seal), Values::files({"eeprom"})},
      {"--trace", "",
       "print a line per instruction, interrupt, wait and motion event\n"
       "(to standard error when --json is given); with --serve, a line per\n"
       "request and reply, decoded, to standard error or --log FILE",
       flag(o.trace)},
      {"--log", "FILE", "with --serve --trace: write the request log to FILE", set(o.log), Values::files()},
      {"--json", "",
       "print the final state as one JSON object instead of the summary;\n"
       "when there is no run (bad option or input), the errors as one object",
       flag(o.json)},
      {"--strict", "",
       "a run-time warning (full call stack, RSUB or RETI with nothing to\n"
       "return to, a handler left without RETI) is a runtime fault (70); a\n"
       "note (an interrupt never raised, a parameter not simulated) is a\n"
       "warning, and so a fault too",
       flag(o.strict)},
      {"--list-targets", "", "list every target found and where it comes from, as tmclasm does", flag(o.list_targets)},
      {"--error-limit", "N", "show at most N errors of the source or scenario (default 20, 0 = all)",
       [&o](const std::string& v) {
         std::int64_t n = 0;
         if (!tmcl::parse_int(v, 0, 1'000'000'000, n))
           return "bad error limit '" + v + "' for --error-limit (a number, 0 for no limit)";
         g_failure.error_limit = o.asm_opts.error_limit = static_cast<int>(n);
         return std::string();
       }},
      {"--serve", "SPEC",
       "act as a virtual module: tcp:HOST:PORT (loopback unless told\n"
       "otherwise; [::1]:PORT for IPv6), pty, stdio, or a serial port\n"
       "(COM3, /dev/ttyUSB0; PORT:BAUD, default 9600) (virtual-module.md).\n"
       "PROGRAM is then optional (a host can download one)",
       [&o](const std::string& v) {
         o.serving = true;
         std::string error;
         tmcl::parse_serve_spec(v, o.serve_opts, error);
         return error;
       },
       Values::words({"tcp:127.0.0.1:2001", "pty", "stdio"}), "tcp:HOST:PORT, pty, stdio or a serial port"},
      {"--autostart", "", "with --serve: start the program at once (also: global 77 = 1)",
       flag(o.serve_opts.autostart)},
      {"--time-scale", "X", "with --serve: simulated seconds per real second (default 1)",
       [&o](const std::string& v) {
         char* end = nullptr;
         errno = 0;
         const double x = std::strtod(v.c_str(), &end);
         if (v.empty() || *end || errno || !(x > 0) || x > 1e9) return std::string("--time-scale needs a number greater than 0");
         o.serve_opts.time_scale = x;
         return std::string();
       },
       {}, "a number"},
      {"--module-address", "N", "with --serve: answer requests to address N (default: global 66, 1)",
       [&o](const std::string& v) { return address_value("--module-address", v, o.serve_opts.protocol.module_address); },
       {}, "a number from 0 to 255"},
      {"--host-address", "N", "with --serve: address replies to N (default: global 76, 2)",
       [&o](const std::string& v) {
         std::optional<std::uint8_t> n;
         std::string error = address_value("--host-address", v, n);
         if (n) o.serve_opts.protocol.host_address = *n;
         return error;
       },
       {}, "a number from 0 to 255"},
      {"--eeprom-locked", "", "with --serve: refuse commands that write the EEPROM (status 5)",
       flag(o.serve_opts.protocol.eeprom_locked)},
      {"--variant", "NAME[,NAME]",
       "with --serve, repeatable: behave as firmware that differs where the\n"
       "manuals are silent (virtual-module.md, \"Firmware variants\"):\n" +
           variant_help(),
       [&o](const std::string& v) {
         std::string error;
         tmcl::parse_firmware_variants(v, o.serve_opts.protocol.variants, error);
         return error;
       },
       Values::words(variant_names()), "a variant name (" + variant_names_text() + ")"},
      {"--max-wall-time", "DURATION", "with --serve: stop by itself after this much real time",
       [&o](const std::string& v) {
         tmcl::SimTime wall = 0;
         std::string error = duration_value("--max-wall-time", v, wall);
         o.serve_opts.max_wall_ms = wall / tmcl::kUsPerMs + (wall % tmcl::kUsPerMs ? 1 : 0);
         return error;
       },
       Values::words(durations)},
      {"--faults", "SPEC",
       "with --serve: drop, corrupt, delay, split, silence or stale replies, by\n"
       "count, command or seeded chance (virtual-module.md, \"Faults\")",
       [&o](const std::string& v) {
         std::string error;
         tmcl::parse_faults(v, o.serve_opts.faults, error);
         return error;
       },
       {}, "a SPEC (e.g. drop@3,corrupt@p=0.1,seed=7)"},
      {"--module", "ADDR[/TARGET][:FILE]",
       "with --serve, repeatable: modules on one bus, each its own VM,\n"
       "EEPROM and address (the first replaces PROGRAM and --module-address)",
       tmcl::cli::append(o.modules)},
      {"--csv", "FILE",
       "write time, position, velocity, acceleration of every motor to FILE\n"
       "at each --sample period, plus one row per event",
       set(o.csv), Values::files({"csv"})},
      {"--sample", "DURATION", "the sampling period of --csv and --plot (default 10ms)",
       [&o](const std::string& v) {
         std::string error = duration_value("--sample", v, o.sample);
         if (error.empty() && o.sample <= 0) error = "--sample needs a duration greater than 0";
         return error;
       },
       Values::words(durations)},
      {"--plot", "FILE.svg", "draw position, velocity and acceleration against time as an SVG", set(o.plot),
       Values::files({"svg"})},
      {"--plot-from", "DURATION", "with --plot: draw from this simulated instant on (default 0)",
       duration("--plot-from", o.plot_from), Values::words(durations)},
      {"--plot-to", "DURATION", "with --plot: draw up to this simulated instant (default: the end)",
       duration("--plot-to", o.plot_to), Values::words(durations)},
      {"--plot-series", "PARAMS",
       "with --plot or --csv: record axis parameters too, as a program reads\n"
       "them (a panel, a column each): 206 the load value, 180 the actual\n"
       "current, or 206,180",
       [&o](const std::string& v) { return plot_series_value(v, o.plot_series); }, Values::words(std::vector<std::string>{"206", "180", "206,180"}),
       "206, 180 or both (206,180)"},
      {"--debug", "",
       "debug PROGRAM with gdb's commands (debugger.md), read from\n"
       "standard input: a terminal, or a pipe or file for scripts; with\n"
       "--serve tcp:... or pty, while the module keeps answering its host",
       flag(o.debug.enabled)},
      {"--debug-commands", "FILE", "debug PROGRAM with the commands in FILE, then quit (gdb -batch -x)",
       [&o](const std::string& v) {
         o.debug.commands_file = v;
         o.debug.enabled = true;
         return std::string();
       },
       Values::files()},
      {"--symbols", "FILE", "with --debug: the labels and source lines of a .bin (tmclasm -f symbols)",
       set(o.debug.symbols), Values::files({"sym"}), "a file (tmclasm -f symbols)"},
      {"--source-dir", "DIR", "with --debug or --dap: look for the sources of a .bin in DIR too",
       [&o](const std::string& v) {
         if (v.empty()) return std::string("--source-dir needs a folder");
         o.debug.source_dirs.push_back(v);
         return std::string();
       },
       Values::dirs()},
      {"--checkpoint-memory", "MIB", "with --debug: memory for reverse execution (default 64)",
       [&o](const std::string& v) {
         char* end = nullptr;
         const long long n = std::strtoll(v.c_str(), &end, 10);
         if (v.empty() || *end || n < 1 || n > 1 << 20)
           return std::string("--checkpoint-memory needs a size in MiB from 1 to 1048576");
         o.debug.checkpoint_bytes = static_cast<std::size_t>(n) << 20;
         return std::string();
       },
       {}, "a size in MiB"},
      {"--dap", "", "the debugger over the Debug Adapter Protocol on stdin/stdout",
       [&o](const std::string&) {
         o.debug.enabled = o.debug.dap = true;
         return std::string();
       }},
      {"--test", "",
       "run test files (*.tmctest; a folder: every one under it) and print\n"
       "PASS or FAIL for each, then 'N passed, N failed' (testing.md)",
       flag(o.testing)},
      {"-j, --jobs", "N", "with --test: run N tests at a time (default: one per core)",
       [&o](const std::string& v) {
         std::int64_t n = 0;
         if (!tmcl::parse_int(v, 1, 256, n)) return std::string("--jobs needs a number of tests at a time, 1 to 256");
         o.test.jobs = static_cast<int>(n);
         return std::string();
       },
       {}, "a number of tests at a time, 1 to 256"},
      {"--junit", "FILE", "with --test: write a JUnit XML report to FILE", set(o.test.junit), Values::files({"xml"})},
      {"--coverage", "FILE", "with --test: write line and branch coverage to FILE (lcov tracefile)", set(o.test.coverage),
       Values::files({"info"})},
      {"--coverage-summary", "", "with --test: print lines and branches covered per file", flag(o.test.coverage_summary)},
      {"--update", "", "with --test: rewrite the values of failing expectations from the run", flag(o.test.update)},
      {"-I", "DIR", "search DIR for #include files", tmcl::cli::append(o.asm_opts.include_dirs), Values::dirs(),
       "a directory"},
      {"-D", "NAME=VALUE", "define an assembler constant",
       [&o](const std::string& v) {
         const auto eq = v.find('=');
         if (eq == std::string::npos || eq == 0) return "bad -D '" + v + "' (expected NAME=VALUE)";
         o.asm_opts.defines.emplace_back(v.substr(0, eq), v.substr(eq + 1));
         return std::string();
       }},
      {"-Werror", "", "", warning("-Werror")},
      {"-Werror=", "NAME", "assembler warnings (all, or the one named) are errors", warning("-Werror="), warnings},
      {"-Wno-", "NAME", "do not report the assembler warning NAME", warning("-Wno-"), warnings},
      {"-W", "NAME", "", warning("-W"), warnings, {}, true},
  };
  t.operands = [](const std::vector<std::string>&, const std::vector<std::string>& given) {
    for (const auto& g : given)
      if (g == "--test") return Values::files({"tmctest"});  // test files, or folders of them
    return Values::files({"tmc", "bin", "dgm"});
  };
  return t;
}

// Returns -1 when the run should go on, otherwise an exit status.
int parse_args(int argc, char** argv, Options& o) {
  const tmcl::cli::Result cl = tmcl::cli::parse(command_line(o), argc, argv);
  if (cl.status == tmcl::cli::Result::Status::Done) return kExitOk;
  if (cl.status == tmcl::cli::Result::Status::Error) return usage_error(cl.error);
  if (o.list_targets) {  // the same list as tmclasm's (one reader: targets.hpp)
    const std::string list = tmcl::format_target_list(tmcl::list_targets());
    return std::fwrite(list.data(), 1, list.size(), stdout) == list.size() && std::fflush(stdout) == 0 ? kExitOk
                                                                                                      : kExitIo;
  }
  o.given = cl.given;
  o.inputs = cl.operands;
  if (cl.operands.size() > 1 && !o.testing)
    return usage_error("only one PROGRAM can be run (got '" + cl.operands[0] + "' and '" + cl.operands[1] + "')");
  const bool have_program = !cl.operands.empty();
  if (have_program) o.program = cl.operands[0];
  if (int r = check_mode_options(o, have_program); r >= 0) return r;
  if (!o.log.empty() && (!o.serving || !o.trace)) return usage_error("--log FILE goes with --serve --trace");
  if ((o.plot_from != 0 || o.plot_to != tmcl::kNever) && o.plot.empty())
    return usage_error("--plot-from and --plot-to go with --plot FILE.svg");
  if (!o.plot_series.empty() && o.plot.empty() && o.csv.empty())
    return usage_error("--plot-series goes with --plot FILE.svg or --csv FILE");
  if (o.plot_to <= o.plot_from) return usage_error("--plot-to must be later than --plot-from");
  if (!o.eeprom_seal.empty()) {
    if (have_program || o.serving || !o.eeprom.empty())
      return usage_error("--eeprom-seal FILE goes alone (it seals FILE and runs nothing)");
    return -1;
  }
  if (!have_program && !o.serving && !o.debug.dap) return usage_error("no PROGRAM given");
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
                 tmcl::SourceMap& sources, tmcl::SourceNames* names) {
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
    if (names) *names = tmcl::source_names(res);
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
  // Program memory in the EEPROM (errata E55): without a PROGRAM (a served module) the module
  // comes up with what the file holds; a PROGRAM given is stored there, as a download stores it.
  const bool from_eeprom = o.program.empty() && image && vm.program_in_eeprom();
  vm.load(from_eeprom ? image->program : program);
  vm.source_of = sources;
  vm.power_on(image);
  if (!o.program.empty() && image) vm.store_program();
  vm.add_inputs(std::move(inputs));
}

// A program in the EEPROM file must fit the module: a module that keeps its program in RAM has
// none there, and program memory has the profile's size.
int tmclrun::check_stored_program(const Options& o, const tmcl::Profile& profile, const tmcl::EepromImage& image) {
  if (image.program.empty()) return -1;
  const std::string words = std::to_string(image.program.size()) + " instruction" + (image.program.size() == 1 ? "" : "s");
  if (profile.program_store != tmcl::ProgramStore::Eeprom)
    return located_error(o.eeprom + ": error: the EEPROM file holds a program (" + words + "), but " + std::string(profile.name) +
                         " keeps its program in " + (profile.program_store == tmcl::ProgramStore::Ram ? "RAM" : "memory the profile does not name") +
                         ": delete its program records and run tmclrun --eeprom-seal");
  const int memory = profile.program_memory;
  if (memory > 0 && image.program.size() > static_cast<std::size_t>(memory)) {
    // The file is sorted (written or sealed): the program records come last, before the checksum.
    const std::size_t first = 3 + image.vars.size() + image.globals.size() + image.bank3.size() + image.axis.size() + image.coords.size();
    return located_error(o.eeprom + ":" + std::to_string(first + static_cast<std::size_t>(memory)) + ": error: the stored program (" +
                         words + ") does not fit the " + std::to_string(memory) + " of " + std::string(profile.name) + "'s program memory");
  }
  return -1;
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

  auto unknown_core = [&o] {
    return usage_error("unknown motion core '" + o.motion + "' (available: " + joined(tmcl::motion_core_names()) + ")");
  };
  // --test (tmclrun_modes.cpp): each test's module is the runner's to find, from -t as given (a
  // profile file's path stays a path: its name need not be a target) or the test's own lines; -t
  // and --motion are checked once here. The operands are tests, not a program naming a target.
  if (o.testing) {
    if (o.target_given) {
      const tmcl::TargetResult t = tmcl::resolve_target(o.target);
      if (!t.profile) return !t.diags.empty() ? file_errors(t.diags) : t.usage ? usage_error(t.error) : input_error("", t.error);
    }
    if (!o.motion.empty() && !tmcl::make_motion_core(o.motion)) return unknown_core();
    return run_tests(o);
  }

  if (!o.target_given) o.target = tmcl::target_named_by_file(o.program, o.target);
  tmcl::TargetResult target = tmcl::resolve_target(o.target);
  if (!target.profile)
    return !target.diags.empty() ? file_errors(target.diags) : target.usage ? usage_error(target.error) : input_error("", target.error);
  const tmcl::Profile* profile = target.profile;
  o.target = std::string(profile->name);
  std::string core_note;
  auto core = o.motion.empty() ? tmcl::make_profile_motion_core(*profile, &core_note) : tmcl::make_motion_core(o.motion);
  if (!core) return unknown_core();
  if (!core_note.empty()) std::fprintf(stderr, "tmclrun: note: %s\n", core_note.c_str());

  // ---- the program (optional with --serve: a host may download one) ----
  std::vector<tmcl::Instruction> program;
  tmcl::SourceMap sources;
  tmcl::SourceNames names;  // --trace shows what the source named
  std::string err;
  if (!o.program.empty() && !o.debug.enabled)
    if (int r = load_program(o, profile, program, sources, o.trace && !o.serving ? &names : nullptr); r >= 0) return r;

  // ---- scenario and EEPROM ----
  std::vector<tmcl::InputEvent> inputs;
  if (!o.scenario.empty()) {
    std::vector<std::uint8_t> sb;
    if (!tmcl::read_file(o.scenario, sb, err, tmcl::kMaxScenarioBytes)) return input_error("", err);
    tmcl::ScenarioOptions sopts;
    sopts.motors = profile->motors;
    sopts.profile = profile;
    sopts.module = o.target;
    if (!core->models_encoder(*profile)) sopts.no_encoder = std::string(core->name());
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
    if (int r = check_stored_program(o, *profile, image); r >= 0) return r;
  }

  // --serve, --debug, --dap: tmclrun_modes.cpp.
  if (o.serving || o.debug.enabled)
    return run_mode(o, *profile, std::move(core), program, sources, std::move(inputs), o.eeprom.empty() ? nullptr : &image);

  // ---- run ----
  // --csv/--plot: the VM drives a recording decorator around the real core.
  bool recording = !o.csv.empty() || !o.plot.empty();
  tmcl::MotionRecorder recorder(profile->motors, o.sample);
  recorder.sample_params(o.plot_series);
  tmcl::RecordingCore recording_core(*core, recorder);
  tmcl::Vm vm(*profile, recording ? static_cast<tmcl::MotionCore&>(recording_core) : *core);
  tmcl::TextTrace trace(o.json ? stderr : stdout, &sources, &names);
  if (o.trace) vm.trace = &trace;
  tmcl::RecordingTrace recording_trace(vm.trace, recorder);
  if (recording) vm.trace = &recording_trace;
  vm.handler_code = handler_code(program);
  set_up_vm(vm, o, program, sources, o.eeprom.empty() ? nullptr : &image, std::move(inputs));
  const auto vars_at_start = vm.vars;  // the summary shows the variables that changed
  vm.start(0);
  // SIGINT, SIGTERM, a closed trace output and the note of an unbounded run (run_control.hpp).
  const bool unbounded = o.limits.until == tmcl::kNever && o.limits.max_steps == UINT64_MAX;
  tmcl::RunControl control(unbounded && ::isatty(2));
  trace.write_failed = [&control] { control.output_closed(); };
  tmcl::RunResult result = control.run(vm, o.limits);

  int status = kExitOk;
  switch (result.halt) {
    case tmcl::Halt::Stop:
    case tmcl::Halt::NotRunning: status = kExitOk; break;
    case tmcl::Halt::Fault: status = kExitFault; break;
    default: status = control.output_was_closed() ? kExitIo : kExitLimit; break;
  }
  // The halt is said once: a fault as an error here (the summary names its kind and place), any
  // other halt in the summary or JSON only.
  if (result.halt == tmcl::Halt::Fault) {
    std::int32_t at = vm.halt_pc;
    std::string where = at >= 0 && static_cast<std::size_t>(at) < sources.size() ? sources[static_cast<std::size_t>(at)] : "";
    std::fprintf(stderr, "%s: error: runtime fault: %s\n", where.empty() ? "tmclrun" : where.c_str(), result.message.c_str());
  }

  if (recording) {
    recording_core.finish(vm.now);
    recorder.show_motors(tmcl::shown_motors(vm));
    std::ostringstream csv, svg;
    // A core in chip units says which, at power-on and from each change on (a divisor written),
    // in the CSV's head; the plot's title only names them (its markers show each change), so a
    // run with many changes keeps a title that fits.
    if (!o.csv.empty()) tmcl::write_csv(csv, recorder, recording_core.units_history("\n# "));
    if (!o.plot.empty()) {
      tmcl::PlotOptions plot;
      plot.title = (o.program == "-" ? std::string("<stdin>") : o.program) + " on " + o.target + " (" +
                   std::string(core->name()) + " motion" + recording_core.units_title() + ")";
      plot.from = o.plot_from;
      plot.to = o.plot_to;
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
    std::fputs(tmcl::state_summary(vm, result, &vars_at_start).c_str(), stdout);
  return status;
}


int main(int argc, char** argv) {
  tmcl::os::init_console();  // Windows: bytes as they are, UTF-8 (os_console.hpp)
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
  tmcl::RunControl::end_by_signal();  // SIGINT or SIGTERM ended the run: its status, 130 or 143
  return status;
}
