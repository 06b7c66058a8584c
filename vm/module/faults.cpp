// Fault injection on the virtual module's line (faults.hpp): parsing --faults and applying the
// rules to each reply frame.
#include "tmcl/faults.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include "tmcl/duration.hpp"
#include "tmcl/isa.hpp"

namespace tmcl {
namespace {

bool parse_u64(std::string_view s, std::uint64_t& out) {
  if (s.empty() || s.size() > 18) return false;
  out = 0;
  for (char c : s) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    out = out * 10 + static_cast<std::uint64_t>(c - '0');
  }
  return true;
}

constexpr std::string_view kKinds[] = {"drop", "corrupt", "delay", "split", "silence", "stale"};

}  // namespace

std::string_view fault_kind_name(FaultRule::Kind kind) { return kKinds[kind]; }

bool parse_faults(std::string_view spec, FaultPlan& plan, std::string& error) {
  plan = FaultPlan{};
  if (spec.empty()) {
    error = "--faults needs at least one rule (e.g. drop@3, corrupt@p=0.1, delay=200ms@cmd=134)";
    return false;
  }
  std::size_t pos = 0;
  while (pos <= spec.size()) {
    const std::size_t comma = std::min(spec.find(',', pos), spec.size());
    const std::string_view rule_text = spec.substr(pos, comma - pos);
    pos = comma + 1;
    auto bad = [&](const std::string& why) {
      error = "--faults: '" + std::string(rule_text) + "': " + why;
      return false;
    };
    if (rule_text.substr(0, 5) == "seed=") {
      if (!parse_u64(rule_text.substr(5), plan.seed)) return bad("the seed is a whole number");
      continue;
    }
    std::string_view head = rule_text, when;
    if (const auto at = rule_text.find('@'); at != std::string_view::npos) {
      head = rule_text.substr(0, at);
      when = rule_text.substr(at + 1);
    }
    std::string_view kind = head, arg;
    if (const auto eq = head.find('='); eq != std::string_view::npos) {
      kind = head.substr(0, eq);
      arg = head.substr(eq + 1);
    }
    FaultRule r;
    bool known = false;
    for (std::size_t k = 0; k < std::size(kKinds); ++k)
      if (kind == kKinds[k]) {
        r.kind = static_cast<FaultRule::Kind>(k);
        known = true;
      }
    if (!known) return bad("unknown fault (drop, corrupt, delay, split, silence, stale)");
    const bool timed = r.kind == FaultRule::Delay || r.kind == FaultRule::Silence || r.kind == FaultRule::Split;
    if (!arg.empty()) {
      if (!timed) return bad(std::string(kind) + " takes no duration");
      auto d = parse_duration(arg);
      if (!d || *d <= 0) return bad("bad duration '" + std::string(arg) + "' (e.g. 200ms)");
      r.duration = *d;
    } else if (r.kind == FaultRule::Split) {
      r.duration = 5 * kUsPerMs;
    } else if (timed) {
      return bad(std::string(kind) + " needs a duration, e.g. " + std::string(kind) + "=200ms");
    }
    if (when.empty()) {
      r.when = FaultRule::Always;
    } else if (when.substr(0, 6) == "every=") {
      r.when = FaultRule::Every;
      if (!parse_u64(when.substr(6), r.n) || r.n == 0) return bad("every=N needs N >= 1");
    } else if (when.substr(0, 2) == "p=") {
      r.when = FaultRule::Probability;
      const std::string p(when.substr(2));
      char* end = nullptr;
      r.probability = std::strtod(p.c_str(), &end);
      if (p.empty() || *end || !(r.probability > 0) || r.probability > 1) return bad("p=X needs 0 < X <= 1");
    } else if (when.substr(0, 4) == "cmd=") {
      r.when = FaultRule::Command;
      std::string_view c = when.substr(4);
      if (const auto hash = c.find('#'); hash != std::string_view::npos) {
        if (!parse_u64(c.substr(hash + 1), r.n) || r.n == 0) return bad("cmd=C#K needs K >= 1");
        c = c.substr(0, hash);
      }
      std::uint64_t code = 0;
      if (parse_u64(c, code) && code <= 255) {
        r.command = static_cast<int>(code);
      } else if (const OpInfo* op = op_by_mnemonic(c); op != nullptr) {
        r.command = op->code;
      } else {
        return bad("unknown command '" + std::string(c) + "' (a number 0-255 or a mnemonic)");
      }
    } else {
      r.when = FaultRule::Nth;
      if (!parse_u64(when, r.n) || r.n == 0) return bad("after '@': N, every=N, cmd=C, cmd=C#K or p=X");
    }
    plan.rules.push_back(r);
  }
  if (plan.rules.empty()) {
    error = "--faults: no fault given, only a seed";
    return false;
  }
  return true;
}

