// -Weeprom-wear: an EEPROM write (STAP, STGP, SCO n, 255, or SGP of a parameter the target
// stores at once) that runs again and again in a loop the analysis sees no bound for. A loop is a
// cycle of the instruction graph without DJNZ's jump back (a DJNZ loop counts down, so it ends);
// a write also repeats when its subroutine is called from such a loop, or runs in a timer
// handler. The components are computed only when the program has an EEPROM write at all.
#include <algorithm>
#include <cstdio>
#include <string>

#include "analysis_internal.hpp"
#include "graph.hpp"

namespace tmcl::detail {
namespace {

constexpr std::int64_t kEepromCycles = 100000;  // a typical EEPROM cell's rated write cycles

std::string duration_text(std::int64_t us) {
  double s = static_cast<double>(us) / 1e6;
  char buf[64];
  if (s < 120) std::snprintf(buf, sizeof buf, "%.0f seconds", s);
  else if (s < 7200) std::snprintf(buf, sizeof buf, "%.0f minutes", s / 60);
  else if (s < 3 * 86400) std::snprintf(buf, sizeof buf, "%.0f hours", s / 3600);
  else std::snprintf(buf, sizeof buf, "%.0f days", s / 86400);
  return buf;
}

}  // namespace

void Walker::check_eeprom() {
  if (writes.empty()) return;
  const int n = static_cast<int>(in.program.size());
  auto succ = [this, n](int i, std::vector<int>& s) {
    const Instruction& x = ins(i);
    const bool t_ok = x.value >= 0 && x.value < n;
    switch (static_cast<Op>(x.op)) {
      case Op::JA:
      case Op::RST:
        if (t_ok) s.push_back(x.value);
        return;
      case Op::JC:
        if (t_ok) s.push_back(x.value);
        break;
      case Op::RSUB:
      case Op::RETI:
      case Op::STOP: return;
      default: break;  // DJNZ: only on; CSUB/CALL: on after the return
    }
    if (i + 1 < n) s.push_back(i + 1);
  };
  std::vector<int> roots;
  for (const auto& r : a.regions) roots.push_back(r.entry);
  int count = 0;
  std::vector<int> scc = strong_components(n, roots, succ, count);
  // A component is a loop when it has two instructions, or one that jumps to itself.
  std::vector<int> size(static_cast<std::size_t>(count), 0);
  std::vector<std::int64_t> wait_ticks(static_cast<std::size_t>(count), 0);
  std::vector<int> first(static_cast<std::size_t>(count), -1);
  for (int i = 0; i < n; ++i) {
    int c = scc[static_cast<std::size_t>(i)];
    if (c < 0) continue;
    ++size[static_cast<std::size_t>(c)];
    if (first[static_cast<std::size_t>(c)] < 0) first[static_cast<std::size_t>(c)] = i;
    const Instruction& x = ins(i);
    if (x.op == static_cast<std::uint8_t>(Op::WAIT) && x.type == 0 && x.value > 0)
      wait_ticks[static_cast<std::size_t>(c)] += x.value;
  }
  auto cyclic = [&](int i) {
    int c = scc[static_cast<std::size_t>(i)];
    if (c < 0) return false;
    if (size[static_cast<std::size_t>(c)] > 1) return true;
    const Instruction& x = ins(i);
    return (x.op == static_cast<std::uint8_t>(Op::JA) || x.op == static_cast<std::uint8_t>(Op::JC)) && x.value == i;
  };
  // Regions that run again and again: called from a loop, or timer handlers (they fire periodically).
  const int nr = static_cast<int>(a.regions.size());
  std::vector<int> loop_site(static_cast<std::size_t>(nr), -2);  // -2: not repeated; -1: a timer handler
  std::vector<int> stack;
  for (int r = 0; r < nr; ++r) {
    const Region& reg = region(r);
    if (reg.kind == RegionKind::Handler)
      for (int v : reg.vectors)
        if (v <= 2 && loop_site[static_cast<std::size_t>(r)] == -2) {
          loop_site[static_cast<std::size_t>(r)] = -1;
          stack.push_back(r);
        }
  }
  for (int site : call_sites) {
    int callee = region_of_entry(ins(site).value);
    if (callee >= 0 && cyclic(site) && loop_site[static_cast<std::size_t>(callee)] == -2) {
      loop_site[static_cast<std::size_t>(callee)] = site;
      stack.push_back(callee);
    }
  }
  while (!stack.empty()) {
    int v = stack.back();
    stack.pop_back();
    for (const auto& e : out[static_cast<std::size_t>(v)])
      if (loop_site[static_cast<std::size_t>(e.to)] == -2) {
        loop_site[static_cast<std::size_t>(e.to)] = loop_site[static_cast<std::size_t>(v)];
        stack.push_back(e.to);
      }
  }
  std::sort(writes.begin(), writes.end());
  for (int i : writes) {
    int r = a.owner[static_cast<std::size_t>(i)];
    int site = r >= 0 ? loop_site[static_cast<std::size_t>(r)] : -2;
    int loop_at = cyclic(i) ? i : site >= 0 ? site : -1;
    if (loop_at < 0 && site != -1) continue;
    std::string what = mnemonic(i) + " writes the EEPROM";
    std::string msg;
    if (loop_at >= 0) {
      int c = scc[static_cast<std::size_t>(loop_at)];
      std::int64_t ticks = wait_ticks[static_cast<std::size_t>(c)];
      std::int64_t period_us = ticks > 0 ? ticks * 10000 : size[static_cast<std::size_t>(c)] * in.instr_time_us;
      msg = what + " each time round a loop with no bound the analysis can see; " +
            (ticks > 0 ? "with the loop's WAIT of " + std::to_string(ticks) + " ticks (" + std::to_string(ticks * 10) +
                             " ms)"
                       : "with no WAIT in the loop (" + std::to_string(size[static_cast<std::size_t>(c)]) +
                             " instructions a pass)") +
            ", a 100,000-cycle EEPROM cell wears out after about " + duration_text(kEepromCycles * period_us);
    } else {
      msg = what + " each time a timer interrupt runs " + region_word(region(r)) +
            ": at 100,000 write cycles a cell wears out after 100,000 periods of the timer";
    }
    auto& d = diags.warning(loc(i), msg, "eeprom-wear");
    if (loop_at >= 0) {
      int c = scc[static_cast<std::size_t>(loop_at)];
      if (loop_at != i) diags.note(d, loc(loop_at), region_word(region(r)) + " is called from the loop here");
      diags.note(d, loc(first[static_cast<std::size_t>(c)]), "the loop starts here");
    }
    (void)kEepromCycles;
  }
}

}  // namespace tmcl::detail
