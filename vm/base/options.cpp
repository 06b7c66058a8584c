// The table-driven command-line parser (tmcl/options.hpp): matching an argument to an option of
// the table, applying it, and what follows from the table: --help, --list-options, --complete.
#include "tmcl/options.hpp"

#include <algorithm>
#include <cstdio>
#include <string_view>

#include "tmcl/diag_text.hpp"
#include "tmcl/version.hpp"

namespace tmcl::cli {

namespace {

// What every tool has; the parser itself answers them.
enum class Builtin { None, Help, Version, ListOptions, Complete };

const std::vector<Option>& builtins() {
  static const std::vector<Option> list = {
      {"--help", "", "show this help", {}},
      {"-h", "", "", {}, {}, {}, true},
      {"--version", "", "show the version", {}},
      {"--list-options", "", "", {}, {}, {}, true},
      {"--complete", "WORD", "", {}, {}, {}, true},
  };
  return list;
}

Builtin builtin_of(const Option* o) {
  const auto& b = builtins();
  if (o == &b[0] || o == &b[1]) return Builtin::Help;
  if (o == &b[2]) return Builtin::Version;
  if (o == &b[3]) return Builtin::ListOptions;
  if (o == &b[4]) return Builtin::Complete;
  return Builtin::None;
}

std::vector<std::string> spellings_of(const std::string& names) {
  std::vector<std::string> out;
  for (std::size_t at = 0; at < names.size();) {
    std::size_t comma = names.find(", ", at);
    if (comma == std::string::npos) comma = names.size();
    out.push_back(names.substr(at, comma - at));
    at = comma + 2;
  }
  return out;
}

bool is_prefix_spelling(std::string_view s) { return s.size() > 2 && (s.back() == '=' || s.back() == '-'); }
bool is_short_spelling(std::string_view s) { return s.size() == 2 && s[0] == '-' && s[1] != '-'; }
bool starts_with(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }

struct Spelling {
  std::string text;
  const Option* option;
};

// Every spelling of the tool's options, then of the built-in ones.
std::vector<Spelling> all_spellings(const Tool& tool) {
  std::vector<Spelling> out;
  for (const auto* table : {&tool.options, &builtins()})
    for (const Option& o : *table)
      for (auto& s : spellings_of(o.names)) out.push_back({std::move(s), &o});
  return out;
}

// One argument matched against the table.
struct Match {
  enum class Kind { Operand, Option, Unknown, NoValueWanted } kind = Kind::Operand;
  const Option* option = nullptr;
  std::string spelling;    // as matched ("-t", "--target", "-Wno-")
  bool has_value = false;  // the value was in the argument itself (attached, after '=')
  std::string value;
};

Match match(const std::vector<Spelling>& spellings, const std::string& arg) {
  Match m;
  if (arg.size() < 2 || arg[0] != '-') return m;  // an operand, or "-" (standard input)
  // Exactly a spelling (not a prefix, which needs its value in the same argument).
  for (const Spelling& s : spellings)
    if (s.text == arg && !is_prefix_spelling(s.text)) {
      m.kind = Match::Kind::Option;
      m.option = s.option;
      m.spelling = s.text;
      return m;
    }
  // A prefix ("-Wno-NAME", "-Werror=NAME"): the longest that fits.
  const Spelling* best = nullptr;
  for (const Spelling& s : spellings)
    if (is_prefix_spelling(s.text) && arg.size() > s.text.size() && starts_with(arg, s.text) &&
        (!best || s.text.size() > best->text.size()))
      best = &s;
  // NAME=VALUE for a spelling of more than two characters.
  if (const std::size_t eq = arg.find('='); !best && eq != std::string::npos) {
    const std::string name = arg.substr(0, eq);
    for (const Spelling& s : spellings)
      if (s.text == name && !is_short_spelling(s.text) && !is_prefix_spelling(s.text)) {
        m.option = s.option;
        m.spelling = s.text;
        m.kind = s.option->value.empty() ? Match::Kind::NoValueWanted : Match::Kind::Option;
        m.has_value = true;
        m.value = arg.substr(eq + 1);
        return m;
      }
  }
  // A two-character spelling with its value attached ("-oFILE").
  for (const Spelling& s : spellings)
    if (!best && is_short_spelling(s.text) && !s.option->value.empty() && starts_with(arg, s.text)) best = &s;
  if (best) {
    m.kind = Match::Kind::Option;
    m.option = best->option;
    m.spelling = best->text;
    m.has_value = true;
    m.value = arg.substr(best->text.size());
    return m;
  }
  if (arg[1] >= '0' && arg[1] <= '9') return m;  // a negative number is an operand
  m.kind = Match::Kind::Unknown;
  return m;
}

std::string needs_text(const Option& o) {
  if (!o.needs.empty()) return o.needs;
  if (starts_with(o.value, "FILE")) return "a file";
  if (o.value == "DIR") return "a folder";
  if (o.value == "N") return "a number";
  if (o.value == "DURATION") return "a duration";
  if (o.value == "NAME") return "a name";
  return o.value;
}

std::string unknown_option(const std::vector<Spelling>& spellings, const std::string& arg) {
  std::string name = arg;
  if (starts_with(name, "--") && name.find('=') != std::string::npos) name.resize(name.find('='));
  std::vector<std::string_view> visible;
  for (const Spelling& s : spellings)
    if (!s.option->hidden && !is_prefix_spelling(s.text)) visible.push_back(s.text);
  std::string error = "unknown option '" + name + "'";
  const std::string hint = closest_match(name, visible);
  if (!hint.empty()) error += " (did you mean '" + hint + "'?)";
  return error;
}

// How --help shows an option: its spellings and its value ("-f, --format FMT", "-Wno-NAME").
std::string shown(const Option& o) {
  if (o.value.empty()) return o.names;
  return o.names + (is_prefix_spelling(o.names) ? "" : " ") + o.value;
}

void add_help_lines(std::string& out, const std::string& left, const std::string& help, int column) {
  std::string line = "  " + left;
  if (line.size() + 2 <= static_cast<std::size_t>(column))
    line.resize(static_cast<std::size_t>(column), ' ');
  else
    line += "  ";
  for (std::size_t at = 0; at <= help.size();) {
    std::size_t nl = help.find('\n', at);
    if (nl == std::string::npos) nl = help.size();
    if (at > 0) line = std::string(static_cast<std::size_t>(column), ' ');
    out += line + help.substr(at, nl - at) + "\n";
    at = nl + 1;
  }
}

}  // namespace

Handler set(std::string& field) {
  return [&field](const std::string& v) {
    field = v;
    return std::string();
  };
}

Handler flag(bool& field) {
  return [&field](const std::string&) {
    field = true;
    return std::string();
  };
}

Handler append(std::vector<std::string>& list) {
  return [&list](const std::string& v) {
    list.push_back(v);
    return std::string();
  };
}

std::string Option::name() const {
  const std::size_t comma = names.rfind(", ");
  return comma == std::string::npos ? names : names.substr(comma + 2);
}

bool Result::has(const std::string& name) const { return std::find(given.begin(), given.end(), name) != given.end(); }

std::string help_text(const Tool& tool) {
  std::string out = tool.usage;
  std::size_t label = 0;  // the width of the groups' labels, and a blank
  for (const Option& o : tool.options)
    if (!o.hidden && !o.group.empty()) label = std::max(label, o.group.size() + 1);
  std::string left, group;
  for (const auto* table : {&tool.options, &builtins()})
    for (const Option& o : *table) {
      if (o.hidden) continue;
      if (left.empty() && !o.group.empty()) {
        left = o.group == group ? std::string(label, ' ') : o.group + std::string(label - o.group.size(), ' ');
      }
      group = o.group;
      left += (left.empty() || left.back() == ' ' ? "" : ", ") + shown(o);
      if (o.help.empty()) continue;  // shares the next option's line
      add_help_lines(out, left, o.help, tool.column);
      left.clear();
    }
  return out + tool.epilogue;
}

std::string option_list(const Tool& tool) {
  std::string out;
  for (const auto* table : {&tool.options, &builtins()})
    for (const Option& o : *table)
      if (!o.hidden) out += o.names + "\t" + o.value + "\n";
  return out;
}

std::string completion(const Tool& tool, const std::vector<std::string>& words) {
  const std::vector<Spelling> spellings = all_spellings(tool);
  const std::string cur = words.empty() ? std::string() : words.back();
  std::vector<std::string> operands, given;
  const Option* pending = nullptr;  // an option whose value is the next word
  bool only_operands = false;       // after "--"
  for (std::size_t i = 0; i + 1 < words.size(); ++i) {
    const std::string& w = words[i];
    if (pending) {
      pending = nullptr;
    } else if (!only_operands && w == "--") {
      only_operands = true;
    } else if (Match m = only_operands ? Match{} : match(spellings, w); m.kind == Match::Kind::Operand) {
      operands.push_back(w);
    } else if (m.kind == Match::Kind::Option) {
      given.push_back(m.option->name());
      if (!m.has_value && !m.option->value.empty()) pending = m.option;
    }
  }

  std::vector<std::string> candidates;
  std::string files_instead;  // a path where words or a file may go: "files EXT..."
  auto offer_words = [&](const Values& v, const std::string& before) {
    if (!v.or_files.empty() && cur.find('/', before.size()) != std::string::npos) {
      files_instead = "files";
      for (const auto& e : v.or_files) files_instead += " " + e;
      return;
    }
    std::vector<std::string> items = v.items;
    if (v.later) {
      std::vector<std::string> more = v.later();
      items.insert(items.end(), more.begin(), more.end());
    }
    for (const std::string& item : items)
      if (starts_with(before + item, cur)) candidates.push_back(before + item);
  };
  Values values;
  if (pending) {
    values = pending->complete;
  } else if (!only_operands && starts_with(cur, "-") && cur != "-") {
    const std::size_t eq = cur.find('=');
    const Match m = match(spellings, cur);
    if (starts_with(cur, "--") && eq != std::string::npos) {
      if (m.kind == Match::Kind::Option && m.option->complete.kind == Values::Kind::Words)
        offer_words(m.option->complete, cur.substr(0, eq + 1));
      else if (m.kind == Match::Kind::Option)
        values = m.option->complete;
    } else {
      for (const Spelling& s : spellings)
        if (!s.option->hidden && starts_with(s.text, cur) && !(is_prefix_spelling(s.text) && s.text == cur))
          candidates.push_back(s.text);
      // The value after a prefix or an attached short option ("-Wno-unr", "-tusb"): the longest
      // spelling that fits.
      const Spelling* best = nullptr;
      for (const Spelling& s : spellings) {
        const bool prefix = is_prefix_spelling(s.text) && starts_with(cur, s.text);
        const bool attached = is_short_spelling(s.text) && !s.option->value.empty() && cur.size() > 2 &&
                              starts_with(cur, s.text);
        if ((prefix || attached) && (!best || s.text.size() > best->text.size())) best = &s;
      }
      if (best && best->option->complete.kind == Values::Kind::Words) offer_words(best->option->complete, best->text);
    }
  } else {
    values = tool.operands ? tool.operands(operands, given) : Values::files();
  }
  if (values.kind == Values::Kind::Words) {
    offer_words(values, "");
  }
  if (!files_instead.empty()) {
    return files_instead + "\n";
  } else if (values.kind == Values::Kind::Words) {
  } else if (values.kind == Values::Kind::Files) {
    std::string out = "files";
    for (const auto& e : values.items) out += " " + e;
    return out + "\n";
  } else if (values.kind == Values::Kind::Dirs) {
    return "dirs\n";
  }
  std::string out = "words\n";
  std::vector<std::string> seen;
  for (const auto& c : candidates) {
    if (std::find(seen.begin(), seen.end(), c) != seen.end()) continue;
    seen.push_back(c);
    out += c + "\n";
  }
  return out;
}

Result parse(const Tool& tool, const std::vector<std::string>& args) {
  Result r;
  const std::vector<Spelling> spellings = all_spellings(tool);
  bool only_operands = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (only_operands) {
      r.operands.push_back(arg);
      continue;
    }
    if (arg == "--") {
      only_operands = true;
      continue;
    }
    Match m = match(spellings, arg);
    if (m.kind == Match::Kind::Operand) {
      r.operands.push_back(arg);
      continue;
    }
    if (m.kind == Match::Kind::Unknown) {
      r.status = Result::Status::Error;
      r.error = unknown_option(spellings, arg);
      return r;
    }
    if (m.kind == Match::Kind::NoValueWanted) {
      r.status = Result::Status::Error;
      r.error = m.spelling + " takes no value";
      return r;
    }
    const Option& o = *m.option;
    switch (builtin_of(&o)) {
      case Builtin::Help: std::fputs(help_text(tool).c_str(), stdout); r.status = Result::Status::Done; return r;
      case Builtin::Version: std::puts(version_line(tool.name.c_str()).c_str()); r.status = Result::Status::Done; return r;
      case Builtin::ListOptions: std::fputs(option_list(tool).c_str(), stdout); r.status = Result::Status::Done; return r;
      case Builtin::Complete: {
        std::vector<std::string> words(args.begin() + static_cast<std::ptrdiff_t>(i) + 1, args.end());
        if (m.has_value) words.insert(words.begin(), m.value);
        std::fputs(completion(tool, words).c_str(), stdout);
        r.status = Result::Status::Done;
        return r;
      }
      case Builtin::None: break;
    }
    if (!o.value.empty() && !m.has_value) {
      if (i + 1 >= args.size()) {
        r.status = Result::Status::Error;
        r.error = m.spelling + " needs " + needs_text(o);
        return r;
      }
      m.value = args[++i];
    }
    r.given.push_back(o.name());
    if (std::string error = o.set ? o.set(m.value) : std::string(); !error.empty()) {
      r.status = Result::Status::Error;
      r.error = std::move(error);
      return r;
    }
  }
  return r;
}

Result parse(const Tool& tool, int argc, char** argv) {
  return parse(tool, std::vector<std::string>(argv + 1, argv + argc));
}

}  // namespace tmcl::cli