FaultInjector::FaultInjector(FaultPlan plan, double scale)
    : plan_(std::move(plan)), scale_(scale > 0 ? scale : 1.0), state_(plan_.seed), command_counts_(plan_.rules.size(), 0) {}

// splitmix64: small, fast and the same everywhere, so a seed means the same faults on any machine.
std::uint64_t FaultInjector::next_random() {
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

bool FaultInjector::hits(FaultRule& rule, std::size_t index, int command) {
  const std::uint64_t nth = counters_.replies;  // 1-based number of this reply
  switch (rule.when) {
    case FaultRule::Always: return true;
    case FaultRule::Nth: return nth == rule.n;
    case FaultRule::Every: return nth % rule.n == 0;
    case FaultRule::Command:
      if (command != rule.command) return false;
      ++command_counts_[index];
      return rule.n == 0 || command_counts_[index] == rule.n;
    case FaultRule::Probability:
      return static_cast<double>(next_random() >> 11) * 0x1.0p-53 < rule.probability;
  }
  return false;
}

void FaultInjector::reply(const std::uint8_t* frame, std::size_t n, int command, SimTime now) {
  ++counters_.replies;
  bool drop = false, silence = false, corrupt = false, split = false, stale = false;
  SimTime delay = 0, silence_for = 0, pause = 0;
  for (std::size_t i = 0; i < plan_.rules.size(); ++i) {
    FaultRule& r = plan_.rules[i];
    if (!hits(r, i, command)) continue;
    switch (r.kind) {
      case FaultRule::Drop: drop = true; break;
      case FaultRule::Silence:
        silence = true;
        silence_for = std::max(silence_for, r.duration);
        break;
      case FaultRule::Corrupt: corrupt = true; break;
      case FaultRule::Delay: delay += r.duration; break;
      case FaultRule::Split:
        split = true;
        pause = std::max(pause, r.duration);
        break;
      case FaultRule::Stale: stale = true; break;
    }
  }
  auto scaled = [&](SimTime wall_us) { return static_cast<SimTime>(static_cast<double>(wall_us) * scale_); };
  if (silence) {
    ++counters_.silenced;
    silent_until_ = std::max(silent_until_, now + scaled(silence_for));
    return;
  }
  if (drop) {
    ++counters_.dropped;
    return;
  }
  std::vector<std::uint8_t> bytes(frame, frame + n);
  const std::vector<std::uint8_t> clean = bytes;
  if (corrupt && !bytes.empty()) {
    ++counters_.corrupted;
    bytes.back() = static_cast<std::uint8_t>(bytes.back() + 1);
  }
  const SimTime due = now + scaled(delay);
  if (delay > 0) ++counters_.delayed;
  // Held bytes keep the line's order: nothing overtakes a delayed reply.
  const SimTime after = held_.empty() ? due : std::max(due, held_.back().due);
  if (stale && !previous_.empty()) {
    ++counters_.stale;
    held_.push_back(Held{after, previous_});
  }
  if (split && bytes.size() > 4) {
    ++counters_.split;
    held_.push_back(Held{after, std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 4)});
    held_.push_back(Held{after + scaled(pause), std::vector<std::uint8_t>(bytes.begin() + 4, bytes.end())});
  } else {
    held_.push_back(Held{after, std::move(bytes)});
  }
  previous_ = clean;
}

void FaultInjector::release(SimTime now, std::vector<std::uint8_t>& out) {
  std::size_t k = 0;
  while (k < held_.size() && held_[k].due <= now) {
    out.insert(out.end(), held_[k].bytes.begin(), held_[k].bytes.end());
    ++k;
  }
  held_.erase(held_.begin(), held_.begin() + static_cast<std::ptrdiff_t>(k));
}

SimTime FaultInjector::next_release() const { return held_.empty() ? kNever : held_.front().due; }

}  // namespace tmcl
