// The debugger's front ends as tmclrun uses them: loading a program with its source positions
// and symbols, and the gdb-like command line of `tmclrun --debug` (docs/debugger.md).
#pragma once

#include <csignal>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "tmcl/asm/assembler.hpp"
#include "tmcl/debugger.hpp"
#include "tmcl/server.hpp"

namespace tmcl::debug {

// Reads PROGRAM (.tmc assembled with its line table and symbols, or a .bin/.dgm image with an
// optional symbols file `symbols`, as tmclasm -f symbols writes it, whose sources are also
// looked for in `source_dirs`) into `info`. Diagnostics go to `messages`; false when the program
// cannot be debugged.
bool load_program_info(const std::string& path, const Profile& profile, AsmOptions asm_options,
                       const std::string& symbols, ProgramInfo& info, std::string& messages,
                       const std::vector<std::string>& source_dirs = {});

struct CliOptions {
  std::string commands_file;  // --debug-commands FILE: run these, then quit (like gdb -batch -x)
  std::string program_name;   // for messages
  std::string tool = "tmclrun";  // names the tool in its messages
  // Set by a signal handler (SIGTERM, SIGHUP): the session ends after the command under way,
  // which the handler paused.
  const volatile std::sig_atomic_t* quit = nullptr;
};

// Runs the command line on `engine` until quit or the end of the commands. Commands come from
// the file, else standard input (echoed with the prompt when it is not a terminal, so a
// transcript reads like a session). Returns tmclrun's exit status for how the program ended.
int run_cli(Target& engine, const CliOptions& options, std::FILE* in, std::FILE* out);

// The command line fed one line at a time, for a front end with its own input loop
// (tmclrun --serve --debug). Output goes to `out`, flushed after every call.
class CommandLine {
 public:
  // echo: print each line after "(tmdb) " (input that is not a terminal); repeat: an empty
  // line repeats the last command (gdb's Enter).
  CommandLine(Target& engine, std::FILE* out, bool echo, bool repeat);
  ~CommandLine();
  CommandLine(const CommandLine&) = delete;
  CommandLine& operator=(const CommandLine&) = delete;
  bool line(std::string text);  // false: quit
  void report(const Stop& stop);  // a stop that no command made (the host stopped the program)
  void note(const std::string& text);  // a line of its own
  int status() const;  // tmclrun's exit status for how the program last ended
  // Tab completion: candidates for the word of `line` that starts at `start` (commands, info
  // subcommands, labels, constants, source files, registers, expression functions).
  std::vector<std::string> completions(const std::string& line, std::size_t start) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::FILE* out_;
};

// `tmclrun --serve SPEC --debug PROGRAM`: the virtual module serves its host while the command
// line debugs the program, in one thread (docs/debugger.md, "Debugging while serving"). Commands
// come from `in` (a pipe or a terminal; not a --debug-commands file). Returns the server's
// status when it failed (71, 74), else the command line's.
int serve_debug(Engine& engine, const ServeOptions& options, std::FILE* in, std::FILE* out);

// `tmclrun --dap`: the Debug Adapter Protocol on `in` and `out` until disconnect. The launch
// request names the program (and may name target, motion, instructionTime, symbols,
// stopOnEntry); these are the defaults from tmclrun's command line.
struct DapSetup {
  std::string target = "generic";
  const Profile* profile = nullptr;  // tmclrun's -t, resolved (a profile file has no name to find it by)
  bool target_given = false;         // -t given: else the program's first line may name the target
  SimTime instr_time = 20;
  AsmOptions asm_options;
  std::vector<std::string> source_dirs;  // --source-dir: where an image's sources may be
  Limits limits;                     // --max-time, --max-steps
  std::vector<InputEvent> inputs;    // --scenario
  std::optional<EepromImage> eeprom; // --eeprom (read at power-up)
  std::string attach_notes;          // tmclctl PORT debug --dap: what attaching found, sent on `attach`
  const volatile std::sig_atomic_t* quit = nullptr;  // SIGTERM, SIGHUP: end as on disconnect
};
int run_dap(const DapSetup& setup, std::FILE* in, std::FILE* out);
// The same on a target attached already (tmclctl PORT debug --dap): `attach` or `launch` confirm
// it; `setup` gives only the assembler's options.
int run_dap(const DapSetup& setup, Target& target, std::FILE* in, std::FILE* out);

// tmclrun's debugger options (its option table sets them, cli/tmclrun.cpp).
struct FrontEnd {
  bool enabled = false;         // --debug, --debug-commands or --dap
  bool dap = false;             // --dap
  std::string commands_file;    // --debug-commands FILE
  std::string symbols;          // --symbols FILE (labels and line table for a .bin)
  std::vector<std::string> source_dirs;  // --source-dir DIR (repeatable): sources of a .bin
  std::size_t checkpoint_bytes = std::size_t{64} << 20;  // --checkpoint-memory MiB
  bool target_given = false;    // set by tmclrun: -t was given (--dap then ignores first-line targets)
};

// Loads PROGRAM and runs the command line (or DAP) on it; with `serve`, while serving a host
// (serve_debug). Returns tmclrun's exit status.
int main(const FrontEnd& fe, const Profile& profile, std::unique_ptr<MotionCore> core, const std::string& program,
         const AsmOptions& asm_options, SimTime instr_time, const Limits& limits, std::vector<InputEvent> inputs,
         const EepromImage* eeprom, const ServeOptions* serve = nullptr);

}  // namespace tmcl::debug
