// The language server's code actions (textDocument/codeAction): the quick fixes the assembler
// and the analysis attach to their diagnostics (Diagnostic::fixes): the did-you-mean
// replacements, "add RETI" and "remove unreachable code". Nothing is worked out here: a fix is
// offered as its diagnostic carries it, for the diagnostics the request's range touches or its
// context lists, as a WorkspaceEdit on the file the fix is in (an included file too).
#include <algorithm>
#include <utility>

#include "tmcl/lsp/server.hpp"

namespace tmcl::lsp {

namespace {

using Value = json::Value;

std::pair<std::int64_t, std::int64_t> point(const Value& p) { return {p["line"].as_int(), p["character"].as_int()}; }

bool is_range(const Value& r) {
  for (const char* end : {"start", "end"})
    if (!r[end]["line"].is_int() || !r[end]["character"].is_int()) return false;
  return true;
}

// Closed ranges, so that a cursor (an empty range) at either end of a diagnostic touches it.
bool touches(const Value& a, const Value& b) {
  return !(point(a["end"]) < point(b["start"]) || point(b["end"]) < point(a["start"]));
}

// A diagnostic the client sends back in context.diagnostics is ours when it starts on the same
// line with the same message (the client may have moved its column with an edit since).
bool listed(const Value& context, std::int64_t line, const std::string& message) {
  for (const Value& theirs : context["diagnostics"].items())
    if (theirs["range"]["start"]["line"].as_int(-1) == line && theirs["message"].is_string() && theirs["message"].as_string() == message)
      return true;
  return false;
}

// A 1-based line and byte column of a source file as an LSP position.
Value position_in(const SourceFile& f, const SourceLoc& at) {
  Value p = Value::object();
  p.set("line", std::max(0, at.line - 1));
  p.set("character", static_cast<long long>(utf16_column(f.line(at.line), static_cast<std::size_t>(std::max(0, at.col - 1)))));
  return p;
}

// context.only asks for some kinds: ours is "quickfix", which "quickfix" and "" (every kind) cover.
bool quickfix_wanted(const Value& context) {
  const Value& only = context["only"];
  if (!only.is_array()) return true;
  for (const Value& k : only.items())
    if (k.is_string() && (k.as_string() == "quickfix" || k.as_string().empty())) return true;
  return false;
}

}  // namespace

Server::Reply Server::code_actions(const Value& params) {
  Target at = target(params, false);
  if (!at) return at.error;
  const Value& range = params["range"];
  if (!is_range(range)) return {Value(), kInvalidParams, "missing params.range (start and end line/character)"};
  Reply r;
  r.result = Value::array();
  const Value& context = params["context"];
  if (!at.doc->result || !quickfix_wanted(context)) return r;
  const AsmResult& res = *at.doc->result;
  // Only the diagnostics with fixes become JSON, and only when selected: a file full of errors
  // answers as fast as a clean one.
  for (const Diagnostic* d : res.diags.sorted(res.sources)) {
    if (d->fixes.empty()) continue;
    SourceLoc shown = shown_at(*d, res);
    std::int64_t line = shown.line - 1;
    bool wanted = line >= range["start"]["line"].as_int() && line <= range["end"]["line"].as_int() &&
                  touches(location_of(shown, res)["range"], range);
    if (!wanted && !listed(context, line, d->message)) continue;
    Value item = diagnostic_json(*d, res);
    for (const Fix& fix : d->fixes) {
      if (fix.begin.file < 0 || fix.begin.file != fix.end.file ||
          static_cast<std::size_t>(fix.begin.file) >= res.sources.files.size())
        continue;
      const SourceFile& f = res.sources.files[static_cast<std::size_t>(fix.begin.file)];
      Value edit = Value::object();
      Value& where = edit.set("range", Value::object());
      where.set("start", position_in(f, fix.begin));
      where.set("end", position_in(f, fix.end));
      edit.set("newText", fix.text);
      Value& action = r.result.push(Value::object());
      action.set("title", fix.title);
      action.set("kind", "quickfix");
      action.set("diagnostics", Value::array()).push(item);
      if (d->fixes.size() == 1) action.set("isPreferred", true);
      action.set("edit", Value::object()).set("changes", Value::object()).set(path_to_uri(f.path), Value::array()).push(std::move(edit));
    }
  }
  return r;
}

}  // namespace tmcl::lsp
