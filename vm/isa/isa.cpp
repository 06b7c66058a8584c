// Expands opcodes.def and keywords.def into the lookup tables declared in isa.hpp.
#include "tmcl/isa.hpp"

#include <algorithm>
#include <cctype>
#include <utility>
#include <vector>

namespace tmcl {
namespace {

#define NUM(f, r) OperandSpec{Field::f, Role::r, KwSet::None}
#define KW(f, s) OperandSpec{Field::f, Role::Keyword, KwSet::s}
#define LABEL(f) OperandSpec{Field::f, Role::Address, KwSet::None}

// One operand array per opcode, so that OpInfo can hold a span.
#define TMCL_OP(code, id, mn, meaning, ...) constexpr OperandSpec operands_##id[] = {__VA_ARGS__ __VA_OPT__(, ) NUM(Type, Data)};
#define TMCL_CTL(code, id, meaning)
#include "tmcl/opcodes.def"
#undef TMCL_OP
#undef TMCL_CTL

// The trailing NUM(Type, Data) above only keeps zero-operand arrays legal; it is cut off here.
template <std::size_t N>
constexpr std::span<const OperandSpec> real_operands(const OperandSpec (&a)[N]) {
  return std::span<const OperandSpec>(a, N - 1);
}

constexpr OpInfo kOps[] = {
#define TMCL_OP(code, id, mn, meaning, ...) OpInfo{code, #id, mn, meaning, real_operands(operands_##id), false},
#define TMCL_CTL(code, id, meaning) OpInfo{code, #id, "", meaning, {}, true},
#include "tmcl/opcodes.def"
#undef TMCL_OP
#undef TMCL_CTL
};

#undef NUM
#undef KW
#undef LABEL

constexpr Keyword kKeywords[] = {
#define KEYWORD(set, name, value) Keyword{KwSet::set, #name, value},
#include "tmcl/keywords.def"
#undef KEYWORD
};

// Each opcode number may appear only once in the table.
constexpr bool opcodes_unique() {
  for (std::size_t i = 0; i < std::size(kOps); ++i)
    for (std::size_t j = i + 1; j < std::size(kOps); ++j)
      if (kOps[i].code == kOps[j].code) return false;
  return true;
}
static_assert(opcodes_unique(), "an opcode is declared twice in opcodes.def");

// Each field may be filled by at most one operand.
constexpr bool fields_unique() {
  for (const auto& op : kOps)
    for (std::size_t i = 0; i < op.operands.size(); ++i)
      for (std::size_t j = i + 1; j < op.operands.size(); ++j)
        if (op.operands[i].field == op.operands[j].field) return false;
  return true;
}
static_assert(fields_unique(), "an opcode fills one field twice");

constexpr char ascii_upper(char c) { return c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c; }

// Mnemonics and keywords are at most 8 characters: a word upper-cased and packed into 64 bits
// is its key, so a lookup is a few integer compares (the assembler does one per line).
bool pack_upper(std::string_view s, std::uint64_t& key) {
  if (s.empty() || s.size() > 8) return false;
  key = 0;
  for (std::size_t i = 0; i < s.size(); ++i) key |= std::uint64_t{static_cast<unsigned char>(ascii_upper(s[i]))} << (8 * i);
  return true;
}

struct OpIndex {
  static constexpr std::size_t kSlots = 512;  // open addressing, well over twice the mnemonics
  std::array<const OpInfo*, 256> by_code{};
  std::array<std::uint64_t, kSlots> mnemonic_keys{};
  std::array<const OpInfo*, kSlots> mnemonic_ops{};
  std::array<std::vector<std::pair<std::uint64_t, const Keyword*>>, 16> by_set;
  // The keys of every set's keywords, open addressing (0: a free slot; no key is 0). The
  // assembler asks of every constant it defines whether its name is a keyword.
  std::array<std::uint64_t, kSlots> keyword_keys{};
  static std::size_t slot(std::uint64_t key) { return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 55); }
  OpIndex() {
    for (const auto& op : kOps) {
      by_code[op.code] = &op;
      std::uint64_t key = 0;
      if (!pack_upper(op.mnemonic, key)) continue;
      std::size_t i = slot(key);
      while (mnemonic_ops[i]) i = (i + 1) % kSlots;
      mnemonic_keys[i] = key;
      mnemonic_ops[i] = &op;
    }
    for (const auto& k : kKeywords) {
      std::uint64_t key = 0;
      pack_upper(k.name, key);
      by_set[static_cast<std::size_t>(k.set)].emplace_back(key, &k);
      if (keyword(key)) continue;  // the same word in two sets
      std::size_t i = slot(key);
      while (keyword_keys[i]) i = (i + 1) % kSlots;
      keyword_keys[i] = key;
    }
  }
  bool keyword(std::uint64_t key) const {
    for (std::size_t i = slot(key);; i = (i + 1) % kSlots) {
      if (!keyword_keys[i]) return false;
      if (keyword_keys[i] == key) return true;
    }
  }
  const OpInfo* mnemonic(std::uint64_t key) const {
    for (std::size_t i = slot(key);; i = (i + 1) % kSlots) {
      if (!mnemonic_ops[i] || mnemonic_keys[i] == key) return mnemonic_ops[i];
    }
  }
};
const OpIndex& index() {
  static const OpIndex idx;
  return idx;
}

}  // namespace

