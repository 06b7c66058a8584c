// The bundled profiles (vm/isa/profiles/*.profile, compiled in by embed_files.cmake) and the
// lookups over a profile's tables. A bundled profile is parsed the first time it is asked for
// and kept for the life of the program, so a tool pays only for the module it uses.
#include "tmcl/profile.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "tmcl/profile_file.hpp"
#include "tmcl/os_files.hpp"

namespace tmcl {

// Generated from vm/isa/profiles/ (embed_files.cmake): file name -> text.
const std::map<std::string, std::string_view>& bundled_profile_files();

namespace {

const ParamInfo* find_param(std::span<const ParamInfo> table, int number) {
  auto it = std::lower_bound(table.begin(), table.end(), number,
                             [](const ParamInfo& p, int n) { return p.number < n; });
  return it != table.end() && it->number == number ? &*it : nullptr;
}


struct Bundled {
  std::recursive_mutex lock;  // based-on loads its base while loading
  std::map<std::string, std::unique_ptr<ProfileStore>, std::less<>> by_file;
  std::vector<const Profile*> all;  // filled by all_profiles()
};

Bundled& bundled() {
  static Bundled b;
  return b;
}

// The bundled file NAME.profile, parsed once; nullptr when there is none. A bundled file that
// does not parse is a defect of the build (tests/profiles parses every one): said on standard
// error, and the profile is missing.
const Profile* load_bundled(std::string_view name) {
  Bundled& b = bundled();
  std::lock_guard<std::recursive_mutex> g(b.lock);
  const std::string file = std::string(name) + std::string(kProfileExtension);
  if (auto it = b.by_file.find(file); it != b.by_file.end()) return it->second ? &it->second->profile : nullptr;
  const auto& files = bundled_profile_files();
  auto text = files.find(file);
  if (text == files.end()) return nullptr;
  std::vector<FileDiag> diags;
  b.by_file[file] = nullptr;  // a based-on cycle ends here
  auto store = parse_profile(std::string(text->second), "<bundled>/" + file, "bundled", diags,
                             [](std::string_view base, std::string&) { return load_bundled(base); });
  if (!store) std::fputs(render_file_diags(diags, 0).c_str(), stderr);
  const Profile* p = store ? &store->profile : nullptr;
  b.by_file[file] = std::move(store);
  return p;
}

}  // namespace

namespace {
// Whether v is in the value set: a plain item holds v less some of the flags (each at most once).
bool in_value_set(std::span<const ValueItem> set, std::int64_t v) {
  std::int64_t flags[8];
  int nflags = 0;
  for (const auto& i : set)
    if (i.flag && nflags < 8) flags[nflags++] = i.lo;
  for (unsigned mask = 0; mask < (1u << nflags); ++mask) {
    std::int64_t w = v;
    for (int f = 0; f < nflags; ++f)
      if (mask & (1u << f)) w -= flags[f];
    for (const auto& i : set)
      if (!i.flag && w >= i.lo && w <= i.hi) return true;
  }
  return false;
}
}  // namespace

bool accepts(const ParamInfo& p, std::int64_t value) {
  bool in_range = value >= p.min && value <= p.max;
  if (!in_range && value >= INT32_MIN && value <= INT32_MAX) {
    const auto u = static_cast<std::int64_t>(static_cast<std::uint32_t>(value));
    in_range = u >= p.min && u <= p.max;
    if (in_range) value = u;
  }
  return in_range && (p.values.empty() || in_value_set(p.values, value));
}

std::string range_text(const ParamInfo& p) {
  std::string s;
  if (p.values.empty()) {
    s = std::to_string(p.min) + " to " + std::to_string(p.max);
  } else {
    const char* sep = "";
    bool flags = false;
    for (const auto& i : p.values) {
      if (i.flag) {
        s += (flags ? ", +" : ", optionally +") + std::to_string(i.lo);
        flags = true;
        continue;
      }
      s += sep + std::to_string(i.lo) + (i.hi != i.lo ? " to " + std::to_string(i.hi) : "");
      sep = ", ";
    }
  }
  return s + (p.unit.empty() ? "" : " " + std::string(p.unit));
}

std::string port_text(const IoPort& p) {
  return std::string(p.output ? "SIO " : "GIO ") + std::to_string(p.number) + ", " + std::to_string(p.bank) +
         (p.name.empty() ? "" : " (" + std::string(p.name) + ")");
}

const IoPort* Profile::read_port(int bank, int number) const {
  for (const auto& p : ports)
    if (p.bank == bank && p.number == number && (!p.output || bank == 2)) return &p;
  return nullptr;
}

const IoPort* Profile::write_port(int bank, int number) const {
  for (const auto& p : ports)
    if (p.bank == bank && p.number == number && p.output) return &p;
  return nullptr;
}

std::string Profile::port_numbers(int bank, bool write) const {
  std::string s;
  for (const auto& p : ports)
    if (p.bank == bank && (write ? p.output : (!p.output || bank == 2)))
      s += (s.empty() ? "" : ", ") + std::to_string(p.number);
  return s.empty() ? "none" : s;
}

bool Profile::digital_input(int n) const {
  if (any_port) return n >= 0 && n < kPortCount;
  const IoPort* p = read_port(0, n);
  return p && p->kind == PortKind::Digital;
}

int Profile::last_port(int bank) const {
  int last = -1;
  for (const auto& p : ports)
    if (p.bank == bank && p.kind != PortKind::Bits && (p.output == (bank == 2))) last = std::max(last, static_cast<int>(p.number));
  return last;
}

std::string param_text(std::string_view kind, int number, const ParamInfo* p) {
  std::string s = std::string(kind) + " " + std::to_string(number);
  if (p && !p->name.empty()) s += " (" + std::string(p->name) + ")";
  return s;
}

std::string access_letters(std::uint8_t access) {
  std::string s;
  if (access & kRead) s += 'R';
  if (access & kWrite) s += 'W';
  if (access & kEeprom) s += 'E';
  if (access & kAutoStore) s += 'A';
  return s;
}

const ParamInfo* Profile::axis_param(int number) const { return find_param(axis_params, number); }

const ParamInfo* Profile::global_param(int bank, int number) const {
  if (bank == 0) return find_param(bank0, number);
  if (bank == 3) return find_param(bank3, number);
  return nullptr;
}

const InterruptVector* Profile::vector(int number) const {
  for (const auto& v : vectors)
    if (v.number == number) return &v;
  return nullptr;
}

std::int64_t Profile::motion_constant(std::string_view constant, std::int64_t otherwise) const {
  for (const auto& c : motion_constants)
    if (c.name == constant) return c.value;
  return otherwise;
}

std::span<const Profile* const> all_profiles() {
  Bundled& b = bundled();
  std::lock_guard<std::recursive_mutex> g(b.lock);
  if (b.all.empty()) {
    if (const Profile* g0 = load_bundled("generic")) b.all.push_back(g0);
    for (const auto& [file, text] : bundled_profile_files()) {
      const std::string_view name = std::string_view(file).substr(0, file.size() - kProfileExtension.size());
      if (name == "generic") continue;
      if (const Profile* p = load_bundled(name)) b.all.push_back(p);
    }
  }
  return b.all;
}

const Profile* find_profile(std::string_view name) {
  if (name.empty() || os::has_separator(name)) return nullptr;
  if (const Profile* p = load_bundled(name)) return p;
  for (const Profile* p : all_profiles())
    if (std::find(p->aliases.begin(), p->aliases.end(), name) != p->aliases.end()) return p;
  return nullptr;
}

const Profile& generic_profile() {
  static const Profile* g = load_bundled("generic");
  if (!g) {
    // Only a broken build gets here (the bundled generic.profile did not parse, said above):
    // an empty profile that accepts everything keeps the tools alive.
    static Profile empty{};
    empty.name = "generic";
    empty.title = "generic";
    empty.any_parameter = true;
    empty.motors = 1;
    empty.user_vars = 256;
    empty.default_motion = "ideal";
    empty.firmware = "0000V100";
    g = &empty;
  }
  return *g;
}

}  // namespace tmcl
