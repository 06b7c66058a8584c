// Inlay hints (the name of a parameter after its bare number: "SAP 4: Maximum positioning speed,
// 0, 1000") and prepareRename (what a rename at a place would rename, or why nothing can be). The
// names come from the target's profile, the only place they are written down; which operand a
// number is comes from the instruction table through context.hpp.
#include "context.hpp"
#include "tmcl/lsp/server.hpp"

namespace tmcl::lsp {

namespace {

constexpr int kHintParameter = 2;  // InlayHintKind.Parameter

// The name the profile gives the value of this operand: a parameter or an interrupt vector.
std::string_view name_in_profile(const Profile& prof, const Context& c, Role role, std::int64_t v) {
  if (v < 0 || v > 0xFFFF) return {};
  int n = static_cast<int>(v);
  const ParamInfo* p = role == Role::AxisParam ? prof.axis_param(n) : role == Role::GlobalParam ? prof.global_param(bank_of(c), n) : nullptr;
  if (p) return p->name;
  if (role == Role::Interrupt)
    if (const InterruptVector* iv = prof.vector(n)) return iv->name;
  return {};
}

}  // namespace

// The byte range of params.range; InvalidParams when it is missing or outside the document.
bool Server::range_param(const Document& doc, const Value& params, std::size_t& begin, std::size_t& end, Reply& err) const {
  const Value& range = params["range"];
  if (!range.is_object()) {
    err = {Value(), kInvalidParams, "missing params.range"};
    return false;
  }
  Value start = Value::object(), stop = Value::object();  // position() reads params.position
  start.set("position", range["start"]);
  stop.set("position", range["end"]);
  if (!position(doc, start, begin, err) || !position(doc, stop, end, err)) return false;
  if (end < begin) {
    err = {Value(), kInvalidParams, "params.range ends before it starts"};
    return false;
  }
  return true;
}

Server::Reply Server::inlay_hints(const Value& params) {
  Reply err;
  Document* doc = find_document(params, err);
  std::size_t begin, end;
  if (!doc || is_test_file(*doc) || !range_param(*doc, params, begin, end, err)) return err;
  const Profile& prof = profile(*doc);
  const std::vector<SourceToken>& toks = doc->tokens;
  Reply r;
  r.result = Value::array();
  for (std::size_t i = 0; i < toks.size(); ++i) {
    const SourceToken& t = toks[i];
    if (t.kind != Kind::Number || t.offset < begin || t.offset >= end) continue;
    Context c = context_at(toks, i);
    const OperandSpec* spec = c.spec();
    if (!spec || c.operands_first[static_cast<std::size_t>(c.operand)] != &t) continue;
    // Bare: the number is the whole operand (a comment may follow it).
    std::size_t k = i + 1;
    while (k < toks.size() && toks[k].kind == Kind::Comment) ++k;
    if (k < toks.size() && toks[k].kind != Kind::Newline && toks[k].text != ",") continue;
    std::string_view name = name_in_profile(prof, c, spec->role, t.number);
    if (name.empty()) continue;
    Value& hint = r.result.push(Value::object());
    hint.set("position", range_of(*doc, t.offset + t.text.size(), 0)["start"]);
    hint.set("label", ": " + std::string(name));
    hint.set("kind", kHintParameter);
  }
  return r;
}

// Only labels and constants can be renamed; anything else gets RequestFailed saying what it is.
Server::Reply Server::prepare_rename(const Value& params) {
  Target at = target(params, true);
  if (!at) return at.error;
  Document* doc = at.doc;
  const SourceToken* t = at.token;
  auto refuse = [](std::string what) {
    return Reply{Value(), kRequestFailed, what + ": only labels and constants can be renamed"};
  };
  if (!t || t->kind == Kind::Punct) return refuse("nothing to rename here");
  std::string text(t->text);
  switch (t->kind) {
    case Kind::Number: return refuse("'" + text + "' is a number");
    case Kind::Comment: return refuse("this is a comment");
    case Kind::Directive: return refuse("'" + text + "' is a directive");
    case Kind::IncludeName: return refuse("'" + text + "' is an include file name");
    case Kind::Name: break;
    default: return refuse("nothing to rename here");
  }
  Context c = context_at(doc->tokens, static_cast<std::size_t>(t - doc->tokens.data()));
  const OperandSpec* spec = c.spec();
  if (c.mnemonic == t) return refuse("'" + text + "' is an instruction mnemonic");
  if (spec && spec->role == Role::Keyword && keyword_value(spec->keywords, text))
    return refuse("'" + text + "' is a keyword of " + std::string(c.op->mnemonic));
  if (!symbol(*doc, text)) return refuse("'" + text + "' is not a defined label or constant");
  Reply r;
  r.result = Value::object();
  r.result.set("range", range_of(*doc, t->offset, t->text.size()));
  r.result.set("placeholder", text);
  return r;
}

}  // namespace tmcl::lsp
