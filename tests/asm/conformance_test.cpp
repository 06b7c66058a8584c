// Every binary example of both manuals (tests/data/manual-binary-forms.tsv, with the
// manuals' mistakes corrected) assembles to exactly the expected 9-byte datagram, as
// `tmclasm -f datagrams --no-append-stop` writes it; likewise the requests of the direct-mode table.
#include <cstdio>
#include <fstream>
#include <sstream>

#include "check.hpp"
#include "data_file.hpp"
#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/output.hpp"

namespace {

struct Row {
  std::string source, expected, where;
};

// Rows of a TSV file in tests/data/: columns `source` and the one named `bytes_column`; comment
// lines skipped. A missing or row-less file has already failed the test, naming the file.
std::vector<Row> read_rows(const std::string& file, const std::string& bytes_column) {
  std::vector<Row> rows;
  std::vector<std::string> header;
  for (const std::string& line : DATA_LINES(file)) {
    std::vector<std::string> cols = ::tmcl_test::tsv_fields(line);
    if (header.empty()) {
      header = cols;
      continue;
    }
    auto col = [&](const std::string& name) -> std::string {
      for (std::size_t i = 0; i < header.size() && i < cols.size(); ++i)
        if (header[i] == name) return cols[i];
      return "";
    };
    rows.push_back({col("source"), col(bytes_column), col("manual") + " " + col("section")});
  }
  return rows;
}

std::string hex(const std::vector<std::uint8_t>& b) {
  std::string s;
  char buf[4];
  for (std::size_t i = 0; i < b.size(); ++i) {
    std::snprintf(buf, sizeof buf, i ? " %02X" : "%02X", b[i]);
    s += buf;
  }
  return s;
}

std::string assemble_datagram(const std::string& source, std::string& errors) {
  tmcl::MemoryReader reader;
  reader.files["row.tmc"] = source + "\n";
  tmcl::AsmOptions opts;
  opts.append_stop = false;
  auto r = tmcl::assemble({"row.tmc"}, opts, reader);
  errors = r.ok() ? "" : r.diags.render(r.sources);
  return hex(tmcl::format_output(tmcl::OutputFormat::Datagrams, r, tmcl::generic_profile(), 1));
}

}  // namespace

TEST(all_manual_binary_forms) {
  auto rows = read_rows("manual-binary-forms.tsv", "expected");
  if (rows.empty()) return;  // already failed, naming the file
  CHECK_EQ(rows.size(), std::size_t{49});
  for (const auto& row : rows) {
    std::string errors;
    std::string got = assemble_datagram(row.source, errors);
    CHECK_EQ(errors, std::string());
    if (got != row.expected) std::fprintf(stderr, "  row %s: %s\n", row.where.c_str(), row.source.c_str());
    CHECK_EQ(got, row.expected);
  }
}

TEST(direct_mode_requests) {
  int checked = 0;
  const auto rows = read_rows("manual-direct-mode-replies.tsv", "request");
  if (rows.empty()) return;  // already failed, naming the file
  for (const auto& row : rows) {
    if (row.source.empty() || row.source[0] == '(') continue;  // control commands have no mnemonic
    std::string errors;
    CHECK_EQ(assemble_datagram(row.source, errors), row.expected);
    ++checked;
  }
  CHECK_EQ(checked, 7);
}
