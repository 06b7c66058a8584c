// The instruction table's name lookups (vm/isa/include/tmcl/isa.hpp): is_keyword and
// op_by_mnemonic answer, for every word the assembler may ask about, what a scan of the tables
// answers (their hash tables must not lose or invent a name), in either case.
#include <cctype>
#include <string>
#include <string_view>

#include "check.hpp"
#include "tmcl/isa.hpp"

namespace {

bool same_ci(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::toupper(static_cast<unsigned char>(a[i])) != std::toupper(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

bool scanned_keyword(std::string_view w) {
  for (const auto& k : tmcl::all_keywords())
    if (same_ci(k.name, w)) return true;
  return false;
}

const tmcl::OpInfo* scanned_op(std::string_view w) {
  for (const auto& op : tmcl::all_ops())
    if (!op.mnemonic.empty() && same_ci(op.mnemonic, w)) return &op;  // control commands have none
  return nullptr;
}

std::string lower(std::string_view w) {
  std::string s(w);
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

TEST(isa_every_keyword_and_mnemonic_is_found_in_either_case) {
  for (const auto& k : tmcl::all_keywords()) {
    CHECK(tmcl::is_keyword(k.name));
    CHECK(tmcl::is_keyword(lower(k.name)));
  }
  for (const auto& op : tmcl::all_ops()) {
    if (op.mnemonic.empty()) continue;  // a control command (direct mode only)
    CHECK(tmcl::op_by_mnemonic(op.mnemonic) == &op);
    CHECK(tmcl::op_by_mnemonic(lower(op.mnemonic)) == &op);
  }
}

TEST(isa_lookups_agree_with_a_scan_of_the_tables) {
  // Every word of one to three letters, then names a program uses and words no table has room
  // for (more than eight characters, empty, a NUL byte).
  std::string w;
  int words = 0;
  for (int len = 1; len <= 3; ++len) {
    int n = 1;
    for (int i = 0; i < len; ++i) n *= 26;
    for (int i = 0; i < n; ++i) {
      w.assign(static_cast<std::size_t>(len), 'A');
      for (int j = 0, v = i; j < len; ++j, v /= 26) w[static_cast<std::size_t>(j)] = static_cast<char>('A' + v % 26);
      CHECK_EQ(tmcl::is_keyword(w), scanned_keyword(w));
      CHECK(tmcl::op_by_mnemonic(w) == scanned_op(w));
      ++words;
    }
  }
  CHECK_EQ(words, 26 + 26 * 26 + 26 * 26 * 26);
  for (std::string_view s : {"Speed", "Motor0", "Trip", "ABSOLUTE", "WAITING", "RELATIVE", "ABCDEFGHI", ""}) {
    CHECK_EQ(tmcl::is_keyword(s), scanned_keyword(s));
    CHECK(tmcl::op_by_mnemonic(s) == scanned_op(s));
  }
  CHECK(!tmcl::is_keyword(std::string_view("\0", 1)));
  CHECK(!tmcl::is_keyword(std::string_view("\0\0\0", 3)));
}

// The named constants the VM switches on (tmcl::kw, isa.hpp) are the keyword table's values.
TEST(keyword_constants_are_the_tables_values) {
  int n = 0;
#define KEYWORD(set, name, value)                                                                        \
  CHECK_EQ(tmcl::kw::set::name, static_cast<int>(tmcl::keyword_value(tmcl::KwSet::set, #name).value_or(255))); \
  ++n;
#include "tmcl/keywords.def"
#undef KEYWORD
  CHECK_EQ(static_cast<std::size_t>(n), tmcl::all_keywords().size());
  CHECK_EQ(tmcl::kw::Move::REL, 1);  // MVP REL (the manual's 3.6.4)
  CHECK_EQ(tmcl::kw::Wait::RFS, 4);
}
