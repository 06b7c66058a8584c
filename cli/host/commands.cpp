// tmclctl's words (commands.hpp): parameters by number or name from the profile tables, and
// names for the status replies.
#include "tmcl/host/commands.hpp"

#include <cctype>
#include <cstdlib>
#include <span>

#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/diag.hpp"

namespace tmcl::host {
namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool number(const std::string& s, int lo, int hi, int& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  const long v = std::strtol(s.c_str(), &end, 0);
  if (*end || v < lo || v > hi) return false;
  out = static_cast<int>(v);
  return true;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::size_t p = 0;
  for (;;) {
    const std::size_t q = s.find(sep, p);
    parts.push_back(s.substr(p, q == std::string::npos ? std::string::npos : q - p));
    if (q == std::string::npos) return parts;
    p = q + 1;
  }
}

// "(next)" and the like left out: "Target (next) position" is what a user calls "target position".
std::string without_parentheses(const std::string& s) {
  std::string out;
  int depth = 0;
  for (char c : s) {
    if (c == '(') ++depth;
    else if (c == ')' && depth > 0) --depth;
    else if (depth == 0) out += c;
  }
  std::string squeezed;  // "target  position" -> "target position"
  for (char c : out)
    if (c != ' ' || (!squeezed.empty() && squeezed.back() != ' ')) squeezed += c;
  while (!squeezed.empty() && squeezed.back() == ' ') squeezed.pop_back();
  return squeezed;
}

// The did-you-mean for a parameter name (`name` and `keys` in lower case, `shown` as the profile
// spells them): a name that matches once its parenthesised words are left out, else the closest
// by edit distance.
std::string closest_name(const std::string& name, const std::vector<std::string>& keys, const std::vector<std::string_view>& shown) {
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (without_parentheses(keys[i]) == name) return std::string(shown[i]);
  const std::string best = closest_match(name, std::vector<std::string_view>(keys.begin(), keys.end()));
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (keys[i] == best) return std::string(shown[i]);
  return {};
}

}  // namespace

std::string ParamRef::label() const {
  static const char* kinds[] = {"axis parameter ", "global parameter ", "I/O port "};
  std::string s = kinds[kind] + std::to_string(number);
  if (info) s += " (" + std::string(info->name) + ")";
  s += kind == Axis ? ", motor " : ", bank ";
  return s + std::to_string(index);
}

bool parse_param(const std::vector<std::string>& words, std::size_t& at, const Profile& profile, bool single_word,
                 ParamRef& out, std::string& error, std::size_t keep) {
  if (at >= words.size()) {
    error = "a parameter is missing (ap N [MOTOR], gp N [BANK], io N [BANK], or a name)";
    return false;
  }
  out = ParamRef{};
  const std::string first = lower(words[at]);
  auto finish = [&](ParamRef::Kind kind, const std::string& num, const std::string* idx) {
    out.kind = kind;
    if (!number(num, 0, 65535, out.number)) {
      error = "bad parameter number '" + num + "'";
      return false;
    }
    if (idx && !number(*idx, 0, 255, out.index)) {
      error = std::string("bad ") + (kind == ParamRef::Axis ? "motor" : "bank") + " '" + *idx + "' (0 to 255)";
      return false;
    }
    out.info = kind == ParamRef::Axis ? profile.axis_param(out.number)
               : kind == ParamRef::Global ? profile.global_param(out.index, out.number)
                                          : nullptr;
    return true;
  };
  auto kind_of = [](const std::string& w, ParamRef::Kind& k) {
    if (w == "ap" || w == "axis") k = ParamRef::Axis;
    else if (w == "gp" || w == "global") k = ParamRef::Global;
    else if (w == "io") k = ParamRef::Io;
    else return false;
    return true;
  };
  ParamRef::Kind kind;
  // ap:N[:I]
  if (const auto parts = split(first, ':'); parts.size() >= 2 && parts.size() <= 3 && kind_of(parts[0], kind)) {
    ++at;
    return finish(kind, parts[1], parts.size() == 3 ? &parts[2] : nullptr);
  }
  // ap N [I]
  if (!single_word && kind_of(first, kind)) {
    if (at + 1 >= words.size()) {
      error = "'" + words[at] + "' needs a parameter number";
      return false;
    }
    const std::string num = words[at + 1];
    at += 2;
    std::string idx;
    int dummy;
    if (words.size() - at > keep && number(words[at], 0, 255, dummy)) idx = words[at++];
    return finish(kind, num, idx.empty() ? nullptr : &idx);
  }
  // NAME[@I] or NAME [I]
  std::string name = first, idx;
  if (const auto atsign = name.find('@'); atsign != std::string::npos) {
    idx = name.substr(atsign + 1);
    name = name.substr(0, atsign);
  }
  ++at;
  // The profile's names: axis parameters, then banks 0 and 3 (the interrupt settings); the first
  // that matches wins.
  struct Table {
    std::span<const ParamInfo> params;
    ParamRef::Kind kind;
    int bank;
  };
  const Table tables[] = {{profile.axis_params, ParamRef::Axis, 0}, {profile.bank0, ParamRef::Global, 0},
                          {profile.bank3, ParamRef::Global, 3}};
  std::vector<std::string> keys;  // every name in lower case, for the did-you-mean
  std::vector<std::string_view> shown;
  for (const Table& t : tables)
    for (const auto& p : t.params) {
      keys.push_back(lower(std::string(p.name)));
      shown.push_back(p.name);
      if (!out.info && keys.back() == name) {
        out.kind = t.kind;
        out.number = p.number;
        out.index = t.bank;
        out.info = &p;
      }
    }
  if (!out.info) {
    int n;
    if (number(name, 0, 65535, n))
      error = "'" + words[at - 1] + "': say which kind of parameter (ap " + name + ", gp " + name + ", io " + name + ")";
    else {
      error = "unknown parameter '" + words[at - 1] + "' for " + std::string(profile.name);
      const std::string hint = closest_name(name, keys, shown);
      if (!hint.empty()) error += "; did you mean '" + hint + "'?";
    }
    return false;
  }
  // A number after the name is its motor (or bank) only when the command has words left for
  // itself: `set 'soft stop enable' 1` sets 1 (motor 0), `set NAME 0 1` sets 1 on motor 0.
  if (idx.empty() && !single_word && words.size() - at > keep) {
    int dummy;
    if (number(words[at], 0, 255, dummy)) idx = words[at++];
  }
  if (!idx.empty()) {
    int given = 0;
    if (!number(idx, 0, 255, given)) {
      error = "bad motor or bank '" + idx + "' (0 to 255)";
      return false;
    }
    // A global parameter's name says its bank; a motor number belongs to axis parameters.
    if (out.kind == ParamRef::Global && given != out.index) {
      error = "'" + std::string(out.info->name) + "' is a global parameter of bank " + std::to_string(out.index) +
              ", not of bank " + idx;
      return false;
    }
    out.index = given;
  }
  return true;
}

