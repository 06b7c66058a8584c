// The checks of the analysis, each reading the regions the walk built (analysis.cpp): call
// depth and recursion over the graph of regions, flows out of subroutines and handlers, RSUB
// and RETI where nothing can be returned to, interrupts, unreachable code and EEPROM wear.
#include <algorithm>
#include <cstdio>
#include <string>

#include "analysis_internal.hpp"
#include "graph.hpp"

namespace tmcl::detail {

std::string Walker::mnemonic(int i) const {
  const OpInfo* info = op_info(ins(i).op);
  return info ? std::string(info->mnemonic) : "instruction";
}

void Walker::depths() {
  const int nr = static_cast<int>(a.regions.size());
  out.assign(static_cast<std::size_t>(nr), {});
  for (const auto& c : calls) out[static_cast<std::size_t>(c.caller)].push_back({c.callee, 1, c.site});
  // A flow into another subroutine or handler runs there in the same frame (a shared tail);
  // a flow into the main program is a leak (-Wstack-leak) and adds nothing to a depth.
  for (const auto& f : flows)
    if (f.from_region != f.to_region && region(f.to_region).kind != RegionKind::Main)
      out[static_cast<std::size_t>(f.from_region)].push_back({f.to_region, 0, f.from});
  std::vector<int> roots(static_cast<std::size_t>(nr));
  for (int r = 0; r < nr; ++r) roots[static_cast<std::size_t>(r)] = r;
  int count = 0;
  comp = strong_components(
      nr, roots,
      [this](int v, std::vector<int>& s) {
        for (const auto& e : out[static_cast<std::size_t>(v)]) s.push_back(e.to);
      },
      count);
  recursive.assign(static_cast<std::size_t>(count), 0);
  best.assign(static_cast<std::size_t>(count), RegionEdge{-1, 0, -1});
  best_from.assign(static_cast<std::size_t>(count), -1);
  std::vector<int> depth(static_cast<std::size_t>(count), 0);
  // Regions by component, callees' components first (Tarjan's numbering).
  std::vector<int> order(static_cast<std::size_t>(nr));
  for (int r = 0; r < nr; ++r) order[static_cast<std::size_t>(r)] = r;
  std::stable_sort(order.begin(), order.end(), [this](int x, int y) {
    return comp[static_cast<std::size_t>(x)] < comp[static_cast<std::size_t>(y)];
  });
  for (std::size_t k = 0; k < order.size();) {
    int c = comp[static_cast<std::size_t>(order[k])];
    std::size_t end = k;
    while (end < order.size() && comp[static_cast<std::size_t>(order[end])] == c) ++end;
    auto& d = depth[static_cast<std::size_t>(c)];
    for (std::size_t m = k; m < end; ++m) {
      int v = order[m];
      for (const auto& e : out[static_cast<std::size_t>(v)]) {
        int tc = comp[static_cast<std::size_t>(e.to)];
        if (tc == c) {
          if (e.weight > 0) recursive[static_cast<std::size_t>(c)] = 1;
          continue;
        }
        int td = depth[static_cast<std::size_t>(tc)];
        int val = td >= kUnbounded ? kUnbounded : td + e.weight;
        if (val > d || (best[static_cast<std::size_t>(c)].to < 0 && val == d && val > 0)) {
          d = val;
          best[static_cast<std::size_t>(c)] = e;
          best_from[static_cast<std::size_t>(c)] = v;
        }
      }
    }
    if (recursive[static_cast<std::size_t>(c)]) d = kUnbounded;
    k = end;
  }
  for (int r = 0; r < nr; ++r) {
    Region& reg = a.regions[static_cast<std::size_t>(r)];
    reg.depth = depth[static_cast<std::size_t>(comp[static_cast<std::size_t>(r)])];
    reg.chain = chain_of(r);
  }
  a.main_depth = a.regions.empty() ? 0 : a.regions[0].depth;
}

std::vector<int> Walker::chain_of(int r) const {
  std::vector<int> chain;
  int cur = r;
  for (std::size_t steps = 0; steps <= a.regions.size(); ++steps) {
    int c = comp[static_cast<std::size_t>(cur)];
    const RegionEdge& e = best[static_cast<std::size_t>(c)];
    if (recursive[static_cast<std::size_t>(c)] || e.to < 0) break;
    if (e.weight > 0) chain.push_back(e.site);
    cur = e.to;
  }
  return chain;
}

namespace {
// The first call of region `r`, for "called from here" notes; -1 when none.
int first_call_of(const std::vector<CallSite>& calls, int r) {
  for (const auto& c : calls)
    if (c.callee == r) return c.site;
  return -1;
}
}  // namespace

void Walker::check_flow() {
  const int nr = static_cast<int>(a.regions.size());
  const int n = static_cast<int>(in.program.size());
  // Which regions run on behalf of the main program and which on behalf of a handler.
  std::vector<int> from_main(static_cast<std::size_t>(nr), 0), from_handler(static_cast<std::size_t>(nr), -1);
  std::vector<int> stack{0};
  if (nr > 0) from_main[0] = 1;
  while (!stack.empty()) {
    int v = stack.back();
    stack.pop_back();
    for (const auto& e : out[static_cast<std::size_t>(v)])
      if (!from_main[static_cast<std::size_t>(e.to)]) {
        from_main[static_cast<std::size_t>(e.to)] = 1;
        stack.push_back(e.to);
      }
  }
  for (int h = 0; h < nr; ++h)
    if (region(h).kind == RegionKind::Handler) from_handler[static_cast<std::size_t>(h)] = h;  // each its own
  for (int h = 0; h < nr; ++h) {
    if (region(h).kind != RegionKind::Handler) continue;
    stack.push_back(h);
    while (!stack.empty()) {
      int v = stack.back();
      stack.pop_back();
      for (const auto& e : out[static_cast<std::size_t>(v)])
        if (from_handler[static_cast<std::size_t>(e.to)] < 0) {
          from_handler[static_cast<std::size_t>(e.to)] = h;
          stack.push_back(e.to);
        }
    }
  }
  // Whether a handler can end in RST, itself or in a subroutine it calls: RST clears the
  // interrupt state (E31), a legitimate way out of a handler, not a handler that never ends (E43).
  auto resets_from = [&](int h) {
    std::vector<char> seen_region(static_cast<std::size_t>(nr), 0);
    std::vector<int> todo{h};
    seen_region[static_cast<std::size_t>(h)] = 1;
    while (!todo.empty()) {
      int v = todo.back();
      todo.pop_back();
      if (!fact(v).resets.empty()) return true;
      for (const auto& e : out[static_cast<std::size_t>(v)])
        if (!seen_region[static_cast<std::size_t>(e.to)]) {
          seen_region[static_cast<std::size_t>(e.to)] = 1;
          todo.push_back(e.to);
        }
    }
    return false;
  };
  auto note_start = [&](Diagnostic& d, int r) {
    diags.note(d, loc(region(r).entry), region_word(region(r)) + " starts here");
  };
  auto note_called = [&](Diagnostic& d, int r) {
    int site = first_call_of(calls, r);
    if (site >= 0) diags.note(d, loc(site), "called from here");
  };

  // Flows between regions.
  std::vector<std::pair<int, int>> seen;
  for (const auto& f : flows) {
    if (f.from < 0 || f.from_region == f.to_region) continue;
    if (std::find(seen.begin(), seen.end(), std::pair{f.from, f.to_region}) != seen.end()) continue;
    seen.emplace_back(f.from, f.to_region);
    const Region& fr = region(f.from_region);
    const Region& tr = region(f.to_region);
    const Instruction& src = ins(f.from);
    const bool jumps = (src.op == static_cast<std::uint8_t>(Op::JA) || src.op == static_cast<std::uint8_t>(Op::JC) ||
                        src.op == static_cast<std::uint8_t>(Op::DJNZ) || src.op == static_cast<std::uint8_t>(Op::RST)) &&
                       src.value == f.to;
    std::string how = jumps ? mnemonic(f.from) + " jumps from " + region_word(fr) + " into " + region_word(tr)
                            : region_word(fr) + " runs on into " + region_word(tr);
    how[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(how[0])));
    if (fr.kind == RegionKind::Main && tr.kind == RegionKind::Subroutine) {
      auto& d = diags.warning(loc(f.from), how + " without CSUB: its RSUB will find the call stack empty", "rsub");
      note_start(d, f.to_region);
      if (!fact(f.to_region).rsubs.empty())
        diags.note(d, loc(fact(f.to_region).rsubs.front()), "this RSUB is then ignored and execution goes on after it");
    } else if (fr.kind == RegionKind::Main && tr.kind == RegionKind::Handler) {
      auto& d = diags.warning(loc(f.from), how + " outside an interrupt: its RETI will be ignored", "reti");
      note_start(d, f.to_region);
    } else if (fr.kind == RegionKind::Subroutine && tr.kind != RegionKind::Subroutine) {
      auto& d = diags.warning(loc(f.from),
                              how + " without RSUB: the return address stays on the call stack, one more each time",
                              "stack-leak");
      note_start(d, f.from_region);
      note_called(d, f.from_region);
    } else if (fr.kind == RegionKind::Handler && tr.kind != RegionKind::Handler) {
      auto& d = diags.warning(loc(f.from), how + " without RETI: other interrupts stay blocked", "reti");
      note_start(d, f.from_region);
      if (!jumps) fix_add_reti(d, f.from);
    }
  }

