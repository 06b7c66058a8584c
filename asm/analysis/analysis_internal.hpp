// The analysis' working state, shared by the walk (analysis.cpp) and the checks (checks.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "tmcl/analysis.hpp"

namespace tmcl::detail {

inline constexpr std::uint8_t kCallTarget = 1, kVectTarget = 2;

// What one region's walk met, by instruction address.
struct RegionFacts {
  std::vector<int> rsubs, retis, stops, waits, falloffs;
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

std::string region_word(const Region& r);

struct Walker {
  Walker(const AnalysisInput& input, Diagnostics& d, const AnalysisOptions& o) : in(input), diags(d), options(o) {}
  const AnalysisInput& in;
  Diagnostics& diags;
  const AnalysisOptions& options;
  Analysis a;

  std::vector<RegionFacts> facts;
  std::vector<int> entry_region;           // per address: the region starting there, or -1
  std::vector<std::uint8_t> target_flags;  // per address: kCallTarget | kVectTarget
  std::unordered_map<int, std::string> labels;
  std::vector<int> queue;                  // regions to walk, in the order found
  std::vector<int> work;                   // the walk's stack of addresses
  std::vector<Flow> flows;
  std::vector<CallSite> calls;
  std::vector<std::pair<int, int>> restarts;  // RST outside the main program: (site, target)
  std::vector<int> bad_jumps, bad_vects, eis, writes;
  std::array<bool, 256> vect_set{};
  std::vector<char> noreturn_at;  // per address: a subroutine there never returns (second pass)
  // Per region: the best edge of its deepest chain (-1: none) and its graph edges.
  std::vector<std::vector<RegionEdge>> out;
  std::vector<int> comp;         // region -> component
  std::vector<RegionEdge> best;  // per component
  std::vector<int> best_from;    // per component: the region the best edge leaves
  std::vector<char> recursive;   // per component

  SourceLoc loc(int address) const;
  std::string label_at(int address) const;
  int region_at(int address);
  void edge(int from, int to, EdgeKind kind);
  void reach(int r, int from, int to);
  void walk(int r, int from, int start);
  void build();
  void pass();
  void depths();
  std::vector<int> chain_of(int region) const;
  void check_flow();
  void check_interrupts();
  void check_unreachable();
  void check_depth();
  void check_eeprom();
  // Fixes for editors (fixes.cpp): a RETI on its own line after instruction `after`, and the
  // removal of the lines of instructions `first` to `last`.
  void fix_add_reti(Diagnostic& d, int after) const;
  void fix_remove(Diagnostic& d, int first, int last) const;

  const Region& region(int r) const { return a.regions[static_cast<std::size_t>(r)]; }
  const RegionFacts& fact(int r) const { return facts[static_cast<std::size_t>(r)]; }
  const Instruction& ins(int i) const { return in.program[static_cast<std::size_t>(i)]; }
  std::string mnemonic(int i) const;
};

}  // namespace tmcl::detail
