// Resolving symbols and evaluating constant expressions. Arithmetic is 64-bit two's complement
// (wrapping, never undefined); the field an operand lands in checks the final range. Constants
// are evaluated on first use, so forward references work; a cycle is reported once, naming it.
//
// In an object (-c) a label's address is "the unit's base + offset" and an imported name is
// unknown until link time, so values are evaluated symbolically (see Value): a number plus at most
// one term. Adding or subtracting a number keeps the term, LABEL - LABEL of one file cancels it;
// anything else (Loop * 2) cannot be completed by a relocation and is an error naming the operand.
#include <algorithm>

#include "internal.hpp"
#include "syntax.hpp"

namespace tmcl::detail {

Resolver::Resolver(std::vector<Unit>& units, Diagnostics& diags, const SourceSet& sources, bool relocatable)
    : units_(units), diags_(diags), sources_(sources), relocatable_(relocatable) {}

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
      const int def = unit.find_def(name);
      if (def < 0) {
        diags_.error(loc, "exported symbol '" + name + "' is not defined in this file");
        continue;
      }
      unit.defs[static_cast<std::size_t>(def)].exported = true;
      auto [pos, fresh] = exported_.emplace(upper(name), std::make_pair(u, def));
      if (!fresh && pos->second != std::make_pair(u, def)) {
        const Unit& other = units_[static_cast<std::size_t>(pos->second.first)];
        const SymDef& first = other.defs[static_cast<std::size_t>(pos->second.second)];
        // Objects carry no source text: name the inputs, so the user knows which files clash.
        std::string inputs = unit.object || other.object
                                 ? " (by " + unit.input_name + " and by " + other.input_name + ")"
                                 : std::string();
        auto& d = diags_.error(unit.defs[static_cast<std::size_t>(def)].loc,
                               "duplicate export '" + name + "'" + inputs);
        diags_.note(d, first.loc, "also defined and exported here");
      }
    }
  }
  for (auto& unit : units_) {
    for (const auto& [key, loc] : unit.imports) {
      if (const int local = unit.find_def(key); local >= 0) {
        auto& d = diags_.error(loc, "'" + unit.defs[static_cast<std::size_t>(local)].name +
                                        "' is imported but also defined in this file");
        diags_.note(d, unit.defs[static_cast<std::size_t>(local)].loc, "defined here");
        continue;
      }
      if (!exported_.count(key) && !relocatable_) {
        undefined_import(static_cast<int>(&unit - units_.data()), key, loc);
        unit.failed_imports.insert(key);  // its uses are not reported again
      }
    }
  }
}

// A source names the #import; an object has no source text, so its first use is shown instead.
void Resolver::undefined_import(int u, const std::string& key, SourceLoc import_loc) {
  const Unit& unit = units_[static_cast<std::size_t>(u)];
  if (!unit.object) {
    diags_.error(import_loc, "imported symbol '" + name_at(import_loc) + "' is not exported by any input file");
    return;
  }
  const ObjectFile& obj = *unit.object;
  std::string name = key;
  std::vector<SourceLoc> uses;
  for (std::size_t i = 0; i < obj.symbols.size(); ++i) {
    if (upper(obj.symbols[i].name) != key || obj.symbols[i].binding != ObjBinding::Import) continue;
    name = obj.symbols[i].name;
    for (const auto& r : obj.relocs)
      if (r.term == ObjTerm::Symbol && r.symbol == i)
        uses.push_back(unit.object_loc(obj.lines[r.index].file, obj.lines[r.index].line));
    for (const auto& s : obj.symbols)
      if (s.term == ObjTerm::Symbol && s.term_symbol == i) uses.push_back(unit.object_loc(s.file, s.line));
  }
  SourceLoc at = uses.empty() ? import_loc : uses.front();
  auto& d = diags_.error(at, "undefined symbol '" + name + "': imported by " + unit.input_name +
                                 ", exported by no input file or library member");
  if (uses.size() > 1)
    diags_.note(d, uses[1], "also used here" + (uses.size() > 2 ? " and in " + std::to_string(uses.size() - 2) +
                                                                      " more place" + (uses.size() > 3 ? "s" : "")
                                                                : std::string()));
  if (uses.empty() || import_loc.line != at.line || import_loc.file != at.file) diags_.note(d, import_loc, "imported here");
}

bool Resolver::known(int unit, const std::string& key) {
  return lookup(unit, key).first >= 0 || units_[static_cast<std::size_t>(unit)].imports.count(key) > 0;
}

