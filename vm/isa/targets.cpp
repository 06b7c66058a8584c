// -t NAME|PATH, the profile search path, --list-targets and the first-line target comment
// (targets.hpp). A profile file is read once per path and change: the language server asks again
// on every edit, and a file edited meanwhile is read anew (the old profile stays alive, as
// something may still point into it).
#include "tmcl/targets.hpp"

#include <dirent.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <mutex>

#include "tmcl/fileio.hpp"
#include "tmcl/os_files.hpp"
#include "tmcl/profile_file.hpp"

namespace tmcl {
namespace {

constexpr std::size_t kMaxProfileBytes = 1u << 20;

bool file_exists(const std::string& path, struct stat& st) { return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode); }

// Which file `path` is (its real path), as by_path keys it: "dir//a.profile", "./a.profile" and
// "a.profile" read in dir are one file.
std::string file_key(const std::string& path, bool exists) {
  const std::string real = exists ? os::real_path(path) : std::string();
  return real.empty() ? path : real;
}

struct Loaded {
  long long mtime = 0, size = -1;
  bool loading = false;  // being read: a based-on line that comes back to it is a cycle
  // The files of a based-on cycle this one is in (by their names), read again at the next request:
  // its error depends on the other files, which may be mended meanwhile.
  std::vector<std::string> cycle;
  std::unique_ptr<ProfileStore> store;
  std::vector<FileDiag> diags;
  std::string error;
};

struct Reading {
  std::string key;   // by_path's
  std::string name;  // the file's name without .profile, as cycles are told
};

struct UserProfiles {
  std::recursive_mutex lock;
  std::map<std::string, Loaded> by_path;
  std::vector<Reading> reading;  // the files being read, each the base of the one before
  std::vector<std::unique_ptr<ProfileStore>> retired;  // replaced by a newer read; kept alive
};

UserProfiles& user_profiles() {
  static UserProfiles u;
  return u;
}

const Profile* lookup_name(std::string_view name, const TargetSearch& search, const std::string& skip_key, std::string& why);

// "a.profile" and "dir/a.profile" are "a".
std::string file_stem(const std::string& path) {
  const std::size_t sep = os::last_separator(path);
  std::string s = sep == std::string::npos ? path : path.substr(sep + 1);
  if (s.size() > kProfileExtension.size() && s.substr(s.size() - kProfileExtension.size()) == kProfileExtension)
    s.resize(s.size() - kProfileExtension.size());
  return s;
}

// "based-on cycle: a -> b -> a", told from `from`: one of the cycle's files, or one based on it
// ("c -> a -> b -> a").
std::string cycle_text(const std::vector<std::string>& cycle, const std::string& from) {
  std::size_t start = 0;
  while (start < cycle.size() && cycle[start] != from) ++start;
  std::string out = "based-on cycle: ";
  if (start == cycle.size()) out += from + " -> ", start = 0;
  for (std::size_t i = 0; i <= cycle.size(); ++i) out += cycle[(start + i) % cycle.size()] + (i < cycle.size() ? " -> " : "");
  return out;
}

// The based-on line of the file read last names `base`, a file that is in a cycle or being read
// (then every file from it on is in the cycle). Returns the message for that line; the file read
// last is read again at the next request too.
std::string based_on_cycle(UserProfiles& u, const Loaded& base) {
  if (u.reading.empty()) return {};
  if (base.loading) {
    std::size_t from = 0;
    while (from < u.reading.size() && &u.by_path[u.reading[from].key] != &base) ++from;
    std::vector<std::string> cycle;
    for (std::size_t i = from; i < u.reading.size(); ++i) cycle.push_back(u.reading[i].name);
    for (std::size_t i = from; i < u.reading.size(); ++i) u.by_path[u.reading[i].key].cycle = cycle;
  }
  const std::vector<std::string>& cycle = base.cycle;
  if (cycle.empty()) return {};
  Loaded& reader = u.by_path[u.reading.back().key];
  const std::string text = cycle_text(cycle, u.reading.back().name);
  if (reader.cycle.empty()) reader.cycle = cycle;
  return text;
}

// Reads the profile file at `path` (cached by path, modification time and size).
const Loaded& load_file(const std::string& path, const TargetSearch& search) {
  UserProfiles& u = user_profiles();
  std::lock_guard<std::recursive_mutex> g(u.lock);
  struct stat st{};
  const bool exists = file_exists(path, st);
  // Cached by the file itself: the same relative path from another folder is another file.
  const std::string key = file_key(path, exists);
  Loaded& entry = u.by_path[key];
  if (entry.loading) return entry;  // no profile yet: the based-on line that asked says so
  const long long mtime = exists ? os::modified_ns(st) : -1;
  const long long size = exists ? static_cast<long long>(st.st_size) : -1;
  if (entry.size == size && entry.mtime == mtime && entry.cycle.empty() &&
      (entry.store || !entry.diags.empty() || !entry.error.empty()))
    return entry;
  if (entry.store) u.retired.push_back(std::move(entry.store));
  entry = Loaded{};
  entry.mtime = mtime;
  entry.size = size;
  std::vector<std::uint8_t> bytes;
  std::string why;
  if (!read_file(path, bytes, why, kMaxProfileBytes)) {
    entry.error = why;
    return entry;
  }
  // `based-on NAME` in a file NAME.profile means the NAME it hides (a user's own usb-2-sd based on
  // the bundled one): the file itself is skipped, however its path is spelled.
  auto based_on = [&search, &key](std::string_view name, std::string& reason) { return lookup_name(name, search, key, reason); };
  entry.loading = true;
  u.reading.push_back({key, file_stem(path)});
  std::vector<FileDiag> diags;
  auto store = parse_profile(std::string(bytes.begin(), bytes.end()), path, path, diags, based_on);
  u.reading.pop_back();
  entry.loading = false;
  entry.store = std::move(store);
  entry.diags = std::move(diags);
  return entry;
}

// A target by name for a based-on line of the file keyed `skip_key` (file_key): NAME.profile in
// the search path (but that file), then the bundled ones. A cycle of based-on lines between files ends at a file being
// read, which has no profile yet: `why` tells the cycle, to every file in it.
const Profile* lookup_name(std::string_view name, const TargetSearch& search, const std::string& skip_key, std::string& why) {
  for (const auto& dir : search.dirs) {
    const std::string path = os::join_path(dir, std::string(name) + std::string(kProfileExtension));
    struct stat st{};
    if (!file_exists(path, st) || file_key(path, true) == skip_key) continue;
    const Loaded& l = load_file(path, search);
    if (l.store && l.store->profile.name == name) return &l.store->profile;
    why = based_on_cycle(user_profiles(), l);
    return nullptr;
  }
  return find_profile(name);
}

std::string not_used(const std::string& path, std::size_t errors) {
  return path + ": " + std::to_string(errors) + " error" + (errors == 1 ? "" : "s") + " in the profile; it is not used";
}

std::vector<std::string> known_names(const TargetSearch& search) {
  std::vector<std::string> names;
  for (const auto& e : list_targets(search))
    if (e.shadowed_by.empty() && e.error.empty() && !e.alias) names.push_back(e.name);
  return names;
}

}  // namespace

