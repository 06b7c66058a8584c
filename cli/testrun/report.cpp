// What CI tools and editors read of a test run: JUnit XML (Jenkins, GitLab, GitHub's test
// reporters), an lcov tracefile (genhtml, editors' coverage gutters) and a short coverage summary.
// The formats' facts: lcov's geninfo(1) tracefile, one record per source file; JUnit's
// testsuites/testsuite/testcase with failure, error and skipped.
#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "tmcl/testrun.hpp"
#include "tmcl/xml.hpp"

namespace tmcl::testrun {

namespace {

std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", s);
  return buf;
}

bool is_branch(const Instruction& i) {
  return i.op == static_cast<std::uint8_t>(Op::JC) || i.op == static_cast<std::uint8_t>(Op::CALL) ||
         i.op == static_cast<std::uint8_t>(Op::DJNZ);
}

// What reaches an address without calling it: a function's entry count leaves these out. CALL
// (opcode 80, "call if condition") is a branch for the branch counts but a call here.
bool is_jump(const Instruction& i) {
  return i.op == static_cast<std::uint8_t>(Op::JA) || i.op == static_cast<std::uint8_t>(Op::JC) ||
         i.op == static_cast<std::uint8_t>(Op::DJNZ);
}

}  // namespace

std::string junit_xml(const SuiteResult& s, const std::string& suite_name) {
  const std::string counts = " tests=\"" + std::to_string(s.tests.size()) + "\" failures=\"" + std::to_string(s.failed) +
                             "\" errors=\"" + std::to_string(s.errors) + "\" skipped=\"" + std::to_string(s.skipped) +
                             "\" time=\"" + seconds_text(s.seconds) + "\"";
  std::string x = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  x += "<testsuites name=\"" + xml_text(suite_name) + "\"" + counts + ">\n";
  x += "  <testsuite name=\"" + xml_text(suite_name) + "\"" + counts +
       (s.timestamp.empty() ? "" : " timestamp=\"" + xml_text(s.timestamp) + "\"") + ">\n";
  for (const TestResult& r : s.tests) {
    // classname: the test's folder with dots (as a package); name: the file without .tmctest.
    const std::filesystem::path p(r.path);
    std::string folder = p.parent_path().generic_string();
    std::replace(folder.begin(), folder.end(), '/', '.');
    while (!folder.empty() && folder.front() == '.') folder.erase(0, 1);
    x += "    <testcase classname=\"" + xml_text(folder.empty() ? suite_name : folder) + "\" name=\"" + xml_text(p.stem().string()) +
         "\" file=\"" + xml_text(r.path) + "\" time=\"" + seconds_text(r.seconds) + "\"";
    // The notes (what the run does not simulate, what a module cannot check) as system-out.
    std::string out;
    for (const std::string& n : r.notes) out += n + "\n";
    const std::string system_out = out.empty() ? "" : "      <system-out>" + xml_text(out) + "</system-out>\n";
    switch (r.status) {
      case TestResult::Pass:
        x += system_out.empty() ? "/>\n" : ">\n" + system_out + "    </testcase>\n";
        continue;
      case TestResult::Skip: x += ">\n      <skipped message=\"" + xml_text(r.skip_reason) + "\"/>\n"; break;
      case TestResult::Error:
        x += ">\n      <error message=\"the test could not run (a bad test file or program)\" type=\"error\">" + xml_text(r.error) +
             "</error>\n";
        break;
      case TestResult::Fail: {
        std::string text;
        for (const Failure& f : r.failures) {
          text += r.path + ":" + std::to_string(f.line) + ": " + f.message + "\n";
          if (!f.where.empty()) text += f.where + "\n";
        }
        const std::string message = r.failures.size() == 1 ? r.failures.front().message
                                                            : std::to_string(r.failures.size()) + " expectations failed; the first: " +
                                                                  r.failures.front().message;
        x += ">\n      <failure message=\"" + xml_text(message) + "\" type=\"expectation\">" + xml_text(text) + "</failure>\n";
        break;
      }
    }
    x += system_out + "    </testcase>\n";
  }
  x += "  </testsuite>\n</testsuites>\n";
  return x;
}

