// The profile file reader (format in profile_file.hpp and docs/profiles.md). One pass over the
// lines: each line is split into words, "quoted" text and ATTR=VALUE attributes, checked against
// the table of statement keys, and applied to the store; every error is collected with its column
// and the reader goes on with the next line, so a user mends a whole file in one go.
#include "tmcl/profile_file.hpp"

#include <algorithm>
#include <cctype>
#include <map>
#include <tuple>

#include "tmcl/isa.hpp"
#include "tmcl/numbers.hpp"
#include "tmcl/os_files.hpp"

namespace tmcl {
namespace {

constexpr std::int64_t kValueMin = -2147483648LL;  // a parameter value is a 32-bit field,
constexpr std::int64_t kValueMax = 4294967295LL;   // signed or unsigned

// Attributes a statement may carry besides src= and unverified, which every statement may.
enum AttrBit : unsigned { kDefault = 1, kUnit = 2, kEepromVars = 4, kFallback = 8, kValues = 16, kNotSimulated = 32 };

struct KeyInfo {
  std::string_view key;
  int min_args, max_args;  // positional arguments (max -1: any number)
  unsigned attrs;
  bool once;               // at most one line with this key
  std::string_view shape;  // for messages
};

constexpr KeyInfo kKeys[] = {
    {"tmcl-profile", 1, 1, 0, true, "tmcl-profile 1"},
    {"name", 1, 1, 0, true, "name NAME"},
    {"title", 1, 1, 0, true, "title \"TEXT\""},
    {"alias", 1, -1, 0, false, "alias NAME..."},
    {"based-on", 1, 1, 0, true, "based-on NAME"},
    {"source", 2, 2, 0, false, "source ID \"TEXT\""},
    {"firmware", 1, 1, 0, true, "firmware NNNNVnnn"},
    {"motors", 1, 1, 0, true, "motors N"},
    {"program-memory", 1, 2, 0, true, "program-memory N|unlimited [eeprom|ram]"},
    {"user-variables", 1, 1, kEepromVars, true, "user-variables N [eeprom=M]"},
    {"coordinates", 1, 1, 0, true, "coordinates N"},
    {"standalone", 1, 1, 0, true, "standalone yes|no"},
    {"include-file", 1, 1, 0, true, "include-file FILE.inc"},
    {"commands", 1, -1, 0, false, "commands N|N-M|MNEMONIC|all..."},
    {"parameters", 1, 1, 0, true, "parameters listed|any"},
    {"motion", 1, 1, kFallback, true, "motion CORE [fallback=CORE]"},
    {"motion-constant", 2, 2, 0, false, "motion-constant NAME VALUE"},
    {"axis", 4, 4, kDefault | kUnit | kValues | kNotSimulated, false,
     "axis N \"NAME\" MIN..MAX ACCESS [default=V] [unit=U] [values=SET] [not-simulated=\"REASON\"]"},
    {"global", 5, 5, kDefault | kUnit | kValues | kNotSimulated, false,
     "global BANK N \"NAME\" MIN..MAX ACCESS [default=V] [unit=U] [values=SET] [not-simulated=\"REASON\"]"},
    {"ports", 1, 1, 0, true, "ports listed|any"},
    {"port", 5, 6, kDefault | kUnit, false, "port BANK N \"NAME\" in|out digital|analog|bits [MIN..MAX] [default=V] [unit=U]"},
    {"vector", 3, 3, 0, false, "vector N NAME \"MEANING\""},
    {"without", 2, -1, 0, false, "without axis N...|global BANK N...|vector N..."},
};

constexpr std::string_view kAttrNames[] = {"src", "unverified", "default", "unit", "eeprom", "fallback", "values", "not-simulated"};

struct Word {
  std::string_view text;
  int col = 0, len = 0;
  bool quoted = false;
};
struct Attr {
  std::string_view key;
  Word value;
  bool has_value = false;
  int col = 0, len = 0;
};

struct Reader {
  ProfileStore& s;
  const std::string& file;
  std::vector<FileDiag>& diags;
  const ProfileLookup& lookup;

  int line_no = 0;
  std::string_view source = {};  // the current line
  std::map<std::string_view, int> seen = {};  // key -> first line
  std::map<std::string_view, bool> attempted = {};  // keys of every line, good or bad
  std::map<std::string_view, int> sources = {};  // source id -> line
  std::map<std::pair<int, int>, int> defined = {};  // (bank or -1 for axis, number) -> line, this file
  std::map<int, int> vectors_defined = {};
  bool started = false, based = false, commands_given = false, stopped = false;
  const Attr* values_ = nullptr;  // the current line's values=, for parameter()
  const Attr* not_simulated_ = nullptr;  // the current line's not-simulated=, for parameter()
  bool any_statement_after_header = false;

  void error(int col, int len, const std::string& msg) {
    diags.push_back({file, line_no, col, std::max(1, len), msg, std::string(source)});
  }
  void error(const Word& w, const std::string& msg) { error(w.col, w.len, msg); }
  void error(const Attr& a, const std::string& msg) { error(a.col, a.len, msg); }

