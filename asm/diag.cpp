// Collecting and rendering diagnostics: location, source line, caret, include chain, notes.
#include "tmcl/asm/diag.hpp"

#include "tmcl/fileio.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <cstdint>
#include <cstring>
#include <tuple>

namespace tmcl {

std::string_view SourceFile::line(int number) const {
  if (number < 1 || static_cast<std::size_t>(number) > line_starts.size()) return {};
  std::size_t begin = line_starts[static_cast<std::size_t>(number - 1)];
  std::size_t end = text.find('\n', begin);
  if (end == std::string::npos) end = text.size();
  if (end > begin && text[end - 1] == '\r') --end;
  return std::string_view(text).substr(begin, end - begin);
}

int SourceSet::add(SourceFile f) {
  f.line_starts.clear();
  // Reserving for lines of 8 bytes on average saves regrowing (which touches twice the memory)
  // and costs nothing where the guess is too high: untouched memory is never faulted in.
  f.line_starts.reserve(f.text.size() / 8 + 16);
  prefer_huge_pages(f.line_starts.data(), f.line_starts.capacity() * sizeof(std::uint32_t));
  f.line_starts.push_back(0);
  for (const char* p = f.text.data(); (p = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(f.text.data() + f.text.size() - p)))) != nullptr;) {
    ++p;
    f.line_starts.push_back(static_cast<std::uint32_t>(p - f.text.data()));
  }
  // A final newline does not start another line.
  if (!f.text.empty() && f.text.back() == '\n') f.line_starts.pop_back();
  files.push_back(std::move(f));
  return static_cast<int>(files.size() - 1);
}

Diagnostic& Diagnostics::error(SourceLoc loc, std::string message) {
  ++errors_;
  list_.push_back({Severity::Error, loc, std::move(message), {}, {}, {}});
  return list_.back();
}

Diagnostics::Kind& Diagnostics::kind(std::string_view name) {
  if (last_kind_ < kinds_.size() && kinds_[last_kind_].name == name) return kinds_[last_kind_];
  for (last_kind_ = 0; last_kind_ < kinds_.size(); ++last_kind_)
    if (kinds_[last_kind_].name == name) return kinds_[last_kind_];
  kinds_.push_back({std::string(name), true, false});
  refresh_kinds();
  return kinds_.back();
}

void Diagnostics::refresh_kinds() {
  for (auto& k : kinds_) {
    k.enabled = k.name.empty() || flags_.enabled(k.name);
    k.error = !k.name.empty() && flags_.is_error(k.name);
  }
}

bool Diagnostics::take(std::string_view name, SourceLoc loc) {
  if (!allows_.empty() && allowed(loc, name)) return false;
  if (kind_limit_ <= 0) return true;
  Kind& k = kind(name);
  if (!k.enabled) return false;
  if (k.error || k.kept < kind_limit_) return true;
  ++warnings_;
  ++k.skipped;
  return false;
}

Diagnostic& Diagnostics::warning(SourceLoc loc, std::string message) {
  if (flags_.all_errors) return error(loc, std::move(message) + " [-Werror]");
  if (!take("", loc)) {
    dropped_ = Diagnostic{Severity::Note, {}, {}, {}, {}, {}};
    return dropped_;
  }
  if (kind_limit_ > 0) ++kind("").kept;
  ++warnings_;
  list_.push_back({Severity::Warning, loc, std::move(message), {}, {}, {}});
  return list_.back();
}

Diagnostic& Diagnostics::warning(SourceLoc loc, std::string message, std::string_view name) {
  if (name.empty()) return warning(loc, std::move(message));
  if (!flags_.enabled(name) || (!allows_.empty() && allowed(loc, name))) {
    dropped_ = Diagnostic{Severity::Note, {}, {}, {}, {}, {}};
    return dropped_;
  }
  if (flags_.is_error(name)) {
    ++errors_;
    list_.push_back({Severity::Error, loc, std::move(message), {}, std::string(name), {}});
  } else if (!take(name, loc)) {
    dropped_ = Diagnostic{Severity::Note, {}, {}, {}, {}, {}};
    return dropped_;
  } else {
    if (kind_limit_ > 0) ++kind(name).kept;
    ++warnings_;
    list_.push_back({Severity::Warning, loc, std::move(message), {}, std::string(name), {}});
  }
  return list_.back();
}

