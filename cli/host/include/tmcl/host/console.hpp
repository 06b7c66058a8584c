// The names of a direct-mode session (tmclctl console and send): each line is assembled by the
// project's assembler, with TMCLParam.tmc, Interrupts.inc (on a module with interrupt vectors)
// and the module's include file (USB-2-SD.inc, ...) predefined and every `NAME = VALUE` and `#include` typed so far kept for the session. Nothing
// here reads source itself: what a line defines is what the assembler reports (its symbols), and
// the session hands those back to it as -D definitions with every later line, so names resolve
// and misspellings get a did-you-mean exactly as in a program. One liberty a console needs: a
// constant typed in the session may be given a new value (the assembler's redefinition errors
// say which names a line redefines); names from include files keep theirs, as in a program.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "tmcl/isa.hpp"
#include "tmcl/profile.hpp"

namespace tmcl::host {

// The bundled include file with the names of `profile`'s parameters: the one its include-file
// line names ("USB-2-SD.inc"; generic inherits the USB-2-SD's), else the one generated from a
// bundled profile ("TMCM-1260.inc"); "" when there is none.
std::string module_include_file(const Profile& profile);

class ConsoleSession {
 public:
  // Predefines TMCLParam.tmc, Interrupts.inc (when the profile lists interrupt vectors) and
  // module_include_file(profile).
  ConsoleSession(const Profile& profile, std::vector<std::string> include_dirs);

  struct Entry {
    enum Kind : std::uint8_t {
      Nothing,  // a comment, or an #include that adds no name
      Send,     // one instruction: `ins`
      Defined,  // names kept for the session: `defined` ("Speed = 1000", ...)
      Error,    // the line does not assemble (or is not one instruction): `messages`
    } kind = Nothing;
    Instruction ins;
    std::vector<std::string> defined;  // "Speed = 2000 (was 1000)" when a typed constant changed
    std::string messages;  // the assembler's diagnostics, warnings included, rendered
  };
  // Assembles one line in the session: an instruction is returned to be sent; names it defines
  // are kept. Diagnostics name the line "<command line>"; the first line's also say which -I
  // folders cannot be searched.
  Entry enter(const std::string& line);

  // The files predefined at the start ("TMCLParam.tmc", "Interrupts.inc", "USB-2-SD.inc").
  const std::vector<std::string>& predefined() const { return predefined_; }
  std::size_t name_count() const { return defines_.size(); }

 private:
  Entry take(const std::string& line, const std::string& origin, bool check_folders);
  const Profile& profile_;
  std::vector<std::string> include_dirs_;
  std::vector<std::pair<std::string, std::string>> defines_;  // NAME, its value in decimal
  std::vector<std::string> origins_;  // per define: the line that defined it, or "FILE (predefined)"
  std::vector<std::string> predefined_;
  bool folders_said_ = false;
};

}  // namespace tmcl::host
