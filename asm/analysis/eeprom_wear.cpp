// -Weeprom-wear: an EEPROM write (STAP, STGP, SCO n, 255, or SGP of a parameter the target
// stores at once) that runs again and again in a loop the analysis sees no bound for. A loop is a
// cycle of the instruction graph without the edges that go round a bounded loop again: DJNZ's
// jump back (it counts down, so it ends), and the JC of a loop bounded by a counter
// (counters.cpp). A write also repeats when its subroutine is called from such a loop, or runs
// in a timer handler. How soon the cell wears out is estimated from the shortest way round the
// loop through the write (or through the call), with its WAITs. The graph's components are
// computed only when the program has an EEPROM write at all.
#include <algorithm>
#include <cstdio>
#include <queue>
#include <string>

#include "analysis_internal.hpp"
#include "graph.hpp"

namespace tmcl::detail {
namespace {

constexpr std::int64_t kEepromCycles = 100000;  // a typical EEPROM cell's rated write cycles
constexpr std::int64_t kTickUs = 10000;         // WAIT TICKS counts 10 ms ticks
constexpr int kMaxRounds = 8;                   // counted loops nested deeper are not looked into

std::string duration_text(std::int64_t us) {
  double s = static_cast<double>(us) / 1e6;
  char buf[64];
  if (s < 120) std::snprintf(buf, sizeof buf, "%.0f seconds", s);
  else if (s < 7200) std::snprintf(buf, sizeof buf, "%.0f minutes", s / 60);
  else if (s < 3 * 86400) std::snprintf(buf, sizeof buf, "%.0f hours", s / 3600);
  else std::snprintf(buf, sizeof buf, "%.0f days", s / 86400);
  return buf;
}

std::string ms_text(std::int64_t us) {
  char buf[64];
  if (us >= 10000) std::snprintf(buf, sizeof buf, "%lld ms", static_cast<long long>((us + 500) / 1000));
  else std::snprintf(buf, sizeof buf, "%.2g ms", static_cast<double>(us) / 1000);
  return buf;
}

// One way round a loop: its time and what makes it up.
struct WearRound {
  std::int64_t us = 0;
  std::int64_t ticks = 0;  // of WAIT TICKS
  int waits = 0;
  int instructions = 0;
  bool event_wait = false;  // a WAIT for a position, switch or reference search: takes longer
};

}  // namespace

void Walker::check_eeprom() {
  if (writes.empty()) return;
  const int n = static_cast<int>(in.program.size());
  // Where control lands other than by running on: the counted-loop patterns stop there.
  AddressBits landing;
  landing.reset(n);
  scan([&](int i, OpClass) { landing.set(ins(i).value); }, [](int) {});
  // Per instruction, the edge cut as one that goes round a counted loop again: 1 its jump,
  // 2 running on.
  std::vector<std::uint8_t> cut(static_cast<std::size_t>(n), 0);
  // The edges of counted loops whose counter is reset around them: the estimate goes round the
  // outer loop when the write is on it too (a burst of writes each time round it).
  std::vector<std::uint8_t> counted(static_cast<std::size_t>(n), 0);
  // The successors of instruction i (at most two) into `s`; their number.
  auto successors = [this, n, &cut](int i, int (&s)[2]) {
    const Instruction& x = ins(i);
    const bool t_ok = x.value >= 0 && x.value < n && !(cut[static_cast<std::size_t>(i)] & 1);
    int k = 0;
    switch (static_cast<Op>(x.op)) {
      case Op::JA:
      case Op::RST:
        if (t_ok) s[k++] = x.value;
        return k;
      case Op::JC:
        if (t_ok) s[k++] = x.value;
        break;
      case Op::RSUB:
      case Op::RETI:
      case Op::STOP: return k;
      default: break;  // DJNZ: only on; CSUB/CALL: on after the return
    }
    if (i + 1 < n && !(cut[static_cast<std::size_t>(i)] & 2)) s[k++] = i + 1;
    return k;
  };
  auto succ = [&successors](int i, std::vector<int>& out_list) {
    int s[2];
    int k = successors(i, s);
    out_list.insert(out_list.end(), s, s + k);
  };
  auto nth = [&successors](int i, int k) {
    int s[2];
    return k < successors(i, s) ? s[k] : -1;
  };
  std::vector<int> roots;
  for (const auto& r : a.regions) roots.push_back(r.entry);
  int count = 0;
  std::vector<int> scc;
  std::vector<int> size;
  CounterFacts facts;
  std::vector<CounterTest> tests;
  // Cut the counted loops, then look again: an inner loop can show its counter only once the
  // outer loop around it is cut.
  for (int round = 0;; ++round) {
    scc = strong_components(n, roots, nth, count);
    size.assign(static_cast<std::size_t>(count), 0);
    for (int i = 0; i < n; ++i)
      if (int c = scc[static_cast<std::size_t>(i)]; c >= 0) ++size[static_cast<std::size_t>(c)];
    if (round == kMaxRounds) break;
    tests.clear();
    CounterTest t;
    for (int i = 0; i < n; ++i) {
      if (ins(i).op != static_cast<std::uint8_t>(Op::JC) || cut[static_cast<std::size_t>(i)]) continue;
      int c = scc[static_cast<std::size_t>(i)];
      if (c >= 0 && size[static_cast<std::size_t>(c)] >= 2 && counter_test(i, scc, landing, t)) tests.push_back(t);
    }
    if (tests.empty()) break;
    counter_facts(scc, tests, facts);
    bool cuts = false;
    for (const auto& test : tests) {
      counted[static_cast<std::size_t>(test.jc)] = static_cast<std::uint8_t>(test.towards);
      if (int e = counted_edges(test, facts)) {
        cut[static_cast<std::size_t>(test.jc)] = static_cast<std::uint8_t>(e);
        cuts = true;
      }
    }
    if (!cuts) break;
  }
  // A component is a loop when it has two instructions, or one that jumps to itself.
  std::vector<int> self;
  auto cyclic = [&](int i) {
    int c = scc[static_cast<std::size_t>(i)];
    if (c < 0) return false;
    if (size[static_cast<std::size_t>(c)] > 1) return true;
    self.clear();
    succ(i, self);
    return std::find(self.begin(), self.end(), i) != self.end();
  };
  // The shortest way round from `at` back to it inside its component (Dijkstra on instruction
  // times: a WAIT TICKS its ticks, any other instruction instr_time_us).
  std::vector<std::int64_t> dist(static_cast<std::size_t>(n), -1);
  std::vector<int> parent(static_cast<std::size_t>(n), -1), touched, next;
  auto time_of = [this](int i) {
    const Instruction& x = ins(i);
    if (x.op == static_cast<std::uint8_t>(Op::WAIT) && x.type == kw::Wait::TICKS && x.value > 0) return x.value * kTickUs;
    return in.instr_time_us;
  };
  auto shortest_round = [&](int at, bool outer) {
    const int c = scc[static_cast<std::size_t>(at)];
    using Item = std::pair<std::int64_t, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
    for (int v : touched) dist[static_cast<std::size_t>(v)] = -1, parent[static_cast<std::size_t>(v)] = -1;
    touched.clear();
    WearRound way;
    int last = -1;  // the instruction that goes back to `at` on the best way found
    std::int64_t best_us = -1;
    open.push({time_of(at), at});
    dist[static_cast<std::size_t>(at)] = time_of(at);
    touched.push_back(at);
    while (!open.empty()) {
      auto [d, v] = open.top();
      open.pop();
      if (d != dist[static_cast<std::size_t>(v)] || (best_us >= 0 && d >= best_us)) continue;
      next.clear();
      succ(v, next);
      for (int w : next) {
        if (scc[static_cast<std::size_t>(w)] != c) continue;
        if (outer && ((w == v + 1 && (counted[static_cast<std::size_t>(v)] & 2)) ||
                      (w == ins(v).value && ins(v).op == static_cast<std::uint8_t>(Op::JC) &&
                       (counted[static_cast<std::size_t>(v)] & 1))))
          continue;
        if (w == at) {
          if (best_us < 0 || d < best_us) best_us = d, last = v;
          continue;
        }
        std::int64_t dw = d + time_of(w);
        if (dist[static_cast<std::size_t>(w)] >= 0 && dist[static_cast<std::size_t>(w)] <= dw) continue;
        if (dist[static_cast<std::size_t>(w)] < 0) touched.push_back(w);
        dist[static_cast<std::size_t>(w)] = dw;
        parent[static_cast<std::size_t>(w)] = v;
        open.push({dw, w});
      }
    }
    way.us = best_us;
    for (int v = last; v >= 0; v = parent[static_cast<std::size_t>(v)]) {
      const Instruction& x = ins(v);
      ++way.instructions;
      if (x.op == static_cast<std::uint8_t>(Op::WAIT)) {
        if (x.type == kw::Wait::TICKS && x.value > 0) way.ticks += x.value, ++way.waits;
        else way.event_wait = true;
      }
      if (v == at) break;
    }
    return way;
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
  // The first instruction of each component, for "the loop starts here".
  std::vector<int> first(static_cast<std::size_t>(count), -1);
  for (int i = n - 1; i >= 0; --i)
    if (int c = scc[static_cast<std::size_t>(i)]; c >= 0) first[static_cast<std::size_t>(c)] = i;
  std::sort(writes.begin(), writes.end());
  for (int i : writes) {
    int r = a.owner[static_cast<std::size_t>(i)];
    int site = r >= 0 ? loop_site[static_cast<std::size_t>(r)] : -2;
    int loop_at = cyclic(i) ? i : site >= 0 ? site : -1;
    if (loop_at < 0 && site != -1) continue;
    if (!want("eeprom-wear", i)) continue;
    std::string what = mnemonic(i) + " writes the EEPROM";
    std::string msg;
    if (loop_at >= 0) {
      WearRound way = shortest_round(loop_at, true);
      if (way.us < 0) way = shortest_round(loop_at, false);
      std::string parts = way.waits > 1   ? "WAITs of " + std::to_string(way.ticks) + " ticks in all"
                          : way.waits == 1 ? "a WAIT of " + std::to_string(way.ticks) + " ticks"
                                           : std::to_string(way.instructions) + " instructions, no WAIT TICKS";
      if (way.event_wait) parts += ", and a WAIT for an event that may take longer";
      msg = what + " each time round a loop with no bound the analysis can see; the shortest way round through " +
            (loop_at == i ? "it" : "the call") + " takes " + ms_text(way.us) + " (" + parts +
            "), so a 100,000-cycle EEPROM cell can wear out after about " + duration_text(kEepromCycles * way.us);
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
  }
}

}  // namespace tmcl::detail
