// Labels and constants by name: the assembler's one rule for comparing names (ASCII letters
// without regard to case, docs/language.md) and its one hash for them, and NameIndex, the
// unit's index of its definitions (internal.hpp). The fast path (fast_symbols.hpp) hashes and
// compares names with the same two functions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <vector>

namespace tmcl::detail {

// A hash of a name that ignores the case of its letters. Upper and lower case differ only in
// bit 5 of each byte; clearing that bit in every byte makes the two cases hash alike (it also
// makes a few other pairs of bytes alike, which only costs a comparison).
inline std::uint64_t name_hash(const char* s, std::size_t n) {
  constexpr std::uint64_t kFold = 0xDFDFDFDFDFDFDFDFull;
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
  h *= 0xC4CEB9FE1A85EC53ull;  // tables index with the low bits: mix the high ones down
  return h ^ (h >> 29);
}
inline std::uint64_t name_hash(std::string_view s) { return name_hash(s.data(), s.size()); }

// Whether two names are the same name: equal once ASCII letters are upper-cased (upper()).
inline bool same_name(const char* a, const char* b, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char x = static_cast<unsigned char>(a[i]), y = static_cast<unsigned char>(b[i]);
    if (x == y) continue;
    const unsigned char lower = static_cast<unsigned char>(x | 0x20);
    if (lower != (y | 0x20) || lower < 'a' || lower > 'z') return false;
  }
  return true;
}
inline bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && same_name(a.data(), b.data(), a.size());
}

// An open-addressing index from names to numbers 0, 1, 2, ... (a unit's definitions). It keeps
// no names of its own: a lookup is given the function that names a number. A slot holds the
// number and the name's hash, so a probe compares names only when the hashes agree; a unit of a
// million names takes 16 MiB, where a std::unordered_map of upper-cased copies took four times
// that in nodes of its own and a third of the time of assembling them (docs/performance.md).
class NameIndex {
 public:
  // The number stored for `name`, or -1. `name_of(k)` is the name number k was added with.
  template <typename NameOf>
  int find(std::string_view name, NameOf&& name_of) const {
    if (slots_.empty()) return -1;
    const auto h = static_cast<std::uint32_t>(name_hash(name));
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = h & mask;; i = (i + 1) & mask) {
      const Slot& s = slots_[i];
      if (s.number < 0) return -1;
      if (s.hash == h && same_name(name_of(s.number), name)) return s.number;
    }
  }

  // Adds `name` as number k; the caller knows that find(name) is -1.
  void add(std::string_view name, int k) {
    if (2 * (count_ + 1) > slots_.size()) grow();
    place({static_cast<std::uint32_t>(name_hash(name)), k});
    ++count_;
  }

 private:
  struct Slot {
    std::uint32_t hash = 0;
    int number = -1;  // -1: empty
  };

  void place(Slot s) {
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = s.hash & mask;
    while (slots_[i].number >= 0) i = (i + 1) & mask;
    slots_[i] = s;
  }

  void grow() {
    std::vector<Slot> old(slots_.empty() ? 64 : 2 * slots_.size());
    old.swap(slots_);
    for (const Slot& s : old)
      if (s.number >= 0) place(s);
  }

  std::vector<Slot> slots_;
  std::size_t count_ = 0;
};

}  // namespace tmcl::detail
