// What tmclrun.cpp, the part of both programs (cli/tmclrun_modes.hpp), gives tmclrun_modes.cpp:
// the options and the steps of a run that serving and debugging share.
#pragma once

#include <string>
#include <vector>

#include "tmcl/asm/assembler.hpp"
#include "tmcl/eeprom.hpp"
#include "tmcl/scenario.hpp"
#include "tmcl/vm.hpp"
#include "tmcl/vm_output.hpp"
#include "tmclrun_modes.hpp"

namespace tmclrun {

// The options of tmclrun.cpp; tmclrun_modes.cpp keeps its own and sets the three flags below.
struct Options {
  std::string target = "generic";  // one default for every tool (docs/errata.md)
  std::string motion;
  tmcl::SimTime instr_time = 20;
  tmcl::Limits limits;
  std::string scenario, eeprom, program;
  std::string eeprom_seal;
  bool trace = false, json = false;
  bool strict = false;  // a run-time warning (docs/tmclrun.md) is a runtime fault
  std::string csv, plot;
  std::string log;  // --serve --trace: the request log (empty: standard error)
  tmcl::SimTime sample = 10 * tmcl::kUsPerMs;
  tmcl::AsmOptions asm_opts;
  bool serving = false;    // --serve
  bool debugging = false;  // --debug, --debug-commands or --dap
  bool dap = false;        // --dap
  bool testing = false;    // --test
  std::vector<std::string> inputs;  // every PROGRAM argument (--test takes several)
};

// ---- tmclrun.cpp ----
int input_error(const std::string& file, const std::string& msg, int status = kExitInput);
// OPT DURATION into `out`: -1 when it parsed, else the status of the usage error reported.
int duration_option(const char* opt, const ValueFn& value, tmcl::SimTime& out);
// Reads o.program (.tmc assembled in-process, .bin, .dgm, or -): -1 on success, else a status.
int load_program(Options& o, const tmcl::Profile* profile, std::vector<tmcl::Instruction>& program,
                 tmcl::SourceMap& sources);
// Gives `vm` the options' timing, the program with its source places, the EEPROM (null: blank)
// and the scenario's inputs, and powers it on.
void set_up_vm(tmcl::Vm& vm, const Options& o, const std::vector<tmcl::Instruction>& program,
               const tmcl::SourceMap& sources, const tmcl::EepromImage* image, std::vector<tmcl::InputEvent> inputs);

}  // namespace tmclrun