std::pair<int, int> Resolver::lookup(int unit, const std::string& key) {
  const Unit& u = units_[static_cast<std::size_t>(unit)];
  if (const int def = u.find_def(key); def >= 0) return {unit, def};
  if (u.imports.count(key)) {
    auto ex = exported_.find(key);
    if (ex != exported_.end()) return ex->second;
  }
  return {-1, -1};
}

namespace {
const char* kNotRelocatable =
    "in an object (-c) a label address or an imported name can only be added to or subtracted from a number, "
    "or two labels of this file subtracted";
}

// The error paths of eval_symbol and eval_node are out of line: those two recurse once per level
// of a constant chain, so their frames must stay small (a message built inline costs stack on
// every level, and the sanitizers multiply it).
void Resolver::report_cycle(int unit, int def) {
  const SymDef& d = units_[static_cast<std::size_t>(unit)].defs[static_cast<std::size_t>(def)];
  auto it = std::find(busy_.begin(), busy_.end(), std::make_pair(unit, def));
  std::string chain;
  for (auto k = it; k != busy_.end(); ++k) {
    SymDef& c = units_[static_cast<std::size_t>(k->first)].defs[static_cast<std::size_t>(k->second)];
    chain += c.name + " -> ";
    c.state = EvalState::Failed;
  }
  chain += d.name;
  diags_.error(d.loc, "constant '" + d.name + "' depends on itself: " + chain);
}

// Reported once: every constant being evaluated fails with it, and so would the rest.
void Resolver::report_too_deep(int unit, int index) {
  // Shown at the innermost constant being evaluated, else at the operand itself.
  SourceLoc at = units_[static_cast<std::size_t>(unit)].nodes[static_cast<std::size_t>(index)].loc;
  if (!busy_.empty())
    at = units_[static_cast<std::size_t>(busy_.back().first)].defs[static_cast<std::size_t>(busy_.back().second)].loc;
  if (!depth_reported_)
    diags_.error(at,
                 "constants and expressions nested more than " + std::to_string(kMaxEvalDepth) +
                     " levels deep (counting each constant and each operator)");
  depth_reported_ = true;
  for (const auto& [bu, bd] : busy_) units_[static_cast<std::size_t>(bu)].defs[static_cast<std::size_t>(bd)].state = EvalState::Failed;
}

bool Resolver::excuse_undefined(int unit, std::string_view name) {
  Unit& u = units_[static_cast<std::size_t>(unit)];
  if (u.missing_include < 0) return false;
  if (u.unreported.insert(upper(name)).second && u.unreported_shown.size() < 3) u.unreported_shown.emplace_back(name);
  return true;
}

void Resolver::note_excused() {
  for (const Unit& u : units_) {
    if (u.missing_include < 0 || u.unreported.empty()) continue;
    Diagnostic& d = diags_.at(static_cast<std::size_t>(u.missing_include));
    std::string names;
    for (std::size_t k = 0; k < u.unreported_shown.size(); ++k)
      names += (k ? ", '" : "'") + u.unreported_shown[k] + "'";
    std::size_t more = u.unreported.size() - u.unreported_shown.size();
    if (more) names += " and " + std::to_string(more) + " more";
    const bool one = u.unreported.size() == 1;
    diags_.note(d, d.loc, names + (one ? " is" : " are") + " used but defined nowhere: not reported as " +
                              (one ? "an error of its own, as the missing file may define it"
                                   : "errors of their own, as the missing file may define them"));
  }
}

std::string Resolver::closest_def(int unit, std::string_view name) const {
  std::vector<std::string_view> names;
  for (const auto& def : units_[static_cast<std::size_t>(unit)].defs) names.push_back(def.name);
  return closest_match(name, names);
}

void Resolver::report_undefined(int unit, const ExprNode& n, const std::string& key) {
  auto& d = diags_.error(n.loc, "use of undefined symbol '" + std::string(n.name) + "'");
  diags_.suggest(d, n.loc, n.name, closest_def(unit, n.name));
  auto ex = exported_.find(key);
  if (ex != exported_.end()) {
    const SymDef& other = units_[static_cast<std::size_t>(ex->second.first)].defs[static_cast<std::size_t>(ex->second.second)];
    diags_.note(d, other.loc, "'" + other.name + "' is exported here; add '#import " + other.name + "' to use it");
  }
}

// The value of a name: its definition, an import (objects), or an error.
std::optional<Value> Resolver::eval_name(int unit, const ExprNode& n, int depth) {
  std::string key = upper(n.name);
  auto [su, sd] = lookup(unit, key);
  if (su >= 0) return eval_symbol(su, sd, depth);
  const Unit& u = units_[static_cast<std::size_t>(unit)];
  if (relocatable_)
    if (auto it = u.import_index.find(key); it != u.import_index.end()) return Value{0, it->second};
  // With an #include missing, a name with no near miss among the unit's and no export elsewhere
  // is most likely one the file defines; a near miss is most likely a typo, and reported.
  if (!u.failed_imports.count(key) &&
      !(u.missing_include >= 0 && closest_def(unit, n.name).empty() && !exported_.count(key) && excuse_undefined(unit, n.name)))
    report_undefined(unit, n, key);
  return std::nullopt;
}

