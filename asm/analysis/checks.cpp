// The checks of the analysis listed in kChecks (analysis_internal.hpp) but -Weeprom-wear's
// (eeprom_wear.cpp), each reading the regions the walk built (analysis.cpp): call depth and
// recursion over the graph of regions, flows out of subroutines and handlers, RSUB and RETI where
// nothing can be returned to, interrupts and unreachable code.
#include <algorithm>
#include <cstdio>
#include <set>
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
  // A flow into another subroutine or handler runs there in the same frame (a shared tail);
  // a flow into the main program is a leak (-Wstack-leak) and adds nothing to a depth.
  out.build(nr, [this](auto add) {
    for (const auto& c : calls) add(c.caller, RegionEdge{c.callee, 1, c.site});
    for (const auto& f : flows)
      if (f.from_region != f.to_region && region(f.to_region).kind != RegionKind::Main)
        add(f.from_region, RegionEdge{f.to_region, 0, f.from});
  });
  std::vector<int> roots(static_cast<std::size_t>(nr));
  for (int r = 0; r < nr; ++r) roots[static_cast<std::size_t>(r)] = r;
  // Each component's depth as it completes (the components its edges lead to have completed
  // before): the deepest of its members' edges out of it, one frame more for a call. Members in
  // the order of their regions, edges in the order met: the first of equal depths is the chain.
  recursive.assign(static_cast<std::size_t>(nr), 0);
  std::vector<int> depth(static_cast<std::size_t>(nr), 0), members;
  std::vector<char> in_order;
  int count = 0;
  comp = strong_components(
      nr, roots,
      [this](int v, int k) {
        auto edges = out[static_cast<std::size_t>(v)];
        return static_cast<std::size_t>(k) < edges.size() ? edges[static_cast<std::size_t>(k)].to : -1;
      },
      count,
      [&](int c, std::span<const int> in_component, const std::vector<int>& comp_of) {
        if (in_component.size() > 1) {
          // In region order. A component of a sixteenth of the regions or more (call-dense code
          // that wraps around is one of 100,000) is put in order by a mark per region, a pass
          // over them all (at most sixteen such components): linear, where sorting is not.
          if (in_component.size() * 16 >= static_cast<std::size_t>(nr)) {
            in_order.assign(static_cast<std::size_t>(nr), 0);
            for (int v : in_component) in_order[static_cast<std::size_t>(v)] = 1;
            members.clear();
            for (int v = 0; v < nr; ++v)
              if (in_order[static_cast<std::size_t>(v)]) members.push_back(v);
          } else {
            members.assign(in_component.begin(), in_component.end());
            std::sort(members.begin(), members.end());
          }
          in_component = members;
        }
        int d = 0;
        RegionEdge best{-1, 0, -1};
        for (int v : in_component)
          for (const auto& e : out[static_cast<std::size_t>(v)]) {
            int tc = comp_of[static_cast<std::size_t>(e.to)];
            if (tc == c) {
              if (e.weight > 0) recursive[static_cast<std::size_t>(c)] = 1;
              continue;
            }
            int td = depth[static_cast<std::size_t>(tc)];
            int val = td >= kUnbounded ? kUnbounded : td + e.weight;
            if (val > d || (best.to < 0 && val == d && val > 0)) {
              d = val;
              best = e;
            }
          }
        const bool cycle = recursive[static_cast<std::size_t>(c)] != 0;
        depth[static_cast<std::size_t>(c)] = cycle ? kUnbounded : d;
        for (int v : in_component) {
          Region& reg = a.regions[static_cast<std::size_t>(v)];
          reg.depth = depth[static_cast<std::size_t>(c)];
          if (!cycle && best.to >= 0) {
            reg.chain_to = best.to;
            reg.chain_site = best.weight > 0 ? best.site : -1;
          }
        }
      });
  recursive.resize(static_cast<std::size_t>(count));
  a.main_depth = a.regions.empty() ? 0 : a.regions[0].depth;
}

bool Walker::want(std::string_view name, int address) {
  SourceLoc at;  // file and line are all a suppression comment needs
  if (address >= 0 && static_cast<std::size_t>(address) < in.lines.size()) {
    at.file = in.lines[static_cast<std::size_t>(address)].file;
    at.line = in.lines[static_cast<std::size_t>(address)].line;
  }
  return diags.take(name, at);
}