namespace {
std::uint64_t line_key(int file, int line) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(file)) << 32) | static_cast<std::uint32_t>(line);
}
bool name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'; }
}  // namespace

bool Diagnostics::allowed(SourceLoc loc, std::string_view name) const {
  auto it = allows_.find(line_key(loc.file, loc.line));
  if (it == allows_.end()) return false;
  return std::find(it->second.begin(), it->second.end(), name) != it->second.end();
}

bool Diagnostics::allow_from_comments(const SourceFile& f, int file) {
  static constexpr std::string_view kMarker = "tmcl: allow";
  const std::string_view text = f.text;
  bool ok = true;
  for (std::size_t p = text.find(kMarker); p != std::string_view::npos; p = text.find(kMarker, p + 1)) {
    auto line = static_cast<int>(std::upper_bound(f.line_starts.begin(), f.line_starts.end(), p) - f.line_starts.begin());
    const std::string_view l = f.line(line);
    const std::size_t col = p - f.line_starts[static_cast<std::size_t>(line - 1)];
    if (col >= l.size()) continue;  // a line too long to have been read as one
    // Alone on its line: nothing but blanks before the comment's "//", "/*" or ";".
    std::size_t opener = l.find_first_of("/;");
    bool alone = opener != std::string_view::npos && opener < col &&
                 l.find_first_not_of(" \t") == opener;
    int target = alone ? line + 1 : line;
    // The names: one word, then more only after commas; anything after is the reason.
    std::size_t q = col + kMarker.size();
    for (;;) {
      while (q < l.size() && (l[q] == ' ' || l[q] == '\t')) ++q;
      std::size_t e = q;
      while (e < l.size() && name_char(l[e])) ++e;
      std::string_view name = l.substr(q, e - q);
      if (name.empty()) break;
      if (find_warning(name)) {
        allows_[line_key(file, target)].emplace_back(name);
      } else {
        std::vector<std::string_view> names;
        for (const auto& w : warning_table()) names.push_back(w.name);
        SourceLoc at{file, line, static_cast<int>(q) + 1, static_cast<int>(e - q)};
        auto& d = warning(at, "'" + std::string(name) + "' in a 'tmcl: allow' comment is not the name of a warning");
        suggest(d, at, name, closest_match(name, names));
        ok = false;
      }
      q = e;
      while (q < l.size() && (l[q] == ' ' || l[q] == '\t')) ++q;
      if (q >= l.size() || l[q] != ',') break;
      ++q;
    }
  }
  return ok;
}

const std::vector<WarningInfo>& warning_table() {
  // Assembler warnings first, then the control-flow analysis (asm/analysis, docs/analysis.md).
  static const std::vector<WarningInfo> table = {
      {"address", true, "a jump, call or VECT address outside the program"},
      {"keyword-value", true, "a number where a keyword stands that names no keyword of that kind"},
      {"keyword-name", true, "a constant with the name of a keyword"},
      {"target", true, "a motor, bank, parameter, variable or value the target module does not have"},
      {"call-depth", true, "CSUB nested deeper than the module's call stack"},
      {"recursion", true, "a subroutine that can call itself"},
      {"stack-leak", true, "a path that leaves a subroutine without RSUB, or loops through CSUB"},
      {"rsub", true, "RSUB reachable with an empty call stack"},
      {"reti", true, "an interrupt handler that can end without RETI, or RETI outside any handler"},
      {"vect", true, "VECT to no instruction, EI of an interrupt no VECT sets, interrupts never enabled"},
      {"unreachable", true, "instructions no path reaches"},
      {"fall-off", true, "a path that runs past the last instruction"},
      {"eeprom-wear", true, "an EEPROM write in a loop without a visible bound"},
      {"wait-in-handler", true, "WAIT inside an interrupt handler"},
  };
  return table;
}