  std::string_view keep(std::string text) { return s.strings.emplace_back(std::move(text)); }

  // Splits the line into positional words and attributes; false after an error.
  bool split(std::vector<Word>& words, std::vector<Attr>& attrs) {
    const std::string_view l = source;
    std::size_t i = 0;
    auto col = [](std::size_t at) { return static_cast<int>(at) + 1; };
    auto quoted = [&](std::size_t at, Word& w) {  // l[at] == '"'
      const std::size_t end = l.find('"', at + 1);
      if (end == std::string_view::npos) {
        error(col(at), static_cast<int>(l.size() - at), "unterminated \"quoted text\" (it ends at the end of the line)");
        return std::string_view::npos;
      }
      w = {l.substr(at + 1, end - at - 1), col(at), static_cast<int>(end - at + 1), true};
      return end + 1;
    };
    while (i < l.size()) {
      const char c = l[i];
      if (c == ' ' || c == '\t' || c == '\r') {
        ++i;
        continue;
      }
      if (c == '#') break;
      if (c == '"') {
        Word w;
        i = quoted(i, w);
        if (i == std::string_view::npos) return false;
        words.push_back(w);
        continue;
      }
      std::size_t j = i;
      while (j < l.size() && l[j] != ' ' && l[j] != '\t' && l[j] != '\r' && l[j] != '"' && l[j] != '#' && l[j] != '=') ++j;
      if (j < l.size() && l[j] == '=') {
        Attr a;
        a.key = l.substr(i, j - i);
        a.col = col(i);
        a.has_value = true;
        std::size_t k = j + 1;
        if (k < l.size() && l[k] == '"') {
          k = quoted(k, a.value);
          if (k == std::string_view::npos) return false;
        } else {
          std::size_t e = k;
          while (e < l.size() && l[e] != ' ' && l[e] != '\t' && l[e] != '\r' && l[e] != '#') ++e;
          a.value = {l.substr(k, e - k), col(k), static_cast<int>(e - k), false};
          k = e;
        }
        a.len = static_cast<int>(k - i);
        if (a.key.empty()) {
          error(a.col, 1, "'=' without an attribute name before it");
          return false;
        }
        attrs.push_back(a);
        i = k;
        continue;
      }
      if (j < l.size() && l[j] == '"') {
        error(col(j), 1, "'\"' inside a word (put a space before the quoted text)");
        return false;
      }
      Word w{l.substr(i, j - i), col(i), static_cast<int>(j - i), false};
      if (w.text == "unverified") {
        attrs.push_back({w.text, {}, false, w.col, w.len});
      } else {
        words.push_back(w);
      }
      i = j;
    }
    return true;
  }

  bool number(const Word& w, std::int64_t lo, std::int64_t hi, std::int64_t& out, const char* what) {
    if (!w.quoted && parse_int(w.text, lo, hi, out)) return true;
    std::int64_t any = 0;
    if (!w.quoted && parse_int(w.text, INT64_MIN, INT64_MAX, any))
      error(w, std::string(what) + " " + std::string(w.text) + " is out of range (" + std::to_string(lo) + " to " +
                   std::to_string(hi) + ")");
    else
      error(w, std::string("expected ") + what + " (a decimal number from " + std::to_string(lo) + " to " +
                   std::to_string(hi) + "), found '" + std::string(w.text) + "'");
    return false;
  }

  static bool valid_name(std::string_view n) {
    if (n.empty() || n.size() > 64) return false;
    for (char c : n)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.' || c == '+')) return false;
    return n != "." && n != "..";
  }

  // MIN..MAX
  bool range(const Word& w, std::int64_t& lo, std::int64_t& hi) {
    const std::size_t dots = w.text.find("..");
    if (w.quoted || dots == std::string_view::npos) {
      error(w, "expected a range MIN..MAX (e.g. 0..2047), found '" + std::string(w.text) + "'");
      return false;
    }
    Word a{w.text.substr(0, dots), w.col, static_cast<int>(dots), false};
    Word b{w.text.substr(dots + 2), w.col + static_cast<int>(dots) + 2, static_cast<int>(w.text.size() - dots - 2), false};
    if (!number(a, kValueMin, kValueMax, lo, "a range's minimum") || !number(b, kValueMin, kValueMax, hi, "a range's maximum"))
      return false;
    if (lo > hi) {
      error(w, "the range's minimum " + std::to_string(lo) + " is above its maximum " + std::to_string(hi));
      return false;
    }
    return true;
  }

  bool access(const Word& w, std::uint8_t& out) {
    out = 0;
    for (char c : w.text) {
      const std::uint8_t bit = c == 'R' ? kRead : c == 'W' ? kWrite : c == 'E' ? kEeprom : c == 'A' ? kAutoStore : 0;
      if (bit == 0 || (out & bit) || w.quoted) {
        error(w, "expected access letters (R, W, E, A; e.g. RWE), found '" + std::string(w.text) + "'");
        return false;
      }
      out |= bit;
    }
    if (!(out & kRead)) {
      error(w, "access '" + std::string(w.text) + "' lacks R: every parameter can be read");
      return false;
    }
    if ((out & kAutoStore) && !(out & kWrite)) {
      error(w, "access A (stored on every write) needs W");
      return false;
    }
    return true;
  }

