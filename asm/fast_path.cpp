// The fast path: a well-formed program in one source file, assembled in two passes over its
// text without tokens, statements or expression trees. Pass 1 finds every label, constant and
// instruction; then the names are indexed; pass 2 evaluates the operands and encodes them.
// Constants are evaluated from their text on first use.
//
// It accepts only what it is sure the full assembler (lexer, parser, resolver, encoder) accepts
// without any diagnostic, and then gives the same result. Anything else -- a directive, .raw,
// -D, a block comment it cannot close, any error or warning, an unusually deep expression --
// makes it give up, and the full assembler, the reference, starts again from the same text.
// Giving up is always safe, so every doubtful case gives up. tests/asm/fast_path_test checks
// that both paths agree on every source in the repository and on thousands of mutations.
#include "fast_symbols.hpp"
#include "fast_text.hpp"
#include "internal.hpp"
#include "tmcl/fileio.hpp"

namespace tmcl::detail {
namespace {

// Deeper than any real program nests; beyond it the full assembler, with its own limits, decides.
constexpr int kMaxFastDepth = 64;

// Binary operators by their first character: C precedence (| ^ & << >> + - * / %), 0 for none.
constexpr auto kPrecedence = [] {
  std::array<std::uint8_t, 256> t{};
  t['|'] = 1;
  t['^'] = 2;
  t['&'] = 3;
  t['<'] = t['>'] = 4;
  t['+'] = t['-'] = 5;
  t['*'] = t['/'] = t['%'] = 6;
  return t;
}();

class FastAssembler {
 public:
  FastAssembler(const SourceFile& file, int index, const Profile& profile, AsmResult& out)
      : file_(file), text_(file.text), index_(index), profile_(profile), out_(out) {
    for (const auto& op : all_ops()) ops_[op.code] = &op;
  }

  // Room for `lines` statements: reserving touches no memory, and regrowing would touch twice.
  void reserve(std::size_t lines) {
    out_.program.reserve(lines + 1);
    out_.lines.reserve(lines + 1);
    operands_.reserve(lines);
    symbols_.all().reserve(lines / 2);
    huge(out_.program);
    huge(out_.lines);
    huge(operands_);
    huge(symbols_.all());
  }

  template <typename T>
  static void huge(const std::vector<T>& v) {
    prefer_huge_pages(v.data(), v.capacity() * sizeof(T));
  }

  bool pass1() {
    LineCount lines{1, text_.begin()};
    const char* p = text_.begin();
    while (p < text_.end()) {
      if (!statement_head(p, lines)) return false;
      if (p < text_.end()) {  // at the newline that ends the statement
        ++p;
        ++lines.line;
        lines.start = p;
      }
    }
    return true;
  }

  bool pass2() {
    if (!symbols_.index()) return false;  // a name defined twice
    Stmt probe;  // what the profile check reads: the opcode (its locations are never shown here)
    Diagnostics scratch;
    for (std::size_t i = 0; i < operands_.size(); ++i) {
      Instruction& ins = out_.program[i];
      const OpInfo* info = ops_[ins.op];
      if (!encode(*info, text_.begin() + operands_[i], ins)) return false;
      probe.op = info;
      check_against_profile(profile_, probe, ins, scratch);
      if (!scratch.all().empty()) return false;
    }
    return true;
  }

  bool finish(const AsmOptions& options) {
    int size = static_cast<int>(out_.program.size());
    if (options.append_stop && (out_.program.empty() || out_.program.back().op != static_cast<std::uint8_t>(Op::STOP))) {
      out_.appended_stop = true;
      out_.program.push_back(Instruction{static_cast<std::uint8_t>(Op::STOP), 0, 0, 0});
      out_.lines.push_back(LineInfo{-1, 0});
    }
    auto total = static_cast<std::int64_t>(out_.program.size());
    for (int i = 0; i < size; ++i) {
      const Instruction& ins = out_.program[static_cast<std::size_t>(i)];
      for (const auto& spec : ops_[ins.op]->operands)  // a jump outside the program is a warning
        if (spec.role == Role::Address && (ins.value < 0 || ins.value >= total)) return false;
    }
    if (profile_.program_memory > 0 && total > profile_.program_memory) return false;
    auto& symbols = symbols_.all();
    if (options.symbols) {
      out_.symbols.reserve(symbols.size());
      huge(out_.symbols);
    }
    for (std::size_t k = 0; k < symbols.size(); ++k) {
      std::int64_t v = 0;
      if (!symbol_value(static_cast<int>(k), 0, v)) return false;  // unused constants are checked too
      if (!options.symbols) continue;
      const FastSymbol& s = symbols[k];
      auto col = static_cast<int>(s.name - (text_.begin() + file_.line_starts[static_cast<std::size_t>(s.line - 1)])) + 1;
      out_.symbols.push_back(
          Symbol{std::string(s.name, s.len), s.kind, v, SourceLoc{index_, s.line, col, static_cast<int>(s.len)}, false});
    }
    out_.inputs.push_back(LinkedInput{file_.name, 0, size, ""});
    out_.profile = &profile_;
    return true;
  }