void Resolver::report_not_relocatable(const SymDef& d) {
  auto& diag = diags_.error(d.loc, "constant '" + d.name + "' is not relocatable: " + kNotRelocatable);
  diags_.note(diag, not_relocatable_, "here");
}

std::optional<Value> Resolver::eval_value(int unit, int node, SourceLoc operand) {
  not_relocatable_pending_ = false;
  auto v = eval_node(unit, node, 0);
  if (!v && not_relocatable_pending_) {
    auto& d = diags_.error(operand, "operand '" + name_at(operand) + "' is not relocatable: " + kNotRelocatable);
    diags_.note(d, not_relocatable_, "here");
  }
  not_relocatable_pending_ = false;
  return v;
}

std::optional<std::int64_t> Resolver::eval(int unit, int node) {
  not_relocatable_pending_ = false;
  auto v = eval_node(unit, node, 0);
  if (!v) return std::nullopt;
  if (v->term != kAbsolute) {  // only reachable in an object: a number that must be final now
    const ExprNode& n = units_[static_cast<std::size_t>(unit)].nodes[static_cast<std::size_t>(node)];
    diags_.error(n.loc, "this value must be known when assembling an object (-c); it depends on an address or import");
    return std::nullopt;
  }
  return v->k;
}

std::optional<Value> Resolver::eval_symbol(int unit, int def, int depth) {
  Unit& u = units_[static_cast<std::size_t>(unit)];
  SymDef& d = u.defs[static_cast<std::size_t>(def)];
  if (d.kind == SymbolKind::Label) {
    if (relocatable_) {
      d.value = d.address;
      d.term = kBaseTerm;
    } else {
      d.value = u.base + d.address;
    }
    d.state = EvalState::Done;
    return Value{d.value, d.term};
  }
  switch (d.state) {
    case EvalState::Done: return Value{d.value, d.term};
    case EvalState::Failed: return std::nullopt;
    case EvalState::Busy: report_cycle(unit, def); return std::nullopt;
    case EvalState::Todo: break;
  }
  d.state = EvalState::Busy;
  busy_.emplace_back(unit, def);
  bool outer_pending = not_relocatable_pending_;
  not_relocatable_pending_ = false;
  auto v = d.obj_symbol >= 0 ? eval_object_symbol(unit, d, depth + 1) : eval_node(unit, d.expr, depth + 1);
  busy_.pop_back();
  SymDef& again = units_[static_cast<std::size_t>(unit)].defs[static_cast<std::size_t>(def)];
  if (!v && not_relocatable_pending_) report_not_relocatable(again);
  not_relocatable_pending_ = outer_pending;
  if (again.state == EvalState::Failed || !v) {
    again.state = EvalState::Failed;
    return std::nullopt;
  }
  again.value = v->k;
  again.term = v->term;
  again.state = EvalState::Done;
  return v;
}

// The value of a linked object's constant: a number, base + number, or an import + number.
std::optional<Value> Resolver::eval_object_symbol(int unit, const SymDef& d, int depth) {
  const Unit& u = units_[static_cast<std::size_t>(unit)];
  const ObjSymbol& s = u.object->symbols[static_cast<std::size_t>(d.obj_symbol)];
  switch (s.term) {
    case ObjTerm::Absolute: return Value{s.value, kAbsolute};
    case ObjTerm::Base: return Value{static_cast<std::int64_t>(static_cast<std::uint64_t>(u.base) + static_cast<std::uint64_t>(s.value)), kAbsolute};
    case ObjTerm::Symbol: {
      std::string key = upper(u.object->symbols[s.term_symbol].name);
      auto [su, sd] = lookup(unit, key);
      if (su < 0) return std::nullopt;  // reported as an undefined import
      auto v = eval_symbol(su, sd, depth);
      if (!v) return std::nullopt;
      return Value{static_cast<std::int64_t>(static_cast<std::uint64_t>(v->k) + static_cast<std::uint64_t>(s.value)), kAbsolute};
    }
  }
  return std::nullopt;
}

