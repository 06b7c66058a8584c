// The control-flow analysis (docs/analysis.md). One walk over the reachable instructions splits
// the program into regions: the main program (from address 0 and every RST target), each
// subroutine (a CSUB/CALL target) and each interrupt handler (a VECT target). A walk stops where
// another region's entry begins and records a "flow" between the two regions instead, so every
// instruction is visited once and belongs to the first region that reached it. The checks then
// read the regions' facts (their RSUBs, RETIs, STOPs, WAITs, flows and calls); the call depth is
// the longest path in the graph of regions, where a call adds one frame and a flow none.
#include "tmcl/analysis.hpp"

#include <algorithm>
#include <string>
#include <unordered_map>

#include "analysis_internal.hpp"
#include "graph.hpp"

namespace tmcl {
namespace detail {

std::string region_word(const Region& r) {
  switch (r.kind) {
    case RegionKind::Main: return "the main program";
    case RegionKind::Subroutine: return "subroutine '" + r.name + "'";
    case RegionKind::Handler: return "interrupt handler '" + r.name + "'";
  }
  return "?";
}

SourceLoc Walker::loc(int address) const {
  SourceLoc l;
  if (address < 0 || static_cast<std::size_t>(address) >= in.lines.size()) return l;
  const LineInfo& li = in.lines[static_cast<std::size_t>(address)];
  l.file = li.file;
  l.line = li.line;
  l.col = 0;
  if (!in.sources || li.file < 0 || static_cast<std::size_t>(li.file) >= in.sources->files.size()) return l;
  // The caret goes under the mnemonic: the first word of the line that is not a label.
  std::string_view text = in.sources->files[static_cast<std::size_t>(li.file)].line(li.line);
  std::size_t p = 0;
  for (;;) {
    while (p < text.size() && (text[p] == ' ' || text[p] == '\t')) ++p;
    std::size_t e = p;
    while (e < text.size() && text[e] != ' ' && text[e] != '\t' && text[e] != ':') ++e;
    if (e < text.size() && text[e] == ':' && e > p) {  // "label: CSUB x"
      p = e + 1;
      continue;
    }
    if (e > p) {
      l.col = static_cast<int>(p) + 1;
      l.len = static_cast<int>(e - p);
    }
    break;
  }
  return l;
}

std::string Walker::label_at(int address) const {
  auto it = labels.find(address);
  return it == labels.end() ? std::string() : it->second;
}

int Walker::region_at(int address) {
  int& r = entry_region[static_cast<std::size_t>(address)];
  if (r >= 0) return r;
  r = static_cast<int>(a.regions.size());
  Region reg;
  reg.kind = (target_flags[static_cast<std::size_t>(address)] & kVectTarget) ? RegionKind::Handler : RegionKind::Subroutine;
  reg.entry = address;
  reg.name = label_at(address);
  if (reg.name.empty())
    reg.name = std::string(reg.kind == RegionKind::Handler ? "handler_" : "sub_") + std::to_string(address);
  a.regions.push_back(std::move(reg));
  facts.emplace_back();
  queue.push_back(r);
  return r;
}

void Walker::edge(int from, int to, EdgeKind kind) {
  if (options.graph) a.edges.push_back({from, to, kind});
}

// Continues region `r` at address `to`, coming from instruction `from` (-1: the region's start).
void Walker::reach(int r, int from, int to) {
  auto t = static_cast<std::size_t>(to);
  if ((target_flags[t] & (kCallTarget | kVectTarget)) && to != a.regions[static_cast<std::size_t>(r)].entry) {
    int q = region_at(to);
    if (q != r) {
      flows.push_back({from, r, q, to});
      return;
    }
  }
  if (a.owner[t] < 0) {
    a.owner[t] = r;
    work.push_back(to);
  } else if (a.owner[t] != r) {
    flows.push_back({from, r, a.owner[t], to});
  }
}

void Walker::walk(int r, int from, int start) {
  reach(r, from, start);
  const int n = static_cast<int>(in.program.size());
  while (!work.empty()) {
    int i = work.back();
    work.pop_back();
    const Instruction& ins = in.program[static_cast<std::size_t>(i)];
    auto f = [this, r]() -> RegionFacts& { return facts[static_cast<std::size_t>(r)]; };  // facts may grow
    const int t = ins.value;
    const bool t_ok = t >= 0 && t < n;
    bool next = true;
    switch (static_cast<Op>(ins.op)) {
      case Op::JA:
        next = false;
        [[fallthrough]];
      case Op::JC:
      case Op::DJNZ:
        if (t_ok) {
          edge(i, t, EdgeKind::Jump);
          reach(r, i, t);
        } else {
          bad_jumps.push_back(i);
        }
        break;
      case Op::CSUB:
      case Op::CALL:
        if (t_ok) {
          edge(i, t, EdgeKind::Call);
          calls.push_back({i, r, region_at(t)});
          // After a subroutine that never returns (it stops, restarts or loops) nothing follows.
          if (!noreturn_at.empty() && noreturn_at[static_cast<std::size_t>(t)]) next = false;
        } else {
          bad_jumps.push_back(i);
        }
        break;
      case Op::RST:
        next = false;
        if (t_ok) {
          edge(i, t, EdgeKind::Jump);
          if (r == 0) reach(r, i, t);
          else restarts.push_back({i, t});  // a reset leaves any region cleanly for the main program
        } else {
          bad_jumps.push_back(i);
        }
        break;
      case Op::VECT:
        if (t_ok) {
          edge(i, t, EdgeKind::Vect);
          int h = region_at(t);
          auto& v = a.regions[static_cast<std::size_t>(h)].vectors;
          if (std::find(v.begin(), v.end(), ins.type) == v.end()) v.push_back(ins.type);
          vect_set[ins.type] = true;
        } else {
          bad_vects.push_back(i);
        }
        break;
      case Op::EI: eis.push_back(i); break;
      // With nothing to return to, RSUB and RETI are ignored (manual; errata E6, E13) and the
      // program goes on: in the main program and in a handler (RSUB), in the main program (RETI).
      case Op::RSUB:
        f().rsubs.push_back(i);
        next = a.regions[static_cast<std::size_t>(r)].kind != RegionKind::Subroutine;
        break;
      case Op::RETI:
        f().retis.push_back(i);
        next = a.regions[static_cast<std::size_t>(r)].kind == RegionKind::Main;
        break;
      case Op::STOP: f().stops.push_back(i); next = false; break;
      case Op::WAIT: f().waits.push_back(i); break;
      case Op::STAP:
      case Op::STGP: writes.push_back(i); break;
      case Op::SCO:
        if (ins.motor == 255) writes.push_back(i);  // E29: SCO n, 255 copies coordinates to the EEPROM
        break;
      case Op::SGP:
        if (in.profile) {
          const ParamInfo* p = in.profile->global_param(ins.motor, ins.type);
          if (p && (p->access & kAutoStore)) writes.push_back(i);
        }
        break;
      default:
        if (!op_info(ins.op)) next = false;  // not an instruction: the VM faults here (E20)
        break;
    }
    if (!next) continue;
    if (i + 1 >= n) {
      f().falloffs.push_back(i);
      continue;
    }
    edge(i, i + 1, EdgeKind::Next);
    reach(r, i, i + 1);
  }
}

void Walker::build() {
  pass();
  // A second pass when some call can never return: the code after it is then not reached from
  // it (the manual's RST example calls a subroutine that restarts the program). Regions that
  // return are found from the first pass; the second can only find fewer paths.
  const int n = static_cast<int>(in.program.size());
  const int nr = static_cast<int>(a.regions.size());
  std::vector<char> returns(static_cast<std::size_t>(nr), 0);
  std::vector<int> stack;
  for (int r = 0; r < nr; ++r)
    if (region(r).kind == RegionKind::Subroutine && !fact(r).rsubs.empty()) {
      returns[static_cast<std::size_t>(r)] = 1;
      stack.push_back(r);
    }
  std::vector<std::vector<int>> flow_in(static_cast<std::size_t>(nr));
  for (const auto& fl : flows)
    if (region(fl.from_region).kind == RegionKind::Subroutine && region(fl.to_region).kind == RegionKind::Subroutine)
      flow_in[static_cast<std::size_t>(fl.to_region)].push_back(fl.from_region);
  while (!stack.empty()) {
    int v = stack.back();
    stack.pop_back();
    for (int u : flow_in[static_cast<std::size_t>(v)])
      if (!returns[static_cast<std::size_t>(u)]) {
        returns[static_cast<std::size_t>(u)] = 1;
        stack.push_back(u);
      }
  }
  bool again = false;
  std::vector<char> noreturn(static_cast<std::size_t>(n), 0);
  for (const auto& c : calls)
    if (!returns[static_cast<std::size_t>(c.callee)] && region(c.callee).kind == RegionKind::Subroutine) {
      noreturn[static_cast<std::size_t>(region(c.callee).entry)] = 1;
      again = true;
    }
  if (!again) return;
  a = Analysis{};
  facts.clear();
  labels.clear();
  queue.clear();
  flows.clear();
  calls.clear();
  restarts.clear();
  bad_jumps.clear();
  bad_vects.clear();
  eis.clear();
  writes.clear();
  vect_set = {};
  noreturn_at = std::move(noreturn);
  pass();
}

void Walker::pass() {
  const int n = static_cast<int>(in.program.size());
  a.owner.assign(static_cast<std::size_t>(n), -1);
  entry_region.assign(static_cast<std::size_t>(n), -1);
  target_flags.assign(static_cast<std::size_t>(n), 0);
  for (const auto& s : in.symbols)
    if (s.kind == SymbolKind::Label && s.value >= 0 && s.value < n) labels.emplace(static_cast<int>(s.value), s.name);
  // Every call and VECT target is an entry, whether or not its caller is reachable, so that a
  // walk stops at a subroutine's label even before the CSUB naming it has been seen.
  for (int i = 0; i < n; ++i) {
    const Instruction& ins = in.program[static_cast<std::size_t>(i)];
    if (ins.value < 0 || ins.value >= n) continue;
    if (ins.op == static_cast<std::uint8_t>(Op::CSUB) || ins.op == static_cast<std::uint8_t>(Op::CALL))
      target_flags[static_cast<std::size_t>(ins.value)] |= kCallTarget;
    else if (ins.op == static_cast<std::uint8_t>(Op::VECT))
      target_flags[static_cast<std::size_t>(ins.value)] |= kVectTarget;
  }
  if (n == 0) return;
  Region main;
  main.kind = RegionKind::Main;
  main.entry = 0;
  main.name = label_at(0).empty() ? "main" : label_at(0);
  a.regions.push_back(main);
  facts.emplace_back();
  entry_region[0] = 0;
  // The main program first: it owns its code; then every region in the order found. A program
  // that begins with a run of JAs is a table of entry points a host starts with command 129
  // (USB-2-SD manual 7.6): each JA of the run starts the main program.
  walk(0, -1, 0);
  for (int i = 1; i < n && in.program[static_cast<std::size_t>(i - 1)].op == static_cast<std::uint8_t>(Op::JA) &&
                  in.program[static_cast<std::size_t>(i)].op == static_cast<std::uint8_t>(Op::JA);
       ++i)
    restarts.push_back({-1, i});
  std::size_t next_restart = 0, next_region = 0;
  for (;;) {
    if (next_restart < restarts.size()) {
      auto [from, to] = restarts[next_restart++];
      walk(0, from, to);
      continue;
    }
    while (next_region < queue.size() && queue[next_region] == 0) ++next_region;
    if (next_region < queue.size()) {
      int r = queue[next_region++];
      walk(r, -1, a.regions[static_cast<std::size_t>(r)].entry);
      continue;
    }
    // Exported labels no call reaches are a linked member's other subroutines, linked with the
    // ones used (a member links whole): subroutines of their own, not unreachable code.
    bool more = false;
    for (const auto& sym : in.symbols) {
      if (sym.kind != SymbolKind::Label || !sym.exported || sym.value < 0 || sym.value >= n) continue;
      auto t = static_cast<std::size_t>(sym.value);
      if (a.owner[t] >= 0 || entry_region[t] >= 0) continue;
      target_flags[t] |= kCallTarget;
      region_at(static_cast<int>(t));
      more = true;
    }
    if (!more) break;
  }
}

}  // namespace detail

Analysis analyze(const AnalysisInput& in, Diagnostics& diags, const AnalysisOptions& options) {
  detail::Walker w(in, diags, options);
  w.build();
  w.depths();
  w.check_flow();
  w.check_interrupts();
  w.check_unreachable();
  w.check_depth();
  w.check_eeprom();
  return std::move(w.a);
}

}  // namespace tmcl
