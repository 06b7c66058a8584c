// tmclrun's debugger entry: the set-up of an engine from tmclrun's loaded inputs and options, so
// that tmclrun itself only forwards (one branch).
#include <unistd.h>

#include <cstdlib>

#include "tmcl/debug_cli.hpp"

namespace tmcl::debug {

int main(const FrontEnd& fe, const Profile& profile, std::unique_ptr<MotionCore> core, const std::string& program,
         const AsmOptions& asm_options, SimTime instr_time, const Limits& limits, std::vector<InputEvent> inputs,
         const EepromImage* eeprom, const ServeOptions* serve) {
  if (fe.dap) {
    DapSetup ds;
    ds.target = std::string(profile.name);
    ds.profile = &profile;
    ds.target_given = fe.target_given;
    ds.instr_time = instr_time;
    ds.asm_options = asm_options;
    ds.source_dirs = fe.source_dirs;
    ds.limits = limits;
    ds.inputs = std::move(inputs);
    if (eeprom) ds.eeprom = *eeprom;
    return run_dap(ds, stdin, stdout);
  }
  if (program.empty() || program == "-") {
    std::fprintf(stderr, "tmclrun: --debug needs a PROGRAM file (standard input carries the commands)\n(see tmclrun --help)\n");
    return 64;
  }
  ProgramInfo info;
  std::string messages;
  bool ok = load_program_info(program, profile, asm_options, fe.symbols, info, messages, fe.source_dirs);
  std::fputs(messages.c_str(), stderr);
  if (!ok) return 65;
  Setup setup;
  setup.profile = &profile;
  setup.core_name = std::string(core->name());
  setup.instr_time = instr_time;
  setup.limits = limits;
  setup.inputs = std::move(inputs);
  if (eeprom) setup.eeprom = *eeprom;
  setup.checkpoint_bytes = fe.checkpoint_bytes;
  setup.serving = serve != nullptr;
  Engine engine(std::move(setup), std::move(info), std::move(core));
  if (serve) {
    if (!fe.commands_file.empty()) {
      std::fprintf(stderr, "tmclrun: --debug-commands does not go with --serve: give the commands on standard input\n(see tmclrun --help)\n");
      return 64;
    }
    return serve_debug(engine, *serve, stdin, stdout);
  }
  CliOptions co;
  co.commands_file = fe.commands_file;
  co.program_name = program;
  return run_cli(engine, co, stdin, stdout);
}

}  // namespace tmcl::debug
