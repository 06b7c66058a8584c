// tmclctl: talks to a TMCL module (or tmclrun --serve) over a serial port or TCP: send one
// instruction, get/set/store parameters, download/verify/upload programs, run/stop/step/reset,
// status, monitor, an interactive console, a bus scan, a probe and test files (tmclctl_testrun.cpp). A
// thin tool: the protocol, transfers and parameter names live in cli/host/ (tmcl_host); see
// docs/tmclctl.md for every command. Exit status: 0 ok, 1 verify mismatch or a test failed,
// 2 error status from the module, 64 usage, 65 bad input, 69 no reply, 74 port, output file or
// standard output error, 130 interrupted.
#include <dirent.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cinttypes>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tmcl/analysis.hpp"
#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/disasm.hpp"
#include "tmcl/debug_module.hpp"
#include "tmcl/duration.hpp"
#include "tmcl/fileio.hpp"
#include "tmcl/host/client.hpp"
#include "tmcl/host/commands.hpp"
#include "tmcl/host/console.hpp"
#include "tmcl/host/port.hpp"
#include "tmcl/host/probe.hpp"
#include "tmcl/host/scan.hpp"
#include "tmcl/host/transfer.hpp"
#include "tmcl/image.hpp"
#include "tmcl/options.hpp"
#include "tmcl/os_console.hpp"
#include "tmcl/os_serial.hpp"
#include "tmcl/plot.hpp"
#include "tmcl/program_image.hpp"
#include "tmcl/targets.hpp"
#include "tmcl/os_files.hpp"
#include "tmclctl_debug_probe.hpp"
#include "tmclctl_testrun.hpp"

namespace {

using tmcl::Instruction;
using tmcl::Op;
namespace host = tmcl::host;

constexpr int kExitOk = 0, kExitMismatch = 1, kExitStatus = 2, kExitUsage = 64, kExitInput = 65, kExitNoReply = 69,
              kExitPort = 74, kExitInterrupted = 130;

const char* kUsage = R"(usage: tmclctl [options] PORT COMMAND [ARGS...]

Talks to a TMCL module over a serial port or TCP.
PORT: a serial device (/dev/ttyACM0, /dev/ttyUSB0, the pty of tmclrun --serve pty) or tcp:HOST:PORT

commands:
  send 'INSTRUCTION'          one instruction in source syntax, e.g. send 'SAP 4, 0, 51200'
  get PARAM                   read a parameter: ap N [MOTOR], gp N [BANK], io N [BANK], or a name
  set PARAM VALUE             write a parameter (SAP, SGP, SIO)
  store PARAM                 store a parameter in the EEPROM (STAP, STGP)
  download FILE...            .tmc (assembled for -t), .bin, .dgm or objects: store, then verify
  upload -o FILE.bin          read program memory into a TMCL-IDE .bin
  run [ADDRESS]               start the program (from ADDRESS, else where it stands)
  stop | step | reset         128, 130, 131
  status                      application status, program counter, registers, firmware
  monitor PARAM...            poll parameters (ap:N[:MOTOR], gp:N[:BANK], io:N[:BANK], NAME[@MOTOR])
  console                     interactive direct mode: instructions in source syntax
  scan                        find the modules on a bus: address, firmware, module type
  probe -o FILE.profile       read what a module has (firmware, parameters, memory) into a draft
                              profile for -t (profiles.md, "Your own module")
  test FILE|DIR...            run test files (*.tmctest) on the module by the wall clock: a smoke
                              test on hardware (testing.md)
  debug PROGRAM               the debugger of tmclrun --debug on the module: load, break, step,
                              print, continue (debugger.md, "Debugging on a module"); --dap: the
                              Debug Adapter Protocol on standard input and output
  debug --probe               what the module's firmware does where a debugger on it depends on
                              it: a report to paste into an issue (the program is put back)

options:
)";

const char* kEpilogue = R"(DURATION: an integer with us, ms, s or min (500ms, 2s).
download checks the program as tmclasm -Werror checks it (the module's profile and the control-flow
analysis) before anything is sent.

examples:
  tmclctl /dev/ttyACM0 download --run prog.tmc
  tmclctl tcp:127.0.0.1:2001 get 'actual position'
  tmclctl /dev/ttyUSB0 --baud 115200 monitor ap:1 ap:3 --every 50ms --for 10s --csv run.csv
  tmclctl /dev/pts/5 scan --range 1-8
  tmclctl /dev/ttyACM0 probe -o mymodule.profile
  tmclctl -t usb-2-sd /dev/ttyACM0 test tests/ --junit hardware.xml

exit status: 0 ok, 1 verify mismatch or a test failed, 2 the module answered with an error
             status, 64 usage error, 65 bad input file, 69 no reply from the module, 74 port
             error, output file or standard output not written, 130 interrupted (Ctrl-C)

documentation: the .md files named above are in share/doc/tmcl/ of the installation
               (/usr/share/doc/tmcl/ from the Debian package); also man tmclctl
)";

const char* const kCommands[] = {"send", "get", "set", "store", "download", "upload", "run", "stop", "step",
                                 "reset", "status", "monitor", "console", "scan", "probe", "test", "debug"};

volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_sigint(int) { g_stop = 1; }

struct Options {
  std::vector<std::string> argv;  // as given, for the resume hint
  std::string port, command;
  std::vector<std::string> args;
  host::ClientOptions client;
  std::string target = "generic";  // one default for every tool (errata E39)
  bool target_given = false;       // -t: else the module's reply to 136 picks the profile
  long baud = 9600;
  bool raw = false, quiet = false;
  std::vector<std::string> include_dirs;
  bool verify = true, run = false, autostart = false;
  int from = 0;
  std::string output, csv, plot, junit;
  tmcl::SimTime every = 100 * tmcl::kUsPerMs, for_time = 0;
  std::string every_text = "100ms";  // as given, for the plot's title
  int range_lo = 1, range_hi = 255;
  std::vector<long> bauds;
  bool timeout_given = false;
  bool debug_probe = false;  // debug --probe
  const tmcl::Profile* profile = nullptr;
  std::string symbols, debug_commands;  // debug: --symbols, --debug-commands
  std::vector<std::string> source_dirs;
  bool no_patch = false, dap = false;
  tmcl::SimTime reconnect = 5000 * tmcl::kUsPerMs;  // debug: how long a lost module may take to come back
};

int usage_error(const std::string& msg) {
  std::fprintf(stderr, "tmclctl: %s\n(see tmclctl --help)\n", msg.c_str());
  return kExitUsage;
}

bool parse_long(const std::string& s, long lo, long hi, long& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(s.c_str(), &end, 0);
  if (*end || errno || v < lo || v > hi) return false;
  out = v;
  return true;
}

