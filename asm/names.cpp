// named_operands and source_names (names.hpp): a line is read again with the lexer's character
// classes, just far enough to find the mnemonic and split the operands at their commas (an
// operand expression has no comma of its own).
#include "tmcl/asm/names.hpp"

#include "chars.hpp"
#include "tmcl/asm/assembler.hpp"
#include "tmcl/isa.hpp"

namespace tmcl {
namespace {

using detail::char_class;
using detail::ident_char;
using detail::ident_start;
using detail::kSpace;

std::string_view trim(std::string_view s) {
  while (!s.empty() && char_class(s.front()) == kSpace) s.remove_prefix(1);
  while (!s.empty() && char_class(s.back()) == kSpace) s.remove_suffix(1);
  return s;
}

bool same_word(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if ((a[i] | 0x20) != (b[i] | 0x20)) return false;
  return true;
}

// Blanks and whole /* ... */ comments from `at` on.
std::size_t skip_blanks(std::string_view s, std::size_t at) {
  for (;;) {
    while (at < s.size() && char_class(s[at]) == kSpace) ++at;
    if (s.substr(at, 2) != "/*") return at;
    const std::size_t close = s.find("*/", at + 2);
    if (close == std::string_view::npos) return s.size();
    at = close + 2;
  }
}

// Whether an operand's text has a name in it: an identifier that does not belong to a number
// literal (0x1F, 0b101, $1F and %101 have letters or digits after a prefix, never a name).
bool has_name(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    if (ident_start(text[i])) return true;
    if (char_class(text[i]) == detail::kDigit || text[i] == '$') {
      ++i;
      while (i < text.size() && ident_char(text[i])) ++i;
      continue;
    }
    ++i;
  }
  return false;
}

// Where the mnemonic starts in `line`, after labels; npos when there is none.
std::size_t mnemonic_at(std::string_view line, std::string_view mnemonic) {
  std::size_t at = skip_blanks(line, 0);
  for (;;) {
    std::size_t end = at;
    while (end < line.size() && ident_char(line[end])) ++end;
    if (end == at || !ident_start(line[at])) return std::string_view::npos;
    const std::size_t after = skip_blanks(line, end);
    if (after < line.size() && line[after] == ':') {  // a label
      at = skip_blanks(line, after + 1);
      continue;
    }
    return same_word(line.substr(at, end - at), mnemonic) ? at : std::string_view::npos;
  }
}

}  // namespace

std::array<std::string, 3> named_operands(std::string_view line, const Instruction& ins) {
  std::array<std::string, 3> out;
  const OpInfo* info = op_info(ins.op);
  if (!info || info->control || info->operands.empty()) return out;
  std::size_t at = mnemonic_at(line, info->mnemonic);
  if (at == std::string_view::npos) {  // the line may start inside a comment that ends on it
    const std::size_t close = line.find("*/");
    if (close == std::string_view::npos) return out;
    line.remove_prefix(close + 2);
    at = mnemonic_at(line, info->mnemonic);
    if (at == std::string_view::npos) return out;
  }
  at += info->mnemonic.size();
  std::string_view rest = line.substr(at);
  for (std::string_view end : {"//", ";", "/*"})
    if (const std::size_t c = rest.find(end); c != std::string_view::npos) rest = rest.substr(0, c);
  for (std::size_t k = 0; k < info->operands.size() && !rest.empty(); ++k) {
    const std::size_t comma = rest.find(',');
    const std::string_view text = trim(rest.substr(0, comma));
    rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 1);
    const OperandSpec& spec = info->operands[k];
    if (!has_name(text) || (spec.keywords != KwSet::None && keyword_value(spec.keywords, text))) continue;
    out[static_cast<std::size_t>(spec.field)] = std::string(text);
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
