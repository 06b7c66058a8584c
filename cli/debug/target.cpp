// The points of every target (debug_target.hpp): breakpoints and watchpoints, their conditions,
// ignore counts and logpoints, and how a location names an address. What a hit does to the
// program is the target's; whether it stops there is decided here, the same on the VM and on a
// module.
#include <algorithm>
#include <cctype>

#include "tmcl/debug_target.hpp"

namespace tmcl::debug {

std::string stop_kind_name(StopKind k) {
  switch (k) {
    case StopKind::Entry: return "entry";
    case StopKind::Breakpoint: return "breakpoint";
    case StopKind::Watchpoint: return "watchpoint";
    case StopKind::Step: return "step";
    case StopKind::Pause: return "pause";
    case StopKind::Exited: return "exited";
    case StopKind::Fault: return "fault";
    case StopKind::Limit: return "limit";
    case StopKind::Blocked: return "blocked";
    case StopKind::NotRunning: return "not-running";
    case StopKind::HistoryStart: return "history-start";
  }
  return "?";
}


bool Target::resolve(const std::string& location, std::int32_t& address, std::string& error) {
  std::string loc = location;
  while (!loc.empty() && std::isspace(static_cast<unsigned char>(loc.back()))) loc.pop_back();
  while (!loc.empty() && std::isspace(static_cast<unsigned char>(loc.front()))) loc.erase(0, 1);
  const std::int32_t size = program_size();
  if (loc.empty()) {
    error = "a location is needed: a label, a line, FILE:LINE or *ADDRESS";
    return false;
  }
  if (loc[0] == '*') {
    Expr e;
    std::int64_t v = 0;
    if (!parse_expr(loc.substr(1), info_, e, error) || !eval(e, v, error)) return false;
    if (v < 0 || v >= size) {
      error = "address " + std::to_string(v) + " is outside the program (0.." + std::to_string(size - 1) + ")";
      return false;
    }
    address = static_cast<std::int32_t>(v);
    return true;
  }
  // LINE or FILE:LINE: the first instruction on that line or the next line that has one.
  std::string file;
  std::string line_text = loc;
  if (auto colon = loc.rfind(':'); colon != std::string::npos) {
    file = loc.substr(0, colon);
    line_text = loc.substr(colon + 1);
  }
  bool numeric = !line_text.empty() && std::all_of(line_text.begin(), line_text.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
  if (numeric && line_text.size() < 9) {
    int line = std::stoi(line_text);
    int file_index = -1;
    if (!file.empty()) {
      for (std::size_t i = 0; i < info_.files.size(); ++i) {
        const std::string& n = info_.files[i].name;
        bool tail = n.size() > file.size() && n.compare(n.size() - file.size(), file.size(), file) == 0 && n[n.size() - file.size() - 1] == '/';
        if (n == file || tail || (!info_.files[i].path.empty() && info_.files[i].path == file)) {
          file_index = static_cast<int>(i);
          break;
        }
      }
      if (file_index < 0) {
        error = "no source file '" + file + "' in the program";
        return false;
      }
    } else {
      const std::int32_t now = pc();
      std::int32_t at = now >= 0 && static_cast<std::size_t>(now) < info_.lines.size() ? now : 0;
      file_index = info_.lines.empty() ? -1 : info_.lines[static_cast<std::size_t>(at)].file;
      if (file_index < 0 && !info_.files.empty()) file_index = 0;
    }
    if (file_index < 0) {
      error = "no line table for this program: use a label or *ADDRESS (or tmclasm -f symbols with --symbols)";
      return false;
    }
    std::int32_t best = -1;
    int best_line = 0;
    for (std::size_t a = 0; a < info_.lines.size() && static_cast<std::int32_t>(a) < size; ++a) {
      const auto& l = info_.lines[a];
      if (l.file != file_index || l.line < line) continue;
      if (best < 0 || l.line < best_line) {
        best = static_cast<std::int32_t>(a);
        best_line = l.line;
      }
    }
    if (best < 0) {
      error = "no code at or after line " + std::to_string(line) + " of " + info_.files[static_cast<std::size_t>(file_index)].name;
      return false;
    }
    address = best;
    return true;
  }
  for (const auto& l : info_.labels) {
    std::string a = l.first, b = loc;
    for (auto& c : a) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (auto& c : b) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (a == b) {
      address = static_cast<std::int32_t>(l.second);
      return true;
    }
  }
  error = "no label, line or address '" + loc + "' (labels: a name; lines: 12 or FILE:12; addresses: *12)";
  return false;
}


int Target::add_breakpoint(std::int32_t address, std::string location, bool temporary) {
  Breakpoint b;
  b.id = next_id_++;
  b.address = address;
  b.location = std::move(location);
  b.temporary = temporary;
  breaks_.push_back(std::move(b));
  points_changed();
  return breaks_.back().id;
}

bool Target::delete_point(int id) {
  auto bi = std::find_if(breaks_.begin(), breaks_.end(), [&](const Breakpoint& b) { return b.id == id; });
  if (bi != breaks_.end()) {
    breaks_.erase(bi);
    points_changed();
    return true;
  }
  auto wi = std::find_if(watches_.begin(), watches_.end(), [&](const Watchpoint& w) { return w.id == id; });
  if (wi == watches_.end()) return false;
  watches_.erase(wi);
  points_changed();
  return true;
}

void Target::delete_all() {
  breaks_.clear();
  watches_.clear();
  points_changed();
}

bool Target::enable_point(int id, bool on) {
  for (auto& b : breaks_)
    if (b.id == id) {
      b.enabled = on;
      points_changed();
      return true;
    }
  for (auto& w : watches_)
    if (w.id == id) {
      w.enabled = on;
      refresh_watches();
      points_changed();
      return true;
    }
  return false;
}

bool Target::set_condition(int id, const std::string& text, std::string& error) {
  for (auto& b : breaks_)
    if (b.id == id) {
      if (text.empty()) {
        b.condition.clear();
        b.cond = Expr{};
        return true;
      }
      Expr e;
      if (!parse_expr(text, info_, e, error)) return false;
      b.condition = text;
      b.cond = std::move(e);
      return true;
    }
  error = "no breakpoint number " + std::to_string(id);
  return false;
}

bool Target::set_ignore(int id, int count) {
  for (auto& b : breaks_)
    if (b.id == id) {
      b.ignore = std::max(count, 0);
      return true;
    }
  return false;
}

int Target::add_watchpoint(const std::string& text, std::string& error) {
  Watchpoint w;
  if (!parse_expr(text, info_, w.expr, error)) return 0;
  std::int64_t v = 0;
  if (!eval(w.expr, v, error)) return 0;
  w.id = next_id_++;
  w.text = text;
  w.old_value = v;
  w.valid = true;
  watches_.push_back(std::move(w));
  points_changed();
  return watches_.back().id;
}

void Target::refresh_watches() {
  for (auto& w : watches_) {
    std::string err;
    w.valid = eval(w.expr, w.old_value, err);
  }
}


std::string Target::interpolate(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '{') {
      out += text[i];
      continue;
    }
    auto close = text.find('}', i);
    if (close == std::string::npos) {
      out += text.substr(i);
      break;
    }
    Expr e;
    std::string err;
    std::int64_t v = 0;
    if (parse_expr(text.substr(i + 1, close - i - 1), info_, e, err) && eval(e, v, err))
      out += std::to_string(v);
    else
      out += "<" + err + ">";
    i = close;
  }
  return out;
}