namespace {
// Gives `value` to every region `g` leads to from the regions on `stack` (emptied) whose mark is
// still `unmarked`; the stack's own regions are marked already.
template <class T>
void spread(const RegionGraph& g, std::vector<int>& stack, std::vector<T>& mark, T unmarked, T value) {
  while (!stack.empty()) {
    int v = stack.back();
    stack.pop_back();
    for (const auto& e : g[static_cast<std::size_t>(v)])
      if (mark[static_cast<std::size_t>(e.to)] == unmarked) {
        mark[static_cast<std::size_t>(e.to)] = value;
        stack.push_back(e.to);
      }
  }
}
}  // namespace

void Walker::check_flow() {
  const int nr = static_cast<int>(a.regions.size());
  const int n = static_cast<int>(in.program.size());
  // Which regions run on behalf of the main program and which on behalf of a handler.
  std::vector<int> from_main(static_cast<std::size_t>(nr), 0), from_handler(static_cast<std::size_t>(nr), -1);
  std::vector<int> stack{0};
  if (nr > 0) from_main[0] = 1;
  spread(out, stack, from_main, 0, 1);
  for (int h = 0; h < nr; ++h)
    if (region(h).kind == RegionKind::Handler) from_handler[static_cast<std::size_t>(h)] = h;  // each its own
  for (int h = 0; h < nr; ++h) {
    if (region(h).kind != RegionKind::Handler) continue;
    stack.push_back(h);
    spread(out, stack, from_handler, -1, h);
  }
  // Which regions can end in RST, themselves or in a region they call or run into: RST clears the
  // interrupt state (E31), a legitimate way out of a handler, not a handler that never ends (E43).
  // Found backwards from the regions with an RST, so each region and edge is looked at once.
  std::vector<char> resets(static_cast<std::size_t>(nr), 0);
  if (any_reset()) {
    RegionGraph into;
    into.build(nr, [&](auto add) {
      for (int v = 0; v < nr; ++v)
        for (const auto& e : out[static_cast<std::size_t>(v)]) add(e.to, RegionEdge{v, e.weight, e.site});
    });
    for (int v = 0; v < nr; ++v)
      if (met_any(v, Fact::Reset)) {
        resets[static_cast<std::size_t>(v)] = 1;
        stack.push_back(v);
      }
    spread(into, stack, resets, char{0}, char{1});
  }
  // Per region: its first call (for "called from here" notes; -1 when none) and whether control
  // flows from it into another region.
  std::vector<int> first_call(static_cast<std::size_t>(nr), -1);
  for (const auto& c : calls)
    if (first_call[static_cast<std::size_t>(c.callee)] < 0) first_call[static_cast<std::size_t>(c.callee)] = c.site;
  std::vector<char> flows_out(static_cast<std::size_t>(nr), 0);
  for (const auto& fl : flows)
    if (fl.to_region != fl.from_region) flows_out[static_cast<std::size_t>(fl.from_region)] = 1;
  auto note_start = [&](Diagnostic& d, int r) {
    diags.note(d, loc(region(r).entry), region_word(region(r)) + " starts here");
  };
  auto note_called = [&](Diagnostic& d, int r) {
    int site = first_call[static_cast<std::size_t>(r)];
    if (site >= 0) diags.note(d, loc(site), "called from here");
  };

  // Flows between regions, each (instruction, region entered) once.
  std::set<std::pair<int, int>> seen;
  for (const auto& f : flows) {
    if (f.from < 0 || f.from_region == f.to_region) continue;
    const Region& fr = region(f.from_region);
    const Region& tr = region(f.to_region);
    const char* kind = fr.kind == RegionKind::Main && tr.kind == RegionKind::Subroutine        ? "rsub"
                       : fr.kind == RegionKind::Main && tr.kind == RegionKind::Handler         ? "reti"
                       : fr.kind == RegionKind::Subroutine && tr.kind != RegionKind::Subroutine ? "stack-leak"
                       : fr.kind == RegionKind::Handler && tr.kind != RegionKind::Handler      ? "reti"
                                                                                               : nullptr;
    if (!kind || !seen.emplace(f.from, f.to_region).second || !want(kind, f.from)) continue;
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
    } else if (fr.kind == RegionKind::Main) {
      auto& d = diags.warning(loc(f.from), how + " outside an interrupt: its RETI will be ignored", "reti");
      note_start(d, f.to_region);
    } else if (fr.kind == RegionKind::Subroutine) {
      auto& d = diags.warning(loc(f.from),
                              how + " without RSUB: the return address stays on the call stack, one more each time",
                              "stack-leak");
      note_start(d, f.from_region);
      note_called(d, f.from_region);
    } else {
      auto& d = diags.warning(loc(f.from), how + " without RETI: other interrupts stay blocked", "reti");
      note_start(d, f.from_region);
      if (!jumps) fix_add_reti(d, f.from);
    }
  }

  for (int r = 0; r < nr; ++r) {
    const Region& reg = region(r);
    const bool handler_ctx = from_handler[static_cast<std::size_t>(r)] >= 0;
    // Most regions are subroutines the main program calls that met nothing but RSUBs (and WAITs):
    // nothing to look at.
    if (reg.kind == RegionKind::Subroutine && !handler_ctx && !met_any(r, Fact::Reti) && !met_any(r, Fact::Falloff))
      continue;
    const RegionFacts f = fact(r);
    if (reg.kind == RegionKind::Main)
      for (int i : f.rsubs)
        if (want("rsub", i))
          diags.warning(loc(i), "RSUB in the main program finds the call stack empty: the module ignores it", "rsub");
    if (reg.kind == RegionKind::Handler)
      for (int i : f.rsubs) {
        if (!want("reti", i)) continue;
        auto& d = diags.warning(loc(i), "RSUB in " + region_word(reg) +
                                            " has no call of the handler's to return from: the module ignores it "
                                            "and the handler goes on without RETI",
                                "reti");
        note_start(d, r);
      }
    if (reg.kind == RegionKind::Main || (reg.kind == RegionKind::Subroutine && from_main[static_cast<std::size_t>(r)]))
      for (int i : f.retis) {
        if (!want("reti", i)) continue;
        auto& d = diags.warning(loc(i), "RETI outside any interrupt handler: the module ignores it", "reti");
        if (reg.kind == RegionKind::Subroutine) {
          note_start(d, r);
          note_called(d, r);
        }
      }
    if (reg.kind == RegionKind::Handler || (reg.kind == RegionKind::Subroutine && handler_ctx))
      for (int i : f.stops) {
        if (!want("reti", i)) continue;
        const Region& h = region(from_handler[static_cast<std::size_t>(r)]);
        auto& d = diags.warning(loc(i), "STOP ends the program inside " + region_word(h) + ", without RETI", "reti");
        if (reg.kind == RegionKind::Subroutine) note_called(d, r);
        else note_start(d, r);
        // The assembler's STOP after a handler at the end of the program: its RETI is missing.
        if (in.appended_stop && i == n - 1 && i > 0) fix_add_reti(d, i - 1);
      }
    if (reg.kind == RegionKind::Handler && f.retis.empty()) {
      bool leaves = flows_out[static_cast<std::size_t>(r)] != 0;
      for (const auto& e : out[static_cast<std::size_t>(r)]) leaves = leaves || e.weight == 0;
      if (!leaves && f.falloffs.empty() && f.rsubs.empty() && f.stops.empty() && !resets[static_cast<std::size_t>(r)] &&
          want("reti", reg.entry))
        diags.warning(loc(reg.entry), region_word(reg) + " never reaches RETI: once it runs, other interrupts stay blocked",
                      "reti");
    }
    for (int i : f.falloffs)
      if (want("fall-off", i))
        diags.warning(loc(i), "execution runs past the last instruction of the program (address " +
                                  std::to_string(n - 1) + "): the module would run whatever its memory holds there",
                      "fall-off");
    if (reg.kind == RegionKind::Handler || (reg.kind == RegionKind::Subroutine && handler_ctx))
      for (int i : f.waits) {
        if (!want("wait-in-handler", i)) continue;
        const Region& h = region(from_handler[static_cast<std::size_t>(r)]);
        auto& d = diags.warning(loc(i), "WAIT inside " + region_word(h) + " blocks every other interrupt until it ends",
                                "wait-in-handler");
        if (reg.kind == RegionKind::Subroutine) note_called(d, r);
        else note_start(d, r);
      }
  }
  if (!in.targets_checked)
    for (int i : bad_jumps)
      if (want("address", i))
        diags.warning(loc(i), "address " + std::to_string(ins(i).value) + " is outside the program (addresses 0 to " +
                                  std::to_string(n - 1) + ")",
                      "address");
}