bool is_profile_path(std::string_view value) {
  return os::has_separator(value) || (value.size() > kProfileExtension.size() &&
                                      value.substr(value.size() - kProfileExtension.size()) == kProfileExtension);
}

TargetSearch TargetSearch::from_environment() {
  TargetSearch s;
  if (const char* path = std::getenv("TMCL_PROFILE_PATH")) {
    for (std::string& dir : os::split_path_list(path)) s.dirs.push_back(std::move(dir));
  }
  for (std::string& dir : os::config_dirs("profiles")) s.dirs.push_back(std::move(dir));
  return s;
}

std::string TargetResult::message(int limit, std::string_view tool) const {
  std::string out = diags.empty() ? std::string() : render_file_diags(diags, limit);
  if (diags.empty() && !usage && !tool.empty()) out += std::string(tool) + ": error: ";
  if (!error.empty()) out += error + "\n";
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

TargetResult resolve_target(std::string_view value, const TargetSearch& search) {
  TargetResult r;
  if (value.empty()) {
    r.usage = true;
    r.error = "-t needs a target name or a profile file";
    return r;
  }
  if (is_profile_path(value)) {
    const Loaded& l = load_file(std::string(value), search);
    r.profile = l.store ? &l.store->profile : nullptr;
    r.diags = l.diags;
    if (!l.error.empty()) r.error = l.error;
    else if (!r.profile) r.error = not_used(std::string(value), l.diags.size());
    return r;
  }
  for (const auto& dir : search.dirs) {
    const std::string path = os::join_path(dir, std::string(value) + std::string(kProfileExtension));
    struct stat st{};
    if (!file_exists(path, st)) continue;
    const Loaded& l = load_file(path, search);
    r.diags = l.diags;
    if (!l.error.empty()) {
      r.error = l.error;
    } else if (l.store && l.store->profile.name != value) {
      r.error = path + ": the file is named after '" + std::string(value) + "' but says 'name " +
                std::string(l.store->profile.name) + "'";
    } else if (l.store) {
      r.profile = &l.store->profile;
    } else {
      r.error = not_used(path, l.diags.size());
    }
    return r;
  }
  if ((r.profile = find_profile(value))) return r;
  r.usage = true;
  const std::vector<std::string> names = known_names(search);
  std::vector<std::string_view> views(names.begin(), names.end());
  const std::string hint = closest_match(value, views);
  // Not the whole list: it grows with every profile, and every message that quoted it would too.
  r.error = "unknown target '" + std::string(value) + "'" + (hint.empty() ? "" : "; did you mean '" + hint + "'?") +
            " (see tmclasm --list-targets; or a profile file, docs/profiles.md)";
  return r;
}

std::vector<TargetEntry> list_targets(const TargetSearch& search) {
  std::vector<TargetEntry> out;
  std::map<std::string, std::string> first;  // name -> origin
  auto add = [&](TargetEntry e) {
    if (e.error.empty()) {
      auto [it, fresh] = first.emplace(e.name, e.origin);
      if (!fresh) e.shadowed_by = it->second;
    }
    out.push_back(std::move(e));
  };
  for (const auto& dir : search.dirs) {
    DIR* d = ::opendir(dir.c_str());
    if (!d) continue;
    std::vector<std::string> files;
    while (dirent* ent = ::readdir(d)) {
      std::string f = ent->d_name;
      if (f.size() > kProfileExtension.size() && f.compare(f.size() - kProfileExtension.size(), kProfileExtension.size(), kProfileExtension) == 0)
        files.push_back(f);
    }
    ::closedir(d);
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
      TargetEntry e;
      e.origin = os::join_path(dir, f);
      e.name = f.substr(0, f.size() - kProfileExtension.size());
      const Loaded& l = load_file(e.origin, search);
      if (l.store && l.store->profile.name != e.name)
        e.error = "names itself '" + std::string(l.store->profile.name) + "'";
      else if (l.store)
        e.title = l.store->profile.title;
      else if (!l.error.empty())
        e.error = l.error;
      else if (!l.diags.empty())
        e.error = std::to_string(l.diags.front().line) + ": " + l.diags.front().message;
      add(std::move(e));
    }
  }
  for (const Profile* p : all_profiles()) {
    TargetEntry e;
    e.name = std::string(p->name);
    e.title = std::string(p->title);
    e.origin = "bundled";
    add(std::move(e));
    for (auto a : p->aliases) {
      TargetEntry alias;
      alias.name = std::string(a);
      alias.title = "= " + std::string(p->name);
      alias.origin = "bundled";
      alias.alias = true;
      add(std::move(alias));
    }
  }
  return out;
}

