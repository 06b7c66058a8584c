// tmclrun's stand-in for tmclrun_modes.cpp (cli/tmclrun_modes.hpp): an option that tmclrun.cpp
// does not know may be one of serving or debugging, which tmclrun-full does. tmclrun becomes
// tmclrun-full (execv with the same arguments, before anything is read or written), which parses
// the whole command line again and reports a truly unknown option itself. tmclrun-full is looked
// for in the installed place (TMCLRUN_FULL_FROM_BIN, relative to tmclrun's own folder), then
// beside tmclrun (the build tree).
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>
#include <string>

#include "tmclrun_modes.hpp"

using namespace tmclrun;

namespace {

// The folder of the running program, from /proc/self/exe; empty when it cannot be read.
std::string own_folder() {
  char path[PATH_MAX];
  const ssize_t n = ::readlink("/proc/self/exe", path, sizeof path - 1);
  if (n <= 0) return {};
  std::string s(path, static_cast<std::size_t>(n));
  const auto slash = s.rfind('/');
  return slash == std::string::npos ? std::string() : s.substr(0, slash);
}

}  // namespace

bool tmclrun::mode_option(const std::string& arg, bool, const ValueFn&, char** argv, Options&, int& status) {
  if (arg.size() < 2 || arg[0] != '-') return false;  // PROGRAM, or - for standard input
  const std::string folder = own_folder();
  std::string tried;
  for (const std::string& candidate : {folder + "/" TMCLRUN_FULL_FROM_BIN, folder + "/tmclrun-full"}) {
    if (folder.empty()) break;
    ::execv(candidate.c_str(), argv);  // returns only when it failed
    tried += (tried.empty() ? "" : ", ") + candidate + " (" + std::strerror(errno) + ")";
  }
  std::string flag = arg;
  const auto eq = flag.find('=');
  if (flag.rfind("--", 0) == 0 && eq != std::string::npos) flag.resize(eq);
  usage_error("'" + flag + "' is not an option of tmclrun itself, and tmclrun-full, which serves and debugs, " +
              "is missing (tried " + (tried.empty() ? "nothing: /proc/self/exe cannot be read" : tried) + ")");
  status = kExitOsErr;
  return true;
}

int tmclrun::check_mode_options(Options&, const std::vector<std::string>&, bool) { return -1; }

int tmclrun::run_mode(Options&, const tmcl::Profile&, std::unique_ptr<tmcl::MotionCore>,
                      const std::vector<tmcl::Instruction>&, const std::vector<std::string>&,
                      std::vector<tmcl::InputEvent>, tmcl::EepromImage*) {
  // mode_option never returns with o.serving or o.debugging set here.
  return kExitOsErr;
}
