// What tmclrun.cpp (the options, loading, the run) and tmclrun_modes.cpp (serving with the
// virtual module, debugging, testing) share: the options, and the steps of a run that both take.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "tmcl/asm/assembler.hpp"
#include "tmcl/debug_cli.hpp"
#include "tmcl/eeprom.hpp"
#include "tmcl/scenario.hpp"
#include "tmcl/server.hpp"
#include "tmcl/testrun.hpp"
#include "tmcl/vm.hpp"
#include "tmcl/vm_output.hpp"

namespace tmclrun {

constexpr int kExitOk = 0, kExitLimit = 3, kExitUsage = 64, kExitInput = 65, kExitFault = 70, kExitOsErr = 71,
              kExitIo = 74;

// Everything the command line sets (tmclrun.cpp's option table).
struct Options {
  std::string target = "generic";  // one default for every tool (docs/errata.md)
  bool target_given = false;       // -t: else the program's first line may name the target
  std::string motion;
  tmcl::SimTime instr_time = 20;
  tmcl::Limits limits;
  std::string scenario, eeprom, program;
  std::string eeprom_seal;
  bool trace = false, json = false;
  bool strict = false;  // a run-time warning (docs/tmclrun.md) is a runtime fault
  bool list_targets = false;  // --list-targets: list the targets and run nothing
  std::string csv, plot;
  tmcl::SimTime plot_from = 0, plot_to = tmcl::kNever;  // --plot-from, --plot-to
  std::vector<int> plot_series;                           // --plot-series 206,180
  std::string log;  // --serve --trace: the request log (empty: standard error)
  tmcl::SimTime sample = 10 * tmcl::kUsPerMs;
  tmcl::AsmOptions asm_opts;
  bool serving = false;                // --serve SPEC
  tmcl::ServeOptions serve_opts;       // --serve and its companions
  std::vector<std::string> modules;    // --module ADDR[/TARGET][:FILE], in order
  tmcl::debug::FrontEnd debug;         // --debug, --debug-commands, --symbols, --checkpoint-memory, --dap
  std::vector<std::string> given;      // the options given, by name (tmcl::cli::Result::given)
  bool testing = false;                // --test
  tmcl::testrun::SuiteOptions test;    // --jobs, --junit, --coverage, --coverage-summary, --update
  std::vector<std::string> inputs;     // every PROGRAM argument (--test takes several)
};

// ---- tmclrun.cpp ----
// Reports the error on standard error (and for --json), returns the exit status.
int usage_error(const std::string& msg);
int input_error(const std::string& file, const std::string& msg, int status = kExitInput);
// Reads o.program (.tmc assembled in-process, .bin, .dgm, or -): -1 on success, else a status.
// With `names`, a source's labels and named operands (for --trace) go there.
int load_program(Options& o, const tmcl::Profile* profile, std::vector<tmcl::Instruction>& program,
                 tmcl::SourceMap& sources, tmcl::SourceNames* names = nullptr);
// Gives `vm` the options' timing, the program with its source places, the EEPROM (null: blank)
// and the scenario's inputs, and powers it on.
void set_up_vm(tmcl::Vm& vm, const Options& o, const std::vector<tmcl::Instruction>& program,
               const tmcl::SourceMap& sources, const tmcl::EepromImage* image, std::vector<tmcl::InputEvent> inputs);
// An EEPROM file's program against the module (kept in RAM, too large): -1 when it fits, else
// the exit status after the error.
int check_stored_program(const Options& o, const tmcl::Profile& profile, const tmcl::EepromImage& image);

// ---- tmclrun_modes.cpp ----
// After all arguments: the checks that involve serving and debugging (--module sets o.program
// and o.target). -1 when the run goes on, else an exit status.
int check_mode_options(Options& o, bool have_program);
// Runs the test files of o.inputs (--test; cli/testrun, docs/testing.md) with -t as given.
int run_tests(Options& o);
// Serves or debugs (o.serving or o.debug.enabled). Returns tmclrun's exit status.
int run_mode(Options& o, const tmcl::Profile& profile, std::unique_ptr<tmcl::MotionCore> core,
             const std::vector<tmcl::Instruction>& program, const std::vector<std::string>& sources,
             std::vector<tmcl::InputEvent> inputs, tmcl::EepromImage* image);

}  // namespace tmclrun
