// What tmclasm shows of an analysis besides warnings: the stack report (--stack-usage: per
// region its deepest chain, like GCC's -fstack-usage for the whole program) and the control-flow
// graph as Graphviz dot (-f dot): basic blocks named by their labels, subroutines and handlers
// as clusters, calls dashed, VECTs dotted, the main program's deepest call chain in red.
#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <unordered_map>

#include "tmcl/analysis.hpp"

namespace tmcl {
namespace {

std::unordered_map<int, std::string> label_map(const AnalysisInput& in) {
  std::unordered_map<int, std::string> m;
  for (const auto& s : in.symbols)
    if (s.kind == SymbolKind::Label) m.emplace(static_cast<int>(s.value), s.name);
  return m;
}

const char* kind_word(RegionKind k) {
  switch (k) {
    case RegionKind::Main: return "main";
    case RegionKind::Subroutine: return "subroutine";
    case RegionKind::Handler: return "handler";
  }
  return "?";
}

// The region that starts at `address`, or -1: a region owns its entry (analysis.cpp).
int region_at_entry(const Analysis& a, std::int64_t address) {
  if (address < 0 || static_cast<std::size_t>(address) >= a.owner.size()) return -1;
  int r = a.owner[static_cast<std::size_t>(address)];
  return r >= 0 && a.regions[static_cast<std::size_t>(r)].entry == address ? r : -1;
}

std::string callee_name(const Analysis& a, const AnalysisInput& in, int site) {
  int to = in.program[static_cast<std::size_t>(site)].value;
  int r = region_at_entry(a, to);
  return r >= 0 ? a.regions[static_cast<std::size_t>(r)].name : "address " + std::to_string(to);
}

// Its deepest chain, to the first call past the call stack's room: every region's whole chain
// would make a chain of n subroutines n * n names long.
std::string chain_text(const Analysis& a, const AnalysisInput& in, int r) {
  const Region& reg = a.regions[static_cast<std::size_t>(r)];
  std::vector<int> chain = deepest_chain(a, r, kCallStackDepth + 1);
  std::string s = reg.name;
  for (int site : chain) s += " > " + callee_name(a, in, site);
  if (reg.depth < kUnbounded && static_cast<std::size_t>(reg.depth) > chain.size())
    s += " > ... (" + std::to_string(static_cast<std::size_t>(reg.depth) - chain.size()) + " more calls)";
  return s;
}

// "MVP ABS, 0, 100" from the instruction table, labels for addresses.
std::string instruction_text(const Instruction& ins, const std::unordered_map<int, std::string>& labels) {
  const OpInfo* info = op_info(ins.op);
  if (!info) return "opcode " + std::to_string(ins.op);
  std::string s(info->mnemonic);
  bool first = true;
  for (const auto& spec : info->operands) {
    s += first ? " " : ", ";
    first = false;
    int v = spec.field == Field::Type ? ins.type : spec.field == Field::Motor ? ins.motor : ins.value;
    if (spec.role == Role::Address) {
      auto it = labels.find(v);
      s += it != labels.end() ? it->second : std::to_string(v);
    } else if (spec.keywords != KwSet::None) {
      auto k = keyword_name(spec.keywords, static_cast<std::uint8_t>(v));
      s += k ? std::string(*k) : std::to_string(v);
    } else {
      s += std::to_string(v);
    }
  }
  return s;
}

// Named apart from std::quoted, which argument-dependent lookup finds for a std::string.
std::string dot_quoted(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

bool ends_block(const Instruction& ins) {
  switch (static_cast<Op>(ins.op)) {
    case Op::JA:
    case Op::JC:
    case Op::DJNZ:
    case Op::RSUB:
    case Op::RETI:
    case Op::STOP:
    case Op::RST: return true;
    default: return !op_info(ins.op);
  }
}

}  // namespace

std::string stack_usage_report(const Analysis& a, const AnalysisInput& in) {
  std::string out = "# call-stack use per region: frames in use at most (the module's stack holds " +
                    std::to_string(kCallStackDepth) + "), deepest chain\n";
  std::size_t w = 6;
  for (const auto& r : a.regions) w = std::max(w, r.name.size());
  // Columns padded to their width, never cut: an address or depth of 7 digits pushes on.
  auto pad = [](std::string& s, std::size_t width) { s.resize(std::max(width, s.size() + 1), ' '); };
  for (std::size_t k = 0; k < a.regions.size(); ++k) {
    const Region& r = a.regions[k];
    std::string line = r.name;
    pad(line, w + 2);
    std::string kind = kind_word(r.kind);
    kind.resize(12, ' ');
    line += kind + "address " + std::to_string(r.entry);
    pad(line, w + 2 + 12 + 14);
    if (r.depth >= kUnbounded) {
      line += "unbounded (recursion)";
    } else {
      // A subroutine's own return address is a frame; entering a handler pushes none (E39).
      int frames = r.depth + (r.kind == RegionKind::Subroutine ? 1 : 0);
      line += "depth " + std::to_string(frames);
      pad(line, w + 2 + 12 + 14 + 10);
      line += chain_text(a, in, static_cast<int>(k));
      if (r.kind == RegionKind::Handler && a.regions[0].depth < kUnbounded && a.regions[0].depth > 0)
        line += "  (" + std::to_string(frames + a.regions[0].depth) + " when it fires at the main program's deepest point)";
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  }
  return out;
}

std::string cfg_dot(const Analysis& a, const AnalysisInput& in) {
  const int n = static_cast<int>(in.program.size());
  auto labels = label_map(in);
  // Basic blocks: a block starts at a region entry, a jump target, after a jump and where a label is.
  std::vector<char> leader(static_cast<std::size_t>(n), 0);
  if (n > 0) leader[0] = 1;
  for (const auto& r : a.regions) leader[static_cast<std::size_t>(r.entry)] = 1;
  for (const auto& e : a.edges)
    if (e.kind == EdgeKind::Jump && e.to >= 0 && e.to < n) leader[static_cast<std::size_t>(e.to)] = 1;
  for (int i = 0; i < n; ++i) {
    if (labels.count(i)) leader[static_cast<std::size_t>(i)] = 1;
    if (i + 1 < n && (ends_block(in.program[static_cast<std::size_t>(i)]) ||
                      a.owner[static_cast<std::size_t>(i)] != a.owner[static_cast<std::size_t>(i + 1)]))
      leader[static_cast<std::size_t>(i + 1)] = 1;
  }
  std::vector<int> block_of(static_cast<std::size_t>(n), 0);
  std::vector<int> starts;
  for (int i = 0; i < n; ++i) {
    if (leader[static_cast<std::size_t>(i)]) starts.push_back(i);
    block_of[static_cast<std::size_t>(i)] = static_cast<int>(starts.size()) - 1;
  }
  // Node names: the block's label where it has one (made unique with its address), else "a<address>".
  std::map<std::string, int> uses;
  for (int s : starts)
    if (labels.count(s)) ++uses[labels[s]];
  auto node = [&](int block) {
    int s = starts[static_cast<std::size_t>(block)];
    auto it = labels.find(s);
    if (it == labels.end()) return dot_quoted("a" + std::to_string(s));
    return dot_quoted(uses[it->second] > 1 ? it->second + "@" + std::to_string(s) : it->second);
  };
  std::vector<int> main_chain = a.regions.empty() ? std::vector<int>{} : deepest_chain(a, 0);
  std::set<int> chain_sites(main_chain.begin(), main_chain.end());
  std::set<int> chain_regions;
  for (int site : chain_sites)
    if (int r = region_at_entry(a, in.program[static_cast<std::size_t>(site)].value); r >= 0) chain_regions.insert(r);
  // The blocks of each region, in address order (each region's cluster lists its own).
  std::vector<std::vector<int>> blocks_of(a.regions.size());
  for (int b = 0; b < static_cast<int>(starts.size()); ++b)
    if (int o = a.owner[static_cast<std::size_t>(starts[static_cast<std::size_t>(b)])]; o >= 0)
      blocks_of[static_cast<std::size_t>(o)].push_back(b);

  std::string out = "digraph program {\n  node [shape=box, fontname=\"monospace\"];\n";
  auto emit_block = [&](std::string& o, int b, const char* indent) {
    int s = starts[static_cast<std::size_t>(b)];
    int e = b + 1 < static_cast<int>(starts.size()) ? starts[static_cast<std::size_t>(b + 1)] : n;
    std::string text;
    if (labels.count(s)) text += labels[s] + ":\\l";
    for (int i = s; i < e; ++i)
      text += std::to_string(i) + ": " + instruction_text(in.program[static_cast<std::size_t>(i)], labels) + "\\l";
    std::string esc;
    for (char c : text) esc += c == '"' ? std::string("\\\"") : std::string(1, c);
    o += std::string(indent) + node(b) + " [label=\"" + esc + "\"";
    if (a.owner[static_cast<std::size_t>(s)] < 0) o += ", style=dashed, color=gray";
    o += "];\n";
  };
  for (std::size_t r = 0; r < a.regions.size(); ++r) {
    const Region& reg = a.regions[r];
    std::string title = reg.kind == RegionKind::Main ? "main program" : std::string(kind_word(reg.kind)) + " " + reg.name;
    if (!reg.vectors.empty()) {
      title += " (interrupt";
      for (int v : reg.vectors) title += " " + std::to_string(v);
      title += ")";
    }
    out += "  subgraph cluster_" + std::to_string(r) + " {\n    label=" + dot_quoted(title) + ";\n";
    if (chain_regions.count(static_cast<int>(r)) || (r == 0 && !chain_sites.empty())) out += "    color=red;\n";
    for (int b : blocks_of[r]) emit_block(out, b, "    ");
    out += "  }\n";
  }
  for (int b = 0; b < static_cast<int>(starts.size()); ++b)
    if (a.owner[static_cast<std::size_t>(starts[static_cast<std::size_t>(b)])] < 0) emit_block(out, b, "  ");
  for (const auto& e : a.edges) {
    if (e.to < 0 || e.to >= n) continue;
    int fb = block_of[static_cast<std::size_t>(e.from)], tb = block_of[static_cast<std::size_t>(e.to)];
    if (e.kind == EdgeKind::Next && fb == tb) continue;
    std::string attrs;
    if (e.kind == EdgeKind::Call) attrs = chain_sites.count(e.from) ? "style=dashed, color=red, penwidth=2, label=\"CSUB\"" : "style=dashed, label=\"CSUB\"";
    if (e.kind == EdgeKind::Vect) attrs = "style=dotted, label=\"VECT\"";
    if (e.kind == EdgeKind::Jump && in.program[static_cast<std::size_t>(e.from)].op != static_cast<std::uint8_t>(Op::JA))
    {
      std::string t = instruction_text(in.program[static_cast<std::size_t>(e.from)], labels);
      attrs = "label=" + dot_quoted(t.substr(0, t.find(',')));
    }
    while (!attrs.empty() && attrs.back() == ' ') attrs.pop_back();
    out += "  " + node(fb) + " -> " + node(tb) + (attrs.empty() ? "" : " [" + attrs + "]") + ";\n";
  }
  out += "}\n";
  return out;
}

}  // namespace tmcl