 private:
  // ---- pass 1: the labels of one statement, then a constant, an instruction or nothing ----
  bool statement_head(const char*& p, LineCount& lines) {
    for (;;) {
      if (!text_.skip_space(p, &lines)) return false;
      if (text_.at_end(p)) {
        p = text_.newline(p);
        return true;
      }
      const char* start = p;
      std::string_view name;
      if (!FastText::ident(p, name)) return false;  // a directive, .raw, a stray character
      int line = lines.line;
      if (!text_.skip_space(p, &lines)) return false;
      if (*p == ':') {
        if (!define(name, SymbolKind::Label, line, static_cast<std::int64_t>(operands_.size()), 0)) return false;
        ++p;
        continue;
      }
      if (*p == '=') {
        if (is_keyword(name)) return false;  // warned about by the full assembler
        if (!define(name, SymbolKind::Constant, line, 0, static_cast<std::uint32_t>(p + 1 - text_.begin()))) return false;
        return text_.skip_statement(p, &lines);
      }
      const OpInfo* op = op_by_mnemonic(name);
      if (!op) return false;
      out_.program.push_back(Instruction{op->code, 0, 0, 0});
      out_.lines.push_back(LineInfo{index_, line});
      operands_.push_back(static_cast<std::uint32_t>(start + name.size() - text_.begin()));
      return text_.skip_statement(p, &lines);
    }
  }

  bool define(std::string_view name, SymbolKind kind, int line, std::int64_t value, std::uint32_t expr) {
    return symbols_.record(FastSymbol{name.data(), value, static_cast<std::uint32_t>(name.size()), expr, line, kind,
                                      kind == SymbolKind::Label ? FastState::Done : FastState::Todo});
  }

  // The value of symbol k; a constant is evaluated from its text the first time.
  bool symbol_value(int k, int depth, std::int64_t& v) {
    FastSymbol& s = symbols_.all()[static_cast<std::size_t>(k)];
    if (s.state == FastState::Done) {
      v = s.value;
      return true;
    }
    if (s.state == FastState::Busy || depth > kMaxFastDepth) return false;  // a cycle, or very deep
    s.state = FastState::Busy;
    const char* p = text_.begin() + s.expr;
    if (!text_.skip_space(p) || text_.at_end(p) || !expr(p, 1, depth + 1, v) || !text_.skip_space(p) ||
        !text_.at_end(p))
      return false;
    FastSymbol& again = symbols_.all()[static_cast<std::size_t>(k)];
    again.value = v;
    again.state = FastState::Done;
    return true;
  }

  // ---- expressions, evaluated as they are read: 64-bit wrapping, as expr.cpp ----
  bool expr(const char*& p, int min_prec, int depth, std::int64_t& v) {
    if (!unary(p, depth, v)) return false;
    for (;;) {
      if (!text_.skip_space(p)) return false;
      const char op = *p;
      int prec = kPrecedence[static_cast<unsigned char>(op)];
      if (prec < min_prec || prec == 0) return true;
      if (op == '/' && p[1] == '/') return true;  // a comment
      if (prec == 4 && p[1] != op) return false;  // a lone '<' or '>'
      p += prec == 4 ? 2 : 1;
      std::int64_t rhs = 0;
      if (depth >= kMaxFastDepth || !expr(p, prec + 1, depth + 1, rhs) || !apply(op, v, rhs)) return false;
    }
  }

  static bool apply(char op, std::int64_t& a, std::int64_t b) {
    auto ua = static_cast<std::uint64_t>(a), ub = static_cast<std::uint64_t>(b);
    switch (op) {
      case '+': a = static_cast<std::int64_t>(ua + ub); return true;
      case '-': a = static_cast<std::int64_t>(ua - ub); return true;
      case '*': a = static_cast<std::int64_t>(ua * ub); return true;
      case '/':
      case '%':
        if (b == 0) return false;
        if (b == -1) a = op == '/' ? static_cast<std::int64_t>(0 - ua) : 0;
        else a = op == '/' ? a / b : a % b;
        return true;
      case '&': a = static_cast<std::int64_t>(ua & ub); return true;
      case '|': a = static_cast<std::int64_t>(ua | ub); return true;
      case '^': a = static_cast<std::int64_t>(ua ^ ub); return true;
      case '<':
      case '>':
        if (b < 0 || b > 63) return false;
        a = op == '<' ? static_cast<std::int64_t>(ua << ub) : (a >> b);
        return true;
      default: return false;
    }
  }

  bool number(const char*& p, std::size_t prefix, int base, std::int64_t& v) const {
    std::size_t at = static_cast<std::size_t>(p - text_.begin());
    DigitsRead r = read_digits(std::string_view(text_.begin(), static_cast<std::size_t>(text_.end() - text_.begin())),
                               at + prefix, base);
    const char* end = text_.begin() + r.end;
    if (r.status != DigitsRead::Ok || non_ascii(*end)) return false;
    p = end;
    v = r.value;
    return true;
  }

