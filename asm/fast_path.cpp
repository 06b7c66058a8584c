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
// that both paths agree byte for byte on every source in the repository.
#include <array>
#include <cstring>

#include "chars.hpp"
#include "internal.hpp"

namespace tmcl::detail {
namespace {

// Deeper than any real program nests; beyond it the full assembler, with its own limits, decides.
constexpr int kMaxFastDepth = 64;

// Identifier characters differ only in bit 5 between the cases, and no two other identifier
// characters differ only there, so masking it compares and hashes names case-insensitively.
constexpr std::uint64_t kFold = 0xDFDFDFDFDFDFDFDFull;

std::uint64_t name_hash(const char* s, std::size_t n) {
  std::uint64_t h = n * 0x9E3779B97F4A7C15ull;
  while (n > 0) {
    std::uint64_t w = 0;
    std::size_t k = n < 8 ? n : 8;
    std::memcpy(&w, s, k);
    h = (h ^ (w & kFold)) * 0xFF51AFD7ED558CCDull;
    h ^= h >> 32;
    s += k;
    n -= k;
  }
  h *= 0xC4CEB9FE1A85EC53ull;  // the table indexes with the low bits: mix the high ones down
  return h ^ (h >> 29);
}

bool same_name(const char* a, const char* b, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i)
    if ((a[i] ^ b[i]) & 0xDF) return false;
  return true;
}

enum class State : std::uint8_t { Todo, Busy, Done };

struct FastSymbol {
  const char* name;
  std::uint32_t len;
  SymbolKind kind;
  State state;
  int line, col;
  std::uint32_t expr;  // constants: where the value's expression starts
  std::int64_t value;  // labels: the address
};

class FastAssembler {
 public:
  FastAssembler(std::string_view src, int file, const Profile& profile, AsmResult& out)
      : src_(src), file_(file), profile_(profile), out_(out) {
    for (const auto& op : all_ops()) ops_[op.code] = &op;
  }

  // Room for `lines` statements: reserving touches no memory, and regrowing would touch twice.
  void reserve(std::size_t lines) {
    out_.program.reserve(lines + 1);
    out_.lines.reserve(lines + 1);
    operands_.reserve(lines);
    symbols_.reserve(lines);
  }

  bool pass1() {
    std::size_t p = 0;
    int line = 1;
    std::size_t line_start = 0;
    while (p < src_.size()) {
      if (!statement_head(p, line, line_start)) return false;
      if (p < src_.size()) {  // at the newline that ends the statement
        ++p;
        ++line;
        line_start = p;
      }
    }
    return true;
  }

  bool pass2() {
    if (!index_symbols()) return false;
    Stmt probe;  // what the profile check reads: the opcode (its locations are never shown here)
    Diagnostics scratch;
    for (std::size_t i = 0; i < operands_.size(); ++i) {
      Instruction& ins = out_.program[i];
      const OpInfo* info = ops_[ins.op];
      if (!encode(*info, operands_[i], ins)) return false;
      probe.op = info;
      check_against_profile(profile_, probe, ins, scratch);
      if (!scratch.all().empty()) return false;
    }
    return true;
  }

  bool finish(const AsmOptions& options, const std::string& input_name) {
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
    out_.symbols.reserve(symbols_.size());
    for (std::size_t k = 0; k < symbols_.size(); ++k) {
      std::int64_t v = 0;
      if (!symbol_value(static_cast<int>(k), 0, v)) return false;  // unused constants are checked too
      const FastSymbol& s = symbols_[k];
      out_.symbols.push_back(Symbol{std::string(s.name, s.len), s.kind, v,
                                    SourceLoc{file_, s.line, s.col, static_cast<int>(s.len)}, false});
    }
    out_.inputs.push_back(LinkedInput{input_name, 0, size, ""});
    out_.profile = &profile_;
    return true;
  }

 private:
  char at(std::size_t p) const { return p < src_.size() ? src_[p] : '\0'; }

