// The control-flow analysis (docs/analysis.md). One walk over the reachable instructions splits
// the program into regions: the main program (from address 0 and every RST target), each
// subroutine (a CSUB/CALL target) and each interrupt handler (a VECT target). A walk stops where
// another region's entry begins and records a "flow" between the two regions instead, so every
// instruction is visited once and belongs to the first region that reached it. The checks then
// read the regions' facts (their RSUBs, RETIs, STOPs, WAITs, flows and calls); the call depth is
// the longest path in the graph of regions, where a call adds one frame and a flow none.
#include "tmcl/analysis.hpp"

#include <algorithm>
#include <bit>
#include <string>

#include "analysis_internal.hpp"
#include "graph.hpp"
#include "tmcl/fileio.hpp"

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

// The region starting at `address` (a call or VECT target), made on first use. A region owns
// its entry from the start: no other region's walk claims a target address (claim() records a
// flow there instead), so owner[] doubles as the table of entries and no second per-address
// table is needed.
int Walker::region_at(int address) {
  int& o = a.owner[static_cast<std::size_t>(address)];
  if (o >= 0) return o;
  o = static_cast<int>(a.regions.size());
  Region& reg = a.regions.emplace_back();
  reg.kind = vect_target.test(address) ? RegionKind::Handler : RegionKind::Subroutine;
  reg.entry = address;
  last_caller.push_back(-1);
  queue.push_back(o);
  return o;
}

int Walker::region_of_entry(int address) const {
  if (address < 0 || static_cast<std::size_t>(address) >= a.owner.size()) return -1;
  int o = a.owner[static_cast<std::size_t>(address)];
  return o >= 0 && region(o).entry == address ? o : -1;
}

void Walker::edge(int from, int to, EdgeKind kind) {
  if (options.graph) a.edges.push_back({from, to, kind});
}

// Region names come from the labels at their entries, given after the walk in one pass over
// the symbols: the walk itself builds no table of label names (a million-line program has a
// hundred thousand labels and a few dozen regions). The first label of an address names it.
void Walker::name_regions() {
  const auto n = static_cast<std::int64_t>(in.program.size());
  std::vector<char> named(a.regions.size(), 0);
  for (const auto& s : in.symbols) {
    if (s.kind != SymbolKind::Label || s.value < 0 || s.value >= n) continue;
    int r = region_of_entry(static_cast<int>(s.value));
    if (r < 0 || named[static_cast<std::size_t>(r)]) continue;
    named[static_cast<std::size_t>(r)] = 1;
    a.regions[static_cast<std::size_t>(r)].name = s.name;
  }
  for (std::size_t r = 0; r < a.regions.size(); ++r) {
    Region& reg = a.regions[r];
    if (named[r]) continue;
    if (reg.kind == RegionKind::Main) reg.name = "main";
    else reg.name = std::string(reg.kind == RegionKind::Handler ? "handler_" : "sub_") + std::to_string(reg.entry);
  }
}

// Region `r` reaches address `to` from instruction `from` (-1: the region's start). True when
// `to` is new to the region and the walk must visit it; false when it was visited already or
// belongs to another region (then the passage is recorded as a flow).
bool Walker::claim(int r, int from, int to) {
  auto t = static_cast<std::size_t>(to);
  if (is_target(to) && to != a.regions[static_cast<std::size_t>(r)].entry) {
    int q = region_at(to);
    if (q != r) {
      flows.push_back({from, r, q, to});
      return false;
    }
  }
  int& o = a.owner[t];
  if (o < 0) {
    o = r;
    return true;
  }
  if (o != r) flows.push_back({from, r, o, to});
  return false;
}

bool Walker::writes_eeprom(const Instruction& x) const {
  switch (static_cast<Op>(x.op)) {
    case Op::STAP:
    case Op::STGP: return true;
    case Op::SCO: return x.motor == 255;  // E29: SCO n, 255 copies coordinates to the EEPROM
    case Op::SGP: {
      const ParamInfo* p = in.profile ? in.profile->global_param(x.motor, x.type) : nullptr;
      return p && (p->access & kAutoStore);
    }
    default: return false;
  }
}

