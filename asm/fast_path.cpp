// The fast path: a well-formed program in one source file, assembled in two passes over its
// text without tokens, statements or expression trees. Pass 1 finds every label, constant and
// instruction; then the names are indexed; pass 2 evaluates the operands and encodes them.
// Constants are evaluated from their text on first use.
//
// It takes one source with its #includes and -D definitions, and accepts only what it is sure
// the full assembler (lexer, parser, resolver, encoder) accepts without any diagnostic, and then
// gives the same result. Anything else -- another directive, .raw, a block comment it cannot
// close, any error or warning, an unusually deep expression -- makes it give up, and the full
// assembler, the reference, starts again from the same text.
// Giving up is always safe, so every doubtful case gives up. tests/asm/fast_path_test checks
// that both paths agree on every source in the repository and on thousands of mutations.
#include <algorithm>
#include <deque>

#include "fast_symbols.hpp"
#include "fast_text.hpp"
#include "finish.hpp"
#include "internal.hpp"
#include "syntax.hpp"
#include "tmcl/fileio.hpp"
#include "tmcl/os_files.hpp"
#include "tmcl/program_image.hpp"
#include "tmcl/targets.hpp"

namespace tmcl::detail {
namespace {

// Deeper than any real program nests; beyond it the full assembler, with its own limits, decides.
constexpr int kMaxFastDepth = 64;

// The binary operator each character starts and its precedence (0: none), from the one
// definition the parser uses (syntax.hpp), as tables for the hot loop.
constexpr auto kOperator = [] {
  std::array<P, 256> t{};
  for (int c = 0; c < 256; ++c) t[static_cast<std::size_t>(c)] = binary_operator_of(static_cast<char>(c));
  return t;
}();
constexpr auto kPrecedence = [] {
  std::array<std::uint8_t, 256> t{};
  for (int c = 0; c < 256; ++c) t[static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(binary_precedence(kOperator[static_cast<std::size_t>(c)]));
  return t;
}();

class FastAssembler {
 public:
  FastAssembler(const AsmOptions& options, FileReader& reader, const Profile& profile, AsmResult& out)
      : options_(options), reader_(reader), profile_(profile), out_(out) {
    for (const auto& op : all_ops()) ops_[op.code] = &op;
  }

  // A source file added to the result: false when the fast path cannot take it.
  bool add_text(int index) {
    if (index > 0xFFFF) return false;  // FastSymbol::file
    texts_.resize(static_cast<std::size_t>(index) + 1, FastText(std::string_view()));
    texts_[static_cast<std::size_t>(index)] = FastText(out_.sources.files[static_cast<std::size_t>(index)].text);
    return true;
  }

  // -D NAME=VALUE, already added as source `index`: a constant whose value is that text.
  bool define_command_line(const std::string& name, int index) {
    return is_valid_name(name) && add_text(index) &&
           define(name, SymbolKind::Constant, 0, index, 0, 0);
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

  // Pass 1 over the root file and, where they are included, the files it includes.
  bool pass1(int root) {
    std::string key = include_key(out_.sources.files[static_cast<std::size_t>(root)].path);
    included_.push_back(key);
    return add_text(root) && scan_file(root, 0, key);
  }

  bool scan_file(int file, int depth, const std::string& key) {
    stack_.push_back(key);
    const FastText& t = texts_[static_cast<std::size_t>(file)];
    LineCount lines{1, t.begin()};
    const char* p = t.begin();
    while (p < t.end()) {
      if (!statement_head(file, depth, p, lines)) return false;
      if (p < t.end()) {  // at the newline that ends the statement
        ++p;
        ++lines.line;
        lines.start = p;
      }
    }
    stack_.pop_back();
    return true;
  }

  bool pass2() {
    if (!symbols_.index()) return false;  // a name defined twice
    Stmt probe;  // what the profile check reads: the opcode (its locations are never shown here)
    Diagnostics scratch;
    for (std::size_t i = 0; i < operands_.size(); ++i) {
      Instruction& ins = out_.program[i];
      const OpInfo* info = ops_[ins.op];
      const FastText& t = texts_[static_cast<std::size_t>(out_.lines[i].file)];
      bool negative = false;
      if (!encode(t, *info, t.begin() + operands_[i], ins, negative)) return false;
      probe.op = info;
      check_against_profile(profile_, probe, ins, scratch, negative);
      if (!scratch.all().empty()) return false;
    }
    return true;
  }

  bool finish(int root) {
    int size = static_cast<int>(out_.program.size());
    if (size == 0) return false;  // an empty program gets the full pipeline's warning
    // finish.hpp, as the full pipeline finishes; what it would report makes the fast path give up
    if (options_.append_stop) out_.appended_stop = append_stop(out_.program, out_.lines);
    std::size_t total = out_.program.size();
    for (int i = 0; i < size; ++i) {
      const Instruction& ins = out_.program[static_cast<std::size_t>(i)];
      for (const auto& spec : ops_[ins.op]->operands)  // a jump outside the program is a warning
        if (spec.role == Role::Address && outside_program(ins.value, total)) return false;
    }
    if (exceeds_memory(profile_, total)) return false;
    for (const auto& r : symbols_.redefinitions()) {  // harmless only with the same value
      std::int64_t first = 0, again = 0;
      if (!symbol_value(static_cast<int>(r.first), 0, first) || !symbol_value(static_cast<int>(r.again), 0, again) ||
          first != again)
        return false;
    }
    const auto& redefined = symbols_.redefinitions();
    auto next_redefined = redefined.begin();
    auto& symbols = symbols_.all();
    if (options_.symbols) {
      out_.symbols.reserve(symbols.size());
      huge(out_.symbols);
    }
    for (std::size_t k = 0; k < symbols.size(); ++k) {
      std::int64_t v = 0;
      if (!symbol_value(static_cast<int>(k), 0, v)) return false;  // unused constants are checked too
      if (next_redefined != redefined.end() && next_redefined->again == k) {
        ++next_redefined;  // not a symbol of its own
        continue;
      }
      const FastSymbol& s = symbols[k];
      if (!options_.symbols || s.line == 0) continue;  // -D definitions are not the program's
      const SourceFile& f = out_.sources.files[s.file];
      auto col = static_cast<int>(s.name - (f.text.data() + f.line_starts[static_cast<std::size_t>(s.line - 1)])) + 1;
      out_.symbols.push_back(
          Symbol{std::string(s.name, s.len), s.kind, v, SourceLoc{s.file, s.line, col, static_cast<int>(s.len)}, false});
    }
    out_.inputs.push_back(LinkedInput{out_.sources.files[static_cast<std::size_t>(root)].name, 0, size, ""});
    out_.profile = &profile_;
    return true;
  }

 private:
  // ---- pass 1: the labels of one statement, then a constant, an instruction, an #include or
  // nothing; leaves p at the statement's newline ----
  bool statement_head(int file, int depth, const char*& p, LineCount& lines) {
    const FastText& t = texts_[static_cast<std::size_t>(file)];
    for (;;) {
      if (!t.skip_space(p, &lines)) return false;
      if (t.at_end(p)) {
        p = t.newline(p);
        return true;
      }
      if (*p == '#') return include(file, depth, p, lines);
      const char* start = p;
      std::string_view name;
      if (!FastText::ident(p, name)) return false;  // .raw, a stray character
      int line = lines.line;
      if (!t.skip_space(p, &lines)) return false;
      if (*p == ':') {
        if (!define(name, SymbolKind::Label, line, file, static_cast<std::int64_t>(operands_.size()), 0)) return false;
        ++p;
        continue;
      }
      if (*p == '=') {
        if (is_keyword(name)) return false;  // warned about by the full assembler
        if (!define(name, SymbolKind::Constant, line, file, 0, static_cast<std::uint32_t>(p + 1 - t.begin())))
          return false;
        return t.skip_statement(p, &lines);
      }
      const OpInfo* op = op_by_mnemonic(name);
      if (!op) return false;
      out_.program.push_back(Instruction{op->code, 0, 0, 0});
      out_.lines.push_back(LineInfo{file, line});
      operands_.push_back(static_cast<std::uint32_t>(start + name.size() - t.begin()));
      return t.skip_statement(p, &lines);
    }
  }

  // #include NAME, "NAME" or <NAME>, read as the lexer and parser read it; the file is scanned
  // where it is included, once. Every other directive is left to the full assembler.
  bool include(int file, int depth, const char*& p, LineCount& lines) {
    const FastText& t = texts_[static_cast<std::size_t>(file)];
    const char* word = p++;
    while (ident_char(*p)) ++p;
    if (upper(std::string_view(word, static_cast<std::size_t>(p - word))) != "#INCLUDE") return false;
    std::string_view text(t.begin(), static_cast<std::size_t>(t.end() - t.begin()));
    IncludeNameSpan span = scan_include_name(text, static_cast<std::size_t>(p - t.begin()));  // as the lexer reads it
    if (span.unclosed) return false;
    std::string name(include_file_name(text.substr(span.begin, span.end - span.begin)));
    p = t.begin() + span.next;
    int line = lines.line;
    if (name.empty() || depth + 1 > kMaxIncludeDepth || !t.skip_space(p, &lines) || !t.at_end(p)) return false;
    p = t.newline(p);
    FoundInclude inc;
    if (!find_include(name, out_.sources.files[static_cast<std::size_t>(file)].path, options_, reader_, inc))
      return false;
    if (std::find(stack_.begin(), stack_.end(), inc.key) != stack_.end()) return false;  // a cycle
    if (std::find(included_.begin(), included_.end(), inc.key) != included_.end()) return true;  // once only
    included_.push_back(inc.key);
    if (inc.text.size() > kMaxFileBytes) return false;
    SourceFile f;
    f.name = inc.path.rfind("<bundled>/", 0) == 0 ? inc.path : os::normal_path(inc.path);
    f.path = inc.path;
    f.text = std::move(inc.text);
    f.includer = file;
    f.include_line = line;
    drop_bom(f.text);
    int index = out_.sources.add(std::move(f));
    const SourceFile& added = out_.sources.files[static_cast<std::size_t>(index)];
    return !first_long_line(added) && out_.diags.allow_from_comments(added, index) && add_text(index) &&
           scan_file(index, depth + 1, inc.key);
  }

  bool define(std::string_view name, SymbolKind kind, int line, int file, std::int64_t value, std::uint32_t expr) {
    return symbols_.record(FastSymbol{name.data(), value, static_cast<std::uint32_t>(name.size()), expr, line,
                                      static_cast<std::uint16_t>(file), kind,
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
    const FastText& t = texts_[s.file];
    const char* p = t.begin() + s.expr;
    if (!t.skip_space(p) || t.at_end(p) || !expr(t, p, 1, depth + 1, v) || !t.skip_space(p) || !t.at_end(p))
      return false;
    FastSymbol& again = symbols_.all()[static_cast<std::size_t>(k)];
    again.value = v;
    again.state = FastState::Done;
    return true;
  }

  // ---- expressions, evaluated as they are read: 64-bit wrapping, as expr.cpp ----
  bool expr(const FastText& t, const char*& p, int min_prec, int depth, std::int64_t& v) {
    if (!unary(t, p, depth, v)) return false;
    for (;;) {
      if (!t.skip_space(p)) return false;
      const char op = *p;
      int prec = kPrecedence[static_cast<unsigned char>(op)];
      if (prec < min_prec || prec == 0) return true;
      if (op == '/' && p[1] == '/') return true;  // a comment
      if (prec == 4 && p[1] != op) return false;  // a lone '<' or '>'
      p += prec == 4 ? 2 : 1;
      std::int64_t rhs = 0;
      if (depth >= kMaxFastDepth || !expr(t, p, prec + 1, depth + 1, rhs)) return false;
      if (apply_binary(kOperator[static_cast<unsigned char>(op)], v, rhs, v) != OpFault::None) return false;
    }
  }

  static bool number(const FastText& t, const char*& p, std::size_t prefix, int base, std::int64_t& v) {
    auto at = static_cast<std::size_t>(p - t.begin());
    DigitsRead r = read_digits(std::string_view(t.begin(), static_cast<std::size_t>(t.end() - t.begin())), at + prefix, base);
    const char* end = t.begin() + r.end;
    if (r.status != DigitsRead::Ok || non_ascii(*end)) return false;
    p = end;
    v = r.value;
    return true;
  }

  bool unary(const FastText& t, const char*& p, int depth, std::int64_t& v) {
    if (!t.skip_space(p)) return false;
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
      if (c == '0' && (p[1] == 'x' || p[1] == 'X')) return number(t, p, 2, 16, v);
      if (c == '0' && (p[1] == 'b' || p[1] == 'B')) return number(t, p, 2, 2, v);
      return number(t, p, 0, 10, v);
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
        if (depth >= kMaxFastDepth || !unary(t, p, depth + 1, v)) return false;
        auto u = static_cast<std::uint64_t>(v);
        if (c == '-') v = static_cast<std::int64_t>(0 - u);
        if (c == '~') v = static_cast<std::int64_t>(~u);
        return true;
      }
      case '(':
        ++p;
        if (depth >= kMaxFastDepth || !expr(t, p, 1, depth + 1, v) || !t.skip_space(p) || *p != ')') return false;
        ++p;
        return true;
      case '$': return number(t, p, 1, 16, v);
      case '%': return (p[1] == '0' || p[1] == '1') && number(t, p, 1, 2, v);
      default: return false;
    }
  }

  // ---- pass 2: one instruction's operands, from just after its mnemonic ----
  // `negative`: whether the value operand is a negative number (the profile check's concern).
  bool encode(const FastText& t, const OpInfo& op, const char* p, Instruction& ins, bool& negative) {
    for (std::size_t k = 0; k < op.operands.size(); ++k) {
      const OperandSpec& spec = op.operands[k];
      if (!t.skip_space(p)) return false;
      if (k > 0) {
        if (*p != ',') return false;
        ++p;
        if (!t.skip_space(p)) return false;
      }
      // After the mnemonic a '%' is the modulo operator to the full lexer, not a binary number.
      if (t.at_end(p) || (k == 0 && *p == '%')) return false;
      std::int64_t v = 0;
      bool keyword = false;
      if (spec.keywords != KwSet::None && ident_start(*p)) {
        const char* q = p;
        std::string_view word;
        if (!FastText::ident(q, word)) return false;
        const char* after = q;
        if (!t.skip_space(after)) return false;
        if (t.at_end(after) || *after == ',') {  // a lone name: a keyword, else a known symbol
          if (auto kw = keyword_value(spec.keywords, word)) {
            v = *kw;
            keyword = true;
            p = q;
          } else if (symbols_.find(word) < 0) {
            return false;  // an unknown keyword
          }
        }
      }
      if (!keyword && !expr(t, p, 1, 0, v)) return false;
      FieldRange fr = range_of(spec.field);
      if (v < fr.min || v > fr.max) return false;
      if (!keyword && spec.keywords != KwSet::None && !keyword_name(spec.keywords, static_cast<std::uint8_t>(v)))
        return false;  // warned about by the full assembler
      put_field(ins, spec.field, v);
      if (spec.field == Field::Value) negative = v < 0;
    }
    return t.skip_space(p) && t.at_end(p);
  }

  const AsmOptions& options_;
  FileReader& reader_;
  const Profile& profile_;
  AsmResult& out_;
  std::deque<FastText> texts_;  // by SourceSet index; a deque, since scanning holds references while includes add texts
  std::vector<std::string> stack_;       // the include chain (keys), for cycles
  std::vector<std::string> included_;    // every file included so far (keys)
  std::vector<std::uint32_t> operands_;  // per instruction: where its operands start
  FastSymbols symbols_;
  std::array<const OpInfo*, 256> ops_{};  // op_info(), without its lookup on every instruction
};

}  // namespace

bool fast_assemble(const std::string& path, const AsmOptions& options, FileReader& reader, std::string& text,
                   AsmResult& out) {
  // A control byte even in a comment: the full assembler says the file is binary data.
  if (options.relocatable || text.size() > kMaxFileBytes || has_binary_control_byte(text)) return false;
  // The target the first line names (`// tmcl-target: NAME`) unless -t names one; one that cannot
  // be used is the full assembler's to report, at its place.
  const Profile* named = options.profile;
  if (!named) {
    if (auto comment = target_comment(text)) {
      named = resolve_target(comment->name).profile;
      if (!named) return false;
    }
  }
  const Profile& profile = named ? *named : generic_profile();
  FastAssembler fa(options, reader, profile, out);
  bool ok = true;
  for (const auto& [name, value] : options.defines) {  // added first, as the full assembler does
    SourceFile d;
    d.name = "<command line -D " + name + ">";
    d.path = d.name;
    d.text = value;
    ok = ok && fa.define_command_line(name, out.sources.add(std::move(d)));
  }
  SourceFile f;
  f.name = path == "-" ? "<stdin>" : path;
  f.path = path;
  f.text = std::move(text);
  bool bom = drop_bom(f.text);
  int root = out.sources.add(std::move(f));
  const SourceFile& added = out.sources.files[static_cast<std::size_t>(root)];
  // `tmcl: allow NAME` comments are read here too, for the analysis after; a wrong name is the
  // full assembler's to report.
  if (ok && !first_long_line(added) && out.diags.allow_from_comments(added, root)) {
    fa.reserve(added.line_starts.size());
    ok = fa.pass1(root) && fa.pass2() && fa.finish(root);
  } else {
    ok = false;
  }
  if (ok) return true;
  text = std::move(out.sources.files[static_cast<std::size_t>(root)].text);
  if (bom) text.insert(0, "\xEF\xBB\xBF");
  out = AsmResult{};
  return false;
}

}  // namespace tmcl::detail
