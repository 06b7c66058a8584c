// The analysis' working state, shared by the walk (analysis.cpp) and the checks (checks.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "tmcl/analysis.hpp"

namespace tmcl::detail {

// One bit per address, packed (a million addresses take 125 KB: every page the analysis touches
// is a page fault the whole process pays for).
struct AddressBits {
  std::vector<std::uint64_t> words;
  void reset(int n) { words.assign((static_cast<std::size_t>(n) + 63) / 64, 0); }
  bool test(int i) const { return (words[static_cast<std::size_t>(i) >> 6] >> (i & 63)) & 1u; }
  void set(int i) { words[static_cast<std::size_t>(i) >> 6] |= std::uint64_t{1} << (i & 63); }
};

// What one region's walk met, by instruction address, in the order met: views of
// Walker::fact_addresses (Walker::fact). All walks record into one list, grouped by region after
// each pass (index_facts): 100,000 regions cost no 600,000 small vectors, and no table per region.
struct RegionFacts {
  std::span<const int> rsubs, retis, stops, waits, falloffs;
  std::span<const int> resets;  // RSTs (outside the main program): a clean way out of any region (E43)
};
enum class Fact : std::uint8_t { Rsub, Reti, Stop, Wait, Falloff, Reset };
inline constexpr int kFactKinds = 6;
struct FactEvent {
  int region;
  int address;
  Fact kind;
};

// Control passes from region `from_region` into `to_region` without a call: a jump or running
// on into another region's code. `from` is the instruction that passes it (-1: a region's start).
struct Flow {
  int from;
  int from_region;
  int to_region;
  int to;
};

struct CallSite {
  int site;
  int caller;  // region
  int callee;  // region
};

// An edge of the region graph: a call (one frame) or a flow (none).
struct RegionEdge {
  int to;
  int weight;
  int site;
};

// A graph of regions as one array of edges grouped by the region they leave (compressed rows):
// one allocation, where a vector per region would be 100,000 on a program of that many.
struct RegionGraph {
  std::vector<int> begin;  // per region, and one more: where its edges start in `edges`
  std::vector<RegionEdge> edges;
  // From the edges `each(add)` gives by calling add(region, edge), each region's in the order
  // given; `each` runs twice (to count, then to place), so no list of them is kept.
  template <class Each>
  void build(int regions, Each each) {
    begin.assign(static_cast<std::size_t>(regions) + 1, 0);
    each([this](int from, const RegionEdge&) { ++begin[static_cast<std::size_t>(from) + 1]; });
    for (std::size_t k = 1; k < begin.size(); ++k) begin[k] += begin[k - 1];
    edges.resize(static_cast<std::size_t>(begin.back()));
    std::vector<int> next(begin.begin(), begin.end() - 1);
    each([&](int from, const RegionEdge& e) { edges[static_cast<std::size_t>(next[static_cast<std::size_t>(from)]++)] = e; });
  }
  std::span<const RegionEdge> operator[](std::size_t v) const {
    return {edges.data() + begin[v], edges.data() + begin[v + 1]};
  }
};

std::string region_word(const Region& r);

// A JC that tests a counter (counters.cpp): the counter, the JC's component of the instruction
// graph, its edges that step the counter towards the bound (1: the jump, 2: running on) and, per
// edge, the writes of the counter found on the way (the only ones the loop may have).
struct CounterTest {
  int jc = -1;
  int component = -1;
  std::uint32_t var = 0;
  int towards = 0;
  std::size_t own[2] = {0, 0};
};
// Who writes the counters of some tests, by component (counters.cpp).
struct CounterFacts {
  std::unordered_map<std::uint64_t, std::size_t> writes_in;  // (component, variable) -> writes
  std::unordered_set<int> calls_in;                          // components with a CSUB or CALL
  std::unordered_set<std::uint32_t> handler_writes, subroutine_writes;
};

// What the walk does at an instruction, by opcode (op_classes(), made once): most instructions
// are Plain and go on to the next without a look at their operands. From kFirstScanned on, the
// classes Walker::scan() looks for; from kFirstTarget on, those that name an address.
enum class OpClass : std::uint8_t { Plain, Ei, Rsub, Reti, Stop, Wait, NotOp, Store, Ja, Branch, Rst, Call, Vect };
inline constexpr OpClass kFirstScanned = OpClass::Store;
inline constexpr OpClass kFirstTarget = OpClass::Ja;
const std::array<OpClass, 256>& op_classes();

struct Walker {
  Walker(const AnalysisInput& input, Diagnostics& d, const AnalysisOptions& o) : in(input), diags(d), options(o) {}
  const AnalysisInput& in;
  Diagnostics& diags;
  const AnalysisOptions& options;
  Analysis a;