// The serial devices a module may be on, and a TCP address (tmclrun --serve's example): what
// completes PORT.
std::vector<std::string> port_words() {
  std::vector<std::string> ports;
  if (DIR* dev = ::opendir("/dev")) {
    while (const dirent* e = ::readdir(dev)) {
      const std::string name = e->d_name;
      if (name.rfind("ttyACM", 0) == 0 || name.rfind("ttyUSB", 0) == 0) ports.push_back("/dev/" + name);
    }
    ::closedir(dev);
  }
  std::sort(ports.begin(), ports.end());
  ports.push_back("tcp:127.0.0.1:2001");
  return ports;
}

// The options, each declared once: --help, the errors, the man-page check and bash completion
// follow from this table (tmcl/options.hpp).
tmcl::cli::Tool command_line(Options& o) {
  using tmcl::cli::flag, tmcl::cli::set, tmcl::cli::Values;
  auto address = [](const char* opt, std::uint8_t& field) {
    return [opt, &field](const std::string& v) {
      long n = 0;
      if (!parse_long(v, 0, 255, n)) return std::string(opt) + " needs an address from 0 to 255";
      field = static_cast<std::uint8_t>(n);
      return std::string();
    };
  };
  auto duration = [](const char* opt, tmcl::SimTime& field) {
    return [opt, &field](const std::string& v) {
      auto d = tmcl::parse_duration(v);
      if (!d || *d <= 0) return std::string(opt) + " needs a duration greater than 0 (e.g. 500ms, 2s)";
      field = *d;
      return std::string();
    };
  };
  const std::string kBauds = tmcl::os::serial::baud_rates_text();
  std::vector<std::string> bauds;
  for (long b : tmcl::os::serial::kBaudRates) bauds.push_back(std::to_string(b));
  const std::vector<std::string> durations{"100ms", "500ms", "1s", "10s"};
  tmcl::cli::Tool t;
  t.name = "tmclctl";
  t.usage = kUsage;
  t.epilogue = kEpilogue;
  t.column = 25;
  t.options = {
      {"-a", "N", "module address (default 1)", address("-a", o.client.module), {}, "an address from 0 to 255"},
      {"--host-address", "N", "host address replies are sent to (default 2)", address("--host-address", o.client.host),
       {}, "an address from 0 to 255"},
      {"-t, --target", "NAME",
       "module profile for names, ranges and memory: a target name or a profile\n"
       "file, as for tmclasm (default: the one whose firmware the module reports\n"
       "to 136, which is read on connect; download: what the program's first\n"
       "line names, // tmcl-target: NAME)",
       [&o](const std::string& v) {
         o.target = v;
         o.target_given = true;
         return std::string();
       },
       Values::words([] { return tmcl::target_names(); }, {"profile"}), "a target name or a profile file"},
      {"--baud", "N", "serial baud rate, 9600 to 1000000 (default 9600; raw 8N1)",
       [&o, kBauds](const std::string& v) {
         long n = 0;
         if (!parse_long(v, 1, 100000000, n) || !host::valid_baud(n)) return std::string("--baud takes ") + kBauds;
         o.baud = n;
         return std::string();
       },
       Values::words(bauds), std::string("a baud rate: ") + kBauds},
      {"--timeout", "DURATION", "wait this long for each reply (default 1s)",
       [&o, duration](const std::string& v) {
         tmcl::SimTime d = 0;
         std::string error = duration("--timeout", d)(v);
         if (!error.empty()) return error;
         o.client.timeout_ms = static_cast<int>(std::min<tmcl::SimTime>(d / 1000 + (d % 1000 ? 1 : 0), 600000));
         o.timeout_given = true;
         return std::string();
       },
       Values::words(durations), "a duration greater than 0 (e.g. 500ms, 2s)"},
      {"--retries", "N", "resend a request this often when no reply comes (default 2)",
       [&o](const std::string& v) {
         long n = 0;
         if (!parse_long(v, 0, 100, n)) return std::string("--retries needs a number from 0 to 100");
         o.client.retries = static_cast<int>(n);
         return std::string();
       },
       {}, "a number from 0 to 100"},
      {"--raw", "", "show every frame sent (>) and received (<) in hex", flag(o.raw)},
      {"-q, --quiet", "", "no progress bar or banners", flag(o.quiet)},
      {"-I", "DIR", "search DIR for #include files (send, console, download)", tmcl::cli::append(o.include_dirs),
       Values::dirs(), "a directory"},
      {"--no-verify", "", "skip reading the program back with 134",
       [&o](const std::string&) {
         o.verify = false;
         return std::string();
       },
       {}, {}, false, "download:"},
      {"--run", "", "reset and start the program afterwards", flag(o.run), {}, {}, false, "download:"},
      {"--autostart", "", "set global parameter 77 and store it: the program starts at power-on", flag(o.autostart),
       {}, {}, false, "download:"},
      {"--from", "N", "resume an interrupted download at address N",
       [&o](const std::string& v) {
         long n = 0;
         if (!parse_long(v, 0, 1 << 20, n)) return std::string("--from needs an address");
         o.from = static_cast<int>(n);
         return std::string();
       },
       {}, "an address", false, "download:"},
      {"-o", "FILE", "the .bin to write (atomically); probe: the draft profile", set(o.output), Values::files({"bin"}), {}, false, "upload:"},
      {"--every", "DURATION", "poll every DURATION (default 100ms)",
       [&o, duration](const std::string& v) {
         o.every_text = v;
         return duration("--every", o.every)(v);
       },
       Values::words(durations), "a duration greater than 0 (e.g. 500ms, 2s)", false, "monitor:"},
      {"--for", "DURATION", "stop after DURATION (default: until Ctrl-C)", duration("--for", o.for_time),
       Values::words(durations), "a duration greater than 0 (e.g. 500ms, 2s)", false, "monitor:"},
      {"--csv", "FILE", "write the rows to FILE instead of standard output", set(o.csv), Values::files({"csv"}), {},
       false, "monitor:"},
      {"--plot", "FILE", "also draw the polled values against time as an SVG (one panel each)", set(o.plot),
       Values::files({"svg"}), {}, false, "monitor:"},
      {"--probe", "", "report what the module does where the debugger depends on it", flag(o.debug_probe), {}, {},
       false, "debug:"},
      {"--junit", "FILE", "write a JUnit XML report to FILE", set(o.junit), Values::files({"xml"}), {}, false, "test:"},
      {"--range", "A-B", "addresses to try (default 1-255)",
       [&o](const std::string& v) {
         long lo = 0, hi = 0;
         const auto dash = v.find('-');
         if (dash == std::string::npos || !parse_long(v.substr(0, dash), 0, 255, lo) ||
             !parse_long(v.substr(dash + 1), lo, 255, hi))
           return std::string("--range needs A-B with 0 <= A <= B <= 255");
         o.range_lo = static_cast<int>(lo);
         o.range_hi = static_cast<int>(hi);
         return std::string();
       },
       Values::words({"1-8", "1-16", "1-32", "1-255", "0-255"}), "A-B with 0 <= A <= B <= 255", false, "scan:"},
      {"--bauds", "LIST", "baud rates to try, comma-separated (serial ports only)",
       [&o](const std::string& v) {
         for (std::size_t p = 0; p <= v.size();) {
           const std::size_t q = std::min(v.find(',', p), v.size());
           long n = 0;
           if (!parse_long(v.substr(p, q - p), 1, 100000000, n) || !host::valid_baud(n))
             return "--bauds: '" + v.substr(p, q - p) + "' is not a supported baud rate";
           o.bauds.push_back(n);
           p = q + 1;
         }
         return std::string();
       },
       {}, "a list such as 9600,115200", false, "scan:"},
      {"--debug-commands", "FILE", "run the debugger's commands from FILE, then quit (like gdb -batch -x)", set(o.debug_commands),
       Values::files({}), {}, false, "debug:"},
      {"--symbols", "FILE", "labels and line table of a .bin PROGRAM (tmclasm -f symbols)", set(o.symbols),
       Values::files({"sym"}), {}, false, "debug:"},
      {"--source-dir", "DIR", "where the sources of a .bin PROGRAM are (repeatable)", tmcl::cli::append(o.source_dirs),
       Values::dirs(), "a directory", false, "debug:"},
      {"--no-patch", "", "breakpoints by stepping alone: program memory is never written (slow)", flag(o.no_patch), {}, {},
       false, "debug:"},
      {"--dap", "", "the Debug Adapter Protocol on standard input and output", flag(o.dap), {}, {}, false, "debug:"},
      {"--reconnect", "DURATION", "a module that stops answering may come back this long (default 5s): then the "
       "breakpoint patches are removed", duration("--reconnect", o.reconnect), Values::words(durations),
       "a duration greater than 0 (e.g. 500ms, 2s)", false, "debug:"},
  };
  t.operands = [](const std::vector<std::string>& before, const std::vector<std::string>&) {
    if (before.empty()) return Values::words(port_words());
    if (before.size() == 1) return Values::words({std::begin(kCommands), std::end(kCommands)});
    const std::string& command = before[1];
    if (command == "download") return Values::files({"tmc", "bin", "dgm", "o", "a"});
    if (command == "test") return Values::files({"tmctest"});
    if (command == "debug") return Values::files({"tmc", "bin", "dgm"});
    if ((command == "get" || command == "set" || command == "store" || command == "monitor") && before.size() == 2)
      return Values::words({"ap", "gp", "io"});
    return Values();
  };
  return t;
}

