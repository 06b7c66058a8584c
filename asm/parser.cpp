// The parser: tokens of a root file and everything it includes into one Unit of statements,
// label and constant definitions, exports and imports. One mistake costs one diagnostic: after
// an error the rest of the line is skipped (panic mode), and an instruction that fails to parse
// still takes its address so that later labels stay where the programmer expects them.
#include <algorithm>

#include "internal.hpp"
#include "syntax.hpp"
#include "tmcl/os_files.hpp"

namespace tmcl::detail {
namespace {

std::vector<std::string_view> mnemonic_names() {
  std::vector<std::string_view> v;
  for (const auto& op : all_ops())
    if (!op.mnemonic.empty()) v.push_back(op.mnemonic);
  return v;
}

std::string operand_names(const OpInfo& op) {
  std::string s;
  for (const auto& o : op.operands) {
    if (!s.empty()) s += ", ";
    s += o.keywords != KwSet::None ? std::string(kwset_name(o.keywords)) : std::string(role_name(o.role));
  }
  return s;
}

class Parser {
 public:
  Parser(const AsmOptions& o, FileReader& r, SourceSet& s, Diagnostics& d, Unit& u)
      : opts_(o), reader_(r), sources_(s), diags_(d), unit_(u) {}

  void define_command_line(const std::string& name, const std::string& value) {
    SourceFile f;
    f.name = "<command line -D " + name + ">";
    f.path = f.name;
    f.text = value;
    int idx = sources_.add(std::move(f));
    Lexer lexer(sources_.files[static_cast<std::size_t>(idx)], idx, diags_);
    start(lexer, idx);
    int e = expr(0);
    if (e >= 0 && !at_eol()) {
      diags_.error(loc(cur()), "unexpected " + describe(cur()) + " after the value of -D " + name);
      e = -1;
    }
    if (int first = unit_.find_def(name); first >= 0) {
      if (e >= 0) unit_.redefinitions.push_back({first, e, SourceLoc{idx, 1, 1, static_cast<int>(value.size())}});
      return;
    }
    {
      SymDef d;
      d.name = name;
      d.kind = SymbolKind::Constant;
      d.expr = e;
      d.loc = SourceLoc{idx, 1, 1, static_cast<int>(value.size())};
      d.from_command_line = true;
      if (e < 0) d.state = EvalState::Failed;  // reported once, here; its uses stay quiet
      unit_.add_def(std::move(d));
    }
  }

  void parse_root(const std::string& path, std::string* preloaded) {
    std::string text;
    if (preloaded) {
      text = std::move(*preloaded);  // the caller read it to tell a source from an object
    } else if (!reader_.read(path, text)) {
      diags_.error(SourceLoc{}, "cannot read '" + path + "': " + reader_.last_error());
      return;
    }
    SourceFile f;
    f.name = path == "-" ? "<stdin>" : path;
    f.path = path;
    f.text = std::move(text);
    if (f.text.size() > kMaxFileBytes) {
      diags_.error(SourceLoc{}, "'" + path + "' is larger than the limit of " + std::to_string(kMaxFileBytes >> 20) + " MiB");
      return;
    }
    // Rough sizes from the file's length save most regrowing on large programs.
    unit_.stmts.reserve(f.text.size() / 40);
    unit_.nodes.reserve(f.text.size() / 20);
    int idx = add_source(std::move(f));
    if (idx < 0) return;
    unit_.root_file = idx;
    std::string key = include_key(path);
    included_.push_back(key);
    parse_file(idx, 0, key);
  }

 private:
  // ---- token cursor ----
  const Token& cur() const { return win_[0]; }
  const Token& next() const { return win_[1]; }
  void advance() {
    prev_ = win_[0];
    win_[0] = win_[1];
    if (win_[1].kind != Tok::End) win_[1] = lexer_->next_token();
  }
  void start(Lexer& lexer, int file) {
    lexer_ = &lexer;
    file_ = file;
    win_[0] = lexer.next_token();
    win_[1] = win_[0].kind == Tok::End ? win_[0] : lexer.next_token();
  }
  bool at_eol() const { return cur().kind == Tok::Newline || cur().kind == Tok::End; }
  bool is_punct(P p) const { return cur().kind == Tok::Punct && cur().punct == p; }
  SourceLoc loc(const Token& t) const {
    return SourceLoc{file_, t.line, t.col, std::max(1, static_cast<int>(t.text.size()))};
  }
  // Stretches a location to the end of the last consumed token, when on the same line.
  void extend_to_previous(SourceLoc& l) const {
    if (prev_.line == l.line && prev_.col >= l.col)
      l.len = prev_.col + static_cast<int>(prev_.text.size()) - l.col;
  }
  void skip_line() {
    while (!at_eol()) advance();
  }
  // Reports an error at the current token unless the lexer already did (a Bad token).
  void fail(const std::string& msg) {
    if (cur().kind != Tok::Bad) diags_.error(loc(cur()), msg);
    skip_line();
  }
  std::string describe(const Token& t) const {
    switch (t.kind) {
      case Tok::Newline:
      case Tok::End: return "end of line";
      default: return "'" + std::string(t.text) + "'";
    }
  }