std::span<const OpInfo> all_ops() { return kOps; }

const OpInfo* op_info(std::uint8_t code) { return index().by_code[code]; }

const OpInfo* op_by_mnemonic(std::string_view mnemonic) {
  std::uint64_t key = 0;
  return pack_upper(mnemonic, key) ? index().mnemonic(key) : nullptr;
}

std::span<const Keyword> all_keywords() { return kKeywords; }

std::optional<std::uint8_t> keyword_value(KwSet set, std::string_view name) {
  std::uint64_t key = 0;
  if (!pack_upper(name, key)) return std::nullopt;
  for (const auto& [k, kw] : index().by_set[static_cast<std::size_t>(set)])
    if (k == key) return kw->value;
  return std::nullopt;
}

bool is_keyword(std::string_view name) {
  std::uint64_t key = 0;
  return pack_upper(name, key) && index().keyword(key);
}

std::optional<std::string_view> keyword_name(KwSet set, std::uint8_t value) {
  for (const auto& k : kKeywords)
    if (k.set == set && k.value == value) return k.name;
  return std::nullopt;
}

std::string_view kwset_name(KwSet set) {
  switch (set) {
    case KwSet::None: return "none";
    case KwSet::Move: return "move type";
    case KwSet::CalcA: return "CALC operation";
    case KwSet::CalcX: return "CALCX operation";
    case KwSet::CalcV: return "CALCV operation";
    case KwSet::CalcVV: return "CALCVV/VA/AV/VX/XV operation";
    case KwSet::Cond: return "condition";
    case KwSet::Wait: return "WAIT condition";
    case KwSet::Cle: return "error flag";
    case KwSet::Rfs: return "RFS action";
  }
  return "?";
}

std::string_view role_name(Role role) {
  switch (role) {
    case Role::Data: return "value";
    case Role::Motor: return "motor";
    case Role::Bank: return "bank";
    case Role::AxisParam: return "axis parameter";
    case Role::GlobalParam: return "global parameter";
    case Role::Var: return "user variable";
    case Role::Coord: return "coordinate";
    case Role::Interrupt: return "interrupt";
    case Role::Port: return "port";
    case Role::Velocity: return "velocity";
    case Role::Position: return "position";
    case Role::Ticks: return "ticks";
    case Role::Address: return "address";
    case Role::Keyword: return "keyword";
  }
  return "?";
}

}  // namespace tmcl
