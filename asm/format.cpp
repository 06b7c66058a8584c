// The source formatter and the token view of a source (format.hpp). Both drive the assembler's
// Lexer, asking it to hand over comments as well; the formatter only re-spaces and re-lines the
// tokens it gets back, never changes one, which is why the assembled bytes cannot change.
#include "tmcl/asm/format.hpp"

#include <algorithm>

#include "internal.hpp"

namespace tmcl {

namespace {

using Kind = SourceToken::Kind;
using detail::P;

SourceToken::Kind kind_of(detail::Tok t) {
  switch (t) {
    case detail::Tok::Ident: return Kind::Name;
    case detail::Tok::Number: return Kind::Number;
    case detail::Tok::Punct: return Kind::Punct;
    case detail::Tok::Directive: return Kind::Directive;
    case detail::Tok::IncludeName: return Kind::IncludeName;
    case detail::Tok::Newline: return Kind::Newline;
    default: return Kind::Bad;
  }
}

bool is_punct(const SourceToken& t, char c) { return t.kind == Kind::Punct && t.text.size() == 1 && t.text[0] == c; }

// Comments lose trailing blanks (and the CR of a CR LF line); nothing else about them changes.
std::string_view trim_right(std::string_view s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// Joins the tokens of a statement or operand: binary operators and '=' spaced, unary operators
// and parentheses tight, ", " between operands.
// `tight` leaves out the optional blanks, for lines that would grow past the assembler's limit.
std::string join(const std::vector<SourceToken>& toks, std::size_t from, std::size_t to, bool tight_ops = false) {
  std::string out;
  const SourceToken* prev = nullptr;
  bool prev_unary = false;
  for (std::size_t i = from; i < to; ++i) {
    const SourceToken& t = toks[i];
    bool op = t.kind == Kind::Punct && !is_punct(t, '(') && !is_punct(t, ')') && !is_punct(t, ',');
    bool unary = op && (is_punct(t, '-') || is_punct(t, '+') || is_punct(t, '~')) &&
                 (prev == nullptr || (prev->kind == Kind::Punct && !is_punct(*prev, ')')) ||
                  prev->kind == Kind::Directive);
    if (prev) {
      bool tight = is_punct(t, ',') || is_punct(t, ')') || is_punct(*prev, '(') || prev_unary ||
                   (tight_ops && (op || (prev->kind == Kind::Punct && !is_punct(*prev, ',') && !is_punct(*prev, ')'))) &&
                    t.kind != Kind::Comment && prev->kind != Kind::Comment);
      if (!tight) out += ' ';
    }
    out += t.kind == Kind::Comment ? trim_right(t.text) : t.text;
    prev = &t;
    prev_unary = unary;
  }
  return out;
}

struct Row {
  enum Type { Blank, Code, CommentOnly } type = Blank;
  int indent = 0;
  std::string code;
  std::string comment;
};

// Display width of the last line of s (a block comment may span lines).
std::size_t last_line_width(const std::string& s) {
  std::size_t nl = s.rfind('\n');
  return nl == std::string::npos ? s.size() : s.size() - nl - 1;
}

void format_line(const std::vector<SourceToken>& line, std::vector<Row>& rows) {
  if (line.empty()) {
    rows.push_back(Row{});
    return;
  }
  std::size_t i = 0;
  // Labels, each alone at column 0.
  while (i + 1 < line.size() && line[i].kind == Kind::Name && line[i].text.front() != '.' && is_punct(line[i + 1], ':')) {
    Row r;
    r.type = Row::Code;
    r.code = std::string(line[i].text) + ":";
    rows.push_back(std::move(r));
    i += 2;
  }
  // Trailing comments: those after the last code token.
  std::size_t end = line.size();
  while (end > i && line[end - 1].kind == Kind::Comment) --end;
  std::string comment;
  for (std::size_t k = end; k < line.size(); ++k) {
    if (!comment.empty()) comment += ' ';
    comment += trim_right(line[k].text);
  }
  if (end == i) {
    if (comment.empty()) return;
    if (i > 0) {  // "Label: // comment"
      rows.back().comment = comment;
      return;
    }
    Row r;
    r.type = Row::CommentOnly;
    r.indent = line[0].col > 1 ? kFormatIndent : 0;
    r.code = comment;
    rows.push_back(std::move(r));
    return;
  }
  Row r;
  r.type = Row::Code;
  r.comment = std::move(comment);
  const SourceToken& first = line[i];
  bool constant = i + 1 < end && first.kind == Kind::Name && is_punct(line[i + 1], '=');
  if (first.kind == Kind::Directive || constant || first.kind != Kind::Name) {
    r.code = join(line, i, end);
  } else {
    // An instruction: the mnemonic (upper case when it is one), then the operands.
    r.indent = kFormatIndent;
    r.code = op_by_mnemonic(first.text) ? detail::upper(first.text) : std::string(first.text);
    std::size_t k = i + 1;
    while (k < end && line[k].kind == Kind::Comment) {  // a block comment right after the mnemonic
      r.code += ' ';
      r.code += line[k].text;
      ++k;
    }
    if (k < end) {
      std::string ops = join(line, k, end);
      if (ops.size() + r.code.size() + 3 >= detail::kMaxLineBytes) ops = join(line, k, end, true);
      r.code += ' ' + ops;
    }
  }
  if (r.code.size() + 3 >= detail::kMaxLineBytes) r.code = join(line, i, end, true);
  rows.push_back(std::move(r));
}

}  // namespace

std::vector<SourceToken> tokenize(std::string_view text, Diagnostics* diags) {
  Diagnostics scratch;
  SourceFile file;
  file.name = "<source>";
  file.text = std::string(text);
  std::vector<detail::Token> comments;
  detail::Lexer lexer(file, 0, diags ? *diags : scratch);
  lexer.keep_comments(&comments);
  std::vector<SourceToken> out;
  auto add = [&](const detail::Token& t, Kind k) {
    std::size_t off = static_cast<std::size_t>(t.text.data() - file.text.data());
    out.push_back(SourceToken{k, text.substr(off, t.text.size()), off, t.line, t.col, t.number});
  };
  std::size_t c = 0;
  for (;;) {
    detail::Token t = lexer.next_token();
    if (t.kind == detail::Tok::End) break;
    // Comments are recorded as the lexer passes them, so all before this token are known now.
    std::size_t off = static_cast<std::size_t>(t.text.data() - file.text.data());
    for (; c < comments.size() && static_cast<std::size_t>(comments[c].text.data() - file.text.data()) < off + (t.text.empty() ? 1 : 0); ++c)
      add(comments[c], Kind::Comment);
    add(t, kind_of(t.kind));
  }
  for (; c < comments.size(); ++c) add(comments[c], Kind::Comment);
  std::stable_sort(out.begin(), out.end(), [](const SourceToken& a, const SourceToken& b) { return a.offset < b.offset; });
  return out;
}

FormatResult format_source(std::string_view text) {
  FormatResult res;
  // A UTF-8 byte order mark stays where it is; the assembler skips it as well.
  if (text.substr(0, 3) == "\xEF\xBB\xBF") {
    res = format_source(text.substr(3));
    if (res.ok) res.text.insert(0, "\xEF\xBB\xBF");
    return res;
  }
  Diagnostics diags;
  std::vector<SourceToken> toks = tokenize(text, &diags);
  if (diags.has_errors()) {
    const Diagnostic& d = diags.all().front();
    res.error = std::to_string(d.loc.line) + ":" + std::to_string(d.loc.col) + ": error: " + d.message;
    return res;
  }
  std::vector<Row> rows;
  std::vector<SourceToken> line;
  for (const SourceToken& t : toks) {
    if (t.kind == Kind::Newline) {
      format_line(line, rows);
      line.clear();
    } else {
      line.push_back(t);
    }
  }
  if (!line.empty()) format_line(line, rows);

  // Blank lines: none at the start or end, runs of them as one.
  std::vector<Row> kept;
  for (Row& r : rows) {
    if (r.type == Row::Blank && (kept.empty() || kept.back().type == Row::Blank)) continue;
    kept.push_back(std::move(r));
  }
  while (!kept.empty() && kept.back().type == Row::Blank) kept.pop_back();

  // Trailing comments line up within each group of lines between blank lines.
  for (std::size_t g = 0; g < kept.size();) {
    std::size_t e = g;
    std::size_t column = 0;
    while (e < kept.size() && kept[e].type != Row::Blank) {
      if (kept[e].type == Row::Code && !kept[e].comment.empty())
        column = std::max(column, static_cast<std::size_t>(kept[e].indent) + last_line_width(kept[e].code) + 2);
      ++e;
    }
    for (std::size_t k = g; k < e; ++k) {
      Row& r = kept[k];
      std::string s(static_cast<std::size_t>(r.indent), ' ');
      s += r.code;
      if (r.type == Row::Code && !r.comment.empty()) {
        std::size_t w = static_cast<std::size_t>(r.indent) + last_line_width(r.code);
        s.append(column > w ? column - w : 1, ' ');
        s += r.comment;
      }
      res.text += s;
      res.text += '\n';
    }
    if (e < kept.size()) res.text += '\n';
    g = e + 1;
  }
  for (std::size_t p = 0, n = 1; p < res.text.size(); ++n) {
    std::size_t nl = res.text.find('\n', p);
    if (nl - p >= detail::kMaxLineBytes) {
      res.error = std::to_string(n) + ":1: error: the line would be longer than the assembler's limit of " +
                  std::to_string(detail::kMaxLineBytes) + " bytes";
      res.text.clear();
      return res;
    }
    p = nl + 1;
  }
  res.ok = true;
  return res;
}

}  // namespace tmcl
