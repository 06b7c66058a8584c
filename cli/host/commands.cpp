// tmclctl's words (commands.hpp): parameters by number or name from the profile tables, and
// names for the status replies.
#include "tmcl/host/commands.hpp"

#include <cctype>
#include <cstdlib>

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

}  // namespace

std::string ParamRef::label() const {
  static const char* kinds[] = {"axis parameter ", "global parameter ", "I/O port "};
  std::string s = kinds[kind] + std::to_string(number);
  if (info) s += " (" + std::string(info->name) + ")";
  s += kind == Axis ? ", motor " : ", bank ";
  return s + std::to_string(index);
}

bool parse_param(const std::vector<std::string>& words, std::size_t& at, const Profile& profile, bool single_word,
                 ParamRef& out, std::string& error) {
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
    if (at < words.size() && number(words[at], 0, 255, dummy)) idx = words[at++];
    return finish(kind, num, idx.empty() ? nullptr : &idx);
  }
  // NAME[@I] or NAME [I]
  std::string name = first, idx;
  if (const auto atsign = name.find('@'); atsign != std::string::npos) {
    idx = name.substr(atsign + 1);
    name = name.substr(0, atsign);
  }
  ++at;
  std::vector<std::string_view> names;
  for (const auto& p : profile.axis_params) {
    names.push_back(p.name);
    if (lower(std::string(p.name)) == name) {
      out.kind = ParamRef::Axis;
      out.number = p.number;
      out.info = &p;
    }
  }
  if (!out.info)
    for (const auto& p : profile.bank0) {
      names.push_back(p.name);
      if (lower(std::string(p.name)) == name) {
        out.kind = ParamRef::Global;
        out.number = p.number;
        out.info = &p;
      }
    }
  if (!out.info) {
    int n;
    if (number(name, 0, 65535, n))
      error = "'" + words[at - 1] + "': say which kind of parameter (ap " + name + ", gp " + name + ", io " + name + ")";
    else {
      error = "unknown parameter '" + words[at - 1] + "' for " + std::string(profile.name);
      const std::string hint = closest_match(name, names);
      if (!hint.empty()) error += "; did you mean '" + hint + "'?";
    }
    return false;
  }
  if (idx.empty() && !single_word && at < words.size()) {
    int dummy;
    if (number(words[at], 0, 255, dummy)) idx = words[at++];
  }
  if (!idx.empty() && !number(idx, 0, 255, out.index)) {
    error = "bad motor or bank '" + idx + "' (0 to 255)";
    return false;
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