std::vector<const Profile*> found_profiles(const TargetSearch& search) {
  std::vector<const Profile*> out;
  for (const TargetEntry& e : list_targets(search)) {
    if (!e.error.empty() || !e.shadowed_by.empty() || e.alias) continue;
    if (e.origin == "bundled") {
      if (const Profile* p = find_profile(e.name)) out.push_back(p);
    } else if (const Loaded& l = load_file(e.origin, search); l.store) {
      out.push_back(&l.store->profile);
    }
  }
  return out;
}

std::vector<std::string> target_names(const TargetSearch& search) {
  std::vector<std::string> names;
  for (const TargetEntry& e : list_targets(search))
    if (e.error.empty() && std::find(names.begin(), names.end(), e.name) == names.end()) names.push_back(e.name);
  return names;
}

std::string format_target_list(const std::vector<TargetEntry>& entries) {
  std::size_t w = 4, t = 5;
  for (const auto& e : entries) {
    w = std::max(w, e.name.size());
    t = std::max(t, e.title.size());
  }
  auto pad = [](std::string s, std::size_t n) {
    // The width counts characters, not bytes (titles may hold UTF-8).
    std::size_t chars = 0;
    for (unsigned char c : s) chars += (c & 0xC0) != 0x80;
    if (chars < n) s.append(n - chars, ' ');
    return s;
  };
  std::string out = pad("NAME", w) + "  " + pad("TITLE", t) + "  FROM\n";
  for (const auto& e : entries) {
    std::string from = e.origin;
    if (!e.error.empty()) from += " (not usable: " + e.error + ")";
    else if (!e.shadowed_by.empty()) from += " (hidden by " + e.shadowed_by + ")";
    std::string line = pad(e.name, w) + "  " + pad(e.title, t) + "  " + from;
    out += line + "\n";
  }
  return out;
}

std::optional<TargetComment> target_comment(std::string_view source) {
  std::size_t i = 0;
  if (source.substr(0, 3) == "\xEF\xBB\xBF") i = 3;
  const std::size_t bom = i;
  const std::size_t eol = std::min(source.find('\n'), source.size());
  auto blanks = [&] {
    while (i < eol && (source[i] == ' ' || source[i] == '\t')) ++i;
  };
  blanks();
  if (source.substr(i, 2) != "//") return std::nullopt;
  i += 2;
  blanks();
  constexpr std::string_view kKey = "tmcl-target:";
  if (source.substr(i, kKey.size()) != kKey) return std::nullopt;
  i += kKey.size();
  blanks();
  std::size_t e = i;
  while (e < eol && source[e] != ' ' && source[e] != '\t' && source[e] != '\r') ++e;
  if (e == i) return std::nullopt;
  return TargetComment{std::string(source.substr(i, e - i)), static_cast<int>(i - bom) + 1};
}

std::string target_named_by_file(const std::string& path, const std::string& otherwise) {
  if (path.empty() || path == "-") return otherwise;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return otherwise;
  char line[4096];  // only the first line counts: a big program is not read twice
  const std::size_t n = std::fread(line, 1, sizeof line, f);
  std::fclose(f);
  auto c = target_comment(std::string_view(line, n));
  return c ? c->name : otherwise;
}

}  // namespace tmcl