  // src=ID[:PLACE][,ID[:PLACE]...]: every ID declared by an earlier source line.
  bool check_sources(const Attr& a) {
    std::string_view v = a.value.text;
    if (v.empty()) {
      error(a, "src= needs a source ID (declared by a 'source ID \"TEXT\"' line)");
      return false;
    }
    for (std::size_t p = 0; p <= v.size();) {
      std::size_t q = std::min(v.find(',', p), v.size());
      std::string_view item = v.substr(p, q - p);
      std::string_view id = item.substr(0, item.find(':'));
      if (!sources.count(id)) {
        std::vector<std::string_view> ids;
        for (const auto& [k, line] : sources) ids.push_back(k);
        std::string hint = closest_match(id, ids);
        error(a.value.col + static_cast<int>(p), static_cast<int>(id.size()),
              "unknown source '" + std::string(id) + "' (declare it first: source " + std::string(id) + " \"TEXT\")" +
                  (hint.empty() ? "" : "; did you mean '" + hint + "'?"));
        return false;
      }
      p = q + 1;
    }
    return true;
  }

  void statement() {
    std::vector<Word> words;
    std::vector<Attr> attrs;
    if (!split(words, attrs)) return;
    if (words.empty() && attrs.empty()) return;
    if (words.empty()) {
      error(attrs[0], "a line starts with a key, not an attribute");
      return;
    }
    const Word key = words[0];
    const KeyInfo* info = nullptr;
    for (const auto& k : kKeys)
      if (k.key == key.text) info = &k;
    if (!started) {
      started = true;
      if (!info || info->key != "tmcl-profile" || words.size() != 2 || words[1].text != "1") {
        error(key, "not a tmcl profile: the first line must be 'tmcl-profile 1' (docs/profiles.md)");
        stopped = true;
        return;
      }
      seen[info->key] = line_no;
      return;
    }
    if (!info) {
      std::vector<std::string_view> names;
      for (const auto& k : kKeys) names.push_back(k.key);
      std::string hint = closest_match(key.text, names);
      error(key, "unknown key '" + std::string(key.text) + "'" + (hint.empty() ? "" : "; did you mean '" + hint + "'?"));
      return;
    }
    attempted[info->key] = true;
    const int nargs = static_cast<int>(words.size()) - 1;
    if (nargs < info->min_args || (info->max_args >= 0 && nargs > info->max_args)) {
      const Word& at = nargs < info->min_args ? key : words[static_cast<std::size_t>(info->max_args) + 1];
      error(at, std::string(nargs < info->min_args ? "too few" : "too many") + " values for '" + std::string(info->key) +
                    "' (expected: " + std::string(info->shape) + ")");
      return;
    }
    if (info->once) {
      auto [it, fresh] = seen.emplace(info->key, line_no);
      if (!fresh) {
        error(key, "a second '" + std::string(info->key) + "' line (the first is line " + std::to_string(it->second) + ")");
        return;
      }
    }
    // Attributes: known, allowed here, given once.
    const Attr* def = nullptr;
    const Attr* unit = nullptr;
    const Attr* eeprom = nullptr;
    const Attr* fallback = nullptr;
    const Attr* values = nullptr;
    const Attr* not_simulated = nullptr;
    const Attr* unverified = nullptr;
    const Attr* src = nullptr;
    bool attrs_ok = true;
    for (const Attr& a : attrs) {
      const Attr** slot = nullptr;
      unsigned need = 0;
      if (a.key == "src") slot = &src;
      else if (a.key == "unverified") slot = &unverified;
      else if (a.key == "default") slot = &def, need = kDefault;
      else if (a.key == "unit") slot = &unit, need = kUnit;
      else if (a.key == "eeprom") slot = &eeprom, need = kEepromVars;
      else if (a.key == "fallback") slot = &fallback, need = kFallback;
      else if (a.key == "values") slot = &values, need = kValues;
      else if (a.key == "not-simulated") slot = &not_simulated, need = kNotSimulated;
      if (!slot) {
        std::string hint = closest_match(a.key, std::vector<std::string_view>(std::begin(kAttrNames), std::end(kAttrNames)));
        error(a.col, static_cast<int>(a.key.size()),
              "unknown attribute '" + std::string(a.key) + "'" + (hint.empty() ? "" : "; did you mean '" + hint + "'?"));
        attrs_ok = false;
        continue;
      }
      if (need && !(info->attrs & need)) {
        error(a, "'" + std::string(info->key) + "' takes no " + std::string(a.key) + "= (expected: " + std::string(info->shape) + ")");
        attrs_ok = false;
        continue;
      }
      if (*slot) {
        error(a, "a second " + std::string(a.key) + " on one line");
        attrs_ok = false;
        continue;
      }
      *slot = &a;
    }
    if (src && !check_sources(*src)) attrs_ok = false;
    const bool param_line = info->key == "axis" || info->key == "global";
    std::uint8_t unverified_facts = 0;
    if (unverified) {
      if (!unverified->has_value) {
        unverified_facts = 0xFF;
      } else if (!param_line) {
        error(*unverified, "'unverified' on a '" + std::string(info->key) + "' line takes no value: the whole line is unverified");
        attrs_ok = false;
      } else {
        std::string_view v = unverified->value.text;
        for (std::size_t p = 0; p <= v.size();) {
          std::size_t q = std::min(v.find(',', p), v.size());
          std::string_view f = v.substr(p, q - p);
          static constexpr std::pair<std::string_view, Fact> kFacts[] = {
              {"name", kFactName}, {"range", kFactRange}, {"access", kFactAccess},
              {"default", kFactDefault}, {"unit", kFactUnit}, {"exists", kFactExists}};
          bool found = false;
          for (const auto& [n, bit] : kFacts)
            if (f == n) unverified_facts |= bit, found = true;
          if (!found) {
            error(unverified->value.col + static_cast<int>(p), static_cast<int>(std::max<std::size_t>(f.size(), 1)),
                  "unknown fact '" + std::string(f) + "' for unverified= (name, range, access, default, unit, exists)");
            attrs_ok = false;
            break;
          }
          p = q + 1;
        }
      }
    }
    if (!attrs_ok) return;
    if (info->key == "based-on" && any_statement_after_header) {
      error(key, "'based-on' must come before the facts it is the base of (right after name and title)");
      return;
    }
    if (info->key != "name" && info->key != "title" && info->key != "source" && info->key != "alias" &&
        info->key != "based-on")
      any_statement_after_header = true;
    if (unverified_facts && !param_line) s.unverified.push_back(keep(std::string(info->key)));
    if (not_simulated && not_simulated->value.text.empty()) {
      error(*not_simulated, "not-simulated= needs the reason the virtual module does not simulate the parameter");
      return;
    }
    values_ = values;
    not_simulated_ = not_simulated;
    apply(*info, words, def, unit, eeprom, fallback, src, unverified_facts);
  }