  // Skips spaces and /* */ comments (which may span lines and do not end a statement).
  bool skip_space(std::size_t& p, int& line, std::size_t& line_start) const {
    while (p < src_.size()) {
      char c = src_[p];
      if (char_class(c) == kSpace) {
        ++p;
      } else if (c == '/' && at(p + 1) == '*') {
        std::size_t close = src_.find("*/", p + 2);
        if (close == std::string_view::npos) return false;
        for (std::size_t q = p + 2; q < close; ++q)
          if (src_[q] == '\n') {
            ++line;
            line_start = q + 1;
          }
        p = close + 2;
      } else {
        break;
      }
    }
    return true;
  }
  bool skip_space(std::size_t& p) const {
    int line = 0;
    std::size_t line_start = 0;
    return skip_space(p, line, line_start);
  }

  // The end of a statement: the end of the text, a newline, or a comment running to the newline.
  bool at_end(std::size_t p) const {
    if (p >= src_.size()) return true;
    char c = src_[p];
    return c == '\n' || c == ';' || (c == '/' && at(p + 1) == '/');
  }

  // Moves p from the end of a statement to its newline (or the end of the text).
  void to_newline(std::size_t& p) const {
    const void* nl = p < src_.size() ? std::memchr(src_.data() + p, '\n', src_.size() - p) : nullptr;
    p = nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - src_.data()) : src_.size();
  }

  // An identifier at p, or an empty one; a byte outside ASCII next to it is an error.
  bool ident(std::size_t& p, std::string_view& name) const {
    std::size_t start = p;
    if (!ident_start(at(p))) return false;
    while (p < src_.size() && ident_char(src_[p])) ++p;
    if (non_ascii(at(p))) return false;
    name = src_.substr(start, p - start);
    return true;
  }

  // Pass 1: the labels of one statement, then a constant, an instruction or nothing; leaves p at
  // the statement's newline.
  bool statement_head(std::size_t& p, int& line, std::size_t& line_start) {
    while (true) {
      if (!skip_space(p, line, line_start)) return false;
      if (at_end(p)) {
        to_newline(p);
        return true;
      }
      std::size_t start = p;
      std::string_view name;
      if (!ident(p, name)) return false;  // a directive, .raw, a stray character
      int name_line = line;
      int col = static_cast<int>(start - line_start) + 1;
      if (!skip_space(p, line, line_start)) return false;
      if (at(p) == ':') {
        if (!define(name, SymbolKind::Label, name_line, col, static_cast<std::int64_t>(operands_.size()), 0)) return false;
        ++p;
        continue;
      }
      if (at(p) == '=') {
        if (is_keyword(name)) return false;  // warned about by the full assembler
        if (!define(name, SymbolKind::Constant, name_line, col, 0, static_cast<std::uint32_t>(p + 1))) return false;
        return skip_statement(p, line, line_start);
      }
      const OpInfo* op = op_by_mnemonic(name);
      if (!op) return false;
      out_.program.push_back(Instruction{op->code, 0, 0, 0});
      out_.lines.push_back(LineInfo{file_, name_line});
      operands_.push_back(static_cast<std::uint32_t>(start + name.size()));
      return skip_statement(p, line, line_start);
    }
  }

  // Skips the rest of a statement (read again in pass 2), counting the lines of its comments.
  bool skip_statement(std::size_t& p, int& line, std::size_t& line_start) const {
    static constexpr auto kStop = [] {
      std::array<bool, 256> t{};
      t['\n'] = t[';'] = t['/'] = true;
      return t;
    }();
    while (true) {
      while (p < src_.size() && !kStop[static_cast<unsigned char>(src_[p])]) ++p;
      if (p < src_.size() && src_[p] == '/' && at(p + 1) == '*') {
        if (!skip_space(p, line, line_start)) return false;
        continue;
      }
      if (p < src_.size() && src_[p] == '/' && at(p + 1) != '/') {
        ++p;  // division
        continue;
      }
      break;  // a newline, a comment to the newline, or the end of the text
    }
    to_newline(p);
    return true;
  }