bool Target::watch_changed(Stop& stop) {
  for (auto& w : watches_) {
    if (!w.enabled) continue;
    std::int64_t v = 0;
    std::string err;
    if (!eval(w.expr, v, err)) continue;
    if (w.valid && v == w.old_value) continue;
    bool was_valid = w.valid;
    stop = Stop{StopKind::Watchpoint, w.id, "", w.old_value, v};
    w.old_value = v;
    w.valid = true;
    ++w.hits;
    if (was_valid) return true;
  }
  return false;
}

bool Target::watching() const {
  for (const auto& w : watches_)
    if (w.enabled) return true;
  return false;
}

// The shared rules of a hit (docs/debugger.md, "Stepping", rule 5): a condition false or
// unreadable, an ignore count, a logpoint; the first breakpoint that stops names the stop, and a
// temporary one is deleted by it.
bool Target::breakpoint_hit(std::int32_t address, Stop& stop) {
  bool hit = false;
  for (std::size_t i = 0; i < breaks_.size(); ++i) {
    Breakpoint& b = breaks_[i];
    if (!b.enabled || b.address != address) continue;
    if (b.cond.root >= 0) {
      std::int64_t v = 0;
      std::string err;
      if (!eval(b.cond, v, err)) {
        stop = Stop{StopKind::Breakpoint, b.id, "error in the condition of breakpoint " + std::to_string(b.id) + ": " + err, 0, 0};
        return true;
      }
      if (v == 0) continue;
    }
    ++b.hits;
    if (b.ignore > 0) {
      --b.ignore;
      continue;
    }
    if (!b.log_message.empty()) {
      if (on_output) on_output(interpolate(b.log_message) + "\n");
      continue;
    }
    if (!hit) stop = Stop{StopKind::Breakpoint, b.id, b.temporary ? "temporary" : "", 0, 0};
    hit = true;
  }
  if (hit && stop.message == "temporary") delete_point(stop.id);
  return hit;
}

}  // namespace tmcl::debug