  void apply(const KeyInfo& info, const std::vector<Word>& w, const Attr* def, const Attr* unit, const Attr* eeprom,
             const Attr* fallback, const Attr* src, std::uint8_t unverified_facts) {
    Profile& p = s.profile;
    const std::string_view k = info.key;
    std::int64_t n = 0;
    if (k == "name") {
      if (!valid_name(w[1].text) || w[1].quoted)
        return error(w[1], "a profile name is letters, digits, '-', '_', '.' and '+' (e.g. tmcm-1110), not '" +
                               std::string(w[1].text) + "'");
      p.name = w[1].text;
    } else if (k == "title") {
      if (w[1].text.empty()) return error(w[1], "the title is empty");
      p.title = w[1].text;
    } else if (k == "alias") {
      for (std::size_t i = 1; i < w.size(); ++i) {
        if (!valid_name(w[i].text) || w[i].quoted) return error(w[i], "an alias is a name like tmcm-1110, not '" + std::string(w[i].text) + "'");
        s.aliases.push_back(w[i].text);
      }
    } else if (k == "based-on") {
      std::string why;
      const Profile* base = lookup ? lookup(w[1].text, why) : nullptr;
      // Its own name means the profile this file hides (docs/profiles.md); without one, a cycle.
      if (!base && why.empty() && !p.name.empty() && w[1].text == p.name)
        why = "based-on cycle: " + std::string(p.name) + " -> " + std::string(p.name) + " (based-on its own name means the profile '" +
              std::string(p.name) + "' this file hides, and there is none)";
      if (!base) return error(w[1], why.empty() ? "unknown profile '" + std::string(w[1].text) + "' for based-on" : why);
      inherit(*base);
      // `based-on NAME unverified`: the base module's facts, which no source confirms for this
      // one (its manual is not at hand): every range, access, default and unit it inherits.
      if (unverified_facts) {
        for (auto* table : {&s.axis, &s.bank0, &s.bank3})
          for (ParamInfo& q : *table) q.unverified |= kFactRange | kFactAccess | kFactDefault | kFactUnit;
        for (IoPort& q : s.ports) q.unverified = true;
      }
    } else if (k == "without") {
      without(w);
    } else if (k == "source") {
      if (!valid_name(w[1].text) || w[1].quoted) return error(w[1], "a source ID is a short name such as M or TMCM1110");
      auto [it, fresh] = sources.emplace(w[1].text, line_no);
      if (!fresh) return error(w[1], "source " + std::string(w[1].text) + " is already declared at line " + std::to_string(it->second));
    } else if (k == "firmware") {
      // Usually a 4-digit module number, 'V', the major digit and two minor digits (1110V103);
      // older modules differ (the TMCM-351's manual shows 351V.442), so any 8 printable
      // characters with a 'V' are taken.
      const std::string_view f = w[1].text;
      bool ok = f.size() == 8 && f.find('V') != std::string_view::npos;
      for (char c : f) ok = ok && c > ' ' && c < 0x7f;
      if (!ok)
        return error(w[1], "the firmware reply to command 136 is 8 characters with a 'V': usually the 4-digit module "
                           "number, 'V', major digit, 2-digit minor (e.g. 1110V103), not '" + std::string(f) + "'");
      p.firmware = f;
    } else if (k == "motors") {
      if (!number(w[1], 1, 255, n, "a motor count")) return;
      p.motors = static_cast<int>(n);
    } else if (k == "program-memory") {
      if (w[1].text == "unlimited") {
        p.program_memory = 0;
      } else {
        if (!number(w[1], 1, 1 << 20, n, "a number of instructions")) return;
        p.program_memory = static_cast<int>(n);
      }
      if (w.size() > 2) {
        if (w[2].text != "eeprom" && w[2].text != "ram")
          return error(w[2], "where the program is kept: 'eeprom' (it survives a power cycle) or 'ram', not '" +
                                 std::string(w[2].text) + "'");
        p.program_store = w[2].text == "eeprom" ? ProgramStore::Eeprom : ProgramStore::Ram;
      }
    } else if (k == "user-variables") {
      if (!number(w[1], 0, 256, n, "a number of user variables")) return;
      p.user_vars = static_cast<int>(n);
      std::int64_t e = 0;
      if (eeprom && !number(eeprom->value, 0, n, e, "a number of EEPROM-backed user variables")) return;
      p.eeprom_user_vars = static_cast<int>(e);
    } else if (k == "coordinates") {
      if (!number(w[1], 0, 256, n, "a number of coordinates per motor")) return;
      p.coords = static_cast<int>(n);
    } else if (k == "include-file") {
      // The module's own include file among the bundled ones (tmclctl's console predefines it).
      const std::string_view f = w[1].text;
      if (f.empty() || os::has_separator(f))
        return error(w[1], "include-file names a bundled include file such as USB-2-SD.inc, not '" + std::string(f) + "'");
      p.include_file = f;
    } else if (k == "standalone") {
      if (w[1].text != "yes" && w[1].text != "no")
        return error(w[1], "standalone takes yes or no, not '" + std::string(w[1].text) + "'");
      p.standalone = w[1].text == "yes";
    } else if (k == "commands") {
      if (!commands_given) p.commands.reset();
      commands_given = true;
      for (std::size_t i = 1; i < w.size(); ++i) command_item(w[i]);
    } else if (k == "parameters") {
      if (w[1].text != "any" && w[1].text != "listed")
        return error(w[1], "parameters takes 'listed' (only the axis and global lines; checked) or 'any' (every number, "
                           "unchecked), not '" + std::string(w[1].text) + "'");
      p.any_parameter = w[1].text == "any";
    } else if (k == "motion") {
      if (!valid_name(w[1].text)) return error(w[1], "a motion core is a name such as tmc4361, not '" + std::string(w[1].text) + "'");
      p.default_motion = w[1].text;
      if (fallback) {
        if (!valid_name(fallback->value.text)) return error(fallback->value, "a motion core is a name such as ideal");
        p.fallback_motion = fallback->value.text;
      }
    } else if (k == "motion-constant") {
      if (!valid_name(w[1].text)) return error(w[1], "a constant's name is a word such as clock");
      if (!number(w[2], INT64_MIN / 2, INT64_MAX / 2, n, "a constant's value")) return;
      for (auto& c : s.constants)
        if (c.name == w[1].text) return error(w[1], "motion constant " + std::string(w[1].text) + " is given twice");
      s.constants.push_back({w[1].text, n});
    } else if (k == "axis" || k == "global") {
      parameter(k == "axis", w, def, unit, src, unverified_facts);
    } else if (k == "ports") {
      if (w[1].text != "any" && w[1].text != "listed")
        return error(w[1], "ports takes 'listed' (only the port lines) or 'any' (every port 0..255 of banks 0 to 2, "
                           "unchecked), not '" + std::string(w[1].text) + "'");
      p.any_port = w[1].text == "any";
    } else if (k == "port") {
      port(w, def, unit, src, unverified_facts != 0);
    } else if (k == "vector") {
      if (!number(w[1], 0, 255, n, "an interrupt number")) return;
      if (w[2].quoted || !valid_name(w[2].text)) return error(w[2], "a vector's name is a symbol such as TI_TIMER0");
      auto [it, fresh] = vectors_defined.emplace(static_cast<int>(n), line_no);
      if (!fresh) return error(w[1], "vector " + std::to_string(n) + " is already defined at line " + std::to_string(it->second));
      InterruptVector v{static_cast<std::uint8_t>(n), w[2].text, w[3].text};
      auto old = std::find_if(s.vectors.begin(), s.vectors.end(), [&](const InterruptVector& x) { return x.number == n; });
      if (old != s.vectors.end()) *old = v;
      else s.vectors.push_back(v);
    }
  }

