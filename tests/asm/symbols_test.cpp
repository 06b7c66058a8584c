// Unit tests of the symbols file's line table (asm/symbols.cpp): what format_symbols writes reads
// back to the same position for every address (through an include, across two units and an
// object), runs are compact, a reader of symbols version 1 that skips '#' lines still sees
// exactly the symbol lines, and files without a line table still read. Messages of malformed
// tables are pinned by tests/golden/disasm/symbols-errors.run.
#include <algorithm>

#include "check.hpp"
#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/output.hpp"
#include "tmcl/asm/symbols.hpp"

namespace {

tmcl::AsmResult linked(tmcl::MemoryReader& reader) {
  reader.files["main.tmc"] = "#import Sub\n  SAP 4, 0, 1\n\n#include part.inc\nloop: CSUB Sub\n  JA loop\n";
  reader.files["part.inc"] = "// included\n  GAP 1, 0\n  GAP 2, 0\n";
  reader.files["sub.tmc"] = "#export Sub\nSub:\n  MVP REL, 0, 5\n  RSUB\n";
  tmcl::AsmOptions opts;
  opts.symbols = true;
  opts.relocatable = true;
  tmcl::AsmResult obj = tmcl::assemble({"sub.tmc"}, opts, reader);
  CHECK(obj.ok() && obj.object);
  auto bytes = tmcl::write_object(*obj.object);
  reader.files["sub.o"] = std::string(bytes.begin(), bytes.end());
  opts.relocatable = false;
  return tmcl::assemble({"main.tmc", "sub.o"}, opts, reader);
}

}  // namespace

TEST(line_table_round_trip_every_address) {
  tmcl::MemoryReader reader;
  tmcl::AsmResult r = linked(reader);
  CHECK(r.ok());
  std::string text = tmcl::format_symbols(r);
  tmcl::LabelNames names;
  int line = 0;
  std::string error;
  CHECK(tmcl::parse_symbols(text, names, line, error));
  CHECK_EQ(error, std::string());
  CHECK_EQ(names.lines.files.size(), std::size_t{3});  // main.tmc, part.inc, sub.tmc
  CHECK_EQ(r.lines.size(), r.program.size());
  for (std::size_t a = 0; a < r.lines.size(); ++a) {
    auto [file, at] = names.lines.at(static_cast<std::int64_t>(a));
    if (r.lines[a].file < 0) {  // the appended STOP
      CHECK_EQ(file, -1);
      continue;
    }
    CHECK(file >= 0);
    if (file < 0) continue;
    CHECK_EQ(names.lines.files[static_cast<std::size_t>(file)], r.sources.files[static_cast<std::size_t>(r.lines[a].file)].name);
    CHECK_EQ(at, r.lines[a].line);
  }
  CHECK_EQ(names.lines.at(-1).first, -1);
  CHECK_EQ(names.lines.at(1000).first, -1);
}

TEST(line_table_runs_are_compact) {
  tmcl::MemoryReader reader;
  tmcl::AsmResult r = linked(reader);
  tmcl::LabelNames names;
  int line = 0;
  std::string error;
  CHECK(tmcl::parse_symbols(tmcl::format_symbols(r), names, line, error));
  // main.tmc:2 | part.inc:2-3 | main.tmc:5-6 | sub.tmc:3-4; the appended STOP has none.
  CHECK_EQ(names.lines.runs.size(), std::size_t{4});
  if (names.lines.runs.size() == 4) {
    CHECK_EQ(names.lines.runs[1].count, std::int64_t{2});
    CHECK_EQ(names.lines.runs[3].address, std::int64_t{5});
  }
}

TEST(version_1_readers_see_only_symbol_lines) {
  tmcl::MemoryReader reader;
  tmcl::AsmResult r = linked(reader);
  std::string text = tmcl::format_symbols(r);
  CHECK_EQ(text.rfind("# tmclasm symbols 1\n", 0), std::size_t{0});
  std::size_t symbols = 0, pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    std::string l = text.substr(pos, end - pos);
    pos = end + 1;
    if (l.empty() || l[0] == '#') continue;
    ++symbols;
    CHECK_EQ(static_cast<int>(std::count(l.begin(), l.end(), '\t')), 4);
    CHECK(l.rfind("label\t", 0) == 0 || l.rfind("const\t", 0) == 0);
  }
  CHECK_EQ(symbols, r.symbols.size());
}

TEST(files_without_line_table_still_read) {
  tmcl::LabelNames names;
  int line = 0;
  std::string error;
  CHECK(tmcl::parse_symbols("# tmclasm symbols 1\n# kind\tname\tvalue\tdefined-at\tscope\nlabel\tA\t3\tp.tmc:2\tlocal\n",
                            names, line, error));
  CHECK_EQ(names.labels.size(), std::size_t{1});
  CHECK(names.lines.empty());
  CHECK_EQ(names.lines.at(3).first, -1);
}

TEST(malformed_tables_name_their_line) {
  const std::string head = "# tmclasm symbols 1\n# tmclasm lines 1\n#file\t0\tp.tmc\n";
  const char* bad[] = {"#lines\t0\t1\t1\t1\n", "#lines\t0\t1\t0\t0\n", "#lines\t-1\t1\t0\t1\n",
                       "#lines\t0\t99999999999\t0\t1\n", "#lines\t2147483647\t2\t0\t1\n", "#lines\t0\t1\t0\n",
                       "#file\t0\tq.tmc\n", "# tmclasm lines 1\n"};
  for (const char* b : bad) {
    tmcl::LabelNames names;
    int line = 0;
    std::string error;
    CHECK(!tmcl::parse_symbols(head + b, names, line, error));
    CHECK_EQ(line, 4);
    CHECK(!error.empty());
  }
}

TEST(crlf_files_read_like_lf_files) {
  tmcl::LabelNames names;
  int line = 0;
  std::string error;
  CHECK(tmcl::parse_symbols("# tmclasm symbols 1\r\nlabel\tA\t3\tp.tmc:2\tlocal\r\n# tmclasm lines 1\r\n#file\t0\tp.tmc\r\n"
                            "#lines\t0\t2\t0\t7\r\n",
                            names, line, error));
  CHECK_EQ(error, std::string());
  CHECK_EQ(names.lines.files.size(), std::size_t{1});
  if (!names.lines.files.empty()) CHECK_EQ(names.lines.files[0], std::string("p.tmc"));
  CHECK_EQ(names.lines.at(1).second, 8);
}