void Coverage::add(const TestResult& r) {
  if (!r.program || r.executed.empty()) return;
  Sums* sums = nullptr;
  for (Sums& s : sums_)
    if (s.program == r.program) sums = &s;
  if (!sums) {
    sums_.push_back({r.program, std::vector<std::uint64_t>(r.executed.size()), std::vector<std::uint64_t>(r.taken.size())});
    sums = &sums_.back();
  }
  for (std::size_t i = 0; i < r.executed.size(); ++i) {
    sums->executed[i] += r.executed[i];
    sums->taken[i] += r.taken[i];
  }
}

std::map<std::string, Coverage::File> Coverage::files() const {
  std::map<std::string, File> out;
  for (const Sums& s : sums_) {
    const Program& p = *s.program;
    const auto& prog = p.info.program;
    auto file_of = [&](std::size_t a) -> File* {
      if (a >= p.info.lines.size()) return nullptr;
      const int f = p.info.lines[a].file;
      if (f < 0 || static_cast<std::size_t>(f) >= p.paths.size() || p.paths[static_cast<std::size_t>(f)].empty()) return nullptr;
      return &out[p.paths[static_cast<std::size_t>(f)]];
    };
    // Lines: a line's count is the most any of its instructions ran (one, in TMCL), summed over
    // the programs that hold it.
    std::map<std::pair<File*, int>, std::uint64_t> lines;
    std::map<std::pair<File*, int>, int> blocks;  // branch instructions seen on a line so far
    for (std::size_t a = 0; a < prog.size(); ++a) {
      File* f = file_of(a);
      if (!f) continue;
      const int line = p.info.lines[a].line;
      auto& n = lines[{f, line}];
      n = std::max(n, s.executed[a]);
      if (is_branch(prog[a])) {
        Branch& b = f->branches[{line, blocks[{f, line}]++}];
        b.ran = b.ran || s.executed[a] > 0;
        b.taken += s.taken[a];
        b.not_taken += s.executed[a] - s.taken[a];
      }
    }
    for (const auto& [key, n] : lines) key.first->lines[key.second] += n;
    for (const Program::Function& fn : p.functions) {
      const auto entry = static_cast<std::size_t>(fn.entry);
      File* f = file_of(entry);
      if (!f) continue;
      std::uint64_t calls = s.executed[entry];
      for (std::size_t a = 0; a < prog.size(); ++a)
        if (is_jump(prog[a]) && prog[a].value == fn.entry)
          calls -= std::min(calls, prog[a].op == static_cast<std::uint8_t>(Op::JA) ? s.executed[a] : s.taken[a]);
      Function& out_fn = f->functions[fn.name];
      out_fn.line = p.info.lines[entry].line;
      out_fn.calls += calls;
    }
  }
  return out;
}

std::string lcov_tracefile(const Coverage& c) {
  std::string t;
  for (const auto& [path, f] : c.files()) {
    t += "SF:" + path + "\n";
    // Functions in line order, as geninfo writes them.
    std::vector<std::pair<int, std::string>> fns;
    for (const auto& [name, fn] : f.functions) fns.emplace_back(fn.line, name);
    std::sort(fns.begin(), fns.end());
    int fn_hit = 0;
    for (const auto& [line, name] : fns) t += "FN:" + std::to_string(line) + "," + name + "\n";
    for (const auto& [line, name] : fns) {
      const std::uint64_t calls = f.functions.at(name).calls;
      fn_hit += calls > 0;
      t += "FNDA:" + std::to_string(calls) + "," + name + "\n";
    }
    t += "FNF:" + std::to_string(fns.size()) + "\nFNH:" + std::to_string(fn_hit) + "\n";
    int br_hit = 0;
    for (const auto& [key, b] : f.branches) {
      const std::string pre = "BRDA:" + std::to_string(key.first) + "," + std::to_string(key.second) + ",";
      // '-': the branch never ran (while its line did, the outcomes are counts, 0 included).
      const bool line_ran = f.lines.count(key.first) && f.lines.at(key.first) > 0;
      const bool dash = !b.ran && !line_ran;
      t += pre + "0," + (dash ? "-" : std::to_string(b.taken)) + "\n";
      t += pre + "1," + (dash ? "-" : std::to_string(b.not_taken)) + "\n";
      br_hit += (b.taken > 0) + (b.not_taken > 0);
    }
    t += "BRF:" + std::to_string(f.branches.size() * 2) + "\nBRH:" + std::to_string(br_hit) + "\n";
    int line_hit = 0;
    for (const auto& [line, n] : f.lines) {
      t += "DA:" + std::to_string(line) + "," + std::to_string(n) + "\n";
      line_hit += n > 0;
    }
    t += "LF:" + std::to_string(f.lines.size()) + "\nLH:" + std::to_string(line_hit) + "\nend_of_record\n";
  }
  return t;
}

