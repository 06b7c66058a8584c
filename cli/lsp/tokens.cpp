// Semantic tokens (textDocument/semanticTokens/full and /range): every token of the assembler's
// lexer (tokenize) that means something, classified by the statement it is in (context.hpp) and by
// the document's last assembly (which names are labels and which constants). Nothing is lexed
// here; block comments are split into one token per line, as clients without multi-line token
// support need, and columns are UTF-16 units like every position of the protocol.
#include <unordered_map>

#include "context.hpp"
#include "tmcl/lsp/server.hpp"

namespace tmcl::lsp {

namespace {

// Token types, numbered by their place in the legend.
enum Type : int { kMnemonic, kTypeKeyword, kLabel, kConstant, kNumber, kComment, kDirective, kIncludeName };
constexpr const char* kTypeNames[] = {"keyword", "enumMember", "function", "variable", "number", "comment", "macro", "string"};
// Modifier bits, likewise.
constexpr int kDeclaration = 1;
constexpr int kReadonly = 2;
constexpr const char* kModifierNames[] = {"declaration", "readonly"};

bool is_punct(const SourceToken* t, std::string_view p) { return t && t->kind == Kind::Punct && t->text == p; }

// The next token of the same line that is not a comment, or nullptr.
const SourceToken* next_code(const std::vector<SourceToken>& toks, std::size_t i) {
  for (++i; i < toks.size() && toks[i].kind != Kind::Newline; ++i)
    if (toks[i].kind != Kind::Comment) return &toks[i];
  return nullptr;
}

}  // namespace

json::Value semantic_token_legend() {
  json::Value legend = json::Value::object();
  json::Value& types = legend.set("tokenTypes", json::Value::array());
  for (const char* t : kTypeNames) types.push(t);
  json::Value& mods = legend.set("tokenModifiers", json::Value::array());
  for (const char* m : kModifierNames) mods.push(m);
  return legend;
}

Server::Reply Server::semantic_tokens(const Value& params, bool in_range) {
  Reply err;
  Document* doc = find_document(params, err);
  std::size_t begin = 0, end = doc ? doc->text.size() : 0;
  if (!doc || is_test_file(*doc) || (in_range && !range_param(*doc, params, begin, end, err))) return err;
  std::unordered_map<std::string, SymbolKind> kinds;  // by lower-case name: names are case-insensitive
  if (doc->result)
    for (const Symbol& s : doc->result->symbols) kinds.emplace(lower(s.name), s.kind);

  Value data = Value::array();
  std::size_t prev_line = 0, prev_char = 0;
  // One token of one line, from byte `offset` of the document, `bytes` long.
  auto emit = [&](std::size_t line, std::size_t offset, std::size_t bytes, int type, int mods) {
    if (bytes == 0 || offset + bytes <= begin || offset >= end) return;
    std::string_view text = std::string_view(doc->text).substr(doc->line_starts[line]);
    std::size_t start = utf16_column(text, offset - doc->line_starts[line]);
    std::size_t length = utf16_column(text, offset + bytes - doc->line_starts[line]) - start;
    data.push(static_cast<long long>(line - prev_line));
    data.push(static_cast<long long>(line == prev_line ? start - prev_char : start));
    data.push(static_cast<long long>(length));
    data.push(type);
    data.push(mods);
    prev_line = line;
    prev_char = start;
  };
  const std::vector<SourceToken>& toks = doc->tokens;
  for (std::size_t i = 0; i < toks.size(); ++i) {
    const SourceToken& t = toks[i];
    auto line = static_cast<std::size_t>(t.line - 1);
    switch (t.kind) {
      case Kind::Number: emit(line, t.offset, t.text.size(), kNumber, 0); break;
      case Kind::Directive: emit(line, t.offset, t.text.size(), kDirective, 0); break;
      case Kind::IncludeName: emit(line, t.offset, t.text.size(), kIncludeName, 0); break;
      case Kind::Comment: {
        std::size_t from = t.offset, stop = t.offset + t.text.size();
        for (std::size_t l = line; from < stop; ++l) {
          std::size_t nl = doc->text.find('\n', from);
          std::size_t piece_end = nl == std::string::npos || nl > stop ? stop : nl;
          std::size_t trimmed = piece_end > from && doc->text[piece_end - 1] == '\r' ? piece_end - 1 : piece_end;
          emit(l, from, trimmed - from, kComment, 0);
          from = piece_end + 1;
        }
        break;
      }
      case Kind::Name: {
        const SourceToken* next = next_code(toks, i);
        Context c = context_at(toks, i);
        const OperandSpec* spec = c.spec();
        if (c.mnemonic == &t) {
          emit(line, t.offset, t.text.size(), kMnemonic, 0);
        } else if (spec && spec->role == Role::Keyword && keyword_value(spec->keywords, t.text)) {
          emit(line, t.offset, t.text.size(), kTypeKeyword, 0);  // a keyword wins over a name
        } else if (is_punct(next, ":") && c.operand < 0) {
          emit(line, t.offset, t.text.size(), kLabel, kDeclaration);
        } else if (is_punct(next, "=") && !c.op) {
          emit(line, t.offset, t.text.size(), kConstant, kDeclaration | kReadonly);
        } else if (t.text.front() == '.') {
          emit(line, t.offset, t.text.size(), kDirective, 0);  // .raw
        } else if (auto k = kinds.find(lower(t.text)); k != kinds.end()) {
          if (k->second == SymbolKind::Label) emit(line, t.offset, t.text.size(), kLabel, 0);
          else emit(line, t.offset, t.text.size(), kConstant, kReadonly);
        }
        break;
      }
      default: break;
    }
  }
  Reply r;
  r.result = Value::object();
  r.result.set("data", std::move(data));
  return r;
}

}  // namespace tmcl::lsp
