// `-t NAME|PATH` for every tool (tmclasm, tmclrun, tmclctl, the language server): where a target's
// profile comes from. A value with a '/' or ending in ".profile" is a user's profile file; a name
// is looked for as NAME.profile in each folder of the search path (TMCL_PROFILE_PATH, then
// ~/.config/tmcl/profiles/), then among the bundled profiles (by name or alias). A source file
// may name its target on its first line, `// tmcl-target: NAME`, which every tool honours unless
// -t is given. Profiles read from files are kept for the life of the program, as the bundled ones.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tmcl/diag_text.hpp"
#include "tmcl/profile.hpp"

namespace tmcl {

// The folders searched for NAME.profile before the bundled profiles, in order.
struct TargetSearch {
  std::vector<std::string> dirs;
  // TMCL_PROFILE_PATH (folders separated by ':'), then $XDG_CONFIG_HOME/tmcl/profiles or, without
  // it, $HOME/.config/tmcl/profiles.
  static TargetSearch from_environment();
};

struct TargetResult {
  const Profile* profile = nullptr;
  bool usage = false;            // the value names no target at all (a usage error), not a bad file
  std::string error;             // what went wrong, one line (empty when `profile` is set)
  std::vector<FileDiag> diags;   // the errors of a malformed profile file
  // Everything to show: the profile file's errors (at most `limit`, 0 = all), then `error`; a
  // lone error of a file, as "TOOL: error: ..." when `tool` is given.
  std::string message(int limit = kDefaultErrorLimit, std::string_view tool = {}) const;
};

// Whether -t VALUE names a profile file (a '/' in it, or ending in ".profile") rather than a
// target by name; a relative one is relative to the current folder, or to the file that names it.
bool is_profile_path(std::string_view value);
// Resolves -t VALUE (see above).
TargetResult resolve_target(std::string_view value, const TargetSearch& search = TargetSearch::from_environment());

// Every profile found: the search path's files, then the bundled ones. A name found earlier
// shadows the same name later; a file that does not parse is listed with its first error.
struct TargetEntry {
  std::string name, title, origin;  // origin: "bundled" or the file
  std::string shadowed_by;          // the origin of the profile that hides this one
  std::string error;                // the file does not parse
  bool alias = false;               // another name of the profile listed before it
};
std::vector<TargetEntry> list_targets(const TargetSearch& search = TargetSearch::from_environment());
// The profiles of the targets found, each once, in the list's order: those a name finds (no alias,
// none hidden by an earlier file, none that does not parse). What compares modules (the
// assembler's note on a renumbered parameter, tmclctl's module by its firmware reply) asks this,
// so a user's own profiles count as the bundled ones do.
std::vector<const Profile*> found_profiles(const TargetSearch& search = TargetSearch::from_environment());
// The names of the targets found, each once, in the list's order (the shell's completion of -t).
std::vector<std::string> target_names(const TargetSearch& search = TargetSearch::from_environment());
// The list as a table for `tmclasm --list-targets`.
std::string format_target_list(const std::vector<TargetEntry>& entries);

// `// tmcl-target: NAME` on the first line of `source` (after an optional byte-order mark and
// blanks): the name and its 1-based column; nothing when the first line says no target.
struct TargetComment {
  std::string name;
  int col = 0;
};
std::optional<TargetComment> target_comment(std::string_view source);
// The target a source file names on its first line, or `otherwise` (a file that cannot be read,
// standard input "-", or no comment).
std::string target_named_by_file(const std::string& path, const std::string& otherwise);

}  // namespace tmcl