  bool unary(const char*& p, int depth, std::int64_t& v) {
    if (!text_.skip_space(p)) return false;
    const char c = *p;
    if (char_class(c) == kDigit) {
      // Most numbers are short decimals: read them here, the rest as the lexer does.
      if (c != '0' || char_class(p[1]) == kDigit || !ident_char(p[1])) {
        std::int64_t n = 0;
        const char* q = p;
        while (char_class(*q) == kDigit && q - p < 18) n = n * 10 + (*q++ - '0');
        if (!ident_char(*q) && !non_ascii(*q)) {
          p = q;
          v = n;
          return true;
        }
      }
      if (c == '0' && (p[1] == 'x' || p[1] == 'X')) return number(p, 2, 16, v);
      if (c == '0' && (p[1] == 'b' || p[1] == 'B')) return number(p, 2, 2, v);
      return number(p, 0, 10, v);
    }
    std::string_view name;
    if (FastText::ident(p, name)) {
      int k = symbols_.find(name);
      return k >= 0 && symbol_value(k, depth, v);
    }
    switch (c) {
      case '-':
      case '+':
      case '~': {
        ++p;
        if (depth >= kMaxFastDepth || !unary(p, depth + 1, v)) return false;
        auto u = static_cast<std::uint64_t>(v);
        if (c == '-') v = static_cast<std::int64_t>(0 - u);
        if (c == '~') v = static_cast<std::int64_t>(~u);
        return true;
      }
      case '(':
        ++p;
        if (depth >= kMaxFastDepth || !expr(p, 1, depth + 1, v) || !text_.skip_space(p) || *p != ')') return false;
        ++p;
        return true;
      case '$': return number(p, 1, 16, v);
      case '%': return (p[1] == '0' || p[1] == '1') && number(p, 1, 2, v);
      default: return false;
    }
  }

  // ---- pass 2: one instruction's operands, from just after its mnemonic ----
  bool encode(const OpInfo& op, const char* p, Instruction& ins) {
    for (std::size_t k = 0; k < op.operands.size(); ++k) {
      const OperandSpec& spec = op.operands[k];
      if (!text_.skip_space(p)) return false;
      if (k > 0) {
        if (*p != ',') return false;
        ++p;
        if (!text_.skip_space(p)) return false;
      }
      // After the mnemonic a '%' is the modulo operator to the full lexer, not a binary number.
      if (text_.at_end(p) || (k == 0 && *p == '%')) return false;
      std::int64_t v = 0;
      bool keyword = false;
      if (spec.keywords != KwSet::None && ident_start(*p)) {
        const char* q = p;
        std::string_view word;
        if (!FastText::ident(q, word)) return false;
        const char* after = q;
        if (!text_.skip_space(after)) return false;
        if (text_.at_end(after) || *after == ',') {  // a lone name: a keyword, else a known symbol
          if (auto kw = keyword_value(spec.keywords, word)) {
            v = *kw;
            keyword = true;
            p = q;
          } else if (symbols_.find(word) < 0) {
            return false;  // an unknown keyword
          }
        }
      }
      if (!keyword && !expr(p, 1, 0, v)) return false;
      FieldRange fr = range_of(spec.field);
      if (v < fr.min || v > fr.max) return false;
      if (!keyword && spec.keywords != KwSet::None && !keyword_name(spec.keywords, static_cast<std::uint8_t>(v)))
        return false;  // warned about by the full assembler
      put_field(ins, spec.field, v);
    }
    return text_.skip_space(p) && text_.at_end(p);
  }

  const SourceFile& file_;
  FastText text_;
  int index_;
  const Profile& profile_;
  AsmResult& out_;
  std::vector<std::uint32_t> operands_;  // per instruction: where its operands start
  FastSymbols symbols_;
  std::array<const OpInfo*, 256> ops_{};  // op_info(), without its lookup on every instruction
};

}  // namespace

bool fast_assemble(const std::string& path, const AsmOptions& options, std::string& text, AsmResult& out) {
  if (!options.defines.empty() || options.relocatable || text.size() > kMaxFileBytes) return false;
  SourceFile f;
  f.name = path == "-" ? "<stdin>" : path;
  f.path = path;
  f.text = std::move(text);
  bool bom = drop_bom(f.text);
  int idx = out.sources.add(std::move(f));
  const SourceFile& added = out.sources.files[static_cast<std::size_t>(idx)];
  const Profile& profile = options.profile ? *options.profile : generic_profile();
  bool done = false;
  if (!first_long_line(added)) {
    FastAssembler fa(added, idx, profile, out);
    fa.reserve(added.line_starts.size());
    done = fa.pass1() && fa.pass2() && fa.finish(options);
  }
  if (done) return true;
  text = std::move(out.sources.files[static_cast<std::size_t>(idx)].text);
  if (bom) text.insert(0, "\xEF\xBB\xBF");
  out = AsmResult{};
  return false;
}

}  // namespace tmcl::detail