namespace {

std::string percent(std::size_t hit, std::size_t found) {
  char buf[48];
  if (found == 0) return std::to_string(hit) + "/0";
  std::snprintf(buf, sizeof buf, "%zu/%zu (%.1f%%)", hit, found, 100.0 * static_cast<double>(hit) / static_cast<double>(found));
  return buf;
}

// "12-14, 20": the lines in `lines`, runs joined.
std::string ranges(const std::vector<int>& lines) {
  std::string s;
  for (std::size_t i = 0; i < lines.size();) {
    std::size_t j = i;
    while (j + 1 < lines.size() && lines[j + 1] == lines[j] + 1) ++j;
    s += (s.empty() ? "" : ", ") + std::to_string(lines[i]) + (j > i ? "-" + std::to_string(lines[j]) : "");
    i = j + 1;
  }
  return s;
}

// A path below the current folder is shown relative to it.
std::string shown(const std::string& path) {
  std::error_code ec;
  const std::string cwd = std::filesystem::current_path(ec).generic_string();
  if (!ec && path.size() > cwd.size() + 1 && path.compare(0, cwd.size(), cwd) == 0 && path[cwd.size()] == '/')
    return path.substr(cwd.size() + 1);
  return path;
}

}  // namespace

std::string coverage_summary(const Coverage& c) {
  std::string s;
  std::size_t lf = 0, lh = 0, bf = 0, bh = 0;
  std::string per_file;
  const auto files = c.files();
  for (const auto& [path, f] : files) {
    std::size_t hit = 0, bhit = 0;
    std::vector<int> missed;
    for (const auto& [line, n] : f.lines) {
      if (n > 0) ++hit;
      else missed.push_back(line);
    }
    // The branches that ran with an outcome no test saw (one that never ran is on a line never run).
    std::vector<int> never_taken, always_taken;
    for (const auto& [key, b] : f.branches) {
      bhit += (b.taken > 0) + (b.not_taken > 0);
      auto& list = b.taken == 0 ? never_taken : always_taken;
      if (b.ran && (b.taken == 0 || b.not_taken == 0) && (list.empty() || list.back() != key.first)) list.push_back(key.first);
    }
    per_file += "  " + shown(path) + ": lines " + percent(hit, f.lines.size()) + ", branches " +
                percent(bhit, f.branches.size() * 2) + "\n";
    if (!missed.empty()) per_file += "    never run: " + ranges(missed) + "\n";
    if (!never_taken.empty()) per_file += "    branches never taken: " + ranges(never_taken) + "\n";
    if (!always_taken.empty()) per_file += "    branches always taken: " + ranges(always_taken) + "\n";
    lf += f.lines.size();
    lh += hit;
    bf += f.branches.size() * 2;
    bh += bhit;
  }
  s += "coverage: lines " + percent(lh, lf) + ", branches " + percent(bh, bf) + " in " + std::to_string(files.size()) +
       (files.size() == 1 ? " file\n" : " files\n");
  return s + per_file;
}

}  // namespace tmcl::testrun