  void command_item(const Word& w) {
    Profile& p = s.profile;
    if (w.text == "all") {
      for (const auto& op : all_ops()) p.commands.set(op.code);
      return;
    }
    if (!w.text.empty() && std::isdigit(static_cast<unsigned char>(w.text[0]))) {
      const std::size_t dash = w.text.find('-');
      std::int64_t a = 0, b = 0;
      Word first{w.text.substr(0, dash), w.col, static_cast<int>(std::min(dash, w.text.size())), false};
      if (!number(first, 0, 255, a, "an opcode")) return;
      b = a;
      if (dash != std::string_view::npos) {
        Word last{w.text.substr(dash + 1), w.col + static_cast<int>(dash) + 1, static_cast<int>(w.text.size() - dash - 1), false};
        if (!number(last, a, 255, b, "the end of an opcode range")) return;
      }
      for (std::int64_t c = a; c <= b; ++c) {
        if (!op_info(static_cast<std::uint8_t>(c))) {
          if (a == b) return error(w, "opcode " + std::to_string(c) + " is not a TMCL command (docs/language.md)");
          continue;  // a range covers the commands there are
        }
        p.commands.set(static_cast<std::size_t>(c));
      }
      return;
    }
    const OpInfo* op = op_by_mnemonic(w.text);
    if (!op) {
      std::vector<std::string_view> names;
      for (const auto& o : all_ops())
        if (!o.mnemonic.empty()) names.push_back(o.mnemonic);
      std::string hint = closest_match(w.text, names);
      return error(w, "'" + std::string(w.text) + "' is not a TMCL command (an opcode, FIRST-LAST, a mnemonic or all)" +
                          (hint.empty() ? "" : "; did you mean '" + hint + "'?"));
    }
    p.commands.set(op->code);
  }

