// Internal data structures of the assembler shared by lexer, parser, resolver and encoder.
// A "unit" is one root file with everything it includes; labels and constants are local to it
// unless exported (#export) and imported elsewhere (#import).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "name_index.hpp"
#include "tmcl/asm/assembler.hpp"
#include "tmcl/codec.hpp"
#include "tmcl/asm/object.hpp"

namespace tmcl::detail {

// Limits that keep hostile input from exhausting memory or the native stack (docs/limits.md).
inline constexpr int kMaxIncludeDepth = 64;
inline constexpr int kMaxExprDepth = 256;       // nesting of parentheses and unary operators
inline constexpr int kMaxEvalDepth = 3000;      // evaluation frames: constants entered + operators
inline constexpr std::size_t kMaxFileBytes = 64u << 20;
inline constexpr std::size_t kMaxLineBytes = 1u << 16;
inline constexpr std::size_t kMaxSymbols = 1u << 20;  // labels and constants per unit

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
  // Comments are skipped; a tool that keeps them (the formatter) gets each one here, as a Token
  // whose text is the whole comment (kind Bad, never returned by next_token).
  void keep_comments(std::vector<Token>* out) { comments_ = out; }

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
  std::vector<Token>* comments_ = nullptr;
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

// A value during resolution. When linking, every value is a number (term kAbsolute). In an
// object (-c) the unit's base address and imported names are unknown, so a value is a number
// plus at most one such term with coefficient 1: what a relocation can complete at link time.
inline constexpr int kAbsolute = -1;
inline constexpr int kBaseTerm = -2;  // the address of the unit's first instruction
struct Value {
  std::int64_t k = 0;
  int term = kAbsolute;  // >= 0: index into Unit::import_order
  friend bool operator==(const Value&, const Value&) = default;
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
  int term = kAbsolute;  // with value: the constant's Value (objects, -c)
  int obj_symbol = -1;   // a linked object's symbol (index into its symbol table)
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
  NameIndex def_index;  // defs by name (find_def, add_def)
  std::vector<Redefinition> redefinitions;
  std::vector<std::pair<std::string, SourceLoc>> exports;
  std::unordered_map<std::string, SourceLoc> imports;  // upper-cased name -> where imported
  std::vector<std::string> import_order;               // upper-cased names, in #import order
  std::unordered_map<std::string, int> import_index;   // upper-cased name -> import_order index
  std::unordered_set<std::string> failed_imports;      // imported but exported by nobody
  // An #include that was not found (its error, an index into the run's diagnostics; -1: none):
  // names used but not defined are then not errors of their own (the file may define them), but
  // listed in a note of that error.
  int missing_include = -1;
  std::unordered_set<std::string> unreported;          // upper-cased names, not reported
  std::vector<std::string> unreported_shown;           // the first few, as spelt
  int base = 0;  // address of the unit's first instruction after linking
  bool no_append_stop = false;  // #no_append_stop