  // ---- files ----
  void parse_file(int file, int depth, const std::string& key) {
    stack_.push_back(key);
    Lexer* saved_lexer = lexer_;
    Token saved_win[2] = {win_[0], win_[1]};
    int saved_file = file_;
    Lexer lexer(sources_.files[static_cast<std::size_t>(file)], file, diags_);
    start(lexer, file);
    while (cur().kind != Tok::End) {
      statement(depth);
      if (!at_eol()) fail("unexpected " + describe(cur()) + " at the end of the statement");
      if (cur().kind == Tok::Newline) advance();
    }
    lexer_ = saved_lexer;
    win_[0] = saved_win[0];
    win_[1] = saved_win[1];
    file_ = saved_file;
    stack_.pop_back();
  }

  // Adds a loaded file; returns -1 when a line is too long to be a source line (the file is
  // then not parsed).
  int add_source(SourceFile f) {
    drop_bom(f.text);
    int idx = sources_.add(std::move(f));
    if (int l = first_long_line(sources_.files[static_cast<std::size_t>(idx)])) {
      diags_.error(SourceLoc{idx, l, 1, 1}, "line is longer than " + std::to_string(kMaxLineBytes) + " bytes");
      return -1;
    }
    diags_.allow_from_comments(sources_.files[static_cast<std::size_t>(idx)], idx);  // `tmcl: allow NAME`
    return idx;
  }

  void include(int depth) {
    advance();
    if (cur().kind != Tok::IncludeName || cur().text.empty()) return fail("#include needs a file name");
    Token nt = cur();
    advance();
    std::string name(include_file_name(nt.text));
    if (name.empty()) return diags_.error(loc(nt), "#include needs a file name"), void();
    if (depth + 1 > kMaxIncludeDepth) {
      diags_.error(loc(nt), "includes nested more than " + std::to_string(kMaxIncludeDepth) + " deep");
      return;
    }
    FoundInclude inc;
    std::vector<std::string> searched;
    bool found = find_include(name, sources_.files[static_cast<std::size_t>(file_)].path, opts_, reader_, inc, &searched);
    if (!found) {
      // One error for the one mistake: what the file would have defined is not reported again.
      if (unit_.missing_include < 0) unit_.missing_include = static_cast<int>(diags_.all().size());
      auto& d = diags_.error(loc(nt), "cannot find include file '" + name + "'");
      std::vector<std::string_view> names;
      for (const auto& b : bundled_includes()) names.push_back(b.first);
      // The fix replaces the name between the quotes or angle brackets.
      SourceLoc inner = loc(nt);
      if (nt.text.size() >= 2 && (nt.text[0] == '"' || nt.text[0] == '<')) inner.col += 1, inner.len -= 2;
      diags_.suggest(d, loc(nt), inner, name, closest_match(name, names));
      std::string where;
      for (std::size_t k = 0; k < searched.size(); ++k)
        where += (k == 0 ? "" : ", ") + searched[k];
      diags_.note(d, loc(nt), "searched " + (where.empty() ? std::string() : where + " and ") +
                                  "the include files bundled with tmcl; name the file's folder with -I DIR");
      return;
    }
    const std::string& key = inc.key;
    if (std::find(stack_.begin(), stack_.end(), key) != stack_.end()) {
      std::string chain;
      auto it = std::find(stack_.begin(), stack_.end(), key);
      for (; it != stack_.end(); ++it) chain += *it + " -> ";
      chain += key;
      diags_.error(loc(nt), "include cycle: " + chain);
      return;
    }
    if (std::find(included_.begin(), included_.end(), key) != included_.end()) return;  // once only
    included_.push_back(key);
    if (inc.text.size() > kMaxFileBytes) {
      diags_.error(loc(nt), "'" + inc.path + "' is larger than the limit of " + std::to_string(kMaxFileBytes >> 20) + " MiB");
      return;
    }
    SourceFile f;
    f.name = inc.path.rfind("<bundled>/", 0) == 0 ? inc.path : os::normal_path(inc.path);
    f.path = inc.path;
    f.text = std::move(inc.text);
    f.includer = file_;
    f.include_line = nt.line;
    int idx = add_source(std::move(f));
    if (idx >= 0) parse_file(idx, depth + 1, key);
  }