  void parameter(bool axis, const std::vector<Word>& w, const Attr* def, const Attr* unit, const Attr* src,
                 std::uint8_t unverified_facts) {
    std::size_t at = 1;
    std::int64_t bank = -1, n = 0, lo = 0, hi = 0, d = 0;
    if (!axis) {
      if (!number(w[at], 0, 3, bank, "a bank")) return;
      if (bank == 1 || bank == 2) {
        return error(w[at], bank == 2 ? "bank 2 holds the user variables: say how many with 'user-variables N'"
                                      : "bank 1 is not used by TMCL modules; global parameters are in banks 0 and 3");
      }
      ++at;
    }
    const Word& num = w[at];
    if (!number(num, 0, 255, n, "a parameter number")) return;
    const Word& name = w[at + 1];
    if (name.text.empty()) return error(name, "the parameter has no name");
    if (!range(w[at + 2], lo, hi)) return;
    std::uint8_t acc = 0;
    if (!access(w[at + 3], acc)) return;
    if (def) {
      if (!number(def->value, lo, hi, d, "a default within the parameter's range")) return;
    } else {
      d = std::clamp<std::int64_t>(0, lo, hi);
    }
    std::span<const ValueItem> set;
    if (values_ && !value_set(*values_, lo, hi, set)) return;
    if (!set.empty() && def) {
      ParamInfo probe{0, {}, lo, hi, 0, 0, {}, {}, 0, set};
      if (!accepts(probe, d)) return error(def->value, "the default " + std::to_string(d) + " is not in the value set");
    }
    auto [it, fresh] = defined.emplace(std::make_pair(static_cast<int>(bank), static_cast<int>(n)), line_no);
    if (!fresh)
      return error(num, std::string(axis ? "axis parameter " : "global parameter ") + std::to_string(n) +
                            (axis ? "" : " of bank " + std::to_string(bank)) + " is already defined at line " +
                            std::to_string(it->second));
    ParamInfo info{static_cast<std::uint16_t>(n), name.text, lo, hi, acc, static_cast<std::int32_t>(static_cast<std::uint32_t>(d)),
                   unit ? unit->value.text : std::string_view{}, src ? src->value.text : std::string_view{},
                   unverified_facts, set, not_simulated_ ? not_simulated_->value.text : std::string_view{}};
    auto& table = axis ? s.axis : bank == 0 ? s.bank0 : s.bank3;
    auto old = std::find_if(table.begin(), table.end(), [&](const ParamInfo& x) { return x.number == n; });
    if (old != table.end()) *old = info;
    else table.push_back(info);
    if (unverified_facts) {
      std::string phrase = axis ? "axis " + std::to_string(n) : "global " + std::to_string(bank) + " " + std::to_string(n);
      if (unverified_facts != 0xFF) {
        static constexpr std::pair<Fact, std::string_view> kFacts[] = {
            {kFactExists, "exists"}, {kFactName, "name"}, {kFactRange, "range"},
            {kFactAccess, "access"}, {kFactDefault, "default"}, {kFactUnit, "unit"}};
        const char* sep = " ";
        for (const auto& [bit, word] : kFacts)
          if (unverified_facts & bit) phrase += sep + std::string(word), sep = ", ";
      }
      s.unverified.push_back(keep(std::move(phrase)));
    }
  }