  // A linked object: its code is already encoded; relocations are applied after resolving.
  const ObjectFile* object = nullptr;
  std::vector<int> object_files;  // the object's file table -> SourceSet index
  std::string input_name;         // "main.tmc", "homing.o", "libmotion.a(homing.o)"
  int size() const { return object ? static_cast<int>(object->code.size()) : static_cast<int>(stmts.size()); }
  // The definition of `name` (in any case), or -1.
  int find_def(std::string_view name) const {
    return def_index.find(name, [this](int k) -> std::string_view { return defs[static_cast<std::size_t>(k)].name; });
  }
  // Adds the definition of a name that find_def does not find yet.
  void add_def(SymDef d) {
    def_index.add(d.name, static_cast<int>(defs.size()));
    defs.push_back(std::move(d));
  }
  // Where instruction `i` of an object came from (no column: objects carry no source text).
  SourceLoc object_loc(std::uint32_t file, std::uint32_t line) const {
    if (file == kNoIndex || file >= object_files.size()) return SourceLoc{};
    return SourceLoc{object_files[file], static_cast<int>(line), 0, 0};
  }
};

std::string upper(std::string_view s);

// Drops a UTF-8 byte-order mark (Windows editors write one); true when there was one.
bool drop_bom(std::string& text);
// An #include'd file as found: its text, the path it was read from, and the key that tells
// whether two includes name the same file (for "once only" and cycles).
struct FoundInclude {
  std::string text, path, key;
};
// Searches for `#include name` as the assembler does: an absolute name as it is; otherwise the
// including file's folder, then the -I folders in order, then the bundled include files (names
// compared case-insensitively). `searched`, when given, receives what was searched, as a message
// says it ("'src' (the including file's folder)", "'inc' (-I)").
bool find_include(const std::string& name, const std::string& including_path, const AsmOptions& options,
                  FileReader& reader, FoundInclude& found, std::vector<std::string>* searched = nullptr);
std::string include_key(const std::string& path);
// The first line of `f` longer than kMaxLineBytes (1-based), or 0 when there is none.
int first_long_line(const SourceFile& f);

// Assembles `text`, the only input `path`, when it is a program the fast path (fast_path.cpp)
// handles: one source (with its #includes and -D definitions) whose result has no diagnostic.
// Otherwise it gives `text` back unchanged and returns false, and the full assembler takes over.
bool fast_assemble(const std::string& path, const AsmOptions& options, FileReader& reader, std::string& text,
                   AsmResult& out);

// The three instruction fields an operand can fill, their ranges and how a value is stored.
struct FieldRange {
  std::int64_t min, max;
  const char* text;
};
inline FieldRange range_of(Field f) {
  if (f == Field::Value) return {INT32_MIN, UINT32_MAX, "-2147483648 to 4294967295"};
  return {0, 255, "0 to 255"};
}
// The field's name (field_name) and how a value is stored come from the codec (codec.hpp).
inline void put_field(Instruction& ins, Field f, std::int64_t v) { set_field(ins, f, v); }

// Parses one root file (following its includes) into a unit.
// `text` is the root file's contents when the caller has read it already (moved from; nullptr: read it).
void parse_unit(const std::string& root, const AsmOptions& options, FileReader& reader, SourceSet& sources,
                Diagnostics& diags, Unit& unit, std::string* text = nullptr);

// Makes a unit of a linked object: its symbols, exports and imports; its files join `sources`.
void object_unit(const ObjectFile& obj, const std::string& input_name, SourceSet& sources, Unit& unit);

// ---- linking (link.cpp) ----------------------------------------------------------------------
// Objects and libraries read in one run; units point into them, so they must not move.
struct Storage {
  std::deque<ObjectFile> objects;
  std::deque<Library> libraries;
};

// One command-line input: a source or an object (one unit), or a library (its chosen members).
struct InputSlot {
  std::string name;
  std::vector<Unit> units;
  const Library* library = nullptr;
  std::vector<std::string> chosen;   // per member: the name it was linked for ("" = not linked)
  std::vector<std::string> reasons;  // per linked member, in `units` order
  std::vector<std::string> unused;   // members not linked, as "lib.a(member.o)"
};

// `first`: the text of files[0] when the caller has read it already (moved from), else nullptr.
void read_inputs(const std::vector<std::string>& files, const AsmOptions& options, FileReader& reader,
                 AsmResult& out, Storage& store, std::vector<InputSlot>& slots, std::string* first = nullptr);
void choose_members(std::vector<InputSlot>& slots, SourceSet& sources);
const Profile& choose_target(const AsmOptions& options, const std::vector<Unit>& units, const SourceSet& sources,
                             Diagnostics& diags);
class Resolver;
// Relocates unit `u` (an object) into out.program, checking what the target needs checked.
void link_object(Resolver& resolver, int u, const Unit& unit, const Profile& profile, AsmResult& out);
// The object of a unit assembled with -c: out.program and out.lines are its code.
ObjectFile build_object(const Unit& unit, Resolver& resolver, const AsmResult& out, const std::vector<ObjReloc>& relocs,
                        const std::vector<std::uint8_t>& flags, const Profile& profile);

// Resolves symbols across units and evaluates expressions.
class Resolver {
 public:
  // `relocatable`: one unit assembled into an object (-c), whose base and imports are unknown.
  Resolver(std::vector<Unit>& units, Diagnostics& diags, const SourceSet& sources, bool relocatable = false);
  // Value of an expression in a unit; nullopt after reporting an error (or a poisoned symbol).
  // An operand that cannot be expressed as a relocation is reported at `operand`.
  std::optional<Value> eval_value(int unit, int node, SourceLoc operand);
  // The same for a number that must be final (never relocatable).
  std::optional<std::int64_t> eval(int unit, int node);
  // Looks up a symbol as `unit` sees it: its own, then imported exports.
  std::pair<int, int> lookup(int unit, const std::string& upper_name);
  // Value of a symbol definition (constants are evaluated on first use).
  std::optional<Value> eval_def(int unit, int def) { return eval_symbol(unit, def, 0); }
  // Whether `unit` can see this name at all (defined or imported).
  bool known(int unit, const std::string& upper_name);
  void check_redefinitions();
  // A name `unit` uses but nobody defines, when an #include of the unit was not found: recorded
  // for the include's error instead of reported (true); false when it is to be reported.
  bool excuse_undefined(int unit, std::string_view name);
  // The note on each missing #include's error naming the uses it excused.
  void note_excused();
  // Did-you-mean for `name` among the unit's own names ("" when none is near).
  std::string closest_def(int unit, std::string_view name) const;
  std::string_view name_of(int unit, int node) const {
    return units_[static_cast<std::size_t>(unit)].nodes[static_cast<std::size_t>(node)].name;
  }
  // Every export and import must match; duplicate exports are reported.
  void link_exports();