void Walker::reach(int r, int from, int to) {
  if (claim(r, from, to)) work.push_back(to);
}

const std::array<OpClass, 256>& op_classes() {
  static const std::array<OpClass, 256> table = [] {
    std::array<OpClass, 256> classes{};
    for (int op = 0; op < 256; ++op) {
      OpClass c = op_info(static_cast<std::uint8_t>(op)) ? OpClass::Plain : OpClass::NotOp;
      switch (static_cast<Op>(op)) {
        case Op::JA: c = OpClass::Ja; break;
        case Op::JC:
        case Op::DJNZ: c = OpClass::Branch; break;
        case Op::CSUB:
        case Op::CALL: c = OpClass::Call; break;
        case Op::RST: c = OpClass::Rst; break;
        case Op::VECT: c = OpClass::Vect; break;
        case Op::EI: c = OpClass::Ei; break;
        case Op::RSUB: c = OpClass::Rsub; break;
        case Op::RETI: c = OpClass::Reti; break;
        case Op::STOP: c = OpClass::Stop; break;
        case Op::WAIT: c = OpClass::Wait; break;
        case Op::STAP:
        case Op::STGP:
        case Op::SCO:
        case Op::SGP: c = OpClass::Store; break;
        default: break;
      }
      classes[static_cast<std::size_t>(op)] = c;
    }
    return classes;
  }();
  return table;
}

// Depth first from `start`. Straight-line code is followed without the work stack: the next
// instruction is taken at once when it is new (the order is the one a stack would give, as the
// next instruction is always pushed last). A plain instruction (most of a program) costs a look
// at its class, at the next instruction's owner and at whether a region starts there.
void Walker::walk(int r, int from, int start) {
  if (from < 0 && start == region(r).entry) work.push_back(start);  // owned since region_at()
  else reach(r, from, start);
  const int n = static_cast<int>(in.program.size());
  const bool graph = options.graph;
  const Instruction* const program = in.program.data();
  int* const owner = a.owner.data();
  while (!work.empty()) {
    int i = work.back();
    work.pop_back();
    for (;;) {
      const Instruction& ins = program[i];
      if (const OpClass c = op_class[ins.op]; c != OpClass::Plain) {
        const int t = ins.value;
        const bool t_ok = t >= 0 && t < n;
        bool next = true;
        switch (c) {
          case OpClass::Ja:
            next = false;
            [[fallthrough]];
          case OpClass::Branch:
            if (t_ok) {
              if (graph) edge(i, t, EdgeKind::Jump);
              reach(r, i, t);
            } else {
              bad_jumps.push_back(i);
            }
            break;
          case OpClass::Call:
            if (t_ok) {
              if (graph) edge(i, t, EdgeKind::Call);
              int q = region_at(t);
              int& last = last_caller[static_cast<std::size_t>(q)];
              if (last != r) calls.push_back({i, r, q});
              last = r;
              if (keep_call_sites) call_sites.push_back(i);
              // After a subroutine that never returns (it stops, restarts or loops) nothing follows.
              if (!noreturn_at.empty() && noreturn_at[static_cast<std::size_t>(t)] &&
                  a.regions[static_cast<std::size_t>(q)].kind == RegionKind::Subroutine)
                next = false;
            } else {
              bad_jumps.push_back(i);
            }
            break;
          case OpClass::Rst:
            next = false;
            if (t_ok) {
              if (graph) edge(i, t, EdgeKind::Jump);
              if (r == 0) reach(r, i, t);
              else {
                // A reset leaves any region cleanly for the main program: it clears the call stack
                // and the interrupt state, so it is also a way out of a handler (errata E31, E43).
                restarts.push_back({i, t});
                met(r, Fact::Reset, i);
              }
            } else {
              bad_jumps.push_back(i);
            }
            break;
          case OpClass::Vect:
            if (t_ok) {
              if (graph) edge(i, t, EdgeKind::Vect);
              int h = region_at(t);
              auto& v = a.regions[static_cast<std::size_t>(h)].vectors;
              if (std::find(v.begin(), v.end(), ins.type) == v.end()) v.push_back(ins.type);
              vect_set[ins.type] = true;
            } else {
              bad_vects.push_back(i);
            }
            break;
          case OpClass::Ei: eis.push_back(i); break;
          // With nothing to return to, RSUB and RETI are ignored (manual; errata E6, E13) and the
          // program goes on: in the main program and in a handler (RSUB), in the main program (RETI).
          case OpClass::Rsub:
            met(r, Fact::Rsub, i);
            next = a.regions[static_cast<std::size_t>(r)].kind != RegionKind::Subroutine;
            break;
          case OpClass::Reti:
            met(r, Fact::Reti, i);
            next = a.regions[static_cast<std::size_t>(r)].kind == RegionKind::Main;
            break;
          case OpClass::Stop: met(r, Fact::Stop, i); next = false; break;
          case OpClass::Wait: met(r, Fact::Wait, i); break;
          case OpClass::Store:
            if (writes_eeprom(ins)) writes.push_back(i);
            break;
          case OpClass::NotOp: next = false; break;  // not an instruction: the VM faults here (E20)
          case OpClass::Plain: break;
        }
        if (!next) break;
      }
      if (i + 1 >= n) {
        met(r, Fact::Falloff, i);
        break;
      }
      if (graph) edge(i, i + 1, EdgeKind::Next);
      // The common case inline: the next instruction is nobody's yet and no region's entry.
      if (int& o = owner[i + 1]; o < 0 && !entry.test(i + 1)) o = r;
      else if (!claim(r, i, i + 1)) break;
      ++i;
    }
  }
}

