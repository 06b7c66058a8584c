// Which module answers, and what it has: `identify` reads command 136 once and finds the profile
// whose firmware reply it matches (by the whole reply, else by the module number before the 'V');
// `probe` asks a module no profile describes for everything that can be read without changing
// it — its firmware, with GAP and GGP over every number of the axis parameters and of banks 0 and
// 3 which parameters exist (a reply other than 100, as 3 or 4, means "not there") and their values,
// how many motors, user variables and coordinates answer, how much program memory 134 can read —
// and writes a draft
// profile (docs/profiles.md, "Your own module") with every fact marked unverified.
#pragma once

#include <string>

#include "tmcl/host/transfer.hpp"
#include "tmcl/profile.hpp"

namespace tmcl::host {

struct Identity {
  bool answered = false;
  std::string version;             // 136 type 0, e.g. "1110V103"
  const Profile* profile = nullptr;  // the profile it matches, bundled or on the search path
};
// One 136 type 0 request without retries (the caller sets the timeout).
Identity identify(Client& client);
// The profile whose firmware is `version`, else the one with its module number (the characters
// before the 'V'); nullptr when none.
const Profile* profile_for_firmware(const std::string& version);

struct ProbeResult {
  Outcome outcome = Outcome::Ok;
  std::string message;  // what went wrong
  std::string text;     // the draft profile
  int axis = 0, bank0 = 0, bank3 = 0;  // parameters found
  int motors = 0;
};
// Probes the module (about 1300 requests; `progress` gets (done, total)). `name` becomes the
// draft's name and title.
ProbeResult probe(Client& client, const std::string& name, const Progress& progress);

}  // namespace tmcl::host
