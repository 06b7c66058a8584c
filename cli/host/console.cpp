// A direct-mode session's names (console.hpp): each line through the assembler, with what the
// earlier lines defined passed back as -D definitions.
#include "tmcl/host/console.hpp"

#include <algorithm>
#include <cctype>
#include <optional>

#include "tmcl/asm/assembler.hpp"
#include "tmcl/host/commands.hpp"
#include "tmcl/param_names.hpp"

namespace tmcl::host {
namespace {

std::string folded(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// One line of source as the file "<command line>", for `profile`, with the session's names as
// -D definitions. Includes are read from disk and the bundled ones; no STOP is appended. An -I
// folder that cannot be searched is warned about when `check_folders` says so.
AsmResult assemble_line(const std::string& line, const Profile& profile, const std::vector<std::string>& include_dirs,
                        const std::vector<std::pair<std::string, std::string>>& defines, bool check_folders) {
  struct Reader final : FileOverlay {
    std::string line;
    bool folders = false;
    std::string folder_problem(const std::string& path) override { return folders ? FileOverlay::folder_problem(path) : ""; }
    bool serve(const std::string& path, std::string& out) override {
      if (path != "<command line>") return false;
      out = line;
      return true;
    }
  } reader;
  reader.line = line + "\n";
  reader.folders = check_folders;
  AsmOptions opt;
  opt.profile = &profile;
  opt.include_dirs = include_dirs;
  opt.defines = defines;
  opt.append_stop = false;
  return assemble({"<command line>"}, opt, reader);
}

}  // namespace

// The module's own include file (include-file in its profile), or the one generated from a
// bundled profile (TMCM-1260.inc: asm/include_files.cpp); none for a profile of one's own without
// an include-file line (also one that hides a bundled name but differs from it), whose generated
// names no program could include either.
std::string module_include_file(const Profile& profile) {
  if (!profile.include_file.empty()) return std::string(profile.include_file);
  if (profile.any_parameter) return {};
  const std::string file = parameter_include_name(profile);
  const auto& bundled = bundled_includes();
  const auto found = bundled.find(file);
  return found != bundled.end() && found->second == parameter_include_text(profile) ? file : std::string();
}

ConsoleSession::ConsoleSession(const Profile& profile, std::vector<std::string> include_dirs)
    : profile_(profile), include_dirs_(std::move(include_dirs)) {
  // Interrupts.inc (TI_TIMER0, ...) on a module with interrupt vectors, as a program would
  // include it for EI, DI and VECT.
  const std::string interrupts = profile.vectors.empty() ? std::string() : std::string("Interrupts.inc");
  for (const std::string& file : {std::string("TMCLParam.tmc"), interrupts, module_include_file(profile)}) {
    if (file.empty()) continue;
    // The bundled files assemble for every profile; a failure here would be a defect of ours,
    // and the session would merely lack the names.
    if (take("#include " + file, file + " (predefined)", false).kind != Entry::Error) predefined_.push_back(file);
  }
}

// An -I folder that cannot be searched is said once, with the first line the user typed.
ConsoleSession::Entry ConsoleSession::enter(const std::string& line) {
  Entry e = take(line, line, !folders_said_);
  folders_said_ = true;
  return e;
}

ConsoleSession::Entry ConsoleSession::take(const std::string& line, const std::string& origin, bool check_folders) {
  Entry e;
  AsmResult r = assemble_line(line, profile_, include_dirs_, defines_, check_folders);
  // The session name a note points at: the assembler says "first defined on the command line"
  // at the -D definition of a name a line redefines.
  auto define_of = [&](const Diagnostic& note) -> std::optional<std::size_t> {
    static const std::string kDefineFile = "<command line -D ";
    if (note.loc.file < 0) return std::nullopt;
    const std::string& file = r.sources.files[static_cast<std::size_t>(note.loc.file)].name;
    if (file.rfind(kDefineFile, 0) != 0) return std::nullopt;
    const std::string name = file.substr(kDefineFile.size(), file.size() - kDefineFile.size() - 1);
    for (std::size_t i = 0; i < defines_.size(); ++i)
      if (defines_[i].first == name) return i;
    return std::nullopt;
  };
  auto typed_here = [&](std::size_t i) { return origins_[i].find("(predefined)") == std::string::npos && origins_[i].rfind("#include", 0) != 0; };
  // When the only errors redefine constants typed in this session, the line gives them new
  // values: their old definitions go, and the line is assembled again.
  std::vector<std::pair<std::string, std::string>> replaced;
  if (!r.ok()) {
    std::vector<std::size_t> old;
    bool only_typed_redefinitions = true;
    for (const Diagnostic& d : r.diags.all()) {
      if (d.severity != Severity::Error) continue;
      bool redefinition = false;
      for (const Diagnostic& n : d.notes)
        if (auto i = define_of(n)) {
          redefinition = true;
          only_typed_redefinitions = only_typed_redefinitions && typed_here(*i);
          old.push_back(*i);
        }
      only_typed_redefinitions = only_typed_redefinitions && redefinition;
    }
    std::sort(old.begin(), old.end());
    old.erase(std::unique(old.begin(), old.end()), old.end());
    auto defines = defines_;
    for (auto i = old.rbegin(); i != old.rend(); ++i) defines.erase(defines.begin() + static_cast<std::ptrdiff_t>(*i));
    if (only_typed_redefinitions) {
      if (AsmResult again = assemble_line(line, profile_, include_dirs_, defines, check_folders); again.ok() && again.program.empty()) {
        for (auto i = old.rbegin(); i != old.rend(); ++i) {
          replaced.push_back(defines_[*i]);
          defines_.erase(defines_.begin() + static_cast<std::ptrdiff_t>(*i));
          origins_.erase(origins_.begin() + static_cast<std::ptrdiff_t>(*i));
        }
        r = std::move(again);
      }
    }
  }
  // The diagnostics, less what means nothing for one line of a session: "the program has no
  // instructions", and notes at a -D definition (said in words instead).
  for (const Diagnostic* d : r.diags.sorted(r.sources)) {
    if (d->severity == Severity::Warning && d->message.rfind("the program has no instructions", 0) == 0) continue;
    Diagnostic shown = *d;
    std::erase_if(shown.notes, [&](const Diagnostic& n) { return define_of(n).has_value(); });
    e.messages += render_diagnostic(shown, r.sources);
    for (const Diagnostic& n : d->notes)
      if (auto i = define_of(n))
        e.messages += "<command line>: note: '" + defines_[*i].first + "' is " + defines_[*i].second + " for the session, from " +
                      (typed_here(*i) ? "'" + origins_[*i] + "'" : origins_[*i]) +
                      "; only constants typed in the session take a new value\n";
  }
  if (!r.ok()) {
    e.kind = Entry::Error;
    return e;
  }
  std::vector<const Symbol*> constants;
  for (const Symbol& s : r.symbols) {
    if (s.kind == SymbolKind::Constant) {
      constants.push_back(&s);
    } else {
      e.kind = Entry::Error;
      e.messages += "<command line>: error: label '" + s.name + "' means nothing in direct mode: nothing was sent\n";
      return e;
    }
  }
  if (r.program.size() > 1 || (r.program.size() == 1 && !constants.empty())) {
    e.kind = Entry::Error;
    e.messages += "<command line>: error: '" + line + "' is " + std::to_string(r.program.size()) +
                  " instructions; one at a time is sent, and nothing was kept\n";
    return e;
  }
  if (r.program.size() == 1) {
    e.kind = Entry::Send;
    e.ins = r.program.front();
    return e;
  }
  for (const Symbol* s : constants) {
    defines_.emplace_back(s->name, std::to_string(s->value));
    origins_.push_back(origin);
    std::string text = s->name + " = " + std::to_string(s->value);
    for (const auto& [name, value] : replaced)
      if (folded(name) == folded(s->name)) text += " (was " + value + ")";
    e.defined.push_back(text);
  }
  e.kind = e.defined.empty() ? Entry::Nothing : Entry::Defined;
  return e;
}

}  // namespace tmcl::host
