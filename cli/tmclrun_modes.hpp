// tmclrun's two programs. tmclrun.cpp (option parsing, loading, the run) is in both.
// tmclrun-full adds tmclrun_modes.cpp: --serve, --debug, --dap and their companions, with the
// virtual module and the debugger. tmclrun adds tmclrun_exec.cpp instead, which hands a command
// line with such an option to tmclrun-full (execv, the same arguments). So the README's quick
// start builds neither library (docs/performance.md, "Build time"), and every option is parsed by
// one piece of code. This header is what tmclrun.cpp calls, light enough for tmclrun_exec.cpp;
// tmclrun.hpp has the rest.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace tmcl {
struct EepromImage;
struct InputEvent;
struct Instruction;
class MotionCore;
struct Profile;
}  // namespace tmcl

namespace tmclrun {

constexpr int kExitOk = 0, kExitLimit = 3, kExitUsage = 64, kExitInput = 65, kExitFault = 70, kExitOsErr = 71,
              kExitIo = 74;

struct Options;  // tmclrun.hpp
using ValueFn = std::function<bool(std::string&)>;

// tmclrun.cpp: reports the error on standard error (and for --json), returns the exit status.
int usage_error(const std::string& msg);

// ---- tmclrun_modes.cpp in tmclrun-full, tmclrun_exec.cpp in tmclrun ----
// Called for every argument tmclrun.cpp does not know (argv: as main() got them). True when it
// was a mode option; `status` is then -1, or the exit status of an error already reported.
bool mode_option(const std::string& arg, bool has_inline, const ValueFn& value, char** argv, Options& o, int& status);
// After all arguments: the checks that involve mode options (--module sets o.program and
// o.target). -1 when the run goes on, else an exit status.
int check_mode_options(Options& o, const std::vector<std::string>& args, bool have_program);
// Serves or debugs (o.serving or o.debugging). Returns tmclrun's exit status.
int run_mode(Options& o, const tmcl::Profile& profile, std::unique_ptr<tmcl::MotionCore> core,
             const std::vector<tmcl::Instruction>& program, const std::vector<std::string>& sources,
             std::vector<tmcl::InputEvent> inputs, tmcl::EepromImage* image);

}  // namespace tmclrun