  for (int r = 0; r < nr; ++r) {
    const Region& reg = region(r);
    const RegionFacts& f = fact(r);
    const bool handler_ctx = from_handler[static_cast<std::size_t>(r)] >= 0;
    if (reg.kind == RegionKind::Main)
      for (int i : f.rsubs)
        diags.warning(loc(i), "RSUB in the main program finds the call stack empty: the module ignores it", "rsub");
    if (reg.kind == RegionKind::Handler)
      for (int i : f.rsubs) {
        auto& d = diags.warning(loc(i), "RSUB in " + region_word(reg) +
                                            " has no call of the handler's to return from: the module ignores it "
                                            "and the handler goes on without RETI",
                                "reti");
        note_start(d, r);
      }
    if (reg.kind == RegionKind::Main || (reg.kind == RegionKind::Subroutine && from_main[static_cast<std::size_t>(r)]))
      for (int i : f.retis) {
        auto& d = diags.warning(loc(i), "RETI outside any interrupt handler: the module ignores it", "reti");
        if (reg.kind == RegionKind::Subroutine) {
          note_start(d, r);
          note_called(d, r);
        }
      }
    if (reg.kind == RegionKind::Handler || (reg.kind == RegionKind::Subroutine && handler_ctx))
      for (int i : f.stops) {
        const Region& h = region(from_handler[static_cast<std::size_t>(r)]);
        auto& d = diags.warning(loc(i), "STOP ends the program inside " + region_word(h) + ", without RETI", "reti");
        if (reg.kind == RegionKind::Subroutine) note_called(d, r);
        else note_start(d, r);
        // The assembler's STOP after a handler at the end of the program: its RETI is missing.
        if (in.appended_stop && i == n - 1 && i > 0) fix_add_reti(d, i - 1);
      }
    if (reg.kind == RegionKind::Handler && f.retis.empty()) {
      bool leaves = false;
      for (const auto& e : out[static_cast<std::size_t>(r)]) leaves = leaves || e.weight == 0;
      for (const auto& fl : flows) leaves = leaves || (fl.from_region == r && fl.to_region != r);
      if (!leaves && f.falloffs.empty() && f.rsubs.empty() && f.stops.empty() && !resets_from(r))
        diags.warning(loc(reg.entry), region_word(reg) + " never reaches RETI: once it runs, other interrupts stay blocked",
                      "reti");
    }
    for (int i : f.falloffs)
      diags.warning(loc(i), "execution runs past the last instruction of the program (address " +
                                std::to_string(n - 1) + "): the module would run whatever its memory holds there",
                    "fall-off");
    if (reg.kind == RegionKind::Handler || (reg.kind == RegionKind::Subroutine && handler_ctx))
      for (int i : f.waits) {
        const Region& h = region(from_handler[static_cast<std::size_t>(r)]);
        auto& d = diags.warning(loc(i), "WAIT inside " + region_word(h) + " blocks every other interrupt until it ends",
                                "wait-in-handler");
        if (reg.kind == RegionKind::Subroutine) note_called(d, r);
        else note_start(d, r);
      }
  }
  if (!in.targets_checked)
    for (int i : bad_jumps)
      diags.warning(loc(i), "address " + std::to_string(ins(i).value) + " is outside the program (addresses 0 to " +
                                std::to_string(n - 1) + ")",
                    "address");
}