bool param_instruction(const ParamRef& p, ParamAction action, std::int32_t value, const Profile& profile, Instruction& out,
                       std::string& error) {
  if (p.number > 255) {
    error = p.label() + ": parameter numbers above 255 do not fit the type byte";
    return false;
  }
  const auto type = static_cast<std::uint8_t>(p.number);
  const auto index = static_cast<std::uint8_t>(p.index);
  const bool known = p.info != nullptr && !profile.any_parameter;
  auto refuse = [&](const char* what) {
    error = p.label() + " " + what + " on " + std::string(profile.name);
    return false;
  };
  // What the module lacks is refused before anything is sent: a motor beyond its axes, a user
  // variable beyond bank 2, and a store of one that has no EEPROM copy (as the module answers 3).
  if (p.kind == ParamRef::Axis && p.index >= profile.motors) {
    error = p.label() + ": " + std::string(profile.name) + " has no motor " + std::to_string(p.index) + " (" +
            (profile.motors == 1 ? std::string("motor 0 only") : "motors 0 to " + std::to_string(profile.motors - 1)) + ")";
    return false;
  }
  if (p.kind == ParamRef::Global && p.index == 2 && p.number >= profile.user_vars)
    return refuse(("is no user variable (bank 2 has 0 to " + std::to_string(profile.user_vars - 1) + ")").c_str());
  if (p.kind == ParamRef::Global && p.index == 2 && action == ParamAction::Store && p.number >= profile.eeprom_user_vars)
    return refuse(profile.eeprom_user_vars == 0
                      ? "has no EEPROM copy (no user variable has one)"
                      : ("has no EEPROM copy (user variables 0 to " + std::to_string(profile.eeprom_user_vars - 1) + " have one)").c_str());
  switch (action) {
    case ParamAction::Get:
      if (known && !(p.info->access & kRead)) return refuse("cannot be read");
      out = Instruction{static_cast<std::uint8_t>(p.kind == ParamRef::Axis ? Op::GAP : p.kind == ParamRef::Global ? Op::GGP : Op::GIO),
                        type, index, 0};
      return true;
    case ParamAction::Set:
      if (known && !(p.info->access & kWrite)) return refuse("is read-only");
      if (known && (value < p.info->min || value > p.info->max))
        return refuse(("takes " + std::to_string(p.info->min) + " to " + std::to_string(p.info->max) + ", not " +
                       std::to_string(value) + ",")
                          .c_str());
      out = Instruction{static_cast<std::uint8_t>(p.kind == ParamRef::Axis ? Op::SAP : p.kind == ParamRef::Global ? Op::SGP : Op::SIO),
                        type, index, value};
      return true;
    case ParamAction::Store:
      if (p.kind == ParamRef::Io) return refuse("has no EEPROM copy (store is for ap and gp)");
      if (known && !(p.info->access & (kEeprom | kAutoStore))) return refuse("is not stored in the EEPROM");
      out = Instruction{static_cast<std::uint8_t>(p.kind == ParamRef::Axis ? Op::STAP : Op::STGP), type, index, 0};
      return true;
  }
  return false;
}

std::string mode_name(std::uint32_t mode) {
  static const char* names[] = {"stopped", "running", "step", "reset", "download"};
  return mode < 5 ? names[mode] : "mode " + std::to_string(mode);
}

}  // namespace tmcl::host
