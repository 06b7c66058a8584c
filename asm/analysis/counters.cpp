// Loops bounded by a counter, for -Weeprom-wear (eeprom_wear.cpp): a JC that tests a variable
// the loop steps by a constant against a constant, as programs write it with GGP/GAP, CALC
// ADD/SUB, AGP/AAP, COMP and JC (the step before or after the test), with CALCV ADD/SUB and
// CALCV COMP on a user variable, or with the accumulator itself as the counter. The JC's edge
// taken while the counter has not reached the bound is taken a bounded number of times, like
// DJNZ's jump back: it is cut from the instruction graph, and a write still in a cycle of what is
// left repeats without a bound (an outer loop around the counted one, say). Both shapes count: a
// loop the JC ends ("save three times, then go on"), and a branch of an endless loop the JC
// guards ("save at most three times").
//
// A pattern counts only where nothing else can change the counter while the loop runs: no other
// instruction of the loop writes it, no subroutine the loop calls (when any subroutine writes it)
// and no interrupt handler. The test and the step must run on every way round: they lie on the
// straight stretch (no jump lands inside it) that ends in the JC, or on the one the edge leads
// into. Scans are short (kScan instructions), so the recognition is linear.
#include <algorithm>
#include <unordered_set>

#include "analysis_internal.hpp"

namespace tmcl::detail {
namespace {

constexpr int kScan = 64;  // the longest stretch looked at on either side of a JC

// A variable a counter can live in: the accumulator, an axis parameter of a motor, a global
// parameter of a bank (bank 2: the user variables).
constexpr std::uint32_t kAccumulator = 1u << 24;
constexpr std::uint32_t kAnyUserVar = 3u << 20;  // an instruction that may write any user variable
constexpr std::uint32_t kEverything = 4u << 20;  // one that may write anything
std::uint32_t axis_var(int motor, int param) { return (1u << 20) | (static_cast<std::uint32_t>(motor) << 8) | static_cast<std::uint32_t>(param); }
std::uint32_t global_var(int bank, int param) { return (2u << 20) | (static_cast<std::uint32_t>(bank) << 8) | static_cast<std::uint32_t>(param); }
bool is_user_var(std::uint32_t v) { return (v >> 8) == ((2u << 12) | 2u); }

constexpr std::uint8_t kCalcCompare = 11;  // the COMP operation of the CALCV family

// What an instruction may write, as far as a counter is concerned (conservative: an unknown
// opcode or a user function writes everything).
struct Effect {
  std::uint32_t var = 0;   // one variable it writes (0: none)
  bool acc = false;        // it writes the accumulator
  bool user_vars = false;  // it may write any user variable
  bool all = false;
};

Effect effect_of(const Instruction& x) {
  Effect e;
  switch (static_cast<Op>(x.op)) {
    case Op::SAP:
    case Op::AAP:
    case Op::RSAP:
    case Op::SAPX:
    case Op::AAPX: e.var = axis_var(x.motor, x.type); break;
    case Op::SGP:
    case Op::AGP:
    case Op::RSGP: e.var = global_var(x.motor, x.type); break;
    case Op::CALCV:
      if (x.type != kCalcCompare) e.var = global_var(2, x.motor);
      break;
    case Op::CALCVA:
    case Op::CALCAV:
      if (x.type != kCalcCompare) e.user_vars = e.acc = true;
      break;
    case Op::CALCVV:
    case Op::CALCVX:
    case Op::CALCXV:
      if (x.type != kCalcCompare) e.user_vars = true;
      break;
    case Op::DJNZ:
    case Op::POPV: e.var = global_var(2, x.type); break;
    case Op::SIV:
    case Op::AIV: e.user_vars = true; break;
    case Op::GAP:
    case Op::GGP:
    case Op::GIO:
    case Op::GCO:
    case Op::GIV:
    case Op::GAPX:
    case Op::CALC:
    case Op::CALCX:
    case Op::POPA:
    case Op::RFS: e.acc = true; break;
    default:
      if (!op_info(x.op) || (x.op >= static_cast<std::uint8_t>(Op::UF0) && x.op <= static_cast<std::uint8_t>(Op::UF7)))
        e.all = true;
      break;
  }
  return e;
}

// Whether it may change the comparison flags JC tests (errata E2: the compares, the CALC family
// and every read into the accumulator).
bool sets_flags(const Instruction& x) {
  switch (static_cast<Op>(x.op)) {
    case Op::COMP:
    case Op::CALCV:
    case Op::CALCVV:
    case Op::CALCVA:
    case Op::CALCAV:
    case Op::CALCVX:
    case Op::CALCXV: return true;
    default: {
      Effect e = effect_of(x);
      return e.acc || e.all;
    }
  }
}

// Whether control passes to the next instruction only by running on (no jump, call or return).
bool straight(const Instruction& x) {
  switch (static_cast<Op>(x.op)) {
    case Op::JA:
    case Op::JC:
    case Op::DJNZ:
    case Op::CSUB:
    case Op::CALL:
    case Op::RSUB:
    case Op::RETI:
    case Op::STOP:
    case Op::RST: return false;
    default: return op_info(x.op) != nullptr;
  }
}

// The accumulator while a stretch runs: a variable's value plus the CALC steps since it was
// loaded (kEntry: the accumulator as the stretch began; 0: unknown).
constexpr std::uint32_t kEntry = kAccumulator;
struct Acc {
  std::uint32_t var = kEntry;
  std::int64_t delta = 0;
};

std::int64_t calc_step(const Instruction& x) { return x.type == 0 ? x.value : -static_cast<std::int64_t>(x.value); }
bool is_add_sub(const Instruction& x) { return x.type == 0 || x.type == 1; }

// One way round as far as the straight stretches around a JC show it: what the last compare
// read, how much each variable was stepped, and by which instructions. A compare is COMP (the
// accumulator against a constant), CALCV COMP (a user variable against one), or what sets the
// flags from a value against zero (errata E2): a CALC ADD/SUB, a CALCV ADD/SUB, a GGP or GAP.
struct Round {
  Acc acc;
  Acc compared;
  int compare = -1;
  struct Step {
    std::uint32_t var;
    int at;
    std::int64_t delta;
  };
  std::vector<Step> steps;

