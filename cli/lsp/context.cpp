// How the language server reads a statement from the assembler's tokens (context.hpp): the
// instruction a token belongs to, its operand, the statement's bank, and name comparison.
#include "context.hpp"

namespace tmcl::lsp {

Context context_at(const std::vector<SourceToken>& toks, std::size_t index) {
  Context c;
  std::size_t b = index;
  while (b > 0 && toks[b - 1].kind != Kind::Newline) --b;
  std::size_t i = b;
  // Skip labels.
  while (i + 1 < toks.size() && toks[i].kind == Kind::Name && toks[i + 1].kind == Kind::Punct && toks[i + 1].text == ":") i += 2;
  while (i < toks.size() && toks[i].kind == Kind::Comment) ++i;
  if (i >= toks.size() || toks[i].kind != Kind::Name) return c;
  if (i + 1 < toks.size() && toks[i + 1].kind == Kind::Punct && toks[i + 1].text == "=") return c;  // "Stop = 3" defines a constant
  c.op = op_by_mnemonic(toks[i].text);
  if (!c.op) return c;
  c.mnemonic = &toks[i];
  // The whole line is read, also past the token, so that a later operand (the bank of SGP) is known.
  int operand = 0;
  bool fresh = true;
  std::size_t k = i + 1;
  for (; k < toks.size() && toks[k].kind != Kind::Newline; ++k) {
    if (toks[k].kind == Kind::Comment) continue;
    if (toks[k].kind == Kind::Punct && toks[k].text == ",") {
      ++operand;
      fresh = true;
      continue;
    }
    if (fresh) {
      c.operands_first.resize(static_cast<std::size_t>(operand) + 1, nullptr);
      c.operands_first[static_cast<std::size_t>(operand)] = &toks[k];
      fresh = false;
    }
    if (k == index) c.operand = operand;
  }
  if (index > i && (index >= k || c.operand < 0)) c.operand = operand;  // past the last token
  return c;
}

int bank_of(const Context& c) {
  for (std::size_t k = 0; k < c.op->operands.size() && k < c.operands_first.size(); ++k)
    if (c.op->operands[k].role == Role::Bank && c.operands_first[k] && c.operands_first[k]->kind == Kind::Number)
      return static_cast<int>(c.operands_first[k]->number);
  return 0;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (auto& ch : out)
    if (ch >= 'A' && ch <= 'Z') ch = static_cast<char>(ch - 'A' + 'a');
  return out;
}

bool same_name(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i] >= 'A' && a[i] <= 'Z' ? static_cast<char>(a[i] - 'A' + 'a') : a[i];
    char y = b[i] >= 'A' && b[i] <= 'Z' ? static_cast<char>(b[i] - 'A' + 'a') : b[i];
    if (x != y) return false;
  }
  return true;
}

}  // namespace tmcl::lsp