  // #export NAME, NAME... / #import NAME, NAME...
  void name_list(bool exporting) {
    std::string what = exporting ? "#export" : "#import";
    advance();
    if (at_eol()) return fail(what + " needs at least one name");
    while (true) {
      if (cur().kind != Tok::Ident) return fail(what + " expects a name, found " + describe(cur()));
      SourceLoc l = loc(cur());
      std::string name(cur().text);
      if (exporting) {
        unit_.exports.emplace_back(name, l);
      } else if (unit_.imports.emplace(upper(name), l).second) {
        unit_.import_index.emplace(upper(name), static_cast<int>(unit_.import_order.size()));
        unit_.import_order.push_back(upper(name));
      }
      advance();
      if (at_eol()) return;
      if (!is_punct(P::Comma)) return fail("expected ',' between names, found " + describe(cur()));
      advance();
    }
  }

  void directive(int depth) {
    std::string d = upper(cur().text);
    if (d == "#INCLUDE") return include(depth);
    if (d == "#EXPORT") return name_list(true);
    if (d == "#IMPORT") return name_list(false);
    if (d == "#NO_APPEND_STOP") {
      // Written by the disassembler for an image that does not end in STOP.
      unit_.no_append_stop = true;
      advance();
      return;
    }
    auto& diag = diags_.error(loc(cur()), "unknown directive '" + std::string(cur().text) + "'");
    diags_.suggest(diag, loc(cur()), cur().text, closest_match(cur().text, {"#include", "#export", "#import", "#no_append_stop"}));
    skip_line();
  }

  // ---- statements ----
  void statement(int depth) {
    // Labels: NAME ':' (any number of them).
    while (cur().kind == Tok::Ident && next().kind == Tok::Punct && next().punct == P::Colon) {
      define_label(cur());
      advance();
      advance();
    }
    if (at_eol()) return;
    const Token& t = cur();
    if (t.kind == Tok::Directive) return directive(depth);
    if (t.kind != Tok::Ident) return fail("expected an instruction, a label or a constant, found " + describe(t));
    if (next().kind == Tok::Punct && next().punct == P::Assign) return constant();
    if (t.text.front() == '.') return raw();
    instruction();
  }

  // The number of names in one unit is limited (docs/limits.md); the first one past the limit
  // is reported, the rest silently dropped.
  bool room_for_symbol(SourceLoc at) {
    if (unit_.defs.size() < kMaxSymbols) return true;
    if (!symbols_reported_)
      diags_.error(at, "more than " + std::to_string(kMaxSymbols) + " labels and constants in one unit");
    symbols_reported_ = true;
    return false;
  }

  void define_label(const Token& t) {
    if (int k = unit_.find_def(t.text); k >= 0) {
      const SymDef& first = unit_.defs[static_cast<std::size_t>(k)];
      auto& d = diags_.error(loc(t), first.kind == SymbolKind::Label
                                         ? "duplicate label '" + std::string(t.text) + "'"
                                         : "'" + std::string(t.text) + "' is already defined as a constant");
      diags_.note(d, first.loc, "first defined here");
      return;
    }
    if (!room_for_symbol(loc(t))) return;
    SymDef d;
    d.name = std::string(t.text);
    d.kind = SymbolKind::Label;
    d.address = static_cast<int>(unit_.stmts.size());
    d.loc = loc(t);
    unit_.add_def(std::move(d));
  }

  void constant() {
    Token name = cur();
    advance();
    advance();
    if (at_eol()) return fail("expected a value after '='");
    int e = expr(0);
    const int defined = unit_.find_def(name.text);
    if (e < 0) {
      // Define it anyway, poisoned, so that its uses do not report it as undefined.
      if (defined < 0) {
        SymDef d;
        d.name = std::string(name.text);
        d.kind = SymbolKind::Constant;
        d.loc = loc(name);
        d.state = EvalState::Failed;
        unit_.add_def(std::move(d));
      }
      return skip_line();
    }
    if (defined >= 0) {
      const SymDef& first = unit_.defs[static_cast<std::size_t>(defined)];
      if (first.kind == SymbolKind::Label) {
        auto& d = diags_.error(loc(name), "'" + std::string(name.text) + "' is already defined as a label");
        diags_.note(d, first.loc, "first defined here");
        return;
      }
      unit_.redefinitions.push_back({defined, e, loc(name)});
      return;
    }
    if (!room_for_symbol(loc(name))) return;
    if (is_keyword(name.text))
      diags_.warning(loc(name), "constant '" + std::string(name.text) + "' has the name of a keyword; where " +
                                    "that keyword may stand, the keyword wins", "keyword-name");
    SymDef d;
    d.name = std::string(name.text);
    d.kind = SymbolKind::Constant;
    d.expr = e;
    d.loc = loc(name);
    unit_.add_def(std::move(d));
  }