int parse_args(int argc, char** argv, Options& o) {
  o.argv.assign(argv + 1, argv + argc);
  const tmcl::cli::Result cl = tmcl::cli::parse(command_line(o), argc, argv);
  if (cl.status == tmcl::cli::Result::Status::Done) return kExitOk;
  if (cl.status == tmcl::cli::Result::Status::Error) return usage_error(cl.error);
  const std::vector<std::string>& words = cl.operands;
  if (words.empty()) return usage_error("no PORT given");
  if (words.size() < 2) return usage_error("no COMMAND given after " + words[0]);
  o.port = words[0];
  o.command = words[1];
  o.args.assign(words.begin() + 2, words.end());
  const tmcl::TargetResult t = tmcl::resolve_target(o.target);
  if (!t.profile && !t.usage) std::fprintf(stderr, "%s\n", t.message(tmcl::kDefaultErrorLimit, "tmclctl").c_str());
  if (!t.profile) return t.usage ? usage_error(t.message()) : kExitInput;
  o.profile = t.profile;
  return -1;
}

// ---- output helpers ----

// Every write to standard output is checked: false, after saying so, when one failed (a full
// disk, a closed pipe).
bool stdout_written() {
  static bool reported = false;
  std::string err;
  if (tmcl::flush_stdout(err)) return true;
  if (!reported) std::fprintf(stderr, "tmclctl: error: %s\n", err.c_str());
  reported = true;
  return false;
}

// An output file, written atomically: complete or not at all. False after saying why.
bool write_output(const std::string& path, const std::string& text) {
  std::string err;
  if (tmcl::write_file_atomic(path, std::vector<std::uint8_t>(text.begin(), text.end()), err)) return true;
  std::fprintf(stderr, "tmclctl: error: %s\n", err.c_str());
  return false;
}

int exit_for(host::Fail f) {
  switch (f) {
    case host::Fail::None: return kExitOk;
    case host::Fail::NoReply: return kExitNoReply;
    case host::Fail::Port: return kExitPort;
    case host::Fail::Cancelled: return kExitInterrupted;
  }
  return kExitPort;
}

int exit_for(host::Outcome o) {
  switch (o) {
    case host::Outcome::Ok: return kExitOk;
    case host::Outcome::NoReply: return kExitNoReply;
    case host::Outcome::Port: return kExitPort;
    case host::Outcome::BadStatus: return kExitStatus;
    case host::Outcome::Mismatch: return kExitMismatch;
    case host::Outcome::Cancelled: return kExitInterrupted;
  }
  return kExitPort;
}

double seconds_since(host::Clock::time_point t0) {
  return std::chrono::duration<double>(host::Clock::now() - t0).count();
}

// avrdude's bar on a terminal ("Writing | ####   | 60% 0.31s"); nothing otherwise.
struct Bar {
  const char* label;
  bool on;
  host::Clock::time_point t0 = host::Clock::now();
  int shown = -1;
  void operator()(int done, int total) {
    if (!on || total <= 0) return;
    const int pct = done * 100 / total;
    if (pct == shown) return;
    shown = pct;
    std::string bar(static_cast<std::size_t>(pct / 2), '#');
    bar.resize(50, ' ');
    std::fprintf(stderr, "\r%s | %s | %3d%% %.2fs", label, bar.c_str(), pct, seconds_since(t0));
    if (done == total) std::fputc('\n', stderr);
    std::fflush(stderr);
  }
  void end() {
    if (on && shown >= 0 && shown < 100) std::fputc('\n', stderr);
  }
};

// ---- commands ----

struct Session {
  Options& o;
  host::Port& port;
  host::Client client;

  // Sends one instruction; prints the failure (naming port, address and frame) and returns the exit status.
  int ask(const Instruction& ins, host::Result& r, bool need_ok = true) {
    r = client.request(ins);
    if (!r.ok()) {
      std::fprintf(stderr, "tmclctl: error: %s\n", r.error.c_str());
      return exit_for(r.fail);
    }
    if (need_ok && r.reply.status != host::kStatusOk) {
      std::fprintf(stderr, "tmclctl: error: module %d answered %d (%s) to %s\n", o.client.module, r.reply.status,
                   host::status_text(r.reply.status).c_str(), client.describe(ins).c_str());
      return kExitStatus;
    }
    return kExitOk;
  }