// Before the first walk, in the one look at every instruction the walk needs anyway (scan(), made
// backwards here): besides the entries, the subroutines that cannot return whatever the walk
// finds, because no RSUB can be reached from their entry by running on and jumping even when every
// call is taken to return and every jump backwards to reach one (more paths than any walk follows,
// so the verdict is safe; without an RSUB in the program it is exact). The walk then stops after
// their calls at once, and when it finds no other subroutine that never returns, build() needs no
// second pass: on call-dense code that never returns (issue 35's "calls" shape) that is half the
// analysis. Backwards, an address's answer is that of the next one or of a jump target ahead, so
// one pass gives all (a jump back counts as reaching an RSUB: no fixed point is needed).
void Walker::scan_and_premark() {
  const int n = static_cast<int>(in.program.size());
  const Instruction* const program = in.program.data();
  std::vector<char> may(static_cast<std::size_t>(n) + 1, 0);  // an RSUB may be reachable from here
  std::vector<int> callees;
  bool any_rsub = false;  // without one no subroutine returns, whatever the jumps back say
  for (int i = n - 1; i >= 0; --i) {
    const Instruction& x = program[i];
    const OpClass c = op_class[x.op];
    char m = may[static_cast<std::size_t>(i) + 1];  // running on (a call too: taken to return)
    if (c >= OpClass::Rsub) {
      const bool t_ok = x.value >= 0 && x.value < n;
      switch (c) {
        case OpClass::Rsub:
          m = 1;
          any_rsub = true;
          break;
        case OpClass::Stop:
        case OpClass::NotOp:
        case OpClass::Rst: m = 0; break;  // an RST's target is no region's entry
        case OpClass::Ja: m = t_ok && (x.value <= i || may[static_cast<std::size_t>(x.value)]); break;
        case OpClass::Branch: m = m || (t_ok && (x.value <= i || may[static_cast<std::size_t>(x.value)])); break;
        case OpClass::Store: keep_call_sites = keep_call_sites || writes_eeprom(x); break;
        case OpClass::Call:
          if (t_ok) {
            entry.set(x.value);
            callees.push_back(x.value);
          }
          break;
        case OpClass::Vect:
          if (t_ok) {
            entry.set(x.value);
            vect_target.set(x.value);
          }
          break;
        default: break;  // RETI and WAIT run on
      }
    }
    may[static_cast<std::size_t>(i)] = m;
  }
  for (int t : callees) {
    if (any_rsub && may[static_cast<std::size_t>(t)]) continue;
    if (noreturn_at.empty()) noreturn_at.assign(static_cast<std::size_t>(n), 0);
    noreturn_at[static_cast<std::size_t>(t)] = 1;
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
    if (region(r).kind == RegionKind::Subroutine && met_any(r, Fact::Rsub)) {
      returns[static_cast<std::size_t>(r)] = 1;
      stack.push_back(r);
    }
  // The flows between subroutines by the region they enter, in one array (a count, a prefix sum,
  // a fill): a vector per region cost an allocation per subroutine on call-dense programs.
  auto between_subroutines = [&](const Flow& fl) {
    return region(fl.from_region).kind == RegionKind::Subroutine && region(fl.to_region).kind == RegionKind::Subroutine;
  };
  std::vector<int> first_in(static_cast<std::size_t>(nr) + 1, 0);
  for (const auto& fl : flows)
    if (between_subroutines(fl)) ++first_in[static_cast<std::size_t>(fl.to_region) + 1];
  for (std::size_t v = 0; v < static_cast<std::size_t>(nr); ++v) first_in[v + 1] += first_in[v];
  std::vector<int> flow_in(static_cast<std::size_t>(first_in.back()));
  {
    std::vector<int> fill(first_in.begin(), first_in.end() - 1);
    for (const auto& fl : flows)
      if (between_subroutines(fl)) flow_in[static_cast<std::size_t>(fill[static_cast<std::size_t>(fl.to_region)]++)] = fl.from_region;
  }
  while (!stack.empty()) {
    int v = stack.back();
    stack.pop_back();
    for (int k = first_in[static_cast<std::size_t>(v)]; k < first_in[static_cast<std::size_t>(v) + 1]; ++k)
      if (int u = flow_in[static_cast<std::size_t>(k)]; !returns[static_cast<std::size_t>(u)]) {
        returns[static_cast<std::size_t>(u)] = 1;
        stack.push_back(u);
      }
  }
  // Again only when a subroutine the first pass let return does not: the ones scan_and_premark()
  // found were already walked as they are.
  bool again = false;
  std::vector<char> noreturn = noreturn_at.empty() ? std::vector<char>(static_cast<std::size_t>(n), 0) : noreturn_at;
  for (const auto& c : calls)
    if (!returns[static_cast<std::size_t>(c.callee)] && region(c.callee).kind == RegionKind::Subroutine) {
      char& no = noreturn[static_cast<std::size_t>(region(c.callee).entry)];
      again = again || !no;
      no = 1;
    }
  if (!again) return;
  a = Analysis{};
  last_caller.clear();
  events.clear();
  queue.clear();
  flows.clear();
  calls.clear();
  call_sites.clear();
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
  a.owner.reserve(static_cast<std::size_t>(n));
  prefer_huge_pages(a.owner.data(), a.owner.capacity() * sizeof(int));  // fewer page faults
  a.owner.assign(static_cast<std::size_t>(n), -1);
  entry.reset(n);
  vect_target.reset(n);
  // Every call and VECT target is an entry, whether or not its caller is reachable, so that a
  // walk stops at a subroutine's label even before the CSUB naming it has been seen.
  const Instruction* const program = in.program.data();
  if (!scanned) {
    scanned = true;
    scan_and_premark();
  } else {
    scan(
        [&](int i, OpClass c) {
          if (c < OpClass::Call) return;  // a jump's target is no region's entry
          entry.set(program[i].value);
          if (c == OpClass::Vect) vect_target.set(program[i].value);
        },
        [&](int i) { keep_call_sites = keep_call_sites || writes_eeprom(program[i]); });
  }
  // One region per entry at most (exported labels nothing calls add a few later).
  std::size_t entries = 1;
  for (std::uint64_t w : entry.words) entries += static_cast<std::size_t>(std::popcount(w));
  a.regions.reserve(entries);
  last_caller.reserve(entries);
  if (n == 0) return;
  Region main;
  main.kind = RegionKind::Main;
  main.entry = 0;
  a.regions.push_back(main);
  last_caller.push_back(-1);
  a.owner[0] = 0;
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
      if (a.owner[t] >= 0) continue;
      entry.set(static_cast<int>(t));
      region_at(static_cast<int>(t));
      more = true;
    }
    if (!more) break;
  }
  index_facts();
}

