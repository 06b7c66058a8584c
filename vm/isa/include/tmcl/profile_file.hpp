// The profile file format (docs/profiles.md): one statement a line, `KEY ARGS... [ATTR=VALUE...]`,
// `#` comments, "quoted" text. Read like the assembler reads a program: every error of the file
// collected with its line, column and a caret, a did-you-mean for a misspelt key or attribute,
// never a crash. The parsed profile owns its storage (ProfileStore) and is seen through the
// `Profile` view the rest of the code uses.
#pragma once

#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "tmcl/diag_text.hpp"
#include "tmcl/profile.hpp"

namespace tmcl {

// A parsed profile and everything its view points into. Not copyable or movable: the view points
// into the members.
struct ProfileStore {
  Profile profile{};
  std::string text;                  // the file, as read
  std::deque<std::string> strings;   // text made while parsing (unverified phrases)
  std::vector<ParamInfo> axis, bank0, bank3;
  std::vector<InterruptVector> vectors;
  std::vector<IoPort> ports;
  std::deque<std::vector<ValueItem>> value_sets;  // the values= sets, at stable addresses
  std::vector<MotionConstant> constants;
  std::vector<std::string_view> aliases, unverified;
  std::string origin_text;

  ProfileStore() = default;
  ProfileStore(const ProfileStore&) = delete;
  ProfileStore& operator=(const ProfileStore&) = delete;
};

// Finds the profile a `based-on NAME` line names; nullptr when there is none, with `why` set when
// there is a better reason to give than "unknown profile" (a based-on cycle).
using ProfileLookup = std::function<const Profile*(std::string_view name, std::string& why)>;

// Parses a profile file. `file` names it in messages; `origin` becomes Profile::origin. Returns
// the profile, or nullptr with every error in `diags`.
std::unique_ptr<ProfileStore> parse_profile(std::string text, const std::string& file, std::string_view origin,
                                            std::vector<FileDiag>& diags, const ProfileLookup& based_on = {});

// The statement keys and attribute names of the format (for docs, completion and did-you-mean).
std::vector<std::string_view> profile_keys();

// A profile as a file draft: every statement of the format, facts in the profile's order, each
// line marked `unverified` where the profile's fact is. `note` is written as a comment at the top.
std::string format_profile(const Profile& p, std::string_view note = {});

}  // namespace tmcl
