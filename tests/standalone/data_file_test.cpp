// The reader of tests/data/ (tests/unit/data_file.hpp) fails a test, naming the file, when a
// table is missing, empty or holds only comments, so a lost data file can never pass as "0 rows".
// Each case below expects exactly one failure and takes it back, so the test passes only if the
// reader reported it.
#include "check.hpp"
#include "data_file.hpp"

#include <cstdio>

namespace {

// Runs `read` and checks that it recorded exactly one failure and returned no rows.
template <typename F>
void expect_one_failure(const char* what, F read) {
  const int before = ::tmcl_test::failures();
  const std::vector<std::string> rows = read();
  const int added = ::tmcl_test::failures() - before;
  ::tmcl_test::failures() = before;
  if (added != 1 || !rows.empty()) ::tmcl_test::fail(__FILE__, __LINE__, std::string("no failure for ") + what);
  else std::fprintf(stderr, "  (the failure above is expected: %s)\n", what);
}

}  // namespace

TEST(missing_file_fails_naming_it) {
  expect_one_failure("a missing file", [] { return DATA_LINES("no-such-table.tsv"); });
}

TEST(empty_file_fails_naming_it) {
  expect_one_failure("an empty file", [] { return DATA_LINES("empty.tsv"); });
  expect_one_failure("a file of comments", [] { return DATA_LINES("comments-only.tsv"); });
}

TEST(rows_skip_comments_and_blank_lines) {
  const auto rows = DATA_LINES("two-rows.tsv");
  CHECK_EQ(rows.size(), std::size_t{2});
  if (rows.size() == 2) {
    CHECK_EQ(::tmcl_test::tsv_fields(rows[0]).size(), std::size_t{3});
    CHECK_EQ(::tmcl_test::tsv_fields(rows[1])[2], std::string());
  }
}