  // 138's second replies that arrived meanwhile, after the output of the request that met them.
  void print_events() {
    for (const auto& e : client.take_events())
      std::printf("event: position reached (motor mask 0x%" PRIX32 ")\n", static_cast<std::uint32_t>(e.value));
  }

  // send / console: status in words and the value.
  int send_and_print(const Instruction& ins) {
    host::Result r;
    if (int rc = ask(ins, r, false); rc != kExitOk) return rc;
    if (ins.op == static_cast<std::uint8_t>(Op::GetFirmwareVersion) && ins.type == 0) {
      std::printf("firmware %s\n", r.reply.version.c_str());
    } else if (ins.op == static_cast<std::uint8_t>(Op::ReadProgramMemory) && ins.type == 0 && r.reply.status == host::kStatusOk) {
      std::printf("address %d: %s\n", ins.value, tmcl::format_instruction(r.reply.stored).c_str());
    } else if (ins.op == static_cast<std::uint8_t>(Op::RestoreFactorySettings) && ins.value == 1234) {
      std::printf("sent (137 is not answered)\n");
    } else {
      std::printf("%d %s, value %" PRId32 "\n", r.reply.status, host::status_text(r.reply.status).c_str(), r.reply.value);
    }
    print_events();
    return r.reply.status == host::kStatusOk || r.reply.status == host::kStatusLoaded ? kExitOk : kExitStatus;
  }

  // send and console: one line in the session's names (host/console.hpp), diagnostics shown.
  std::optional<host::ConsoleSession> session = std::nullopt;
  host::ConsoleSession::Entry enter(const std::string& text) {
    if (!session) session.emplace(*o.profile, o.include_dirs);
    auto e = session->enter(text);
    std::fflush(stdout);  // in order with the output before it when both go to one file
    std::fputs(e.messages.c_str(), stderr);
    return e;
  }

  // On connect: 136 says which module answers. Without -t its profile is used; with -t naming
  // another module, a warning. A module that does not answer at once is left to the command.
  void identify_module() {
    client.set_timeout(std::min(o.client.timeout_ms, 300));
    const host::Identity id = host::identify(client);
    client.set_timeout(o.client.timeout_ms);
    client.set_retries(o.client.retries);
    if (!id.answered) return;
    const auto number = [](std::string_view fw) { return fw.substr(0, fw.find('V')); };
    if (o.target_given) {
      if (o.profile->name != "generic" && number(o.profile->firmware) != number(id.version))
        std::fprintf(stderr, "tmclctl: warning: module %d reports firmware %s%s, not %s (-t %s is used)\n", o.client.module,
                     id.version.c_str(), id.profile ? (" (" + std::string(id.profile->title) + ")").c_str() : "",
                     std::string(o.profile->title).c_str(), o.target.c_str());
    } else if (id.profile) {
      o.profile = id.profile;
    } else if (!o.quiet) {
      std::fprintf(stderr, "tmclctl: note: no profile knows firmware %s; using generic (`tmclctl %s probe -o NAME.profile` "
                           "drafts one)\n", id.version.c_str(), o.port.c_str());
    }
  }

  int cmd_probe() {
    if (o.output.empty() || !o.args.empty()) return usage_error("probe takes -o FILE.profile and no arguments");
    const bool tty = !o.quiet && ::isatty(2);
    Bar bar{"Probing  ", tty};
    const std::size_t sep = tmcl::os::last_separator(o.output);
    std::string name = o.output.substr(sep == std::string::npos ? 0 : sep + 1);
    if (name.size() > 8 && name.compare(name.size() - 8, 8, ".profile") == 0) name.resize(name.size() - 8);
    const host::ProbeResult r = host::probe(client, name.empty() ? "probed" : name, std::ref(bar));
    bar.end();
    if (r.outcome != host::Outcome::Ok) {
      std::fprintf(stderr, "tmclctl: error: %s; nothing written\n", r.message.c_str());
      return exit_for(r.outcome);
    }
    if (!write_output(o.output, r.text)) return kExitPort;
    if (!o.quiet)
      std::printf("wrote %s: %d axis parameters, %d global parameters (bank 0), %d interrupt settings, %d motor%s; "
                  "every fact unverified\n", o.output.c_str(), r.axis, r.bank0, r.bank3, r.motors, r.motors == 1 ? "" : "s");
    return kExitOk;
  }

  int cmd_send() {
    if (o.args.size() != 1) return usage_error("send takes one instruction in quotes, e.g. send 'SAP 4, 0, 51200'");
    const auto e = enter(o.args[0]);
    if (e.kind == host::ConsoleSession::Entry::Send) return send_and_print(e.ins);
    if (e.kind != host::ConsoleSession::Entry::Error)
      std::fprintf(stderr, "tmclctl: error: '%s' is no instruction: send takes one\n", o.args[0].c_str());
    return kExitInput;
  }

  int cmd_param(host::ParamAction action) {
    std::size_t at = 0;
    host::ParamRef p;
    std::string err;
    // set keeps its last word for the value: an optional motor must not swallow it.
    const std::size_t keep = action == host::ParamAction::Set ? 1 : 0;
    if (!host::parse_param(o.args, at, *o.profile, false, p, err, keep)) return usage_error(err);
    long value = 0;
    if (action == host::ParamAction::Set) {
      if (at >= o.args.size() || !parse_long(o.args[at], INT32_MIN, INT32_MAX, value))
        return usage_error("set needs a value (a 32-bit integer) after the parameter");
      ++at;
    }
    if (at != o.args.size()) return usage_error("unexpected '" + o.args[at] + "'");
    Instruction ins;
    if (!host::param_instruction(p, action, static_cast<std::int32_t>(value), *o.profile, ins, err)) {
      std::fprintf(stderr, "tmclctl: error: %s\n", err.c_str());
      return kExitInput;
    }
    host::Result r;
    if (int rc = ask(ins, r); rc != kExitOk) return rc;
    if (action == host::ParamAction::Get)
      std::printf("%" PRId32 "\n", r.reply.value);
    else if (!o.quiet)
      std::printf("%s: %s\n", p.label().c_str(), action == host::ParamAction::Set ? "set" : "stored");
    return kExitOk;
  }