// Groups what the walks met by region, and a region's by kind, each kind in the order met: a
// counting sort by region, placing the kinds one after another (a pass over the list each).
void Walker::index_facts() {
  const std::size_t nr = a.regions.size();
  fact_begin.assign(nr + 1, 0);
  fact_mask.assign(nr, 0);
  std::array<bool, kFactKinds> present{};
  for (const auto& e : events) {
    ++fact_begin[static_cast<std::size_t>(e.region) + 1];
    fact_mask[static_cast<std::size_t>(e.region)] |= static_cast<std::uint8_t>(1u << static_cast<int>(e.kind));
    present[static_cast<std::size_t>(e.kind)] = true;
  }
  for (std::size_t r = 1; r <= nr; ++r) fact_begin[r] += fact_begin[r - 1];
  std::vector<int> next(fact_begin.begin(), fact_begin.end() - 1);
  fact_addresses.resize(events.size());
  fact_kinds.resize(events.size());
  for (int kind = 0; kind < kFactKinds; ++kind) {
    if (!present[static_cast<std::size_t>(kind)]) continue;
    for (const auto& e : events) {
      if (static_cast<int>(e.kind) != kind) continue;
      auto k = static_cast<std::size_t>(next[static_cast<std::size_t>(e.region)]++);
      fact_addresses[k] = e.address;
      fact_kinds[k] = e.kind;
    }
  }
  events = {};  // grouped now: its memory serves what comes next
}

