// The language server's requests about a place in a document: hover (instruction syntax and
// meaning from the instruction table, parameter facts from the target's profile, constant values,
// label addresses, include targets), definition, references, completion, document symbols and
// formatting. Tokens come from the assembler's lexer (tokenize), facts from its last assembly.
#include <algorithm>

#include "context.hpp"
#include "tmcl/lsp/server.hpp"

namespace tmcl::lsp {

namespace {

std::string access_text(std::uint8_t a) {
  const std::string s = access_letters(a);
  return s.empty() ? "-" : s;
}

std::string param_text(const ParamInfo& p) {
  std::string unit = p.unit.empty() ? "" : " " + std::string(p.unit);
  return std::to_string(p.number) + ": " + std::string(p.name) + ", " + std::to_string(p.min) + "…" +
         std::to_string(p.max) + unit + ", " + access_text(p.access) + ", default " + std::to_string(p.default_value) + unit;
}

std::string operand_name(const OperandSpec& o) {
  if (o.role == Role::Keyword) return std::string(kwset_name(o.keywords));
  return std::string(role_name(o.role));
}

std::string syntax_of(const OpInfo& op) {
  std::string s(op.mnemonic);
  for (std::size_t i = 0; i < op.operands.size(); ++i) s += (i ? ", <" : " <") + operand_name(op.operands[i]) + ">";
  return s;
}

json::Value markdown(std::string text) {
  json::Value h = json::Value::object();
  json::Value& c = h.set("contents", json::Value::object());
  c.set("kind", "markdown");
  c.set("value", std::move(text));
  return h;
}

}  // namespace

const Symbol* Server::symbol(const Document& doc, std::string_view name) const {
  if (!doc.result) return nullptr;
  for (const Symbol& s : doc.result->symbols)
    if (same_name(s.name, name)) return &s;
  return nullptr;
}

bool Server::position(const Document& doc, const Value& params, std::size_t& offset, Reply& err) const {
  const Value& pos = params["position"];
  if (!pos["line"].is_int() || !pos["character"].is_int() || pos["line"].as_int() < 0 || pos["character"].as_int() < 0) {
    err = {Value(), kInvalidParams, "missing or negative params.position.line/character"};
    return false;
  }
  auto line = static_cast<std::size_t>(pos["line"].as_int());
  if (line >= doc.line_starts.size()) {
    err = {Value(), kInvalidParams,
           "position line " + std::to_string(line) + " is outside the document (" + std::to_string(doc.line_starts.size()) + " lines)"};
    return false;
  }
  offset = offset_of(doc.text, doc.line_starts, line, static_cast<std::size_t>(pos["character"].as_int()));
  return true;
}

Server::Target Server::target(const Value& params, bool with_position) {
  Target at;
  Document* doc = find_document(params, at.error);
  if (!doc || is_test_file(*doc)) return at;  // a test file has no TMCL to ask about: a null answer
  if (with_position) {
    if (!position(*doc, params, at.offset, at.error)) return at;
    at.token = token_at(*doc, at.offset);
  }
  at.doc = doc;
  return at;
}

// The token under (or just before) the cursor.
const SourceToken* Server::token_at(const Document& doc, std::size_t offset) const {
  auto it = std::upper_bound(doc.tokens.begin(), doc.tokens.end(), offset,
                             [](std::size_t o, const SourceToken& t) { return o < t.offset; });
  if (it == doc.tokens.begin()) return nullptr;
  const SourceToken& t = *(it - 1);
  if (t.kind == Kind::Newline || offset > t.offset + t.text.size()) return nullptr;
  return &t;
}

Server::Value Server::range_of(const Document& doc, std::size_t offset, std::size_t len) const {
  auto line_of = [&](std::size_t o) {
    return static_cast<std::size_t>(std::upper_bound(doc.line_starts.begin(), doc.line_starts.end(), o) - doc.line_starts.begin()) - 1;
  };
  auto pos = [&](std::size_t o) {
    std::size_t l = line_of(o);
    Value p = Value::object();
    p.set("line", static_cast<long long>(l));
    p.set("character", static_cast<long long>(utf16_column(std::string_view(doc.text).substr(doc.line_starts[l]), o - doc.line_starts[l])));
    return p;
  };
  Value r = Value::object();
  r.set("start", pos(offset));
  r.set("end", pos(offset + len));
  return r;
}

Server::Reply Server::hover(const Value& params) {
  Target at = target(params, true);
  if (!at) return at.error;
  Document* doc = at.doc;
  const SourceToken* t = at.token;
  Reply r;
  if (!t) return r;
  std::size_t index = static_cast<std::size_t>(t - doc->tokens.data());
  Context c = context_at(doc->tokens, index);
  const Profile& prof = profile(*doc);
  std::string text;
  if (c.mnemonic == t) {
    text = "```tmcl\n" + syntax_of(*c.op) + "\n```\n" + std::string(c.op->meaning) + " (opcode " + std::to_string(c.op->code) + ")";
  } else if (t->kind == Kind::Directive && lower(t->text) == "#include" && index + 1 < doc->tokens.size()) {
    t = &doc->tokens[index + 1];
  }
  if (t->kind == Kind::IncludeName && doc->result) {
    int line = t->line;
    for (const SourceFile& f : doc->result->sources.files)
      if (f.includer == 0 && f.include_line == line) text = "includes `" + f.path + "`";
    if (text.empty()) text = "include file not found";
  }
  // A parameter number (or a constant standing for one) in an operand that names a parameter.
  std::optional<std::int64_t> value;
  const Symbol* sym = nullptr;
  if (t->kind == Kind::Number) {
    value = t->number;  // as the lexer read it, in any base
  } else if (t->kind == Kind::Name && c.mnemonic != t) {
    sym = symbol(*doc, t->text);
    if (sym) {
      value = sym->value;
      text = sym->kind == SymbolKind::Label ? "label `" + sym->name + "`: address " + std::to_string(sym->value)
                                            : "constant `" + sym->name + "` = " + std::to_string(sym->value);
    } else if (c.op && c.operand >= 0 && static_cast<std::size_t>(c.operand) < c.op->operands.size() &&
               c.op->operands[static_cast<std::size_t>(c.operand)].role == Role::Keyword) {
      auto kv = keyword_value(c.op->operands[static_cast<std::size_t>(c.operand)].keywords, t->text);
      if (kv) text = "keyword `" + std::string(t->text) + "` = " + std::to_string(*kv);
    }
  }
  if (value && c.op && c.operand >= 0 && static_cast<std::size_t>(c.operand) < c.op->operands.size()) {
    Role role = c.op->operands[static_cast<std::size_t>(c.operand)].role;
    const ParamInfo* p = nullptr;
    // A number the profile has no entry for: the target does not have it, except generic, which
    // accepts every number (as the assembler does) but has no name or range for it.
    auto unknown = [&](const std::string& what) {
      text += (text.empty() ? "" : "\n\n") + what + ": " +
              (prof.any_parameter ? "no name or range known; " + std::string(prof.name) +
                                        " accepts every parameter number (the target setting picks a module's table)"
                                  : "not a parameter of " + std::string(prof.name));
    };
    if (role == Role::AxisParam) {
      p = prof.axis_param(static_cast<int>(*value));
      if (!p) unknown("axis parameter " + std::to_string(*value));
    } else if (role == Role::GlobalParam) {
      int bank = bank_of(c);
      p = prof.global_param(bank, static_cast<int>(*value));
      if (!p) unknown("global parameter " + std::to_string(*value) + " of bank " + std::to_string(bank));
    }
    if (p) text += (text.empty() ? "" : "\n\n") + param_text(*p) + " (" + std::string(prof.name) + ")";
    // The profile's not-simulated= reason, the same words tmclrun's note gives at run time.
    if (p && !p->not_simulated.empty()) text += "\n\nnot simulated by tmclrun: " + std::string(p->not_simulated);
  }
  if (text.empty()) return r;
  r.result = markdown(text);
  r.result.set("range", range_of(*doc, t->offset, t->text.size()));
  return r;
}

Server::Reply Server::definition(const Value& params) {
  Target at = target(params, true);
  if (!at) return at.error;
  Reply r;
  const SourceToken* t = at.token;
  if (!t || t->kind != Kind::Name) return r;
  const Symbol* s = symbol(*at.doc, t->text);
  if (!s || s->defined_at.file < 0) return r;
  r.result = location_of(s->defined_at, *at.doc->result);
  return r;
}

Server::Reply Server::references(const Value& params) {
  Target at = target(params, true);
  if (!at) return at.error;
  Document* doc = at.doc;
  Reply r;
  const SourceToken* t = at.token;
  if (!t || t->kind != Kind::Name) return r;
  std::string name(t->text);
  bool with_decl = params["context"]["includeDeclaration"].as_bool(true);
  const Symbol* s = symbol(*doc, name);
  r.result = Value::array();
  // Every file of the unit: a name used in an include is the same symbol.
  const AsmResult& res = *doc->result;
  for (std::size_t f = 0; f < res.sources.files.size(); ++f) {
    const SourceFile& file = res.sources.files[f];
    auto toks = tokenize(file.text);
    for (std::size_t k = 0; k < toks.size(); ++k) {
      if (toks[k].kind != Kind::Name || !same_name(toks[k].text, name)) continue;
      bool is_decl = s && static_cast<int>(f) == s->defined_at.file && toks[k].line == s->defined_at.line && toks[k].col == s->defined_at.col;
      if (is_decl && !with_decl) continue;
      r.result.push(location_of(SourceLoc{static_cast<int>(f), toks[k].line, toks[k].col, static_cast<int>(toks[k].text.size())}, res));
    }
  }
  return r;
}

Server::Reply Server::completion(const Value& params) {
  Target at = target(params, true);
  if (!at) return at.error;
  Document* doc = at.doc;
  std::size_t offset = at.offset;
  Reply r;
  r.result = Value::array();
  auto item = [&](std::string label, int kind, std::string detail) {
    Value& i = r.result.push(Value::object());
    i.set("label", std::move(label));
    i.set("kind", kind);
    if (!detail.empty()) i.set("detail", std::move(detail));
  };
  // The token before the cursor decides: the first word of a line is a mnemonic; after it, the
  // operand's role decides what fits.
  auto it = std::lower_bound(doc->tokens.begin(), doc->tokens.end(), offset,
                             [](const SourceToken& t, std::size_t o) { return t.offset + t.text.size() < o; });
  bool in_token = it != doc->tokens.end() && it->offset < offset && it->kind != Kind::Newline;
  // Cursor after the last token of a line (or in blank space): the context is that of a new token.
  Context c;
  if (!doc->tokens.empty()) {
    std::size_t line_begin = doc->line_starts[static_cast<std::size_t>(std::upper_bound(doc->line_starts.begin(), doc->line_starts.end(), offset) - doc->line_starts.begin()) - 1];
    std::vector<SourceToken> line;
    for (const SourceToken& t : doc->tokens)
      if (t.offset >= line_begin && t.offset < offset && t.kind != Kind::Newline) line.push_back(t);
    if (!in_token) line.push_back(SourceToken{Kind::Name, std::string_view(), offset, 0, 0});
    line.push_back(SourceToken{Kind::Newline, std::string_view(), offset, 0, 0});
    c = context_at(line, line.size() - 2);
    if (!line.empty() && line.front().kind == Kind::Directive && lower(line.front().text) == "#include") {
      complete_include(*doc, r.result);
      return r;
    }
  }
  const Profile& prof = profile(*doc);
  if (!c.op || c.operand < 0) {
    for (const OpInfo& op : all_ops())
      if (!op.mnemonic.empty() && !op.control) item(std::string(op.mnemonic), 14, std::string(op.meaning));
    return r;
  }
  const auto& ops = c.op->operands;
  Role role = static_cast<std::size_t>(c.operand) < ops.size() ? ops[static_cast<std::size_t>(c.operand)].role : Role::Data;
  if (role == Role::Keyword) {
    for (const Keyword& k : all_keywords())
      if (k.set == ops[static_cast<std::size_t>(c.operand)].keywords) item(std::string(k.name), 14, std::to_string(k.value));
  } else if (role == Role::AxisParam) {
    for (const ParamInfo& p : prof.axis_params) item(std::to_string(p.number), 12, param_text(p));
  } else if (role == Role::GlobalParam) {
    for (const ParamInfo& p : prof.bank0) item(std::to_string(p.number), 12, param_text(p) + " (bank 0)");
  }
  if (doc->result)
    for (const Symbol& s : doc->result->symbols) {
      if (role == Role::Address && s.kind != SymbolKind::Label) continue;
      item(s.name, s.kind == SymbolKind::Label ? 18 : 21,
           (s.kind == SymbolKind::Label ? "label, address " : "constant = ") + std::to_string(s.value));
    }
  return r;
}

Server::Reply Server::document_symbols(const Value& params) {
  Target at = target(params, false);
  if (!at) return at.error;
  Document* doc = at.doc;
  Reply r;
  r.result = Value::array();
  if (!doc->result) return r;
  for (const Symbol& s : doc->result->symbols) {
    if (s.defined_at.file != 0) continue;  // this file's own symbols
    Value& o = r.result.push(Value::object());
    o.set("name", s.name);
    o.set("kind", s.kind == SymbolKind::Label ? 12 : 14);  // Function, Constant
    o.set("detail", (s.kind == SymbolKind::Label ? "address " : "= ") + std::to_string(s.value));
    Value loc = location_of(s.defined_at, *doc->result);
    o.set("range", loc["range"]);
    o.set("selectionRange", loc["range"]);
  }
  return r;
}

Server::Reply Server::formatting(const Value& params) {
  Target at = target(params, false);
  if (!at) return at.error;
  Document* doc = at.doc;
  FormatResult f = format_source(doc->text);
  if (!f.ok) return {Value(), kRequestFailed, "cannot format: " + f.error};
  Reply r;
  r.result = Value::array();
  if (f.text == doc->text) return r;
  Value& edit = r.result.push(Value::object());
  edit.set("range", range_of(*doc, 0, doc->text.size()));
  edit.set("newText", f.text);
  return r;
}

// Rename of a label or constant: every use in the file and the files it includes, as one
// WorkspaceEdit. The new name must be a valid name that is not a mnemonic or keyword.
Server::Reply Server::rename(const Value& params) {
  Target at = target(params, true);
  if (!at) return at.error;
  Document* doc = at.doc;
  const SourceToken* t = at.token;
  if (!t || t->kind != Kind::Name || !symbol(*doc, t->text))
    return {Value(), kInvalidParams, "no label or constant at this position to rename"};
  std::string to = params["newName"].as_string();
  if (!is_valid_name(to) || op_by_mnemonic(to) || is_keyword(to))
    return {Value(), kInvalidParams, "'" + to + "' is not a valid label or constant name"};
  if (symbol(*doc, to) && !same_name(to, t->text)) return {Value(), kInvalidParams, "'" + to + "' is already defined"};  // "loop" -> "Loop" respells
  Value refs_params = params;
  refs_params.set("context", Value::object()).set("includeDeclaration", true);
  Reply refs = references(refs_params);
  Reply r;
  r.result = Value::object();
  Value& changes = r.result.set("changes", Value::object());
  for (const Value& loc : refs.result.items()) {
    Value* list = changes.find(loc["uri"].as_string());
    if (!list) list = &changes.set(loc["uri"].as_string(), Value::array());
    Value& edit = list->push(Value::object());
    edit.set("range", loc["range"]);
    edit.set("newText", to);
  }
  return r;
}

// Workspace symbols: the labels and constants of every open document whose name contains the
// query (case-insensitive).
Server::Reply Server::workspace_symbols(const Value& params) {
  Reply r;
  r.result = Value::array();
  std::string q = lower(params["query"].as_string());
  for (const auto& [uri, doc] : docs_) {
    if (!doc.result) continue;
    for (const Symbol& s : doc.result->symbols) {
      if (s.defined_at.file != 0 || lower(s.name).find(q) == std::string::npos) continue;
      Value& o = r.result.push(Value::object());
      o.set("name", s.name);
      o.set("kind", s.kind == SymbolKind::Label ? 12 : 14);
      o.set("location", location_of(s.defined_at, *doc.result));
    }
  }
  return r;
}

// Signature help: the instruction's syntax from the table, its operands as parameters, and the
// operand the cursor is in as the active one.
Server::Reply Server::signature_help(const Value& params) {
  Target at = target(params, true);
  if (!at) return at.error;
  Document* doc = at.doc;
  std::size_t offset = at.offset;
  Reply r;
  std::size_t line_begin = doc->line_starts[static_cast<std::size_t>(
      std::upper_bound(doc->line_starts.begin(), doc->line_starts.end(), offset) - doc->line_starts.begin()) - 1];
  std::vector<SourceToken> line;
  for (const SourceToken& t : doc->tokens)
    if (t.offset >= line_begin && t.offset < offset && t.kind != Kind::Newline) line.push_back(t);
  line.push_back(SourceToken{Kind::Name, std::string_view(), offset, 0, 0});
  line.push_back(SourceToken{Kind::Newline, std::string_view(), offset, 0, 0});
  Context c = context_at(line, line.size() - 2);
  if (!c.op || c.operand < 0 || c.op->operands.empty()) return r;
  std::string label(c.op->mnemonic);
  Value sig = Value::object();
  Value ps = Value::array();
  for (std::size_t i = 0; i < c.op->operands.size(); ++i) {
    label += i ? ", " : " ";
    std::string name = "<" + operand_name(c.op->operands[i]) + ">";
    Value& p = ps.push(Value::object());
    Value& range = p.set("label", Value::array());
    range.push(static_cast<long long>(label.size()));
    label += name;
    range.push(static_cast<long long>(label.size()));
  }
  sig.set("label", label);
  sig.set("documentation", std::string(c.op->meaning));
  sig.set("parameters", std::move(ps));
  r.result = Value::object();
  r.result.set("signatures", Value::array()).push(std::move(sig));
  r.result.set("activeSignature", 0);
  r.result.set("activeParameter", std::min<int>(c.operand, static_cast<int>(c.op->operands.size()) - 1));
  return r;
}

// Folding: each label's block (up to the line before the next label, without trailing blank
// lines) and every comment spanning several lines.
Server::Reply Server::folding_ranges(const Value& params) {
  Target at = target(params, false);
  if (!at) return at.error;
  Document* doc = at.doc;
  Reply r;
  r.result = Value::array();
  auto add = [&](int first, int last, const char* kind) {
    if (last <= first) return;
    Value& f = r.result.push(Value::object());
    f.set("startLine", first);
    f.set("endLine", last);
    if (kind) f.set("kind", kind);
  };
  std::vector<int> labels;
  const auto& toks = doc->tokens;
  for (std::size_t i = 0; i < toks.size(); ++i) {
    if (toks[i].kind == Kind::Comment) {
      int lines = static_cast<int>(std::count(toks[i].text.begin(), toks[i].text.end(), '\n'));
      add(toks[i].line - 1, toks[i].line - 1 + lines, "comment");
    }
    bool line_start = i == 0 || toks[i - 1].kind == Kind::Newline;
    if (line_start && toks[i].kind == Kind::Name && i + 1 < toks.size() && toks[i + 1].kind == Kind::Punct && toks[i + 1].text == ":")
      labels.push_back(toks[i].line - 1);
  }
  auto blank = [&](int line) {
    std::size_t b = doc->line_starts[static_cast<std::size_t>(line)];
    std::size_t e = static_cast<std::size_t>(line) + 1 < doc->line_starts.size() ? doc->line_starts[static_cast<std::size_t>(line) + 1] : doc->text.size();
    return doc->text.find_first_not_of(" \t\r\n", b) >= e;
  };
  for (std::size_t k = 0; k < labels.size(); ++k) {
    int last = k + 1 < labels.size() ? labels[k + 1] - 1 : static_cast<int>(doc->line_starts.size()) - 1;
    while (last > labels[k] && blank(last)) --last;
    add(labels[k], last, nullptr);
  }
  return r;
}

}  // namespace tmcl::lsp