  int load_program(std::vector<Instruction>& program) {
    if (o.args.empty()) return usage_error("download needs a FILE");
    const std::string& first = o.args[0];
    auto ext = [](const std::string& s, const char* e) {
      const std::string x(e);
      if (s.size() < x.size()) return false;
      for (std::size_t i = 0; i < x.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(s[s.size() - x.size() + i])) != x[i]) return false;
      return true;
    };
    if (o.args.size() == 1 && (ext(first, ".bin") || ext(first, ".dgm"))) {
      std::vector<std::uint8_t> bytes;
      std::string err, messages;
      if (!tmcl::read_file(first, bytes, err)) {
        std::fprintf(stderr, "tmclctl: error: %s\n", err.c_str());
        return kExitInput;
      }
      const bool ok = tmcl::read_program_image(first, bytes, program, messages);
      std::fputs(messages.c_str(), stderr);
      if (!ok) return kExitInput;
    } else {
      // The program's first line may name its target; -t wins, else it wins over 136.
      if (!o.target_given) {
        const std::string named = tmcl::target_named_by_file(first, "");
        if (!named.empty()) {
          const tmcl::TargetResult t = tmcl::resolve_target(named);
          if (!t.profile) {
            std::fprintf(stderr, "%s:1: error: %s\n", first.c_str(), t.message(1).c_str());
            return kExitInput;
          }
          if (t.profile->name != o.profile->name && o.profile->name != "generic")
            std::fprintf(stderr, "tmclctl: warning: %s is for %s, the module is %s\n", first.c_str(),
                         std::string(t.profile->title).c_str(), std::string(o.profile->title).c_str());
          o.profile = t.profile;
        }
      }
      // The checks of tmclasm -Werror: the module's profile and the control-flow analysis.
      tmcl::AsmOptions opt;
      opt.profile = o.profile;
      opt.include_dirs = o.include_dirs;
      opt.symbols = true;
      opt.warnings_are_errors = true;
      tmcl::DiskReader reader;
      tmcl::AsmResult r = tmcl::assemble(o.args, opt, reader);
      if (r.ok()) tmcl::analyze(tmcl::analysis_input(r), r.diags);
      std::fputs(r.diags.render(r.sources).c_str(), stderr);
      if (!r.ok()) {
        std::fprintf(stderr, "tmclctl: the program has errors (warnings count, as with tmclasm -Werror); nothing sent\n");
        // Refused for warnings alone: perhaps one this version added to a program an older one
        // sent. Say how to go on (docs/analysis.md, "New warnings").
        bool only_warnings = true;
        for (const auto& d : r.diags.all()) only_warnings = only_warnings && (d.severity != tmcl::Severity::Error || !d.name.empty());
        if (only_warnings)
          std::fprintf(stderr, "tmclctl: note: a warning counts as an error here, a new one too; fix the line, or allow the "
                               "warning there with a comment '// tmcl: allow NAME' (docs/analysis.md, \"New warnings\")\n");
        return kExitInput;
      }
      program = r.program;
    }
    if (program.empty()) {
      std::fprintf(stderr, "%s: error: the program is empty\n", first.c_str());
      return kExitInput;
    }
    const int memory = o.profile->program_memory;
    if (memory > 0 && program.size() > static_cast<std::size_t>(memory)) {
      std::fprintf(stderr, "%s: error: %zu instructions do not fit the %d of %s program memory\n", first.c_str(), program.size(),
                   memory, std::string(o.profile->name).c_str());
      return kExitInput;
    }
    if (o.from > static_cast<int>(program.size())) {
      std::fprintf(stderr, "tmclctl: error: --from %d is past the end of the program (%zu instructions)\n", o.from, program.size());
      return kExitUsage;
    }
    return -1;
  }

  // The command line as given, with --from N after "download" (an earlier --from dropped).
  std::string resume_command(int from) const {
    std::string line = "tmclctl";
    bool inserted = false;
    for (std::size_t i = 0; i < o.argv.size(); ++i) {
      if (o.argv[i] == "--from") {
        ++i;
        continue;
      }
      if (o.argv[i].rfind("--from=", 0) == 0) continue;
      const std::string& a = o.argv[i];
      const bool plain = a.find_first_of(" '\"\\$`*?;&|<>()") == std::string::npos && !a.empty();
      line += " " + (plain ? a : "'" + a + "'");
      if (a == "download" && !inserted) {
        line += " --from " + std::to_string(from);
        inserted = true;
      }
    }
    return line;
  }

  int cmd_download() {
    std::vector<Instruction> program;
    if (int rc = load_program(program); rc >= 0) return rc;
    // An image may be an upload of a module a killed debugging session left patched.
    const std::string& first = o.args[0];
    const std::string ext = first.size() > 4 ? first.substr(first.size() - 4) : "";
    if (ext == ".bin" || ext == ".dgm") warn_patches(program);
    const bool tty = !o.quiet && ::isatty(2);
    const int memory = o.profile->program_memory;
    const int total = static_cast<int>(program.size());
    const auto t0 = host::Clock::now();
    Bar bar{"Writing  ", tty};
    host::TransferResult tr = host::download(client, program, o.from, memory, std::ref(bar));
    bar.end();
    if (tr.outcome == host::Outcome::Cancelled) {
      // Leave download mode so that the module answers normally again, then say how to resume.
      g_stop = 0;
      client.set_retries(0);
      client.request(Instruction{static_cast<std::uint8_t>(Op::ExitDownloadMode), 0, 0, 0});
      std::fprintf(stderr,
                   "tmclctl: interrupted after %d of %d instructions; the module holds a partial program.\n"
                   "tmclctl: resume with: %s\n",
                   tr.done, total, resume_command(tr.done).c_str());
      return kExitInterrupted;
    }
    if (tr.outcome != host::Outcome::Ok) {
      std::fprintf(stderr, "tmclctl: error: %s\n", tr.message.c_str());
      if (tr.done > o.from)
        std::fprintf(stderr, "tmclctl: %d of %d instructions were stored; resume with --from %d\n", tr.done, total, tr.done);
      return exit_for(tr.outcome);
    }
    const double t_write = seconds_since(t0);
    if (!o.quiet)
      std::printf("wrote %d instructions to module %d in %.2fs\n", total - o.from, o.client.module, t_write);
    if (o.verify) {
      const auto t1 = host::Clock::now();
      Bar vbar{"Reading  ", tty};
      tr = host::verify(client, program, 0, memory, std::ref(vbar));
      vbar.end();
      if (tr.outcome == host::Outcome::Cancelled) {
        std::fprintf(stderr, "tmclctl: interrupted while verifying; the program is stored but not verified\n");
        return kExitInterrupted;
      }
      if (tr.outcome != host::Outcome::Ok) {
        std::fprintf(stderr, "tmclctl: error: %s\n", tr.message.c_str());
        return exit_for(tr.outcome);
      }
      if (!o.quiet) std::printf("verified %d instructions in %.2fs\n", total, seconds_since(t1));
    }
    host::Result r;
    if (o.autostart && o.profile->program_store == tmcl::ProgramStore::Ram)
      std::fprintf(stderr, "tmclctl: warning: %s keeps its program in RAM: after a power cycle there is no program to "
                           "start (autostart is set anyway)\n", std::string(o.profile->title).c_str());
    if (o.autostart) {
      const Instruction set77{static_cast<std::uint8_t>(Op::SGP), 77, 0, 1};
      if (int rc = ask(set77, r); rc != kExitOk) return rc;
      const tmcl::ParamInfo* p = o.profile->global_param(0, 77);
      if (!p || !(p->access & tmcl::kAutoStore)) {  // auto-stored parameters are in the EEPROM already
        if (int rc = ask(Instruction{static_cast<std::uint8_t>(Op::STGP), 77, 0, 0}, r); rc != kExitOk) return rc;
      }
      if (!o.quiet) std::printf("autostart on (global parameter 77 = 1, stored)\n");
    }
    if (o.run) {
      if (int rc = ask(Instruction{static_cast<std::uint8_t>(Op::ResetApplication), 0, 0, 0}, r); rc != kExitOk) return rc;
      if (int rc = ask(Instruction{static_cast<std::uint8_t>(Op::RunApplication), 0, 0, 0}, r); rc != kExitOk) return rc;
      if (!o.quiet) std::printf("running\n");
    }
    return kExitOk;
  }

  // tmclctl PORT debug PROGRAM: the debugger on the module (cli/debug, debug_module.hpp). Ctrl-C
  // pauses the program there instead of cancelling a request.
  int cmd_debug() {
    if (o.args.size() != 1) return usage_error("debug needs one PROGRAM (.tmc, or .bin with --symbols)");
    tmcl::debug::ModuleFrontEnd fe;
    fe.program = o.args[0];
    fe.symbols = o.symbols;
    fe.source_dirs = o.source_dirs;
    fe.include_dirs = o.include_dirs;
    fe.commands_file = o.debug_commands;
    fe.dap = o.dap;
    fe.setup.patch = !o.no_patch;
    fe.setup.reconnect_ms = static_cast<int>(o.reconnect / tmcl::kUsPerMs);
    fe.setup.reconnect = [this](std::string& error) -> host::Client* {
      (reopened ? *reopened : port).close();
      std::unique_ptr<host::Port> again = host::Port::open(o.port, o.baud, o.client.timeout_ms, error);
      if (!again) return nullptr;
      reopened = std::move(again);
      reclient = std::make_unique<host::Client>(*reopened, o.client);
      return reclient.get();
    };
    host::Port::set_cancel_flag(nullptr);
    return tmcl::debug::debug_module(client, *o.profile, std::move(fe), stdin, stdout);
  }
  std::unique_ptr<host::Port> reopened = nullptr;  // debug: the port opened again after it was lost
  std::unique_ptr<host::Client> reclient = nullptr;

  int cmd_upload() {
    if (o.output.empty()) return usage_error("upload needs -o FILE.bin");
    if (!o.args.empty()) return usage_error("upload takes no arguments besides -o FILE");
    std::vector<Instruction> program;
    Bar bar{"Reading  ", false};
    host::TransferResult tr = host::upload(client, o.profile->program_memory, program, std::ref(bar));
    if (tr.outcome != host::Outcome::Ok) {
      std::fprintf(stderr, "tmclctl: error: %s%s\n", tr.message.c_str(),
                   tr.outcome == host::Outcome::Cancelled ? "; nothing written" : "");
      return exit_for(tr.outcome);
    }
    warn_patches(program);
    const std::vector<std::uint8_t> bin = tmcl::write_bin(program);
    if (!write_output(o.output, std::string(bin.begin(), bin.end()))) return kExitPort;
    if (!o.quiet) std::printf("read %zu instructions into %s\n", program.size(), o.output.c_str());
    return kExitOk;
  }

  // Jumps to themselves in program memory: what a debugger's breakpoint patch looks like, left
  // by a `tmclctl PORT debug` session that was killed (kill -9) while the program ran.
  void warn_patches(const std::vector<Instruction>& memory) {
    for (std::int32_t a : tmcl::debug::self_jumps(memory))
      std::fprintf(stderr,
                   "tmclctl: warning: address %d holds a jump to itself (JA %d): an endless loop, or a debugger's breakpoint "
                   "patch; if a `tmclctl PORT debug` session was killed, `tmclctl PORT debug PROGRAM` puts the "
                   "instruction back\n",
                   static_cast<int>(a), static_cast<int>(a));
  }

  int cmd_control(Op op) {
    Instruction ins{static_cast<std::uint8_t>(op), 0, 0, 0};
    if (op == Op::RunApplication && !o.args.empty()) {
      long at = 0;
      if (o.args.size() != 1 || !parse_long(o.args[0], 0, 1 << 20, at)) return usage_error("run takes one program address");
      ins.type = 1;
      ins.value = static_cast<std::int32_t>(at);
    } else if (!o.args.empty()) {
      return usage_error(o.command + " takes no arguments");
    }
    host::Result r;
    if (int rc = ask(ins, r); rc != kExitOk) return rc;
    return kExitOk;
  }

  int cmd_status() {
    if (!o.args.empty()) return usage_error("status takes no arguments");
    const auto ctl = [](Op op, std::uint8_t type) { return Instruction{static_cast<std::uint8_t>(op), type, 0, 0}; };
    host::Result r0, r1, r2, r3, v0, v1;
    for (auto [ins, r] : {std::pair{ctl(Op::GetApplicationStatus, 0), &r0}, std::pair{ctl(Op::GetApplicationStatus, 1), &r1},
                          std::pair{ctl(Op::GetApplicationStatus, 2), &r2}, std::pair{ctl(Op::GetApplicationStatus, 3), &r3},
                          std::pair{ctl(Op::GetFirmwareVersion, 0), &v0}, std::pair{ctl(Op::GetFirmwareVersion, 1), &v1}})
      if (int rc = ask(ins, *r); rc != kExitOk) return rc;
    const auto s0 = static_cast<std::uint32_t>(r0.reply.value), s1 = static_cast<std::uint32_t>(r1.reply.value);
    std::printf("mode:             %s\n", host::mode_name(s0 >> 24).c_str());
    std::printf("waiting:          %s\n", (s0 >> 16 & 0xFF) ? "yes" : "no");
    std::printf("program counter:  %u\n", s1 & 0xFFFF);
    std::printf("download pointer: %u\n", s0 & 0xFFFF);
    std::printf("accumulator:      %" PRId32 "\n", r2.reply.value);
    std::printf("x register:       %" PRId32 "\n", r3.reply.value);
    const tmcl::Profile* p = host::profile_for_firmware(v0.reply.version);
    std::printf("firmware:         %s (0x%08" PRIX32 ")%s%s\n", v0.reply.version.c_str(), static_cast<std::uint32_t>(v1.reply.value),
                p ? ", " : "", p ? std::string(p->title).c_str() : "");
    return kExitOk;
  }

  int cmd_monitor() {
    std::vector<host::ParamRef> params;
    std::vector<Instruction> reads;
    for (std::size_t at = 0; at < o.args.size();) {
      host::ParamRef p;
      std::string err;
      if (!host::parse_param(o.args, at, *o.profile, true, p, err)) return usage_error(err);
      Instruction ins;
      if (!host::param_instruction(p, host::ParamAction::Get, 0, *o.profile, ins, err)) {
        std::fprintf(stderr, "tmclctl: error: %s\n", err.c_str());
        return kExitInput;
      }
      params.push_back(p);
      reads.push_back(ins);
    }
    if (params.empty()) return usage_error("monitor needs at least one parameter (e.g. ap:1, gp:128, 'actual position')");
    const bool table = o.csv.empty() && ::isatty(1);
    std::string csv = "time_s";
    std::vector<std::string> names, short_names;  // "Maximum positioning speed [0]", "ap:4:0"
    for (const auto& p : params) {
      std::string label = p.info ? std::string(p.info->name) : p.label();
      for (char& c : label)
        if (c == ',') c = ';';
      names.push_back(label + (p.kind == host::ParamRef::Axis ? " [" + std::to_string(p.index) + "]" : ""));
      csv += "," + names.back();
      const char* kind = p.kind == host::ParamRef::Axis ? "ap:" : p.kind == host::ParamRef::Global ? "gp:" : "io:";
      short_names.push_back(kind + std::to_string(p.number) + ":" + std::to_string(p.index));
    }
    csv += "\n";
    // --plot: the rows as time series, one panel per parameter (cli/report's plot).
    tmcl::Plot plot;
    for (std::size_t i = 0; i < params.size(); ++i)
      plot.panels.push_back({names[i], "", std::string(tmcl::plot_colour(i)), short_names[i], false, {{}}, {}});
    if (table) {
      std::printf("%10s", "time (s)");
      for (const auto& name : short_names) std::printf(" %14s", name.c_str());
      std::printf("\n");
    } else if (o.csv.empty()) {
      std::fputs(csv.c_str(), stdout);
    }
    const auto t0 = host::Clock::now();
    const auto every = std::chrono::microseconds(o.every);
    int rc = kExitOk;
    for (std::int64_t row = 0;; ++row) {
      const auto due = t0 + every * row;
      if (o.for_time > 0 && due - t0 >= std::chrono::microseconds(o.for_time)) break;
      while (host::Clock::now() < due && !g_stop) std::this_thread::sleep_for(std::min<host::Clock::duration>(due - host::Clock::now(), std::chrono::milliseconds(50)));
      if (g_stop) break;
      char line[64];
      std::snprintf(line, sizeof line, "%.3f", std::chrono::duration<double>(every * row).count());
      std::string text = line;
      if (table) std::printf("%10s", line);
      std::vector<std::int32_t> values;
      for (const auto& ins : reads) {
        host::Result r;
        rc = ask(ins, r);
        if (rc != kExitOk) break;
        values.push_back(r.reply.value);
        text += "," + std::to_string(r.reply.value);
        if (table) std::printf(" %14" PRId32, r.reply.value);
      }
      if (rc == kExitInterrupted) {
        rc = kExitOk;  // Ctrl-C is how a monitor without --for ends
        break;
      }
      if (rc != kExitOk) break;
      csv += text + "\n";
      plot.times.push_back(o.every * row);
      for (std::size_t i = 0; i < values.size(); ++i) plot.panels[i].lines[0].push_back(values[i]);
      if (table)
        std::printf("\n");
      else if (o.csv.empty())
        std::printf("%s\n", text.c_str());
      if ((table || o.csv.empty()) && !stdout_written()) {
        rc = kExitPort;  // a full disk or a closed pipe ends it
        break;
      }
    }
    // What was polled is kept even when polling ended with an error.
    if (!o.csv.empty() && !write_output(o.csv, csv)) rc = kExitPort;
    if (!o.plot.empty()) {
      tmcl::PlotOptions opt;
      opt.title = "tmclctl monitor: module " + std::to_string(o.client.module) + " on " + o.port + ", every " + o.every_text;
      const int panels = static_cast<int>(params.size());
      opt.height = std::max(opt.height, 104 + 62 + panels * 170 + (panels - 1) * 26);  // >= 170 px a panel
      std::ostringstream svg;
      tmcl::write_svg(svg, plot, opt);
      if (!write_output(o.plot, svg.str())) rc = kExitPort;
    }
    return rc;
  }

  int cmd_console() {
    if (!o.args.empty()) return usage_error("console takes no arguments");
    const bool tty = ::isatty(0);
    std::vector<std::string> history;
    std::string line;
    int last = kExitOk;
    for (;;) {
      if (tty) {
        std::printf("tmcl> ");
        std::fflush(stdout);
      }
      g_stop = 0;
      if (!std::getline(std::cin, line)) break;
      const auto b = line.find_first_not_of(" \t"), e = line.find_last_not_of(" \t\r");
      line = b == std::string::npos ? "" : line.substr(b, e - b + 1);
      if (line.empty()) continue;
      if (!tty) std::printf("tmcl> %s\n", line.c_str());  // piped: each command before its reply
      if (line == "quit" || line == "exit") break;
      if (line == "!!") {
        if (history.empty()) {
          std::printf("no earlier instruction\n");
          continue;
        }
        line = history.back();
        std::printf("%s\n", line.c_str());
      }
      if (line == "help") {
        if (!session) enter("");
        std::string files;
        const auto& predefined = session->predefined();
        for (std::size_t i = 0; i < predefined.size(); ++i)
          files += (i == 0 ? "" : i + 1 == predefined.size() ? " and " : ", ") + predefined[i];
        std::printf(
            "Type an instruction in source syntax (SAP 4, 0, 51200; GAP 1, 0; MVP ABS, 0, 1000; .raw 136, 0, 0, 0).\n"
            "Names work as in a program: %s are included, and NAME = VALUE and\n"
            "#include lines are kept for the session. 'history' lists this session's lines, '!!' repeats\n"
            "the last one, 'quit' (or end of input) leaves.\n",
            files.empty() ? "no names" : files.c_str());
        continue;
      }
      if (line == "history") {
        for (std::size_t i = 0; i < history.size(); ++i) std::printf("%4zu  %s\n", i + 1, history[i].c_str());
        continue;
      }
      const auto entry = enter(line);
      if (entry.kind == host::ConsoleSession::Entry::Error) {
        last = kExitInput;
        continue;
      }
      if (entry.kind != host::ConsoleSession::Entry::Nothing) history.push_back(line);
      if (entry.kind != host::ConsoleSession::Entry::Send) {  // names kept: a few shown, else how many
        const auto& d = entry.defined;
        for (std::size_t i = 0; d.size() <= 3 && i < d.size(); ++i) std::printf("%s\n", d[i].c_str());
        if (d.size() > 3) std::printf("%zu names defined\n", d.size());
        continue;
      }
      last = send_and_print(entry.ins);
      std::fflush(stdout);
      if (last == kExitPort) return last;  // the line is gone
    }
    return last == kExitInput || last == kExitStatus || last == kExitNoReply ? kExitOk : last;
  }

  // The modules on the line, found by host::scan_bus; a bar on a terminal meanwhile, which each
  // line of output first wipes (and is drawn again after).
  int scan_here(int& found) {
    Bar bar{"Scanning ", !o.quiet && ::isatty(2)};
    const auto wipe = [&bar] {
      if (bar.on && bar.shown >= 0) std::fprintf(stderr, "\r%80s\r", "");
      bar.shown = -1;
    };
    host::ScanOptions so{o.range_lo, o.range_hi, o.timeout_given ? o.client.timeout_ms : host::default_scan_timeout_ms(port),
                         !o.timeout_given};
    const host::ScanResult r = host::scan_bus(client, so, [&](const host::ScanFound& f) {
      wipe();
      if (f.late && !o.quiet)
        std::fprintf(stderr, "tmclctl: note: module %d answered after the timeout; now %d ms per address\n", f.address, f.timeout_ms);
      std::printf("address %3d: firmware %s (0x%08" PRIX32 "), %s\n", f.address, f.version.c_str(), static_cast<std::uint32_t>(f.binary),
                  f.profile ? std::string(f.profile->title).c_str() : "unknown module type");
      std::fflush(stdout);
      ++found;
    }, std::ref(bar));
    bar.end();
    if (r.fail == host::Fail::Port) {
      std::fprintf(stderr, "tmclctl: error: %s\n", r.error.c_str());
      return kExitPort;
    }
    return g_stop ? kExitInterrupted : kExitOk;
  }
};