  // values=ITEM,ITEM...: N, A..B, or +F (a number that may be added: a flag bit).
  bool value_set(const Attr& a, std::int64_t lo, std::int64_t hi, std::span<const ValueItem>& out) {
    std::vector<ValueItem> set;
    std::string_view v = a.value.text;
    for (std::size_t p = 0; p <= v.size();) {
      std::size_t q = std::min(v.find(',', p), v.size());
      std::string_view item = v.substr(p, q - p);
      Word w{item, a.value.col + static_cast<int>(p), static_cast<int>(std::max<std::size_t>(item.size(), 1)), false};
      ValueItem vi{0, 0, false};
      if (!item.empty() && item[0] == '+') {
        Word f{item.substr(1), w.col + 1, w.len - 1, false};
        if (!number(f, 1, kValueMax, vi.lo, "a flag to add")) return false;
        vi.hi = vi.lo;
        vi.flag = true;
      } else if (const std::size_t dots = item.find(".."); dots != std::string_view::npos) {
        if (!range(w, vi.lo, vi.hi)) return false;
      } else {
        if (!number(w, kValueMin, kValueMax, vi.lo, "a value")) return false;
        vi.hi = vi.lo;
      }
      if (!vi.flag && (vi.lo < lo || vi.hi > hi)) {
        error(w, "value set item '" + std::string(item) + "' is outside the parameter's range " + std::to_string(lo) + ".." +
                     std::to_string(hi));
        return false;
      }
      set.push_back(vi);
      p = q + 1;
    }
    if (std::none_of(set.begin(), set.end(), [](const ValueItem& i) { return !i.flag; })) {
      error(a.value, "a value set needs at least one value or range besides the flags");
      return false;
    }
    out = s.value_sets.emplace_back(std::move(set));
    return true;
  }

  void port(const std::vector<Word>& w, const Attr* def, const Attr* unit, const Attr* src, bool unverified) {
    std::int64_t bank = 0, n = 0, lo = 0, hi = 1, d = 0;
    if (!number(w[1], 0, 2, bank, "an I/O bank (0 digital inputs, 1 analog inputs, 2 outputs)")) return;
    if (!number(w[2], 0, 255, n, "a port number")) return;
    if (w[3].text.empty()) return error(w[3], "the port has no name");
    if (w[4].text != "in" && w[4].text != "out")
      return error(w[4], "a port is 'in' (GIO reads it) or 'out' (SIO writes it), not '" + std::string(w[4].text) + "'");
    const bool output = w[4].text == "out";
    PortKind kind = PortKind::Digital;
    if (w[5].text == "analog") kind = PortKind::Analog;
    else if (w[5].text == "bits") kind = PortKind::Bits;
    else if (w[5].text != "digital")
      return error(w[5], "a port is digital, analog or bits (every digital port of the bank at once), not '" +
                             std::string(w[5].text) + "'");
    if (kind == PortKind::Bits) hi = 255;
    if ((kind == PortKind::Bits) != (n == 255))
      return error(w[2], kind == PortKind::Bits ? "a bits port (every port of the bank at once) is number 255"
                                                : "a port number is 0 to " + std::to_string(kPortCount - 1) + " (255: a bits port)");
    if (w.size() > 6 && !range(w[6], lo, hi)) return;
    if (kind == PortKind::Analog && w.size() <= 6) return error(w[5], "an analog port needs its range MIN..MAX (e.g. 0..4095)");
    if (def) {
      if (!number(def->value, lo, hi, d, "a default within the port's range")) return;
    }
    for (const auto& o : s.ports)
      if (o.bank == bank && o.number == n && o.output == output && !based)
        return error(w[2], std::string(output ? "output" : "input") + " port " + std::to_string(n) + " of bank " +
                               std::to_string(bank) + " is already defined");
    IoPort port{static_cast<std::uint8_t>(bank), static_cast<std::uint8_t>(n), w[3].text, output, kind, lo, hi,
                static_cast<std::int32_t>(d), unit ? unit->value.text : std::string_view{}, src ? src->value.text : std::string_view{},
                unverified};
    auto old = std::find_if(s.ports.begin(), s.ports.end(),
                            [&](const IoPort& x) { return x.bank == bank && x.number == n && x.output == output; });
    if (old != s.ports.end()) *old = port;
    else s.ports.push_back(port);
  }

