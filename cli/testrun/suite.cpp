// Running many tests: finding the files, running them several at a time in one process (threads
// share the loaded programs; a process per test would cost more than most tests), reporting each
// result in the files' order as soon as it is known, and `tmclrun --test` itself: the closing
// line, the reports (JUnit, lcov, the coverage summary) and --update, which rewrites the values
// of failing expectations for review in git diff.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <mutex>
#include <set>
#include <thread>

#include "tmcl/fileio.hpp"
#include "tmcl/testrun.hpp"

namespace tmcl::testrun {

bool find_tests(const std::vector<std::string>& paths, std::vector<std::string>& out, std::string& error) {
  namespace fs = std::filesystem;
  std::set<std::string> seen;
  auto add = [&](const std::string& p) {
    if (seen.insert(p).second) out.push_back(p);
  };
  for (const std::string& path : paths) {
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (ec || !fs::exists(st)) {
      error = "'" + path + "': no such file or folder";
      return false;
    }
    if (!fs::is_directory(st)) {
      add(fs::path(path).lexically_normal().generic_string());
      continue;
    }
    std::vector<std::string> found;
    for (fs::recursive_directory_iterator it(path, fs::directory_options::skip_permission_denied, ec), end; !ec && it != end;
         it.increment(ec))
      if (it->path().extension() == ".tmctest" && it->is_regular_file(ec))
        found.push_back(it->path().lexically_normal().generic_string());  // "./a.tmctest" as "a.tmctest"
    if (ec) {
      error = "'" + path + "': " + ec.message();
      return false;
    }
    std::sort(found.begin(), found.end());
    for (const auto& f : found) add(f);
  }
  return true;
}

SuiteResult run_suite(const std::vector<std::string>& files, const SuiteOptions& options,
                      const std::function<void(const TestResult&)>& done) {
  const auto t0 = std::chrono::steady_clock::now();
  SuiteResult s;
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  char stamp[32];
  if (::gmtime_r(&now, &utc) && std::strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%S", &utc)) s.timestamp = stamp;
  s.tests.resize(files.size());
  ProgramCache cache;
  std::vector<char> finished(files.size(), 0);
  std::size_t reported = 0;
  std::atomic<std::size_t> next{0};
  std::mutex lock;
  auto work = [&] {
    for (std::size_t i; (i = next++) < files.size();) {
      TestResult r = options.run_one ? options.run_one(files[i], cache) : run_test_file(files[i], options.run, cache);
      std::lock_guard<std::mutex> g(lock);
      s.tests[i] = std::move(r);
      finished[i] = 1;
      for (; reported < files.size() && finished[reported]; ++reported) done(s.tests[reported]);
    }
  };
  const std::size_t wanted = options.jobs > 0 ? static_cast<std::size_t>(options.jobs) : std::thread::hardware_concurrency();
  const std::size_t jobs = std::clamp<std::size_t>(wanted, 1, std::max<std::size_t>(files.size(), 1));
  std::vector<std::thread> helpers;
  for (std::size_t j = 1; j < jobs; ++j) helpers.emplace_back(work);
  work();
  for (auto& h : helpers) h.join();
  for (const TestResult& r : s.tests) {
    switch (r.status) {
      case TestResult::Pass: ++s.passed; break;
      case TestResult::Fail: ++s.failed; break;
      case TestResult::Error: ++s.errors; break;
      case TestResult::Skip: ++s.skipped; break;
    }
  }
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return s;
}

std::string result_text(const TestResult& r) {
  std::string notes;
  for (const std::string& n : r.notes) notes += "  " + n + "\n";
  switch (r.status) {
    case TestResult::Pass: return "PASS " + r.path + "\n" + notes;
    case TestResult::Skip: return "SKIP " + r.path + " (" + r.skip_reason + ")\n";
    case TestResult::Error: return "ERROR " + r.path + "\n";
    case TestResult::Fail: break;
  }
  std::string s = "FAIL " + r.path + "\n";
  for (const Failure& f : r.failures) {
    s += "  " + r.path + ":" + std::to_string(f.line) + ": " + f.message + "\n";
    for (std::size_t b = 0; !f.where.empty() && b <= f.where.size();) {
      const std::size_t e = std::min(f.where.find('\n', b), f.where.size());
      s += "    " + f.where.substr(b, e - b) + "\n";
      b = e + 1;
    }
  }
  return s + notes;
}

std::string summary_line(const SuiteResult& s) {
  std::string line = std::to_string(s.passed) + " passed, ";
  if (s.updated > 0) line += std::to_string(s.updated) + " updated, ";
  line += std::to_string(s.failed) + " failed";
  if (s.skipped > 0) line += ", " + std::to_string(s.skipped) + " skipped";
  if (s.errors > 0) line += ", " + std::to_string(s.errors) + (s.errors == 1 ? " error" : " errors");
  return line + "\n";
}

namespace {

bool write_text(const std::string& tool, const std::string& path, const std::string& text, std::FILE* err) {
  std::string why;
  if (write_file_atomic(path, std::vector<std::uint8_t>(text.begin(), text.end()), why)) return true;
  std::fprintf(err, "%s: error: %s\n", tool.c_str(), why.c_str());
  return false;
}

// --update: rewrites the value of every failing expectation that has one to rewrite, saying
// which it rewrote and why it left each other. Returns how many failed tests now describe the
// run (every failure rewritten and the file written); the others still fail.
int update_files(const std::string& tool, const SuiteResult& s, std::FILE* out, std::FILE* err) {
  int updated = 0;
  for (const TestResult& r : s.tests) {
    if (r.status != TestResult::Fail) continue;
    bool all = true;
    std::vector<std::uint8_t> bytes;
    std::string why;
    if (!read_file(r.path, bytes, why, kMaxScenarioBytes)) {
      std::fprintf(err, "%s: error: %s\n", tool.c_str(), why.c_str());
      continue;
    }
    // Lines are edited in place; the file's line breaks (LF or CRLF) stay as they were.
    std::string text(bytes.begin(), bytes.end());
    std::vector<std::size_t> starts{0};
    for (std::size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') starts.push_back(i + 1);
    std::vector<std::pair<std::size_t, const Failure*>> edits;  // (offset, failure), in line order
    for (const Failure& f : r.failures) {
      if (f.update.empty()) {
        std::fprintf(out, "not updated: %s:%d: %s\n", r.path.c_str(), f.line,
                     (f.no_update.empty() ? std::string("there is no value to rewrite") : f.no_update).c_str());
        all = false;
        continue;
      }
      const std::size_t at = starts[static_cast<std::size_t>(f.line - 1)] + static_cast<std::size_t>(f.update_col - 1);
      std::fprintf(out, "updated %s:%d: %s (was %s)\n", r.path.c_str(), f.line, f.update.c_str(),
                   text.substr(at, static_cast<std::size_t>(f.update_len)).c_str());
      edits.emplace_back(at, &f);
    }
    if (edits.empty()) continue;
    // From the last edit back, so the earlier offsets stay right.
    for (auto e = edits.rbegin(); e != edits.rend(); ++e)
      text.replace(e->first, static_cast<std::size_t>(e->second->update_len), e->second->update);
    if (!write_text(tool, r.path, text, err)) all = false;
    if (all) ++updated;
  }
  return updated;
}

}  // namespace

int run_command(const std::vector<std::string>& paths, const SuiteOptions& options, std::FILE* out, std::FILE* err) {
  std::vector<std::string> files;
  std::string why;
  if (!find_tests(paths, files, why)) {
    std::fprintf(err, "%s: error: %s\n", options.run.tool.c_str(), why.c_str());
    return 65;
  }
  if (files.empty()) {
    std::fprintf(err, "%s: error: no test files (*.tmctest) in %s\n", options.run.tool.c_str(),
                 paths.empty() ? "." : paths.front().c_str());
    return 65;
  }
  SuiteOptions o = options;
  if (!o.coverage.empty() || o.coverage_summary) o.run.coverage = true;
  Coverage coverage;
  std::set<const Program*> warned;
  SuiteResult s = run_suite(files, o, [&](const TestResult& r) {
    if (r.status == TestResult::Error) std::fputs(r.error.c_str(), err);
    if (!r.messages.empty() && r.program && warned.insert(r.program.get()).second) std::fputs(r.messages.c_str(), err);
    std::fputs(result_text(r).c_str(), out);
    std::fflush(out);
    if (o.run.coverage) coverage.add(r);
  });
  const std::string& tool = o.run.tool;
  // After --update the closing line counts the rewritten tests apart (their files now describe
  // the run), the others still fail, and the status says the same; JUnit reports the run itself.
  const int updated = o.update && s.failed > 0 ? update_files(tool, s, out, err) : 0;
  int status = s.errors > 0 ? 65 : s.failed > updated ? 1 : 0;
  if (!o.junit.empty() && !write_text(tool, o.junit, junit_xml(s, tool), err)) status = 74;
  if (!o.coverage.empty() && !write_text(tool, o.coverage, lcov_tracefile(coverage), err)) status = 74;
  if (o.coverage_summary) std::fputs(coverage_summary(coverage).c_str(), out);
  s.updated = updated;
  s.failed -= updated;
  std::fputs(summary_line(s).c_str(), out);
  return status;
}

}  // namespace tmcl::testrun