int cmd_scan(Options& o, std::unique_ptr<host::Port>& port) {
  if (!o.args.empty()) return usage_error("scan takes no arguments (--range A-B, --bauds LIST)");
  int found = 0;
  std::vector<long> bauds = o.bauds.empty() ? std::vector<long>{o.baud} : o.bauds;
  if (!port->is_serial() && !o.bauds.empty()) return usage_error("--bauds goes with a serial port, not " + o.port);
  for (std::size_t i = 0; i < bauds.size(); ++i) {
    if (i > 0) {
      port.reset();
      std::string err;
      port = host::Port::open(o.port, bauds[i], o.client.timeout_ms, err);
      if (!port) {
        std::fprintf(stderr, "tmclctl: error: %s\n", err.c_str());
        return kExitPort;
      }
    }
    if (bauds.size() > 1) std::printf("at %ld baud:\n", bauds[i]);
    Session s{o, *port, host::Client(*port, o.client)};
    if (int rc = s.scan_here(found); rc != kExitOk) return rc;
  }
  if (!o.quiet) std::printf("%d module%s found\n", found, found == 1 ? "" : "s");
  return found > 0 ? kExitOk : kExitNoReply;
}

int run(int argc, char** argv) {
  Options o;
  if (int r = parse_args(argc, argv, o); r >= 0) return r;

  // No restart: a blocked poll returns and the flag is seen at once.
  tmcl::os::catch_signal(SIGINT, on_sigint, false);
  tmcl::os::catch_signal(SIGTERM, on_sigint, false);
  // A reader that goes away (`monitor ... | head`) is a failed write, which ends the command with
  // status 74 once it has kept what it has (monitor's --csv and --plot), instead of a death by
  // SIGPIPE that loses them.
  tmcl::os::ignore_broken_pipe();
  host::Port::set_cancel_flag(&g_stop);

  bool known = false;
  for (const char* c : kCommands) known = known || o.command == c;
  if (!known) return usage_error("unknown command '" + o.command + "'");
  if ((!o.csv.empty() || !o.plot.empty()) && o.command != "monitor") return usage_error("--csv and --plot go with monitor");
  if (!o.junit.empty() && o.command != "test") return usage_error("--junit goes with test");
  if (o.debug_probe && o.command != "debug") return usage_error("--probe goes with debug");
  if (o.debug_probe && !o.args.empty()) return usage_error("debug --probe takes no arguments");
  if (o.command == "test" && o.args.empty()) return usage_error("test needs test files or folders (FILE.tmctest or DIR)");

  std::string err;
  std::unique_ptr<host::Port> port = host::Port::open(o.port, o.baud, o.client.timeout_ms, err);
  if (!port) {
    std::fprintf(stderr, "tmclctl: error: %s\n", err.c_str());
    return kExitPort;
  }
  if (o.raw)
    o.client.on_frame = [](bool out, const std::uint8_t* p, std::size_t n) {
      std::printf("%s %s\n", out ? ">" : "<", host::hex(p, n).c_str());
    };
  if (o.command == "scan") return cmd_scan(o, port);
  Session s{o, *port, host::Client(*port, o.client)};
  const std::string& c = o.command;
  if (c == "probe") return s.cmd_probe();
  s.identify_module();
  if (c == "send") return s.cmd_send();
  if (c == "get") return s.cmd_param(host::ParamAction::Get);
  if (c == "set") return s.cmd_param(host::ParamAction::Set);
  if (c == "store") return s.cmd_param(host::ParamAction::Store);
  if (c == "download") return s.cmd_download();
  if (c == "upload") return s.cmd_upload();
  if (c == "run") return s.cmd_control(Op::RunApplication);
  if (c == "stop") return s.cmd_control(Op::StopApplication);
  if (c == "step") return s.cmd_control(Op::StepApplication);
  if (c == "reset") return s.cmd_control(Op::ResetApplication);
  if (c == "status") return s.cmd_status();
  if (c == "monitor") return s.cmd_monitor();
  if (c == "debug") return o.debug_probe ? tmclctl_debug_probe(s.client, *o.profile, o.client.module, &g_stop) : s.cmd_debug();
  if (c == "test") {
    host::Fail failed = host::Fail::None;
    const int status = tmclctl_test(s.client, *o.profile, o.target_given ? o.target : std::string(o.profile->name), o.args,
                                    o.include_dirs, o.junit, &g_stop, failed);
    return status != kExitInterrupted && failed != host::Fail::None ? exit_for(failed) : status;
  }
  return s.cmd_console();
}

}  // namespace

int main(int argc, char** argv) {
  tmcl::os::init_console();  // Windows: bytes as they are, UTF-8 (os_console.hpp)
  const int status = run(argc, argv);
  return stdout_written() ? status : kExitPort;
}