std::vector<std::string> warning_names() {
  std::vector<std::string> names;
  for (const auto& w : warning_table()) names.emplace_back(w.name);
  return names;
}

const WarningInfo* find_warning(std::string_view name) {
  for (const auto& w : warning_table())
    if (w.name == name) return &w;
  return nullptr;
}

bool WarningOptions::enabled(std::string_view name) const {
  if (errors.count(name)) return true;
  if (off.count(name)) return false;
  if (on.count(name)) return true;
  const WarningInfo* w = find_warning(name);
  return w == nullptr || w->on_by_default;
}

bool WarningOptions::is_error(std::string_view name) const { return all_errors || errors.count(name) > 0; }

bool WarningOptions::parse(std::string_view arg, std::string& error) {
  error.clear();
  if (arg == "-Werror") {
    all_errors = true;
    return true;
  }
  if (arg.substr(0, 2) != "-W" || arg.size() == 2) return false;
  std::string_view name = arg.substr(2);
  if (name == "all") {
    // As GCC reads it: every warning on, but a -Wno-NAME, before or after, keeps its warning off
    // (enabled() reads `off` first), so `-Wno-unreachable -Wall` still drops that one.
    for (const auto& w : warning_table()) on.insert(std::string(w.name));
    return true;
  }
  std::set<std::string, std::less<>>* into = &on;
  if (name.substr(0, 6) == "error=") {
    name = name.substr(6);
    into = &errors;
  } else if (name.substr(0, 3) == "no-") {
    name = name.substr(3);
    into = &off;
  }
  if (!find_warning(name)) {
    std::vector<std::string_view> names;
    for (const auto& w : warning_table()) names.push_back(w.name);
    error = "unknown warning '" + std::string(name) + "' in " + std::string(arg);
    std::string hint = closest_match(name, names);
    if (!hint.empty()) error += " (did you mean '" + hint + "'?)";
    return false;
  }
  if (into != &off) off.erase(std::string(name));
  if (into == &off) {
    on.erase(std::string(name));
    errors.erase(std::string(name));
  }
  into->insert(std::string(name));
  return true;
}

void Diagnostics::note(Diagnostic& d, SourceLoc loc, std::string message) {
  d.notes.push_back({Severity::Note, loc, std::move(message), {}, {}, {}});
}

void Diagnostics::suggest(Diagnostic& d, SourceLoc loc, std::string_view wrote, const std::string& hint) {
  suggest(d, loc, loc, wrote, hint);
}

void Diagnostics::suggest(Diagnostic& d, SourceLoc loc, SourceLoc replace, std::string_view wrote, const std::string& hint) {
  if (hint.empty()) return;
  note(d, loc, "did you mean '" + hint + "'?");
  SourceLoc end = replace;
  end.col += replace.len;
  d.fixes.push_back({"replace '" + std::string(wrote) + "' with '" + hint + "'", replace, end, hint});
}

namespace {

const char* severity_word(Severity s) {
  switch (s) {
    case Severity::Note: return "note";
    case Severity::Warning: return "warning";
    case Severity::Error: return "error";
  }
  return "?";
}

void render_one(std::string& out, const Diagnostic& d, const SourceSet& sources, bool with_chain) {
  const SourceFile* f = (d.loc.file >= 0 && static_cast<std::size_t>(d.loc.file) < sources.files.size())
                            ? &sources.files[static_cast<std::size_t>(d.loc.file)]
                            : nullptr;
  if (f && with_chain) {
    // "In file included from" lines, innermost includer first.
    for (const SourceFile* c = f; c->includer >= 0;) {
      const SourceFile& parent = sources.files[static_cast<std::size_t>(c->includer)];
      out += "In file included from " + parent.name + ":" + std::to_string(c->include_line) + ":\n";
      c = &parent;
    }
  }
  // Column 0: a place known only by file and line (an object's instruction), with no text to show.
  if (f && d.loc.col <= 0)
    out += f->name + ":" + std::to_string(d.loc.line) + ": ";
  else if (f)
    out += f->name + ":" + std::to_string(d.loc.line) + ":" + std::to_string(d.loc.col) + ": ";
  else
    out += "tmclasm: ";
  out += severity_word(d.severity);
  out += ": " + d.message;
  if (!d.name.empty()) out += (d.severity == Severity::Error ? " [-Werror=" : " [-W") + d.name + "]";
  out += "\n";
  if (f && d.loc.line > 0 && d.loc.col > 0) {
    std::string_view line = f->line(d.loc.line);
    // The same line-and-caret form as every other file reader's (diag_text.hpp).
    if (!line.empty() || d.loc.col <= 1) out += caret_lines(line, d.loc.col, d.loc.len);
  }
}

}  // namespace

