// The fast path's labels and constants (fast_path.cpp): recorded in definition order during
// pass 1, then indexed in one sweep. Names are compared case-insensitively, as everywhere in
// the assembler (docs/language.md), with the assembler's name_hash and same_name (name_index.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <vector>

#include "internal.hpp"
#include "name_index.hpp"
#include "tmcl/fileio.hpp"

namespace tmcl::detail {

enum class FastState : std::uint8_t { Todo, Busy, Done };

struct FastSymbol {
  const char* name;     // in the source text (or the -D option)
  std::int64_t value;   // labels: the address; constants once Done
  std::uint32_t len;
  std::uint32_t expr;   // constants: offset of the value's expression in the text of `file`
  int line;             // 0: defined on the command line (-D)
  std::uint16_t file;   // index into the result's SourceSet
  SymbolKind kind;
  FastState state;
};

class FastSymbols {
 public:
  std::vector<FastSymbol>& all() { return symbols_; }

  // False past the unit's limit on names (the full assembler reports it).
  bool record(FastSymbol s) {
    if (symbols_.size() >= kMaxSymbols) return false;
    symbols_.push_back(s);
    return true;
  }

  // A constant defined again (harmless when the values agree): its definitions, in order.
  struct Redefinition {
    std::uint32_t first, again;
  };
  const std::vector<Redefinition>& redefinitions() const { return redefinitions_; }

  // Indexes every recorded name in one sweep that prefetches the slots a few names ahead, since
  // nearly every slot touched is a cache miss. A constant defined again is not indexed again but
  // listed in redefinitions(); false when a label is involved (an error).
  bool index() {
    std::size_t n = symbols_.size(), size = 1024;
    while (size < 2 * n) size *= 2;
    slots_.reserve(size);
    prefer_huge_pages(slots_.data(), size * sizeof(std::uint64_t));
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
      if (int first = find(std::string_view(s.name, s.len), h); first >= 0) {
        if (s.kind != SymbolKind::Constant || symbols_[static_cast<std::size_t>(first)].kind != SymbolKind::Constant)
          return false;
        redefinitions_.push_back({static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(k)});
        continue;
      }
      std::size_t i = static_cast<std::size_t>(h) & mask;
      while (slots_[i] != 0) i = (i + 1) & mask;
      slots_[i] = (h & ~0xFFFFFFFFull) | (k + 1);
    }
    return true;
  }

  // The index of `name`, or -1.
  int find(std::string_view name) const { return find(name, name_hash(name)); }

 private:
  // A slot holds the hash's high half and the index + 1, so a probe compares names only when
  // the hashes agree (each name compared is another cache miss).
  int find(std::string_view name, std::uint64_t h) const {
    if (slots_.empty()) return -1;
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = static_cast<std::size_t>(h) & mask;; i = (i + 1) & mask) {
      std::uint64_t v = slots_[i];
      if (v == 0) return -1;
      if ((v ^ h) >> 32) continue;
      std::size_t k = (v & 0xFFFFFFFFu) - 1;
      const FastSymbol& s = symbols_[k];
      if (s.len == name.size() && same_name(s.name, name.data(), name.size())) return static_cast<int>(k);
    }
  }

  std::vector<FastSymbol> symbols_;  // in definition order
  std::vector<std::uint64_t> slots_;
  std::vector<Redefinition> redefinitions_;  // in the order of the second definitions
};

}  // namespace tmcl::detail
