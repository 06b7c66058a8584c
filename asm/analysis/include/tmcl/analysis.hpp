// Static analysis of a linked TMCL program's control flow (docs/analysis.md): the control-flow
// graph of the whole image, with the main program, every subroutine (CSUB/CALL target) and every
// interrupt handler (VECT target) as a region, the call-stack depth along every path, and the
// analysis' warnings (warning_table(), docs/analysis.md) as Diagnostics with notes showing the path.
//
// It needs only instructions, so it runs alike on sources, linked units and .bin images; source
// positions (AsmResult::lines and sources) and label names (symbols) are optional. It is linear
// in the program's size: every instruction is visited once to find regions, once more only when
// an EEPROM write asks whether it sits in a loop.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/diag.hpp"
#include "tmcl/isa.hpp"
#include "tmcl/profile.hpp"

namespace tmcl {

struct AnalysisInput {
  std::span<const Instruction> program;
  std::span<const LineInfo> lines;   // one per instruction, or empty (no source positions)
  const SourceSet* sources = nullptr;  // where `lines` point (to place the caret on the line)
  std::span<const Symbol> symbols;   // label names for regions and graph nodes (may be empty)
  const Profile* profile = nullptr;  // for auto-stored global parameters; nullptr: generic
  bool appended_stop = false;        // the last instruction is the assembler's STOP
  bool targets_checked = false;      // the assembler already warned of addresses outside (-Waddress)
  std::int64_t instr_time_us = 20;   // time per instruction, for the EEPROM-wear estimate
};

// What the analysis reads of an assembled program (label names only when the assembly collected
// them). `targets_checked`: the assembler has already warned of jump targets outside the program.
inline AnalysisInput analysis_input(const AsmResult& result, bool targets_checked = true) {
  AnalysisInput in;
  in.program = result.program;
  in.lines = result.lines;
  in.sources = &result.sources;
  in.symbols = result.symbols;
  in.profile = result.profile;
  in.appended_stop = result.appended_stop;
  in.targets_checked = targets_checked;
  return in;
}

// The call stack of both modules holds 8 return addresses (CSUB/CALL manuals; errata E5).
inline constexpr int kCallStackDepth = 8;
inline constexpr int kUnbounded = 1 << 30;  // the depth of a region that can recurse

enum class RegionKind : std::uint8_t { Main, Subroutine, Handler };

struct Region {
  RegionKind kind = RegionKind::Main;
  int entry = 0;              // address of its first instruction
  std::string name;           // its label, "main", or "sub_12" / "handler_12" without one
  std::vector<int> vectors;   // handlers: the interrupt numbers whose VECT names it
  // Frames its calls can push at most below its own (kUnbounded when it can recurse).
  int depth = 0;
  // The first step of its deepest chain: the region it leads into (-1: none, or it recurses) and
  // the call there (its address; -1 when control runs or jumps on into that region's code without
  // a call). deepest_chain() follows the steps; a list per region would make a chain of n
  // subroutines cost n * n.
  int chain_to = -1;
  int chain_site = -1;
};

// One control-flow edge between instructions: the next instruction, a jump, a call, a VECT.
enum class EdgeKind : std::uint8_t { Next, Jump, Call, Vect };
struct CfgEdge {
  int from;
  int to;
  EdgeKind kind;
};

struct Analysis {
  std::vector<Region> regions;  // regions[0] is the main program
  std::vector<int> owner;       // per instruction: its region, -1 when unreachable
  std::vector<CfgEdge> edges;   // filled only when AnalysisOptions::graph
  int main_depth = 0;           // = regions[0].depth
  bool handlers_share_stack = true;  // errata E39: a handler's CSUBs push onto the same stack
};

struct AnalysisOptions {
  bool graph = false;  // fill Analysis::edges (for -f dot)
};

// Builds the graph and reports every warning into `diags` (named, so -Wno-NAME and -Werror=NAME
// apply). Notes carry the path: the chain of calls, where a subroutine starts, and so on.
Analysis analyze(const AnalysisInput& in, Diagnostics& diags, const AnalysisOptions& options = {});

// The call sites (instruction addresses) of region `r`'s deepest chain, outermost first, at most
// `limit` of them.
std::vector<int> deepest_chain(const Analysis& a, int r, std::size_t limit = static_cast<std::size_t>(-1));

// tmclasm --stack-usage: per region, its maximum depth and deepest chain, as text.
std::string stack_usage_report(const Analysis& a, const AnalysisInput& in);

// tmclasm -f dot: the graph as Graphviz dot; subroutines and handlers as clusters, labels as node
// names, the deepest call chain in red. Needs an Analysis made with AnalysisOptions::graph.
std::string cfg_dot(const Analysis& a, const AnalysisInput& in);

}  // namespace tmcl