  std::int64_t stepped(std::uint32_t var) const {
    std::int64_t sum = 0;
    for (const auto& st : steps) sum += st.var == var ? st.delta : 0;
    return sum;
  }

  void run(const Instruction& x, int at) {
    const auto op = static_cast<Op>(x.op);
    if (op == Op::CALC && is_add_sub(x) && acc.var != 0) {
      acc.delta += calc_step(x);
      if (acc.var == kEntry) steps.push_back({kEntry, at, calc_step(x)});
      compared = acc;
      compare = at;
    } else if (op == Op::GGP || op == Op::GAP) {
      acc = {op == Op::GGP ? global_var(x.motor, x.type) : axis_var(x.motor, x.type), 0};
      compared = acc;
      compare = at;
    } else if (op == Op::AGP || op == Op::AAP) {
      std::uint32_t v = op == Op::AGP ? global_var(x.motor, x.type) : axis_var(x.motor, x.type);
      if (acc.var == v && acc.delta != 0) {
        steps.push_back({v, at, acc.delta});
        acc.delta = 0;  // the accumulator holds the new value
      }
    } else if (op == Op::CALCV && is_add_sub(x)) {
      steps.push_back({global_var(2, x.motor), at, calc_step(x)});
      compared = {global_var(2, x.motor), 0};
      compare = at;
    } else if (op == Op::COMP) {
      compared = acc;
      compare = at;
    } else if (op == Op::CALCV && x.type == kCalcCompare) {
      compared = {global_var(2, x.motor), 0};
      compare = at;
    } else {
      Effect e = effect_of(x);
      if (e.acc || e.all) acc.var = 0;
    }
  }
};

}  // namespace

// The JC at `j` as a counter test: whether it tests a counter (`t.var`), and per edge that stays
// in its component of `scc` whether taking it steps the counter towards the bound: taken only
// while the counter has not reached the bound, and every way from it back to the JC steps the
// counter that way. Then the loop it goes round ends (the JC ends a loop), or the branch it leads
// into runs out (the JC guards a branch of an endless loop, "save at most three times").
bool Walker::counter_test(int j, const std::vector<int>& scc, const AddressBits& landing, CounterTest& t) const {
  const int n = static_cast<int>(in.program.size());
  const Instruction& jc = ins(j);
  const int c = scc[static_cast<std::size_t>(j)];
  // The condition after a compare: EQ, NE, GT, GE, LT or LE.
  static constexpr int kEq = 2, kNe = 3, kGt = 4, kGe = 5, kLt = 6, kLe = 7;
  const int cond = jc.type == 0 ? kEq : jc.type == 1 ? kNe : jc.type;
  if (cond < kEq || cond > kLe) return false;
  // The stretch that ends in the JC: every way to the JC runs all of it.
  int start = j;
  for (int k = 0; k < kScan && !landing.test(start) && start > 0 && straight(ins(start - 1)); ++k) --start;
  Round before;
  for (int p = start; p < j; ++p) before.run(ins(p), p);
  if (before.compare < 0) return false;
  for (int p = before.compare + 1; p < j; ++p)
    if (sets_flags(ins(p))) return false;  // the JC tests something else
  t = CounterTest{};
  t.jc = j;
  t.component = c;
  t.var = before.compared.var;
  if (t.var == 0) return false;
  for (int edge = 1; edge <= 2; ++edge) {
    const int to = edge == 1 ? jc.value : j + 1;
    if (to < 0 || to >= n || scc[static_cast<std::size_t>(to)] != c) continue;
    const int taken = edge == 1 ? cond
                      : cond == kEq ? kNe : cond == kNe ? kEq : cond == kGt ? kLe : cond == kGe ? kLt : cond == kLt ? kGe : kGt;
    // The stretch the edge leads into (unless it is the JC's own), stepping after the test.
    Round round = before;
    if (to != start)
      for (int p = to, k = 0; p < n && k < kScan && (k == 0 || !landing.test(p)); ++p, ++k) {
        round.run(ins(p), p);
        if (!straight(ins(p))) break;
      }
    const std::int64_t step = round.stepped(t.var);
    // Towards the bound: up while below it, down while above it, or by one while not at it.
    const bool towards = ((taken == kLt || taken == kLe) && step > 0) || ((taken == kGt || taken == kGe) && step < 0) ||
                         (taken == kNe && (step == 1 || step == -1));
    if (!towards) continue;
    t.towards |= edge;
    std::size_t own = 0;
    for (const auto& st : round.steps) own += st.var == t.var && scc[static_cast<std::size_t>(st.at)] == c;
    t.own[edge - 1] = own;
  }
  return t.towards != 0;
}

// Of the edges counter_test found stepping towards the bound, those the counter bounds (1: the
// jump, 2: running on): nothing else may write the counter while the loop runs, so its only
// writers in the loop are the steps found, no subroutine the loop calls writes it, nor an
// interrupt handler.
int Walker::counted_edges(const CounterTest& t, const CounterFacts& cf) const {
  const std::uint32_t var = t.var;
  auto count = [&](std::uint32_t v) {
    auto it = cf.writes_in.find((static_cast<std::uint64_t>(static_cast<std::uint32_t>(t.component)) << 32) | v);
    return it == cf.writes_in.end() ? std::size_t{0} : it->second;
  };
  if (count(kEverything) != 0 || (is_user_var(var) && count(kAnyUserVar) != 0)) return 0;
  if (var != kAccumulator && cf.handler_writes.count(var)) return 0;  // a handler keeps the accumulator (E41)
  if (cf.calls_in.count(t.component) && (var == kAccumulator || cf.subroutine_writes.count(var) ||
                                         (is_user_var(var) && cf.subroutine_writes.count(kAnyUserVar))))
    return 0;
  int cuts = 0;
  for (int edge = 1; edge <= 2; ++edge)
    if ((t.towards & edge) && count(var) == t.own[edge - 1]) cuts |= edge;
  return cuts;
}

// Who writes the counters of `tests`: per component of `scc` that has a test, the writes of each
// such counter (and the instructions that write any user variable or everything), whether the
// component calls a subroutine; and which of the counters subroutines and handlers write.
void Walker::counter_facts(const std::vector<int>& scc, const std::vector<CounterTest>& tests, CounterFacts& cf) const {
  const int n = static_cast<int>(in.program.size());
  cf = CounterFacts{};
  std::vector<std::uint32_t> vars;
  std::unordered_set<int> components;
  bool any_user_var = false;
  for (const auto& t : tests) {
    if (std::find(vars.begin(), vars.end(), t.var) == vars.end()) vars.push_back(t.var);
    components.insert(t.component);
    any_user_var = any_user_var || is_user_var(t.var);
  }
  const bool acc = std::find(vars.begin(), vars.end(), kAccumulator) != vars.end();
  auto counted = [&](std::uint32_t v) { return v && std::find(vars.begin(), vars.end(), v) != vars.end(); };
  for (int i = 0; i < n; ++i) {
    const Instruction& x = ins(i);
    Effect e = effect_of(x);
    const bool user = any_user_var && (e.user_vars || e.all);
    if (!counted(e.var) && !(acc && e.acc) && !user && !e.all && x.op != static_cast<std::uint8_t>(Op::CSUB) &&
        x.op != static_cast<std::uint8_t>(Op::CALL))
      continue;  // nothing any test asks about
    const int c = scc[static_cast<std::size_t>(i)];
    if (c >= 0 && components.count(c)) {
      auto key = [c](std::uint32_t v) { return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c)) << 32) | v; };
      if (counted(e.var)) ++cf.writes_in[key(e.var)];
      if (acc && e.acc) ++cf.writes_in[key(kAccumulator)];
      if (e.user_vars) ++cf.writes_in[key(kAnyUserVar)];
      if (e.all) ++cf.writes_in[key(kEverything)];
      if (x.op == static_cast<std::uint8_t>(Op::CSUB) || x.op == static_cast<std::uint8_t>(Op::CALL)) cf.calls_in.insert(c);
    }
    int r = a.owner[static_cast<std::size_t>(i)];
    if (r < 0 || region(r).kind == RegionKind::Main) continue;
    auto& into = region(r).kind == RegionKind::Handler ? cf.handler_writes : cf.subroutine_writes;
    if (counted(e.var)) into.insert(e.var);
    if (e.user_vars || e.all) into.insert(kAnyUserVar);
  }
}

}  // namespace tmcl::detail
