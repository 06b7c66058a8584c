// Unit tests of the assembler's names (asm/name_index.hpp): same_name is exactly "equal once
// upper-cased" (upper(), the rule of docs/language.md) for every pair of bytes, name_hash agrees
// with it, and NameIndex finds every name it was given, in any case, through its growth and
// with names whose hashes collide, and nothing else.
#include <string>
#include <vector>

#include "check.hpp"
#include "internal.hpp"

using tmcl::detail::name_hash;
using tmcl::detail::NameIndex;
using tmcl::detail::same_name;
using tmcl::detail::upper;

TEST(same_name_is_equality_after_upper_for_every_byte_pair) {
  int wrong = 0, hash_disagrees = 0;
  for (int a = 0; a < 256; ++a) {
    for (int b = 0; b < 256; ++b) {
      const std::string x(1, static_cast<char>(a)), y(1, static_cast<char>(b));
      const std::string xs = "n" + x + "_9", ys = "N" + y + "_9";  // inside a longer name too
      const bool want = upper(x) == upper(y);
      if (same_name(x, y) != want || same_name(xs, ys) != want) ++wrong;
      if (want && name_hash(xs) != name_hash(ys)) ++hash_disagrees;
    }
  }
  CHECK_EQ(wrong, 0);
  CHECK_EQ(hash_disagrees, 0);
  CHECK(!same_name("ab", "abc"));
  CHECK(same_name("", ""));
  // Bit 5 alone tells '@' from '`' and '[' from '{': different names, though they hash alike.
  CHECK(!same_name("A@", "a`"));
  CHECK(!same_name("x[", "X{"));
  CHECK_EQ(name_hash("A@"), name_hash("a`"));
}

TEST(name_index_finds_every_name_in_any_case_through_growth) {
  std::vector<std::string> names;
  NameIndex index;
  auto name_of = [&](int k) -> std::string_view { return names[static_cast<std::size_t>(k)]; };
  CHECK_EQ(index.find("anything", name_of), -1);  // empty
  for (int i = 0; i < 100000; ++i) {
    names.push_back((i % 2 ? "Speed_" : "loop") + std::to_string(i));
    index.add(names.back(), i);
  }
  int missed = 0, invented = 0;
  for (int i = 0; i < 100000; ++i) {
    if (index.find(upper(names[static_cast<std::size_t>(i)]), name_of) != i) ++missed;
    if (index.find(names[static_cast<std::size_t>(i)] + "x", name_of) != -1) ++invented;
  }
  CHECK_EQ(missed, 0);
  CHECK_EQ(invented, 0);
  CHECK_EQ(index.find("SPEED_1", name_of), 1);
  CHECK_EQ(index.find("speed_1", name_of), 1);
  CHECK_EQ(index.find("Speed_0", name_of), -1);  // 0 is loop0
}

TEST(name_index_tells_apart_names_that_hash_alike) {
  // Names differing only in bit 5 of a non-letter hash alike: each probe must compare the names.
  std::vector<std::string> names = {"A@", "A`", "B[", "B{", "C_", "C\x7f"};
  NameIndex index;
  auto name_of = [&](int k) -> std::string_view { return names[static_cast<std::size_t>(k)]; };
  for (int k = 0; k < static_cast<int>(names.size()); ++k) index.add(names[static_cast<std::size_t>(k)], k);
  for (int k = 0; k < static_cast<int>(names.size()); ++k) CHECK_EQ(index.find(names[static_cast<std::size_t>(k)], name_of), k);
  CHECK_EQ(index.find("a`", name_of), 1);
  CHECK_EQ(index.find("c\x7f", name_of), 5);
  CHECK_EQ(index.find("D@", name_of), -1);
}