// `depth` counts native frames of evaluation: every operand of a unary or binary operator and
// every constant entered adds one, so no input -- long constant chains, deep operator nesting, or
// both multiplied -- can exhaust the native stack (kMaxEvalDepth, reported once).
std::optional<Value> Resolver::eval_node(int unit, int index, int depth) {
  if (depth > kMaxEvalDepth) {
    report_too_deep(unit, index);
    return std::nullopt;
  }
  const ExprNode n = units_[static_cast<std::size_t>(unit)].nodes[static_cast<std::size_t>(index)];
  switch (n.kind) {
    case ExprKind::Number: return Value{n.number, kAbsolute};
    case ExprKind::Symbol: return eval_name(unit, n, depth);
    case ExprKind::Unary: {
      auto v = eval_node(unit, n.lhs, depth + 1);
      if (!v) return std::nullopt;
      if (n.op != P::Plus && v->term != kAbsolute) {
        if (!not_relocatable_pending_) not_relocatable_ = n.loc;
        not_relocatable_pending_ = true;
        return std::nullopt;
      }
      auto u = static_cast<std::uint64_t>(v->k);
      switch (n.op) {
        case P::Minus: return Value{static_cast<std::int64_t>(0 - u), kAbsolute};
        case P::Tilde: return Value{static_cast<std::int64_t>(~u), kAbsolute};
        default: return v;
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
      auto acc = eval_node(unit, bottom, depth + 1);
      bool ok = acc.has_value();
      for (auto it = spine.rbegin(); it != spine.rend(); ++it) {
        const ExprNode op = units_[static_cast<std::size_t>(unit)].nodes[static_cast<std::size_t>(*it)];
        auto rhs = eval_node(unit, op.rhs, depth + 1);
        if (!ok || !rhs) {
          ok = false;
          continue;
        }
        acc = combine(op, *acc, *rhs);
        ok = acc.has_value();
      }
      return ok ? acc : std::nullopt;
    }
  }
  return std::nullopt;
}

// A binary operation on values that may carry a term (objects only).
std::optional<Value> Resolver::combine(const ExprNode& n, Value a, Value b) {
  auto add = [](std::int64_t x, std::int64_t y, bool minus) {
    auto ux = static_cast<std::uint64_t>(x), uy = static_cast<std::uint64_t>(y);
    return static_cast<std::int64_t>(minus ? ux - uy : ux + uy);
  };
  if (a.term == kAbsolute && b.term == kAbsolute) {
    auto v = apply(n, a.k, b.k);
    if (!v) return std::nullopt;
    return Value{*v, kAbsolute};
  }
  if (n.op == P::Plus && (a.term == kAbsolute || b.term == kAbsolute))
    return Value{add(a.k, b.k, false), a.term == kAbsolute ? b.term : a.term};
  if (n.op == P::Minus && b.term == kAbsolute) return Value{add(a.k, b.k, true), a.term};
  if (n.op == P::Minus && a.term == b.term && a.term == kBaseTerm) return Value{add(a.k, b.k, true), kAbsolute};
  if (!not_relocatable_pending_) not_relocatable_ = n.loc;
  not_relocatable_pending_ = true;
  return std::nullopt;
}

// One binary operation (apply_binary, syntax.hpp: the fast path computes with it too), with the
// reason when it has no value.
std::optional<std::int64_t> Resolver::apply(const ExprNode& n, std::int64_t a, std::int64_t b) {
  std::int64_t v = 0;
  switch (apply_binary(n.op, a, b, v)) {
    case OpFault::None: return v;
    case OpFault::DivisionByZero: diags_.error(n.loc, "division by zero"); break;
    case OpFault::ModuloByZero: diags_.error(n.loc, "modulo by zero"); break;
    case OpFault::ShiftCount:
      diags_.error(n.loc, "shift count " + std::to_string(b) + " is outside 0 to 63");
      break;
    case OpFault::NotBinary: break;
  }
  return std::nullopt;
}

void Resolver::check_redefinitions() {
  for (int u = 0; u < static_cast<int>(units_.size()); ++u) {
    Unit& unit = units_[static_cast<std::size_t>(u)];
    for (const auto& r : unit.redefinitions) {
      auto first = eval_symbol(u, r.first, 0);
      auto second = eval_value(u, r.expr, r.loc);
      if (!first || !second || *first == *second) continue;
      const SymDef& d = unit.defs[static_cast<std::size_t>(r.first)];
      auto text = [](Value v) { return std::to_string(v.k) + (v.term == kAbsolute ? "" : " plus an address"); };
      auto& diag = diags_.error(r.loc, "constant '" + d.name + "' redefined with a different value (" +
                                           text(*second) + "; it was " + text(*first) + ")");
      diags_.note(diag, d.loc, d.from_command_line ? "first defined on the command line" : "first defined here");
    }
  }
}

}  // namespace tmcl::detail