  // .raw OPCODE, TYPE, MOTOR, VALUE: any record, for what the mnemonic form cannot express.
  void raw() {
    Stmt s;
    s.loc = loc(cur());
    s.address = static_cast<int>(unit_.stmts.size());
    if (upper(cur().text) != ".RAW") {
      auto& d = diags_.error(loc(cur()), "unknown directive '" + std::string(cur().text) + "'");
      diags_.note(d, loc(cur()), "the raw instruction form is '.raw OPCODE, TYPE, MOTOR, VALUE'");
      s.count = -1;
      unit_.stmts.push_back(s);
      return skip_line();
    }
    advance();
    s.count = -1;  // until all four operands have parsed
    for (int k = 0; k < 4; ++k) {
      if (k > 0) {
        if (!is_punct(P::Comma)) {
          unit_.stmts.push_back(s);
          return fail(".raw expects 4 operands (opcode, type, motor, value), found " + describe(cur()));
        }
        advance();
      }
      Operand o;
      o.loc = loc(cur());
      o.expr = expr(0);
      extend_to_previous(o.loc);
      if (o.expr < 0) {
        unit_.stmts.push_back(s);
        return skip_line();
      }
      s.operands[static_cast<std::size_t>(k)] = o;
    }
    if (is_punct(P::Comma)) {
      unit_.stmts.push_back(s);
      return fail("too many operands: .raw takes 4 (opcode, type, motor, value)");
    }
    s.count = 4;
    unit_.stmts.push_back(s);
  }

  void instruction() {
    const Token& mn = cur();
    Stmt s;
    s.loc = loc(mn);
    s.address = static_cast<int>(unit_.stmts.size());
    s.op = op_by_mnemonic(mn.text);
    if (!s.op) {
      std::string hint = closest_match(mn.text, mnemonic_names());
      bool alone = next().kind == Tok::Newline || next().kind == Tok::End;
      if (alone && hint.empty()) {
        // Most likely a label without its ':'; define it so that its uses are not errors too.
        auto& d = diags_.error(loc(mn), "unknown instruction mnemonic '" + std::string(mn.text) + "'");
        diags_.note(d, loc(mn), "a label needs a ':' after its name");
        define_label(mn);
        return skip_line();
      }
      auto& d = diags_.error(loc(mn), "unknown instruction mnemonic '" + std::string(mn.text) + "'");
      diags_.suggest(d, loc(mn), mn.text, hint);
      s.op = nullptr;
      s.count = -1;  // poisoned: takes its address, encodes nothing
      unit_.stmts.push_back(s);
      return skip_line();
    }
    advance();
    const auto& specs = s.op->operands;
    std::size_t want = specs.size();
    for (std::size_t k = 0; k < want; ++k) {
      if (k > 0) {
        if (at_eol()) {
          s.count = -1;
          unit_.stmts.push_back(s);
          auto& d = diags_.error(loc(cur()), std::string(s.op->mnemonic) + " expects " + std::to_string(want) +
                                                 " operands (" + operand_names(*s.op) + "), found " +
                                                 std::to_string(k));
          (void)d;
          return;
        }
        if (!is_punct(P::Comma)) {
          s.count = -1;
          unit_.stmts.push_back(s);
          return fail("expected ',' after operand " + std::to_string(k) + " of " + std::string(s.op->mnemonic) +
                      ", found " + describe(cur()));
        }
        advance();
      }
      if (at_eol()) {
        s.count = -1;
        unit_.stmts.push_back(s);
        diags_.error(loc(cur()), std::string(s.op->mnemonic) + " expects " + std::to_string(want) +
                                     (want == 1 ? " operand (" : " operands (") + operand_names(*s.op) + "), found " +
                                     std::to_string(k));
        return;
      }
      Operand o;
      o.loc = loc(cur());
      const OperandSpec& spec = specs[k];
      bool lone_ident = cur().kind == Tok::Ident && (next().kind == Tok::Newline || next().kind == Tok::End ||
                                                     (next().kind == Tok::Punct && next().punct == P::Comma));
      if (spec.keywords != KwSet::None && lone_ident) {
        if (auto v = keyword_value(spec.keywords, cur().text)) {
          o.keyword = *v;
          advance();
          s.operands[k] = o;
          continue;
        }
      }
      o.lone_symbol = lone_ident;
      o.expr = expr(0);
      extend_to_previous(o.loc);
      if (o.expr < 0) {
        s.count = -1;
        unit_.stmts.push_back(s);
        return skip_line();
      }
      s.operands[k] = o;
    }
    if (!at_eol()) {
      if (is_punct(P::Comma)) {
        s.count = -1;
        unit_.stmts.push_back(s);
        std::string msg = std::string(s.op->mnemonic) + " takes " +
                          (want == 0 ? std::string("no operands")
                                     : std::to_string(want) + (want == 1 ? " operand (" : " operands (") +
                                           operand_names(*s.op) + ")");
        return fail("too many operands: " + msg);
      }
      if (want == 0) {
        s.count = -1;
        unit_.stmts.push_back(s);
        return fail(std::string(s.op->mnemonic) + " takes no operands, found " + describe(cur()));
      }
    }
    s.count = static_cast<int>(want);
    unit_.stmts.push_back(s);
  }