RegionFacts Walker::fact(int r) const {
  RegionFacts f;
  if (static_cast<std::size_t>(r) + 1 >= fact_begin.size()) return f;
  const auto begin = static_cast<std::size_t>(fact_begin[static_cast<std::size_t>(r)]);
  const auto end = static_cast<std::size_t>(fact_begin[static_cast<std::size_t>(r) + 1]);
  std::span<const int>* of[kFactKinds] = {&f.rsubs, &f.retis, &f.stops, &f.waits, &f.falloffs, &f.resets};
  for (std::size_t k = begin; k < end;) {
    std::size_t e = k;
    while (e < end && fact_kinds[e] == fact_kinds[k]) ++e;
    *of[static_cast<std::size_t>(fact_kinds[k])] = std::span<const int>(fact_addresses.data() + k, e - k);
    k = e;
  }
  return f;
}

bool Walker::any_reset() const {
  return std::find(fact_kinds.begin(), fact_kinds.end(), Fact::Reset) != fact_kinds.end();
}

}  // namespace detail

std::vector<int> deepest_chain(const Analysis& a, int r, std::size_t limit) {
  std::vector<int> chain;
  for (std::size_t steps = 0; r >= 0 && steps <= a.regions.size() && chain.size() < limit; ++steps) {
    const Region& reg = a.regions[static_cast<std::size_t>(r)];
    if (reg.chain_site >= 0) chain.push_back(reg.chain_site);
    r = reg.chain_to;
  }
  return chain;
}

Analysis analyze(const AnalysisInput& in, Diagnostics& diags, const AnalysisOptions& options) {
  detail::Walker w(in, diags, options);
  w.build();
  w.name_regions();
  w.depths();
  for (detail::Check check : detail::kChecks) (w.*check)();
  return std::move(w.a);
}

}  // namespace tmcl