 private:
  std::optional<Value> eval_node(int unit, int node, int depth);
  std::optional<Value> eval_symbol(int unit, int def, int depth);
  std::optional<Value> eval_object_symbol(int unit, const SymDef& d, int depth);
  std::optional<Value> combine(const ExprNode& op, Value a, Value b);
  std::optional<std::int64_t> apply(const ExprNode& op, std::int64_t a, std::int64_t b);
  void undefined_import(int unit, const std::string& key, SourceLoc import_loc);
  std::optional<Value> eval_name(int unit, const ExprNode& n, int depth);
  [[gnu::noinline]] void report_not_relocatable(const SymDef& d);
  [[gnu::noinline]] void report_cycle(int unit, int def);
  [[gnu::noinline]] void report_too_deep(int unit, int node);
  [[gnu::noinline]] void report_undefined(int unit, const ExprNode& n, const std::string& key);
  std::string name_at(SourceLoc loc) const;
  std::vector<Unit>& units_;
  Diagnostics& diags_;
  const SourceSet& sources_;
  bool relocatable_;
  bool depth_reported_ = false;
  SourceLoc not_relocatable_{};  // where an expression stopped being relocatable (file -1: nowhere)
  bool not_relocatable_pending_ = false;
  std::unordered_map<std::string, std::pair<int, int>> exported_;  // upper name -> (unit, def)
  std::vector<std::pair<int, int>> busy_;  // constants being evaluated, for cycle messages
};

// Checks one encoded instruction against the module profile (errors and warnings).
// `negative_value`: the value operand was written as a negative number (the field holds its
// two's complement), which a parameter that takes no negative values reads as a huge one.
void check_against_profile(const Profile& profile, const Stmt& stmt, const Instruction& ins, Diagnostics& diags,
                           bool negative_value = false);

}  // namespace tmcl::detail
