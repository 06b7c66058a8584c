// The symbols file's one reader and its line table's writer (docs/tmclasm.md, "symbols"). The
// line table is written as lines that begin with '#', which a reader of symbols version 1 skips
// as comments: host programs and older tmcl tools keep reading the labels of a new file.
#include "tmcl/asm/symbols.hpp"

#include <algorithm>
#include <cstdlib>
#include <map>

#include "tmcl/asm/assembler.hpp"
#include "tmcl/fileio.hpp"

namespace tmcl {
namespace {

constexpr const char* kSymbolsHeader = "# tmclasm symbols 1";
constexpr const char* kLinesHeader = "# tmclasm lines ";
constexpr int kLinesVersion = 1;

std::vector<std::string> split_symbol_fields(const std::string& line) {
  std::vector<std::string> f;
  for (std::size_t p = 0;;) {
    std::size_t t = line.find('\t', p);
    f.push_back(line.substr(p, t == std::string::npos ? std::string::npos : t - p));
    if (t == std::string::npos) break;
    p = t + 1;
  }
  return f;
}

// A decimal number from 0 to `max`, nothing else (no sign, no blanks).
bool decimal(const std::string& s, std::int64_t max, std::int64_t& out) {
  if (s.empty() || s.size() > 12) return false;
  std::int64_t v = 0;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
    v = v * 10 + (c - '0');
  }
  if (v > max) return false;
  out = v;
  return true;
}

constexpr std::int64_t kMaxSymbolsInt = 0x7FFFFFFF;

}  // namespace

std::pair<int, int> LineTable::at(std::int64_t address) const {
  auto it = std::upper_bound(runs.begin(), runs.end(), address,
                             [](std::int64_t a, const Run& r) { return a < r.address; });
  if (it == runs.begin()) return {-1, 0};
  --it;
  if (address >= it->address + it->count) return {-1, 0};
  return {it->file, it->line + static_cast<int>(address - it->address)};
}