void Walker::check_interrupts() {
  const int n = static_cast<int>(in.program.size());
  if (!in.targets_checked)
    for (int i : bad_vects)
      if (want("vect", i))
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
    if (!vect_set[static_cast<std::size_t>(v)] && want("vect", i))
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
  const int* const owner = a.owner.data();
  for (int i = 0; i < last;) {
    // Reached code eight instructions at a time: only an unreached one has a negative owner.
    while (i + 8 <= last && (owner[i] | owner[i + 1] | owner[i + 2] | owner[i + 3] | owner[i + 4] | owner[i + 5] |
                             owner[i + 6] | owner[i + 7]) >= 0)
      i += 8;
    while (i < last && owner[i] >= 0) ++i;
    if (i >= last) break;
    int j = i;
    while (j < last && owner[j] < 0) ++j;
    int count = j - i;
    if (!want("unreachable", i)) {
      i = j;
      continue;
    }
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
  // The breadth-first search's tables, made once and reset where each search wrote (a program
  // with thousands of cycles must not clear a table of all regions for each).
  std::vector<int> prev_site(a.regions.size(), -2), prev_region(a.regions.size(), -1);
  std::vector<int> q;
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
    if (!want("recursion", call->site)) continue;
    // The way back from the callee to v inside the component (breadth first, so the shortest).
    for (int x : q) {
      prev_site[static_cast<std::size_t>(x)] = -2;
      prev_region[static_cast<std::size_t>(x)] = -1;
    }
    q.assign(1, call->to);
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
    // A cycle through thousands of subroutines is shown by its first calls and its last: the
    // notes between say nothing new, and building them cost more than the analysis itself.
    constexpr std::size_t kShownCalls = 8;
    for (std::size_t k = 0; k < sites.size(); ++k) {
      if (k == kShownCalls && sites.size() > kShownCalls + 1) k = sites.size() - 1;
      int s = sites[k], to = region_of_entry(ins(s).value);
      std::string skipped = k > kShownCalls ? std::to_string(k - kShownCalls) + " calls further on, " : std::string();
      diags.note(d, loc(s), skipped + "which calls " + (to >= 0 ? region_word(region(to)) : std::string("a subroutine")) + " here");
    }
  }

  // -Wcall-depth: the main program's deepest chain, then each handler on top of it.
  auto callee_word = [&](int site) {
    int to = region_of_entry(ins(site).value);
    return to >= 0 ? region_word(region(to)) : std::string("a subroutine");
  };
  const Region& main = region(0);
  // Only the calls a message names: the 9th, and those below it.
  const std::vector<int> main_chain = deepest_chain(a, 0, kCallStackDepth + 1);
  if (main.depth < kUnbounded && main.depth > kCallStackDepth) {
    const auto& ch = main_chain;
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
    const std::vector<int> chain = deepest_chain(a, h, kCallStackDepth + 1);
    int site = chain[static_cast<std::size_t>(idx)];
    if (!want("call-depth", site)) continue;
    auto& d = diags.warning(loc(site), mnemonic(site) + " in " + region_word(reg) +
                                           " is the 9th nested call when the interrupt fires while the main program is " +
                                           std::to_string(main.depth) +
                                           " calls deep: handlers share the call stack (errata E39), so the module "
                                           "ignores it",
                            "call-depth");
    for (int k = idx - 1; k >= 0; --k)
      diags.note(d, loc(chain[static_cast<std::size_t>(k)]), callee_word(chain[static_cast<std::size_t>(k)]) +
                                                              " called from here, in the handler");
    for (int k = main.depth - 1; k >= 0; --k)
      diags.note(d, loc(main_chain[static_cast<std::size_t>(k)]),
                 k == main.depth - 1 ? "the interrupt can fire inside " + callee_word(main_chain[static_cast<std::size_t>(k)]) +
                                           ", called from here " + std::to_string(main.depth) + " calls deep"
                                     : "call " + std::to_string(k + 1) + " of the main program's deepest chain");
  }
}

}  // namespace tmcl::detail
