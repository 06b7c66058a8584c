// Resolving symbols and evaluating constant expressions. Arithmetic is 64-bit two's complement
// (wrapping, never undefined); the field an operand lands in checks the final range. Constants
// are evaluated on first use, so forward references work; a cycle is reported once, naming it.
#include <algorithm>

#include "internal.hpp"

namespace tmcl::detail {

Resolver::Resolver(std::vector<Unit>& units, Diagnostics& diags, const SourceSet& sources)
    : units_(units), diags_(diags), sources_(sources) {}

// The name written at a location (imports keep only their location and upper-cased key).
std::string Resolver::name_at(SourceLoc loc) const {
  if (loc.file < 0) return "?";
  std::string_view line = sources_.files[static_cast<std::size_t>(loc.file)].line(loc.line);
  auto start = static_cast<std::size_t>(loc.col - 1);
  if (start >= line.size()) return "?";
  return std::string(line.substr(start, static_cast<std::size_t>(loc.len)));
}

void Resolver::link_exports() {
  for (int u = 0; u < static_cast<int>(units_.size()); ++u) {
    Unit& unit = units_[static_cast<std::size_t>(u)];
    for (const auto& [name, loc] : unit.exports) {
      std::string key = upper(name);
      auto it = unit.by_name.find(key);
      if (it == unit.by_name.end()) {
        diags_.error(loc, "exported symbol '" + name + "' is not defined in this file");
        continue;
      }
      unit.defs[static_cast<std::size_t>(it->second)].exported = true;
      auto [pos, fresh] = exported_.emplace(key, std::make_pair(u, it->second));
      if (!fresh && pos->second != std::make_pair(u, it->second)) {
        const SymDef& first = units_[static_cast<std::size_t>(pos->second.first)].defs[static_cast<std::size_t>(pos->second.second)];
        auto& d = diags_.error(unit.defs[static_cast<std::size_t>(it->second)].loc, "duplicate export '" + name + "'");
        diags_.note(d, first.loc, "also defined and exported here");
      }
    }
  }
  for (auto& unit : units_) {
    for (const auto& [key, loc] : unit.imports) {
      auto local = unit.by_name.find(key);
      if (local != unit.by_name.end()) {
        auto& d = diags_.error(loc, "'" + unit.defs[static_cast<std::size_t>(local->second)].name +
                                        "' is imported but also defined in this file");
        diags_.note(d, unit.defs[static_cast<std::size_t>(local->second)].loc, "defined here");
        continue;
      }
      if (!exported_.count(key)) {
        diags_.error(loc, "imported symbol '" + name_at(loc) + "' is not exported by any input file");
        unit.failed_imports.insert(key);  // its uses are not reported again
      }
    }
  }
}

std::pair<int, int> Resolver::lookup(int unit, const std::string& key) {
  const Unit& u = units_[static_cast<std::size_t>(unit)];
  auto it = u.by_name.find(key);
  if (it != u.by_name.end()) return {unit, it->second};
  if (u.imports.count(key)) {
    auto ex = exported_.find(key);
    if (ex != exported_.end()) return ex->second;
  }
  return {-1, -1};
}

std::optional<std::int64_t> Resolver::eval(int unit, int node) { return eval_node(unit, node, 0); }

std::optional<std::int64_t> Resolver::eval_symbol(int unit, int def, int depth, SourceLoc use) {
  Unit& u = units_[static_cast<std::size_t>(unit)];
  SymDef& d = u.defs[static_cast<std::size_t>(def)];
  if (d.kind == SymbolKind::Label) {
    d.value = u.base + d.address;
    d.state = EvalState::Done;
    return d.value;
  }
  switch (d.state) {
    case EvalState::Done: return d.value;
    case EvalState::Failed: return std::nullopt;
    case EvalState::Busy: {
      auto it = std::find(busy_.begin(), busy_.end(), std::make_pair(unit, def));
      std::string chain;
      for (auto k = it; k != busy_.end(); ++k) {
        SymDef& c = units_[static_cast<std::size_t>(k->first)].defs[static_cast<std::size_t>(k->second)];
        chain += c.name + " -> ";
        c.state = EvalState::Failed;
      }
      chain += d.name;
      diags_.error(d.loc, "constant '" + d.name + "' depends on itself: " + chain);
      return std::nullopt;
    }
    case EvalState::Todo: break;
  }
  if (depth > kMaxEvalDepth) {
    // Reported once: every constant of the chain fails with it, and so would the rest.
    if (!depth_reported_)
      diags_.error(use.file >= 0 ? use : d.loc,
                   "constants refer to constants more than " + std::to_string(kMaxEvalDepth) + " levels deep");
    depth_reported_ = true;
    for (const auto& [bu, bd] : busy_) units_[static_cast<std::size_t>(bu)].defs[static_cast<std::size_t>(bd)].state = EvalState::Failed;
    d.state = EvalState::Failed;
    return std::nullopt;
  }
  d.state = EvalState::Busy;
  busy_.emplace_back(unit, def);
  auto v = eval_node(unit, d.expr, depth + 1);
  busy_.pop_back();
  SymDef& again = units_[static_cast<std::size_t>(unit)].defs[static_cast<std::size_t>(def)];
  if (again.state == EvalState::Failed || !v) {
    again.state = EvalState::Failed;
    return std::nullopt;
  }
  again.value = *v;
  again.state = EvalState::Done;
  return v;
}

std::optional<std::int64_t> Resolver::eval_node(int unit, int index, int depth) {
  const ExprNode n = units_[static_cast<std::size_t>(unit)].nodes[static_cast<std::size_t>(index)];
  switch (n.kind) {
    case ExprKind::Number: return n.number;
    case ExprKind::Symbol: {
      std::string key = upper(n.name);
      auto [su, sd] = lookup(unit, key);
      if (su >= 0) return eval_symbol(su, sd, depth, n.loc);
      if (units_[static_cast<std::size_t>(unit)].failed_imports.count(key)) return std::nullopt;
      auto& d = diags_.error(n.loc, "use of undefined symbol '" + std::string(n.name) + "'");
      std::vector<std::string_view> names;
      const Unit& u = units_[static_cast<std::size_t>(unit)];
      for (const auto& def : u.defs) names.push_back(def.name);
      std::string hint = closest_match(n.name, names);
      if (!hint.empty()) diags_.note(d, n.loc, "did you mean '" + hint + "'?");
      auto ex = exported_.find(key);
      if (ex != exported_.end()) {
        const SymDef& other = units_[static_cast<std::size_t>(ex->second.first)].defs[static_cast<std::size_t>(ex->second.second)];
        diags_.note(d, other.loc, "'" + other.name + "' is exported here; add '#import " + other.name + "' to use it");
      }
      return std::nullopt;
    }
    case ExprKind::Unary: {
      auto v = eval_node(unit, n.lhs, depth);
      if (!v) return std::nullopt;
      auto u = static_cast<std::uint64_t>(*v);
      switch (n.op) {
        case P::Minus: return static_cast<std::int64_t>(0 - u);
        case P::Tilde: return static_cast<std::int64_t>(~u);
        default: return *v;
      }
    }
    case ExprKind::Binary: {
      // Left-associative chains (a + b + c + ...) are evaluated along their left spine in a
      // loop, so a long flat expression costs no native stack.
      std::vector<int> spine;
      int bottom = index;
      while (true) {
        const ExprNode& b = units_[static_cast<std::size_t>(unit)].nodes[static_cast<std::size_t>(bottom)];
        if (b.kind != ExprKind::Binary) break;
        spine.push_back(bottom);
        bottom = b.lhs;
      }
      auto acc = eval_node(unit, bottom, depth);
      bool ok = acc.has_value();
      for (auto it = spine.rbegin(); it != spine.rend(); ++it) {
        const ExprNode op = units_[static_cast<std::size_t>(unit)].nodes[static_cast<std::size_t>(*it)];
        auto rhs = eval_node(unit, op.rhs, depth);
        if (!ok || !rhs) {
          ok = false;
          continue;
        }
        acc = apply(op, *acc, *rhs);
        ok = acc.has_value();
      }
      return ok ? acc : std::nullopt;
    }
  }
  return std::nullopt;
}

// One binary operation, wrapping like the 64-bit two's complement machine it models.
std::optional<std::int64_t> Resolver::apply(const ExprNode& n, std::int64_t a, std::int64_t b) {
  auto ua = static_cast<std::uint64_t>(a), ub = static_cast<std::uint64_t>(b);
  switch (n.op) {
    case P::Plus: return static_cast<std::int64_t>(ua + ub);
    case P::Minus: return static_cast<std::int64_t>(ua - ub);
    case P::Star: return static_cast<std::int64_t>(ua * ub);
    case P::Slash:
    case P::Percent:
      if (b == 0) {
        diags_.error(n.loc, n.op == P::Slash ? "division by zero" : "modulo by zero");
        return std::nullopt;
      }
      if (b == -1) return n.op == P::Slash ? static_cast<std::int64_t>(0 - ua) : 0;
      return n.op == P::Slash ? a / b : a % b;
    case P::Amp: return static_cast<std::int64_t>(ua & ub);
    case P::Pipe: return static_cast<std::int64_t>(ua | ub);
    case P::Caret: return static_cast<std::int64_t>(ua ^ ub);
    case P::Shl:
    case P::Shr:
      if (b < 0 || b > 63) {
        diags_.error(n.loc, "shift count " + std::to_string(b) + " is outside 0 to 63");
        return std::nullopt;
      }
      return n.op == P::Shl ? static_cast<std::int64_t>(ua << ub) : (a >> b);
    default: return std::nullopt;
  }
}

void Resolver::check_redefinitions() {
  for (int u = 0; u < static_cast<int>(units_.size()); ++u) {
    Unit& unit = units_[static_cast<std::size_t>(u)];
    for (const auto& r : unit.redefinitions) {
      auto first = eval_symbol(u, r.first, 0, r.loc);
      auto second = eval_node(u, r.expr, 0);
      if (!first || !second || *first == *second) continue;
      const SymDef& d = unit.defs[static_cast<std::size_t>(r.first)];
      auto& diag = diags_.error(r.loc, "constant '" + d.name + "' redefined with a different value (" +
                                           std::to_string(*second) + "; it was " + std::to_string(*first) + ")");
      diags_.note(diag, d.loc, d.from_command_line ? "first defined on the command line" : "first defined here");
    }
  }
}

}  // namespace tmcl::detail