  // ---- symbols: open addressing; a slot holds the hash's high half and the index + 1, so a probe
  // compares names only when the hashes agree (each name compared is a cache miss) ----
  static std::uint64_t slot_value(std::uint64_t h, std::size_t k) { return (h & ~0xFFFFFFFFull) | (k + 1); }

  int find(std::string_view name, std::uint64_t h) const {
    std::size_t mask = slots_.size() - 1;
    for (std::size_t i = static_cast<std::size_t>(h) & mask;; i = (i + 1) & mask) {
      std::uint64_t v = slots_[i];
      if (v == 0) return -1;
      if ((v ^ h) >> 32) continue;
      const FastSymbol& s = symbols_[(v & 0xFFFFFFFFu) - 1];
      if (s.len == name.size() && same_name(s.name, name.data(), name.size()))
        return static_cast<int>((v & 0xFFFFFFFFu) - 1);
    }
  }

  // Pass 1 records names; they are indexed afterwards in one sweep that prefetches the slots a
  // few names ahead, since nearly every slot touched is a cache miss. False on a name defined twice.
  bool index_symbols() {
    std::size_t n = symbols_.size(), size = 1024;
    while (size < 2 * n) size *= 2;
    slots_.assign(size, 0);
    const std::size_t mask = size - 1;
    constexpr std::size_t kAhead = 16;
    std::array<std::uint64_t, kAhead> ahead{};
    auto hash_of = [&](std::size_t k) { return name_hash(symbols_[k].name, symbols_[k].len); };
    for (std::size_t k = 0; k < n && k < kAhead; ++k) {
      ahead[k] = hash_of(k);
      __builtin_prefetch(&slots_[ahead[k] & mask]);
    }
    for (std::size_t k = 0; k < n; ++k) {
      std::uint64_t h = ahead[k % kAhead];
      if (k + kAhead < n) {
        ahead[k % kAhead] = hash_of(k + kAhead);
        __builtin_prefetch(&slots_[ahead[k % kAhead] & mask]);
      }
      const FastSymbol& s = symbols_[k];
      if (find({s.name, s.len}, h) >= 0) return false;  // redefined: left to the full assembler
      std::size_t i = static_cast<std::size_t>(h) & mask;
      while (slots_[i] != 0) i = (i + 1) & mask;
      slots_[i] = slot_value(h, k);
    }
    return true;
  }

  bool define(std::string_view name, SymbolKind kind, int line, int col, std::int64_t value, std::uint32_t expr) {
    if (symbols_.size() >= kMaxSymbols) return false;
    symbols_.push_back(FastSymbol{name.data(), static_cast<std::uint32_t>(name.size()), kind,
                                  kind == SymbolKind::Label ? State::Done : State::Todo, line, col, expr, value});
    return true;
  }

  // The value of symbol k; a constant is evaluated from its text the first time.
  bool symbol_value(int k, int depth, std::int64_t& v) {
    FastSymbol& s = symbols_[static_cast<std::size_t>(k)];
    if (s.state == State::Done) {
      v = s.value;
      return true;
    }
    if (s.state == State::Busy || depth > kMaxFastDepth) return false;  // a cycle, or very deep
    s.state = State::Busy;
    std::size_t p = s.expr;
    if (!skip_space(p) || at_end(p) || !expr(p, 1, depth + 1, v) || !skip_space(p) || !at_end(p)) return false;
    FastSymbol& again = symbols_[static_cast<std::size_t>(k)];
    again.value = v;
    again.state = State::Done;
    return true;
  }

  // ---- expressions, evaluated as they are read: C precedence, 64-bit wrapping (expr.cpp) ----
  static int precedence(char c, char next, int& len) {
    len = 1;
    switch (c) {
      case '|': return 1;
      case '^': return 2;
      case '&': return 3;
      case '<':
      case '>': len = 2; return next == c ? 4 : 0;
      case '+':
      case '-': return 5;
      case '*':
      case '/':
      case '%': return 6;
      default: return 0;
    }
  }