  // without axis N... | global BANK N... | vector N...: the base has them, this module does not.
  void without(const std::vector<Word>& w) {
    if (!based) return error(w[0], "'without' takes parameters or vectors away from a profile's base: it needs a based-on line");
    const std::string_view what = w[1].text;
    std::size_t at = 2;
    std::int64_t bank = -1, n = 0;
    if (what == "global") {
      if (w.size() < 4) return error(w[1], "without global BANK N...: a bank and at least one number");
      if (!number(w[2], 0, 3, bank, "a bank")) return;
      if (bank != 0 && bank != 3) return error(w[2], "global parameters are in banks 0 and 3");
      at = 3;
    } else if (what != "axis" && what != "vector") {
      return error(w[1], "without takes 'axis', 'global BANK' or 'vector', not '" + std::string(what) + "'");
    }
    for (std::size_t i = at; i < w.size(); ++i) {
      if (!number(w[i], 0, 255, n, what == "vector" ? "an interrupt number" : "a parameter number")) return;
      bool gone = false;
      if (what == "vector") {
        gone = std::erase_if(s.vectors, [&](const InterruptVector& v) { return v.number == n; }) > 0;
      } else {
        auto& table = what == "axis" ? s.axis : bank == 0 ? s.bank0 : s.bank3;
        gone = std::erase_if(table, [&](const ParamInfo& q) { return q.number == n; }) > 0;
      }
      if (!gone) return error(w[i], "the base has no " + std::string(what == "global" ? "global parameter" : what == "axis" ? "axis parameter" : "vector") +
                                    " " + std::to_string(n) + " to take away");
    }
  }

  // based-on: everything of the base, which this file's lines then change.
  void inherit(const Profile& b) {
    Profile& p = s.profile;
    const std::string_view name = p.name, title = p.title;
    p = b;
    p.name = name;
    p.title = title;
    s.axis.assign(b.axis_params.begin(), b.axis_params.end());
    s.bank0.assign(b.bank0.begin(), b.bank0.end());
    s.bank3.assign(b.bank3.begin(), b.bank3.end());
    s.vectors.assign(b.vectors.begin(), b.vectors.end());
    s.ports.assign(b.ports.begin(), b.ports.end());
    s.constants.assign(b.motion_constants.begin(), b.motion_constants.end());
    based = true;
  }

  void finish() {
    Profile& p = s.profile;
    auto missing = [&](const char* key, const char* shape) {
      if (attempted.count(key)) return;  // there is one, with an error of its own
      diags.push_back({file, 1, 0, 1, "the profile has no '" + std::string(key) + "' line (" + shape + ")", ""});
    };
    missing("name", "name NAME");
    if (!based && !attempted.count("based-on")) {
      missing("firmware", "firmware NNNNVnnn, the reply to command 136");
      missing("motors", "motors N");
      missing("commands", "commands N|N-M|MNEMONIC|all...");
      if (p.standalone) missing("program-memory", "program-memory N|unlimited [eeprom|ram]");
    }
    if (p.title.empty()) p.title = p.name;
    if (p.default_motion.empty()) p.default_motion = "ideal";
    if (!p.standalone) p.program_memory = 0;
    auto by_number = [](const ParamInfo& a, const ParamInfo& b) { return a.number < b.number; };
    std::stable_sort(s.axis.begin(), s.axis.end(), by_number);
    std::stable_sort(s.bank0.begin(), s.bank0.end(), by_number);
    std::stable_sort(s.bank3.begin(), s.bank3.end(), by_number);
    std::stable_sort(s.vectors.begin(), s.vectors.end(),
                     [](const InterruptVector& a, const InterruptVector& b) { return a.number < b.number; });
    p.axis_params = s.axis;
    p.bank0 = s.bank0;
    p.bank3 = s.bank3;
    p.vectors = s.vectors;
    std::stable_sort(s.ports.begin(), s.ports.end(), [](const IoPort& a, const IoPort& b) {
      return std::tie(a.bank, a.number, a.output) < std::tie(b.bank, b.number, b.output);
    });
    p.ports = s.ports;
    p.motion_constants = s.constants;
    p.aliases = s.aliases;
    p.unverified = s.unverified;
    p.text = s.text;
  }
};

}  // namespace

std::unique_ptr<ProfileStore> parse_profile(std::string text, const std::string& file, std::string_view origin,
                                            std::vector<FileDiag>& diags, const ProfileLookup& based_on) {
  auto store = std::make_unique<ProfileStore>();
  store->text = std::move(text);
  store->origin_text = std::string(origin);
  Profile& p = store->profile;
  p.user_vars = 256;
  p.any_parameter = false;
  const std::size_t before = diags.size();
  Reader r{*store, file, diags, based_on};
  const std::string_view all = store->text;
  if (all.find('\0') != std::string_view::npos) {
    diags.push_back({file, 0, 0, 1, "not a tmcl profile: the file holds NUL bytes (a binary file?)", ""});
    return nullptr;
  }
  for (std::size_t pos = 0; pos < all.size() && !r.stopped;) {
    std::size_t end = all.find('\n', pos);
    if (end == std::string_view::npos) end = all.size();
    r.source = all.substr(pos, end - pos);
    ++r.line_no;
    pos = end + 1;
    r.statement();
  }
  if (!r.started) diags.push_back({file, 1, 0, 1, "not a tmcl profile: the file is empty (the first line must be 'tmcl-profile 1')", ""});
  else if (!r.stopped) r.finish();
  if (diags.size() != before) return nullptr;
  p.origin = store->origin_text;
  return store;
}

std::vector<std::string_view> profile_keys() {
  std::vector<std::string_view> keys;
  for (const auto& k : kKeys) keys.push_back(k.key);
  for (auto a : kAttrNames) keys.push_back(a);
  return keys;
}

}  // namespace tmcl
