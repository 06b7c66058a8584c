// named_operands and source_names (names.hpp): a line is read again with the assembler's own
// lexer (tokenize, format.hpp), just far enough to find the mnemonic and split the operands at
// their commas (an operand expression has no comma of its own); comments are its tokens too.
#include "tmcl/asm/names.hpp"

#include <vector>

#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/format.hpp"
#include "tmcl/isa.hpp"

namespace tmcl {
namespace {

using TokKind = SourceToken::Kind;

bool same_word(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if ((a[i] | 0x20) != (b[i] | 0x20)) return false;
  return true;
}

bool is_mark(const SourceToken& t, char c) { return t.kind == TokKind::Punct && t.text.size() == 1 && t.text[0] == c; }

// The tokens of the line, comments included, up to its end (the first Newline).
std::vector<SourceToken> line_tokens(std::string_view line) {
  std::vector<SourceToken> out;
  for (const SourceToken& t : tokenize(line)) {
    if (t.kind == TokKind::Newline) break;
    out.push_back(t);
  }
  return out;
}

// Where the mnemonic is in `toks`, after labels and comments; npos when it is not there.
std::size_t mnemonic_at(const std::vector<SourceToken>& toks, std::string_view mnemonic) {
  std::size_t i = 0;
  for (;;) {
    while (i < toks.size() && toks[i].kind == TokKind::Comment) ++i;
    if (i == toks.size() || toks[i].kind != TokKind::Name) return std::string_view::npos;
    std::size_t next = i + 1;
    while (next < toks.size() && toks[next].kind == TokKind::Comment) ++next;
    if (next < toks.size() && is_mark(toks[next], ':')) {  // a label
      i = next + 1;
      continue;
    }
    return same_word(toks[i].text, mnemonic) ? i : std::string_view::npos;
  }
}

// An operand's tokens [from, to) as written, but a comment among them as one blank.
std::string operand_text(std::string_view line, const std::vector<SourceToken>& toks, std::size_t from, std::size_t to) {
  std::string text;
  std::size_t prev_end = std::string_view::npos;
  bool comment_between = false;
  for (std::size_t k = from; k < to; ++k) {
    const SourceToken& t = toks[k];
    if (t.kind == TokKind::Comment) {
      comment_between = true;
      continue;
    }
    if (prev_end != std::string_view::npos) text += comment_between ? std::string_view(" ") : line.substr(prev_end, t.offset - prev_end);
    text += t.text;
    prev_end = t.offset + t.text.size();
    comment_between = false;
  }
  return text;
}

}  // namespace

std::array<std::string, 3> named_operands(std::string_view line, const Instruction& ins) {
  std::array<std::string, 3> out;
  const OpInfo* info = op_info(ins.op);
  if (!info || info->control || info->operands.empty()) return out;
  std::vector<SourceToken> toks = line_tokens(line);
  std::size_t at = mnemonic_at(toks, info->mnemonic);
  if (at == std::string_view::npos) {  // the line may start inside a comment that ends on it
    const std::size_t close = line.find("*/");
    if (close == std::string_view::npos) return out;
    line.remove_prefix(close + 2);
    toks = line_tokens(line);
    at = mnemonic_at(toks, info->mnemonic);
    if (at == std::string_view::npos) return out;
  }
  std::size_t from = at + 1;
  for (std::size_t k = 0; k < info->operands.size() && from < toks.size(); ++k) {
    std::size_t to = from;
    bool named = false;  // a name, not a number literal (0x1F, $1F, %101 are Numbers)
    for (; to < toks.size() && !is_mark(toks[to], ','); ++to) named = named || toks[to].kind == TokKind::Name;
    const std::string text = operand_text(line, toks, from, to);
    from = to + 1;
    const OperandSpec& spec = info->operands[k];
    if (!named || (spec.keywords != KwSet::None && keyword_value(spec.keywords, text))) continue;
    out[static_cast<std::size_t>(spec.field)] = text;
  }
  return out;
}

SourceNames source_names(const AsmResult& result) {
  SourceNames names;
  for (const auto& s : result.symbols)
    if (s.kind == SymbolKind::Label) names.labels.emplace(s.value, s.name);
  names.operands.resize(result.program.size());
  for (std::size_t a = 0; a < result.program.size() && a < result.lines.size(); ++a) {
    const LineInfo& li = result.lines[a];
    if (li.file < 0 || static_cast<std::size_t>(li.file) >= result.sources.files.size()) continue;
    names.operands[a] = named_operands(result.sources.files[static_cast<std::size_t>(li.file)].line(li.line), result.program[a]);
  }
  return names;
}

}  // namespace tmcl