  bool expr(std::size_t& p, int min_prec, int depth, std::int64_t& v) {
    if (!unary(p, depth, v)) return false;
    while (true) {
      if (!skip_space(p)) return false;
      if (at_end(p)) return true;
      int len = 0;
      char op = src_[p];
      int prec = precedence(op, at(p + 1), len);
      if (prec < min_prec || prec == 0) return true;
      p += static_cast<std::size_t>(len);
      std::int64_t rhs = 0;
      if (!expr(p, prec + 1, depth + 1, rhs) || !apply(op, v, rhs)) return false;
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

  bool number(std::size_t& p, std::size_t prefix, int base, std::int64_t& v) const {
    DigitsRead r = read_digits(src_, p + prefix, base);
    if (r.status != DigitsRead::Ok || non_ascii(at(r.end))) return false;
    p = r.end;
    v = r.value;
    return true;
  }

  bool unary(std::size_t& p, int depth, std::int64_t& v) {
    if (depth > kMaxFastDepth || !skip_space(p)) return false;
    char c = at(p);
    if (c == '-' || c == '+' || c == '~') {
      ++p;
      if (!unary(p, depth + 1, v)) return false;
      auto u = static_cast<std::uint64_t>(v);
      if (c == '-') v = static_cast<std::int64_t>(0 - u);
      if (c == '~') v = static_cast<std::int64_t>(~u);
      return true;
    }
    if (c == '(') {
      ++p;
      if (!expr(p, 1, depth + 1, v) || !skip_space(p) || at(p) != ')') return false;
      ++p;
      return true;
    }
    if (char_class(c) == kDigit) {
      char x = at(p + 1);
      if (c == '0' && (x == 'x' || x == 'X')) return number(p, 2, 16, v);
      if (c == '0' && (x == 'b' || x == 'B')) return number(p, 2, 2, v);
      return number(p, 0, 10, v);
    }
    if (c == '$') return number(p, 1, 16, v);
    if (c == '%') return (at(p + 1) == '0' || at(p + 1) == '1') && number(p, 1, 2, v);
    std::string_view name;
    if (!ident(p, name)) return false;
    int k = find(name, name_hash(name.data(), name.size()));
    return k >= 0 && symbol_value(k, depth, v);
  }

  // ---- pass 2: one instruction's operands ----
  bool encode(const OpInfo& op, std::size_t p, Instruction& ins) {
    for (std::size_t k = 0; k < op.operands.size(); ++k) {
      const OperandSpec& spec = op.operands[k];
      if (!skip_space(p)) return false;
      if (k > 0) {
        if (at(p) != ',') return false;
        ++p;
        if (!skip_space(p)) return false;
      }
      // After the mnemonic a '%' is the modulo operator to the full lexer, not a binary number.
      if (at_end(p) || (k == 0 && at(p) == '%')) return false;
      std::int64_t v = 0;
      bool keyword = false;
      if (spec.keywords != KwSet::None && ident_start(at(p))) {
        std::size_t q = p;
        std::string_view word;
        if (!ident(q, word)) return false;
        std::size_t after = q;
        if (!skip_space(after)) return false;
        if (at_end(after) || at(after) == ',') {  // a lone name: a keyword, else a known symbol
          if (auto kw = keyword_value(spec.keywords, word)) {
            v = *kw;
            keyword = true;
            p = q;
          } else if (find(word, name_hash(word.data(), word.size())) < 0) {
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
    return skip_space(p) && at_end(p);
  }

  std::string_view src_;
  int file_;
  const Profile& profile_;
  AsmResult& out_;
  std::vector<std::uint32_t> operands_;  // per instruction: where its operands start
  std::vector<FastSymbol> symbols_;      // in definition order
  std::vector<std::uint64_t> slots_;
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
    FastAssembler fa(added.text, idx, profile, out);
    fa.reserve(added.line_starts.size());
    done = fa.pass1() && fa.pass2() && fa.finish(options, added.name);
  }
  if (done) return true;
  text = std::move(out.sources.files[static_cast<std::size_t>(idx)].text);
  if (bom) text.insert(0, "\xEF\xBB\xBF");
  out = AsmResult{};
  return false;
}

}  // namespace tmcl::detail