  // ---- expressions: precedence climbing, C precedence (binary_precedence, syntax.hpp) ----
  static int precedence(P p) { return binary_precedence(p); }

  int node(ExprNode n) {
    unit_.nodes.push_back(n);
    return static_cast<int>(unit_.nodes.size() - 1);
  }

  // Returns the node index, or -1 after reporting an error.
  int expr(int depth, int min_prec = 1) {
    int lhs = unary(depth);
    if (lhs < 0) return -1;
    while (cur().kind == Tok::Punct && precedence(cur().punct) >= min_prec) {
      Token op = cur();
      int prec = precedence(op.punct);
      advance();
      int rhs = expr(depth + 1, prec + 1);
      if (rhs < 0) return -1;
      ExprNode n{ExprKind::Binary, op.punct, 0, {}, lhs, rhs, loc(op)};
      lhs = node(n);
    }
    return lhs;
  }

  int unary(int depth) {
    if (depth > kMaxExprDepth) {
      diags_.error(loc(cur()), "expression nested more than " + std::to_string(kMaxExprDepth) + " levels deep");
      return -1;
    }
    const Token t = cur();
    if (t.kind == Tok::Punct && (t.punct == P::Minus || t.punct == P::Plus || t.punct == P::Tilde)) {
      advance();
      int operand = unary(depth + 1);
      if (operand < 0) return -1;
      return node(ExprNode{ExprKind::Unary, t.punct, 0, {}, operand, -1, loc(t)});
    }
    if (t.kind == Tok::Punct && t.punct == P::LParen) {
      advance();
      int inner = expr(depth + 1);
      if (inner < 0) return -1;
      if (!is_punct(P::RParen)) {
        auto& d = diags_.error(loc(cur()), "expected ')', found " + describe(cur()));
        diags_.note(d, loc(t), "to match this '('");
        return -1;
      }
      advance();
      return inner;
    }
    if (t.kind == Tok::Number) {
      advance();
      return node(ExprNode{ExprKind::Number, P::None, t.number, {}, -1, -1, loc(t)});
    }
    if (t.kind == Tok::Ident && t.text.front() != '.') {
      advance();
      return node(ExprNode{ExprKind::Symbol, P::None, 0, t.text, -1, -1, loc(t)});
    }
    if (t.kind != Tok::Bad) diags_.error(loc(t), "expected a value, found " + describe(t));
    return -1;
  }

  const AsmOptions& opts_;
  FileReader& reader_;
  SourceSet& sources_;
  Diagnostics& diags_;
  Unit& unit_;
  Lexer* lexer_ = nullptr;
  Token win_[2];  // the current token and the one after it
  Token prev_;    // the token consumed last, for the extent of an operand
  bool symbols_reported_ = false;
  int file_ = -1;
  std::vector<std::string> stack_;     // include chain (keys)
  std::vector<std::string> included_;  // every file included so far (keys)
};

}  // namespace

void parse_unit(const std::string& root, const AsmOptions& options, FileReader& reader, SourceSet& sources,
                Diagnostics& diags, Unit& unit, std::string* text) {
  Parser p(options, reader, sources, diags, unit);
  for (const auto& [name, value] : options.defines) p.define_command_line(name, value);
  p.parse_root(root, text);
  unit.input_name = root == "-" ? "<stdin>" : root;
}

}  // namespace tmcl::detail