std::string render_diagnostic(const Diagnostic& d, const SourceSet& sources) {
  std::string out;
  render_one(out, d, sources, true);
  for (const auto& n : d.notes) render_one(out, n, sources, false);
  return out;
}

std::vector<const Diagnostic*> Diagnostics::sorted(const SourceSet& sources) const {
  // In source order, whichever phase found them; location-less ones (limits, files) last.
  std::vector<const Diagnostic*> order;
  for (const auto& d : list_) order.push_back(&d);
  // The key of a place is the path to it from its root file: the root's index, then the line of
  // each #include on the way, then line and column, so included files sort where they are included.
  auto key = [&sources](const Diagnostic* d) {
    std::vector<int> k;
    if (d->loc.file < 0) return std::vector<int>{INT32_MAX};
    k.push_back(d->loc.col);
    k.push_back(d->loc.line);
    int f = d->loc.file;
    while (sources.files[static_cast<std::size_t>(f)].includer >= 0) {
      k.push_back(sources.files[static_cast<std::size_t>(f)].include_line);
      f = sources.files[static_cast<std::size_t>(f)].includer;
    }
    k.push_back(f);
    std::reverse(k.begin(), k.end());
    return k;
  };
  std::vector<std::vector<int>> keys;
  for (const auto* d : order) keys.push_back(key(d));
  std::vector<std::size_t> idx(order.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  std::stable_sort(idx.begin(), idx.end(), [&keys](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
  std::vector<const Diagnostic*> by_place;
  for (auto i : idx) by_place.push_back(order[i]);
  return by_place;
}

std::string Diagnostics::render(const SourceSet& sources, int error_limit) const {
  // Past the limit (--error-limit) nothing more is shown, only how much was left out: 1 MB of
  // garbage gives 100,000 errors, and the first ones are the ones a user reads.
  // Warnings of one kind past the limit are summed up in one line per kind: 80,000 unreachable
  // stretches are one finding to read, not 80,000.
  std::string out;
  int shown = 0;
  long long more_errors = 0, more_warnings = 0;
  std::map<std::string, long long, std::less<>> shown_of_kind, more_of_kind;
  for (const auto& k : kinds_)
    if (k.skipped > 0) more_of_kind[k.name] += k.skipped;
  for (const auto* d : sorted(sources)) {
    if (error_limit > 0 && shown >= error_limit) {
      ++(d->severity == Severity::Error ? more_errors : more_warnings);
      continue;
    }
    if (error_limit > 0 && d->severity == Severity::Warning && ++shown_of_kind[d->name] > error_limit) {
      ++more_of_kind[d->name];
      continue;
    }
    out += render_diagnostic(*d, sources);
    if (d->severity == Severity::Error) ++shown;
  }
  if (more_errors + more_warnings > 0) out += more_errors_note("", more_errors, more_warnings);
  for (const auto& [name, count] : more_of_kind)
    out += "note: " + std::to_string(count) + " more " + (name.empty() ? std::string() : "-W" + name + " ") + "warning" +
           (count == 1 ? "" : "s") + " not shown (--error-limit N changes the limit, 0 shows all)\n";
  return out;
}

}  // namespace tmcl
