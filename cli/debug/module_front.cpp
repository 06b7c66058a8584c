// tmclctl PORT debug PROGRAM (debug_module.hpp): the program loaded with its source positions,
// the module attached, the command line run on it, and every breakpoint patch removed however
// the session ends: quit, the end of the commands, Ctrl-C (a pause), SIGTERM and SIGHUP (the
// command under way is paused, then the session ends), a lost connection.
#include <csignal>

#include "tmcl/debug_cli.hpp"
#include "tmcl/debug_module.hpp"
#include "tmcl/os_console.hpp"

namespace tmcl::debug {
namespace {

#ifdef SIGHUP
constexpr int kHangUp = SIGHUP;
#else
constexpr int kHangUp = SIGTERM;  // Windows has no SIGHUP: SIGTERM is caught twice, harmlessly
#endif

volatile std::sig_atomic_t g_quit = 0;
Target* g_module = nullptr;
extern "C" void tmcl_debug_on_quit_signal(int) {
  g_quit = 1;
  if (g_module) g_module->pause();
}

}  // namespace

int debug_module(host::Client& client, const Profile& profile, ModuleFrontEnd fe, std::FILE* in, std::FILE* out) {
  ProgramInfo info;
  std::string messages;
  AsmOptions asm_options;
  asm_options.include_dirs = fe.include_dirs;
  const bool ok = load_program_info(fe.program, profile, asm_options, fe.symbols, info, messages, fe.source_dirs);
  for (std::size_t at = 0; (at = messages.find("tmclrun: ", at)) != std::string::npos;)
    messages.replace(at, 9, "tmclctl: ");  // the loader is tmclrun's; the tool here is tmclctl
  std::fputs(messages.c_str(), stderr);
  if (!ok) return 65;
  if (fe.setup.program_name.empty()) fe.setup.program_name = fe.program;
  ModuleTarget target(client, profile, std::move(info), fe.setup);
  target.on_output = [out](const std::string& s) {
    std::fputs(s.c_str(), out);
    std::fflush(out);
  };
  std::string notes, error;
  if (!target.attach(notes, error)) {
    std::fprintf(stderr, "tmclctl: error: %s\n", error.c_str());
    return 69;
  }
  if (!fe.dap) {  // over DAP the notes go out as output events once the client asks (attach)
    std::fputs(notes.c_str(), out);
    std::fflush(out);
  }

  g_quit = 0;
  g_module = &target;
  os::SavedSignal old_term, old_hup;
  os::catch_signal(SIGTERM, tmcl_debug_on_quit_signal, false, &old_term);
  os::catch_signal(kHangUp, tmcl_debug_on_quit_signal, false, &old_hup);
  if (fe.dap) {
    DapSetup ds;
    ds.quit = &g_quit;
    ds.asm_options = asm_options;
    ds.source_dirs = fe.source_dirs;
    ds.attach_notes = notes;
    const int status = run_dap(ds, target, in, out);
    os::restore_signal(kHangUp, old_hup);  // in reverse order (on Windows both are SIGTERM)
    os::restore_signal(SIGTERM, old_term);
    g_module = nullptr;
    std::string left;
    if (!target.restore(left)) {
      std::fprintf(stderr, "tmclctl: error: %s\n", left.c_str());
      return 69;
    }
    return status;
  }
  CliOptions co;
  co.commands_file = fe.commands_file;
  co.program_name = fe.program;
  co.quit = &g_quit;
  co.tool = "tmclctl";
  int status = run_cli(target, co, in, out);
  std::string left;
  const bool restored = target.restore(left);
  os::restore_signal(kHangUp, old_hup);
  os::restore_signal(SIGTERM, old_term);
  g_module = nullptr;
  if (g_quit && restored) std::fprintf(out, "[session ended by a signal; program memory is as loaded]\n");
  std::fflush(out);
  if (!restored) {
    std::fprintf(stderr, "tmclctl: error: %s\n", left.c_str());
    return 69;
  }
  if (status == 0 && target.lost()) return 69;
  return g_quit ? 143 : status;
}

}  // namespace tmcl::debug
