// Internal data structures of the assembler shared by lexer, parser, resolver and encoder.
// A "unit" is one root file with everything it includes; labels and constants are local to it
// unless exported (#export) and imported elsewhere (#import).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "tmcl/asm/assembler.hpp"

namespace tmcl::detail {

// Limits that keep hostile input from exhausting memory or the native stack (docs/limits.md).
inline constexpr int kMaxIncludeDepth = 64;
inline constexpr int kMaxExprDepth = 256;       // nesting of parentheses and unary operators
inline constexpr int kMaxEvalDepth = 2000;      // constants referring to constants, transitively
inline constexpr std::size_t kMaxFileBytes = 64u << 20;
inline constexpr std::size_t kMaxLineBytes = 1u << 16;

enum class Tok : std::uint8_t { Ident, Number, Punct, Directive, IncludeName, Newline, Bad, End };

enum class P : std::uint8_t {
  None, Comma, Colon, Assign, LParen, RParen, Plus, Minus, Star, Slash, Percent,
  Amp, Pipe, Caret, Tilde, Shl, Shr,
};

struct Token {
  Token() = default;
  explicit Token(Tok k) : kind(k) {}
  Token(Tok k, P p, std::string_view t, std::int64_t n, int l, int c)
      : kind(k), punct(p), text(t), number(n), line(l), col(c) {}
  Tok kind = Tok::End;
  P punct = P::None;
  std::string_view text;  // points into the SourceFile text
  std::int64_t number = 0;
  int line = 0;
  int col = 0;
};

// Splits one file into tokens on demand (the parser pulls them, so a file is never held as a
// token array); reports bad characters and malformed numbers to diags.
class Lexer {
 public:
  Lexer(const SourceFile& f, int index, Diagnostics& d) : src_(f.text), file_(index), diags_(d) {}
  Token next_token();

 private:
  void step();
  SourceLoc loc_at(std::size_t p, int len) const;
  void push(Tok k, std::size_t p, std::size_t len, P punct = P::None, std::int64_t num = 0);
  bool after_operand() const;
  char peek(std::size_t k) const { return pos_ + k < src_.size() ? src_[pos_ + k] : '\0'; }
  void skip_to_eol();
  void block_comment();
  void ident();
  void directive();
  void include_name();
  void number();
  void digits(std::size_t start, std::size_t prefix, int base);
  bool punct();

  std::string_view src_;
  int file_;
  Diagnostics& diags_;
  Token pending_[2];  // a step produces at most two tokens (#include and its name)
  int pending_count_ = 0;
  int pending_head_ = 0;
  Token last_ = Token(Tok::Newline);
  std::size_t pos_ = 0;
  std::size_t line_start_ = 0;
  int line_ = 1;
  int finished_ = 0;  // 1: final Newline sent, 2: End sent
};

// ---- expressions --------------------------------------------------------------------------
enum class ExprKind : std::uint8_t { Number, Symbol, Unary, Binary };

struct ExprNode {
  ExprKind kind;
  P op = P::None;
  std::int64_t number = 0;
  std::string_view name;  // Symbol
  int lhs = -1;
  int rhs = -1;
  SourceLoc loc;
};

// ---- statements and symbols ---------------------------------------------------------------
struct Operand {
  int expr = -1;          // node index, or -1 for a keyword
  bool lone_symbol = false;  // a single name where a keyword may stand
  std::uint8_t keyword = 0;
  SourceLoc loc;
};

struct Stmt {
  const OpInfo* op = nullptr;  // nullptr: .raw
  std::array<Operand, 4> operands{};
  int count = 0;
  SourceLoc loc;  // the mnemonic
  int address = 0;  // within the unit
};

enum class EvalState : std::uint8_t { Todo, Busy, Done, Failed };

struct SymDef {
  std::string name;  // as spelt
  SymbolKind kind;
  int expr = -1;     // constants
  int address = 0;   // labels, within the unit
  SourceLoc loc;
  EvalState state = EvalState::Todo;
  std::int64_t value = 0;
  bool exported = false;
  bool from_command_line = false;
};

struct Redefinition {
  int first;   // SymDef index
  int expr;    // the second definition's expression
  SourceLoc loc;
};

struct Unit {
  int root_file = -1;
  std::vector<Stmt> stmts;
  std::vector<ExprNode> nodes;
  std::vector<SymDef> defs;
  std::unordered_map<std::string, int> by_name;  // upper-cased name -> defs index
  std::vector<Redefinition> redefinitions;
  std::vector<std::pair<std::string, SourceLoc>> exports;
  std::unordered_map<std::string, SourceLoc> imports;  // upper-cased name -> where imported
  std::unordered_set<std::string> failed_imports;      // imported but exported by nobody
  int base = 0;  // address of the unit's first instruction after linking
};

std::string upper(std::string_view s);

// Parses one root file (following its includes) into a unit.
void parse_unit(const std::string& root, const AsmOptions& options, FileReader& reader, SourceSet& sources,
                Diagnostics& diags, Unit& unit);

// Resolves symbols across units and evaluates expressions.
class Resolver {
 public:
  Resolver(std::vector<Unit>& units, Diagnostics& diags, const SourceSet& sources);
  // Value of an expression in a unit; nullopt after reporting an error (or a poisoned symbol).
  std::optional<std::int64_t> eval(int unit, int node);
  // Looks up a symbol as `unit` sees it: its own, then imported exports.
  std::pair<int, int> lookup(int unit, const std::string& upper_name);
  // Value of a symbol definition (constants are evaluated on first use).
  std::optional<std::int64_t> eval_def(int unit, int def) { return eval_symbol(unit, def, 0, SourceLoc{}); }
  void check_redefinitions();
  std::string_view name_of(int unit, int node) const {
    return units_[static_cast<std::size_t>(unit)].nodes[static_cast<std::size_t>(node)].name;
  }
  // Every export and import must match; duplicate exports are reported.
  void link_exports();

 private:
  std::optional<std::int64_t> eval_node(int unit, int node, int depth);
  std::optional<std::int64_t> eval_symbol(int unit, int def, int depth, SourceLoc use);
  std::optional<std::int64_t> apply(const ExprNode& op, std::int64_t a, std::int64_t b);
  std::string name_at(SourceLoc loc) const;
  std::vector<Unit>& units_;
  Diagnostics& diags_;
  const SourceSet& sources_;
  bool depth_reported_ = false;
  std::unordered_map<std::string, std::pair<int, int>> exported_;  // upper name -> (unit, def)
  std::vector<std::pair<int, int>> busy_;  // constants being evaluated, for cycle messages
};

// Checks one encoded instruction against the module profile (errors and warnings).
void check_against_profile(const Profile& profile, const Stmt& stmt, const Instruction& ins, Diagnostics& diags);

}  // namespace tmcl::detail