  std::vector<int> last_caller;     // per region: the region whose call of it was recorded last (calls)
  std::vector<FactEvent> events;    // what the walks met, region by region as they went
  // The same grouped by region, and in a region by kind: region r's are from fact_begin[r] to
  // fact_begin[r + 1].
  std::vector<int> fact_begin, fact_addresses;
  std::vector<Fact> fact_kinds;
  std::vector<std::uint8_t> fact_mask;  // per region: bit k set when it met a fact of kind k
  AddressBits entry, vect_target;  // per address: a CSUB/CALL or VECT names it (entry), a VECT does
  std::vector<int> queue;                  // regions to walk, in the order found
  std::vector<int> work;                   // the walk's stack of addresses
  std::vector<Flow> flows;
  // The calls between regions, in the order the walk met them, without repeats in a row of the
  // same caller and callee: a later call of the same subroutine from the same region changes no
  // depth, chain or note (each reads the first edge that fits), and a loop of 100,000 CSUBs of
  // one subroutine would otherwise make 100,000 entries.
  std::vector<CallSite> calls;
  // Every call the walk met, in order, for -Weeprom-wear (a call from a loop repeats a write):
  // kept only when the program has an EEPROM write at all.
  std::vector<int> call_sites;
  bool keep_call_sites = false;
  std::vector<std::pair<int, int>> restarts;  // RST outside the main program: (site, target)
  std::vector<int> bad_jumps, bad_vects, eis, writes;
  std::array<bool, 256> vect_set{};
  const std::array<OpClass, 256>& op_class = op_classes();  // NotOp: not in the table (E20)
  // Per address: a subroutine there never returns (scan_and_premark(), and the second pass).
  std::vector<char> noreturn_at;
  // Per region: the best edge of its deepest chain (-1: none) and its graph edges.
  RegionGraph out;
  std::vector<int> comp;        // region -> component
  std::vector<char> recursive;  // per component

  SourceLoc loc(int address) const;
  int region_at(int address);
  int region_of_entry(int address) const;
  bool is_target(int address) const { return entry.test(address); }
  // The one search for where control lands other than by running on, before any walk: target(i,
  // class) for each jump, RST, call and VECT whose target is inside the program (the walk's region
  // entries; -Weeprom-wear's landing points), store(i) for each STAP, STGP, SCO and SGP.
  template <class Target, class Store>
  void scan(Target target, Store store) const {
    const int n = static_cast<int>(in.program.size());
    const Instruction* const program = in.program.data();
    for (int i = 0; i < n; ++i) {
      const OpClass c = op_class[program[i].op];
      if (c < kFirstScanned) continue;
      if (c == OpClass::Store) store(i);
      else if (c >= kFirstTarget && program[i].value >= 0 && program[i].value < n) target(i, c);
    }
  }
  void name_regions();
  void edge(int from, int to, EdgeKind kind);
  bool claim(int r, int from, int to);
  void reach(int r, int from, int to);
  void walk(int r, int from, int start);
  void met(int r, Fact kind, int address) { events.push_back({r, address, kind}); }
  void index_facts();
  void scan_and_premark();
  bool scanned = false;  // the first pass's scan_and_premark() is done
  void build();
  void pass();
  void depths();
  // Whether a warning `name` at instruction `address` is worth building: false (and the warning
  // only counted) when the tool keeps no more of its kind, so 80,000 of one kind cost little; also
  // false (not counted) when a comment allows it there (Diagnostics::take).
  bool want(std::string_view name, int address);
  // The checks (kChecks below): each reads the regions, facts and graph built above and reports
  // its warnings through want() and diags.
  void check_flow();         // checks.cpp: flows out of regions, RSUB, RETI, STOP, WAIT, fall-off, addresses
  void check_interrupts();   // checks.cpp: VECT and EI
  void check_unreachable();  // checks.cpp
  void check_depth();        // checks.cpp: recursion and the call stack's depth
  void check_eeprom();       // eeprom_wear.cpp
  // -Weeprom-wear's loops bounded by a counter (counters.cpp).
  bool counter_test(int jc, const std::vector<int>& scc, const AddressBits& landing, CounterTest& t) const;
  void counter_facts(const std::vector<int>& scc, const std::vector<CounterTest>& tests, CounterFacts& cf) const;
  int counted_edges(const CounterTest& t, const CounterFacts& cf) const;
  // Fixes for editors (fixes.cpp): a RETI on its own line after instruction `after`, and the
  // removal of the lines of instructions `first` to `last`.
  void fix_add_reti(Diagnostic& d, int after) const;
  void fix_remove(Diagnostic& d, int first, int last) const;

  const Region& region(int r) const { return a.regions[static_cast<std::size_t>(r)]; }
  RegionFacts fact(int r) const;
  bool met_any(int r, Fact kind) const {
    return (fact_mask[static_cast<std::size_t>(r)] >> static_cast<int>(kind)) & 1u;
  }
  bool any_reset() const;
  const Instruction& ins(int i) const { return in.program[static_cast<std::size_t>(i)]; }
  std::string mnemonic(int i) const;
  bool writes_eeprom(const Instruction& x) const;
};

// The checks analyze() runs after the walk, in the order their warnings come out. A new warning
// (docs/architecture.md, "A new warning"): its check is a member of Walker, in a file of its own
// when it is more than a few lines, and a row here.
using Check = void (Walker::*)();
inline constexpr Check kChecks[] = {&Walker::check_flow, &Walker::check_interrupts, &Walker::check_unreachable,
                                    &Walker::check_depth, &Walker::check_eeprom};

}  // namespace tmcl::detail