void Walker::check_interrupts() {
  const int n = static_cast<int>(in.program.size());
  if (!in.targets_checked)
    for (int i : bad_vects)
      diags.warning(loc(i), "VECT " + std::to_string(ins(i).type) + " names address " + std::to_string(ins(i).value) +
                                ", which is not an instruction of the program (0 to " + std::to_string(n - 1) + ")",
                    "vect");
  int global = -1, single = -1;
  std::vector<int> sorted = eis;
  std::sort(sorted.begin(), sorted.end());
  for (int i : sorted) {
    int v = ins(i).type;
    if (v == 255) {
      if (global < 0) global = i;
      continue;
    }
    if (single < 0) single = i;
    if (!vect_set[static_cast<std::size_t>(v)])
      diags.warning(loc(i), "EI " + std::to_string(v) + " enables interrupt " + std::to_string(v) +
                                ", but no VECT gives it a handler: it is never served",
                    "vect");
  }
  if (single >= 0 && global < 0)
    diags.warning(loc(single), "interrupt " + std::to_string(ins(single).type) +
                                   " is enabled, but interrupts are never enabled globally (EI 255): no handler runs",
                  "vect");
  if (global >= 0 && single < 0)
    diags.warning(loc(global), "interrupts are enabled globally, but no single interrupt is (EI n): no handler runs",
                  "vect");
}

