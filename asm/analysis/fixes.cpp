// The fixes the analysis attaches to its warnings (Diagnostic::fixes), which editors offer as
// code actions: "add RETI" where a handler falls through or ends, and "remove unreachable code".
// Both are whole lines in the canonical layout of the formatter, and both are left out whenever
// the source around them is not plain enough to edit safely (no sources, a run spanning files,
// a constant or directive or a comment spanning lines inside the run).
#include <string>

#include "analysis_internal.hpp"
#include "tmcl/asm/format.hpp"

namespace tmcl::detail {

namespace {

// Where the line after `line` starts, or the end of `line` when it is the last: the place to
// insert a new line after it, or the exclusive end of a run of lines ending with it.
SourceLoc after_line(const SourceFile& f, int file, int line, bool& at_end) {
  // After a final newline the next line exists for an editor (empty), so only a last line
  // without one ends at its end.
  at_end = static_cast<std::size_t>(line) >= f.line_starts.size() && (f.text.empty() || f.text.back() != '\n');
  if (!at_end) return SourceLoc{file, line + 1, 1, 0};
  return SourceLoc{file, line, static_cast<int>(f.line(line).size()) + 1, 0};
}

}  // namespace

void Walker::fix_add_reti(Diagnostic& d, int after) const {
  SourceLoc at = loc(after);
  if (!in.sources || at.file < 0 || at.line < 1) return;
  const SourceFile& f = in.sources->files[static_cast<std::size_t>(at.file)];
  bool at_end = false;
  SourceLoc where = after_line(f, at.file, at.line, at_end);
  std::string line = std::string(static_cast<std::size_t>(kFormatIndent), ' ') + "RETI";
  d.fixes.push_back({"add RETI", where, where, at_end ? "\n" + line : line + "\n"});
}

void Walker::fix_remove(Diagnostic& d, int first, int last) const {
  SourceLoc from = loc(first), to = loc(last);
  if (!in.sources || from.file < 0 || from.file != to.file || from.line < 1 || to.line < from.line) return;
  const SourceFile& f = in.sources->files[static_cast<std::size_t>(from.file)];
  // The instructions' lines and the mnemonic's column on each.
  std::vector<int> mnemonic_col(static_cast<std::size_t>(to.line - from.line + 1), 0);
  for (int i = first; i <= last; ++i) {
    SourceLoc l = loc(i);
    if (l.file != from.file || l.line < from.line || l.line > to.line || l.col < 1) return;
    mnemonic_col[static_cast<std::size_t>(l.line - from.line)] = l.col;
  }
  // Labels stay (something may still name them), one per line as the formatter puts them;
  // comments and blank lines in the run go; any other line (a constant, a directive) or a comment
  // not closed on its line: no fix.
  std::string kept;
  for (int line = from.line; line <= to.line; ++line) {
    std::string_view text = f.line(line);
    int col = mnemonic_col[static_cast<std::size_t>(line - from.line)];
    std::size_t code_end = col > 0 ? static_cast<std::size_t>(col - 1) : text.size();
    Diagnostics lexical;
    std::vector<SourceToken> toks = tokenize(text, &lexical);
    if (lexical.has_errors()) return;
    std::vector<const SourceToken*> words;  // before the instruction: label names and their ':'
    for (const SourceToken& t : toks)
      if (t.offset < code_end && t.kind != SourceToken::Kind::Comment && t.kind != SourceToken::Kind::Newline) words.push_back(&t);
    if (words.size() % 2) return;
    for (std::size_t k = 0; k < words.size(); k += 2) {
      if (words[k]->kind != SourceToken::Kind::Name || words[k + 1]->text != ":") return;
      kept += std::string(words[k]->text) + ":\n";
    }
  }
  bool at_end = false;
  SourceLoc stop = after_line(f, from.file, to.line, at_end);
  if (at_end && !kept.empty()) kept.pop_back();
  d.fixes.push_back({"remove unreachable code", SourceLoc{from.file, from.line, 1, 0}, stop, kept});
}

}  // namespace tmcl::detail