bool parse_symbols(const std::string& text, LabelNames& out, int& error_line, std::string& error) {
  int line_no = 0;
  bool header = false, in_table = false;
  auto fail = [&](std::string what) {
    error_line = line_no;
    error = std::move(what);
    return false;
  };
  for (const std::string& line : split_lines(text)) {
    ++line_no;
    if (line_no == 1) {
      if (line != kSymbolsHeader)
        return fail(std::string("expected '") + kSymbolsHeader + "' (a file written by tmclasm -f symbols)");
      header = true;
      continue;
    }
    if (line.rfind(kLinesHeader, 0) == 0) {
      std::string v = line.substr(std::string(kLinesHeader).size());
      if (in_table) return fail("a second line table ('" + line + "')");
      std::int64_t version = 0;
      if (!decimal(v, kMaxSymbolsInt, version)) return fail("expected '# tmclasm lines 1'");
      if (version != kLinesVersion)
        return fail("line table version " + v + "; this tool reads version 1 (write the symbols again with this tmclasm)");
      in_table = true;
      continue;
    }
    bool file_record = line.rfind("#file\t", 0) == 0, lines_record = line.rfind("#lines\t", 0) == 0;
    if ((file_record || lines_record) && !in_table)
      return fail("a line-table record before the line '# tmclasm lines 1'");
    if (file_record) {
      auto f = split_symbol_fields(line);
      std::int64_t index = 0;
      if (f.size() != 3 || !decimal(f[1], kMaxSymbolsInt, index) || f[2].empty())
        return fail("expected '#file', the file's number and its path, tab-separated");
      if (index != static_cast<std::int64_t>(out.lines.files.size()))
        return fail("file number " + f[1] + " out of order (expected " + std::to_string(out.lines.files.size()) + ")");
      out.lines.files.push_back(f[2]);
      continue;
    }
    if (lines_record) {
      auto f = split_symbol_fields(line);
      std::int64_t v[4] = {};
      if (f.size() != 5) return fail("expected '#lines' and 4 tab-separated numbers: address, count, file, line");
      static const char* what[4] = {"address", "count", "file number", "line"};
      for (int k = 0; k < 4; ++k)
        if (!decimal(f[static_cast<std::size_t>(k) + 1], kMaxSymbolsInt, v[k]))
          return fail(std::string("invalid ") + what[k] + " '" + f[static_cast<std::size_t>(k) + 1] +
                      "' (a decimal number from 0 to 2147483647)");
      if (v[1] < 1) return fail("count 0: a run has at least one instruction");
      if (v[3] < 1) return fail("line 0: lines count from 1");
      if (v[2] >= static_cast<std::int64_t>(out.lines.files.size()))
        return fail("file number " + f[3] + " has no '#file' record (" +
                    (out.lines.files.empty() ? std::string("there is none before this line")
                                             : "the files before this line are numbered 0 to " +
                                                   std::to_string(out.lines.files.size() - 1)) +
                    ")");
      if (v[0] < out.lines.end())
        return fail("address " + f[1] + " is not after the previous run, which ends before " +
                    std::to_string(out.lines.end()) + " (runs are in address order and do not overlap)");
      if (v[0] + v[1] - 1 > kMaxSymbolsInt || v[3] + v[1] - 1 > kMaxSymbolsInt) return fail("the run goes past address or line 2147483647");
      out.lines.runs.push_back({v[0], v[1], static_cast<int>(v[2]), static_cast<int>(v[3])});
      continue;
    }
    if (line.empty() || line[0] == '#') continue;  // comments
    if (in_table) return fail("a symbol after the line table (the line table ends the file)");
    auto f = split_symbol_fields(line);
    if (f.size() != 5 || (f[0] != "label" && f[0] != "const"))
      return fail("expected 'label' or 'const' and 5 tab-separated fields");
    if (f[0] != "label") continue;
    char* endp = nullptr;
    long long v = std::strtoll(f[2].c_str(), &endp, 10);
    if (f[2].empty() || *endp || !is_valid_name(f[1])) return fail("invalid label name or address");
    out.labels.emplace_back(f[1], v);
  }
  if (!header) {
    line_no = 0;
    return fail(std::string("empty file (expected '") + kSymbolsHeader + "')");
  }
  return true;
}

bool load_symbols(const std::string& path, const std::string& tool, LabelNames& out, std::string& message) {
  std::vector<std::uint8_t> bytes;
  std::string err;
  if (!read_file(path, bytes, err)) {
    message = tool + ": error: " + err;
    return false;
  }
  int line = 0;
  if (!parse_symbols(std::string(bytes.begin(), bytes.end()), out, line, err)) {
    message = path + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": error: " + err;
    return false;
  }
  return true;
}

std::string format_line_table(const AsmResult& r) {
  std::string out = std::string(kLinesHeader) + std::to_string(kLinesVersion) +
                    "\n# #file\tnumber\tpath\n# #lines\taddress\tcount\tfile\tline\n";
  std::map<int, int> number;  // source file -> its number in the table, in order of first use
  std::string files, runs;
  LineTable::Run run{};
  bool open = false;
  auto flush = [&] {
    if (open)
      runs += "#lines\t" + std::to_string(run.address) + "\t" + std::to_string(run.count) + "\t" +
              std::to_string(run.file) + "\t" + std::to_string(run.line) + "\n";
    open = false;
  };
  for (std::size_t a = 0; a < r.lines.size(); ++a) {
    const LineInfo& li = r.lines[a];
    if (li.file < 0) {  // the appended STOP has no source
      flush();
      continue;
    }
    auto [it, added] = number.emplace(li.file, static_cast<int>(number.size()));
    if (added)
      files += "#file\t" + std::to_string(it->second) + "\t" + r.sources.files[static_cast<std::size_t>(li.file)].name + "\n";
    auto ai = static_cast<std::int64_t>(a);
    if (open && run.file == it->second && run.address + run.count == ai && run.line + run.count == li.line) {
      ++run.count;
      continue;
    }
    flush();
    run = {ai, 1, it->second, li.line};
    open = true;
  }
  flush();
  return out + files + runs;
}

}  // namespace tmcl