void Walker::check_unreachable() {
  const int n = static_cast<int>(in.program.size());
  const int last = in.appended_stop ? n - 1 : n;  // the appended STOP is not the user's code
  for (int i = 0; i < last;) {
    if (a.owner[static_cast<std::size_t>(i)] >= 0) {
      ++i;
      continue;
    }
    int j = i;
    while (j < last && a.owner[static_cast<std::size_t>(j)] < 0) ++j;
    int count = j - i;
    auto& d = diags.warning(loc(i),
                            count == 1 ? std::string("unreachable instruction: no path from address 0, a subroutine or an "
                                                     "interrupt handler reaches it")
                                       : "unreachable code: no path from address 0, a subroutine or an interrupt handler "
                                         "reaches these " + std::to_string(count) + " instructions",
                            "unreachable");
    if (count > 1) diags.note(d, loc(j - 1), "the unreachable code ends here");
    fix_remove(d, i, j - 1);
    i = j;
  }
}

void Walker::check_depth() {
  const int nr = static_cast<int>(a.regions.size());
  // -Wrecursion: once per cycle of calls, at one call of the cycle, with the way round as notes.
  std::vector<char> reported(recursive.size(), 0);
  for (int v = 0; v < nr; ++v) {
    int c = comp[static_cast<std::size_t>(v)];
    if (!recursive[static_cast<std::size_t>(c)] || reported[static_cast<std::size_t>(c)]) continue;
    const RegionEdge* call = nullptr;
    for (const auto& e : out[static_cast<std::size_t>(v)])
      if (e.weight > 0 && comp[static_cast<std::size_t>(e.to)] == c) {
        call = &e;
        break;
      }
    if (!call) continue;
    reported[static_cast<std::size_t>(c)] = 1;
    // The way back from the callee to v inside the component (breadth first, so the shortest).
    std::vector<int> prev_site(a.regions.size(), -2), prev_region(a.regions.size(), -1);
    std::vector<int> q{call->to};
    prev_site[static_cast<std::size_t>(call->to)] = -1;
    for (std::size_t k = 0; k < q.size() && prev_site[static_cast<std::size_t>(v)] == -2; ++k)
      for (const auto& e : out[static_cast<std::size_t>(q[k])])
        if (comp[static_cast<std::size_t>(e.to)] == c && prev_site[static_cast<std::size_t>(e.to)] == -2) {
          prev_site[static_cast<std::size_t>(e.to)] = e.weight > 0 ? e.site : -1;
          prev_region[static_cast<std::size_t>(e.to)] = q[k];
          q.push_back(e.to);
        }
    const Region& callee = region(call->to);
    std::string msg = v == call->to ? region_word(callee) + " calls itself"
                                    : region_word(callee) + " can call itself through " + region_word(region(v));
    auto& d = diags.warning(loc(call->site), msg + ": its call depth has no bound, and the module ignores every CSUB "
                                                   "beyond the 8th",
                            "recursion");
    std::vector<int> sites;
    for (int x = v; x != call->to && x >= 0; x = prev_region[static_cast<std::size_t>(x)])
      if (prev_site[static_cast<std::size_t>(x)] >= 0) sites.push_back(prev_site[static_cast<std::size_t>(x)]);
    std::reverse(sites.begin(), sites.end());
    for (int s : sites) {
      int to = region_of_entry(ins(s).value);
      diags.note(d, loc(s), "which calls " + (to >= 0 ? region_word(region(to)) : std::string("a subroutine")) + " here");
    }
  }

  // -Wcall-depth: the main program's deepest chain, then each handler on top of it.
  auto callee_word = [&](int site) {
    int to = region_of_entry(ins(site).value);
    return to >= 0 ? region_word(region(to)) : std::string("a subroutine");
  };
  const Region& main = region(0);
  if (main.depth < kUnbounded && main.depth > kCallStackDepth) {
    const auto& ch = main.chain;
    int site = ch[kCallStackDepth];
    auto& d = diags.warning(loc(site), mnemonic(site) + " is the 9th nested call on this path (the chain is " +
                                           std::to_string(main.depth) +
                                           " calls deep): the call stack holds 8 return addresses, so the module "
                                           "ignores it and " + callee_word(site) + " does not run",
                            "call-depth");
    for (int k = kCallStackDepth - 1; k >= 0; --k)
      diags.note(d, loc(ch[static_cast<std::size_t>(k)]),
                 "call " + std::to_string(k + 1) + ": " + callee_word(ch[static_cast<std::size_t>(k)]) + " called from here");
  }
  bool global = false;
  for (int i : eis) global = global || ins(i).type == 255;
  if (!global || main.depth > kCallStackDepth) return;
  for (int h = 0; h < nr; ++h) {
    const Region& reg = region(h);
    if (reg.kind != RegionKind::Handler || reg.depth >= kUnbounded || main.depth + reg.depth <= kCallStackDepth) continue;
    int idx = kCallStackDepth - main.depth;
    int site = reg.chain[static_cast<std::size_t>(idx)];
    auto& d = diags.warning(loc(site), mnemonic(site) + " in " + region_word(reg) +
                                           " is the 9th nested call when the interrupt fires while the main program is " +
                                           std::to_string(main.depth) +
                                           " calls deep: handlers share the call stack (errata E39), so the module "
                                           "ignores it",
                            "call-depth");
    for (int k = idx - 1; k >= 0; --k)
      diags.note(d, loc(reg.chain[static_cast<std::size_t>(k)]), callee_word(reg.chain[static_cast<std::size_t>(k)]) +
                                                                  " called from here, in the handler");
    for (int k = main.depth - 1; k >= 0; --k)
      diags.note(d, loc(main.chain[static_cast<std::size_t>(k)]),
                 k == main.depth - 1 ? "the interrupt can fire inside " + callee_word(main.chain[static_cast<std::size_t>(k)]) +
                                           ", called from here " + std::to_string(main.depth) + " calls deep"
                                     : "call " + std::to_string(k + 1) + " of the main program's deepest chain");
  }
}

}  // namespace tmcl::detail
