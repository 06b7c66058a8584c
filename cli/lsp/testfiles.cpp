// Test files (*.tmctest, docs/testing.md) in the language server: their diagnostics as the test
// runner reports them (the test file's own, and its program's when it does not assemble), a
// "Run test" code lens, and the command it runs (tmcl.runTest), which runs the test on the VM and
// shows each unmet expectation as a diagnostic on its line. The runner is cli/testrun's, as
// tmclrun --test uses it.
#include "tmcl/lsp/server.hpp"
#include "tmcl/testrun.hpp"

namespace tmcl::lsp {

namespace {

constexpr const char* kRunTest = "tmcl.runTest";

Server::Value range_on(const std::string& line_text, int line, int col, int len) {
  // FileDiag columns are bytes (1-based; 0 = the whole line); LSP's are UTF-16 units.
  const auto begin = static_cast<std::size_t>(col > 0 ? col - 1 : 0);
  const auto end = col > 0 ? begin + static_cast<std::size_t>(std::max(1, len)) : line_text.size();
  Server::Value r = Server::Value::object();
  Server::Value& s = r.set("start", Server::Value::object());
  s.set("line", std::max(0, line - 1));
  s.set("character", static_cast<long long>(utf16_column(line_text, begin)));
  Server::Value& e = r.set("end", Server::Value::object());
  e.set("line", std::max(0, line - 1));
  e.set("character", static_cast<long long>(utf16_column(line_text, std::min(end, line_text.size()))));
  return r;
}

std::string doc_line(const Document& doc, int line) {
  if (line < 1 || static_cast<std::size_t>(line) > doc.line_starts.size()) return "";
  const std::size_t b = doc.line_starts[static_cast<std::size_t>(line - 1)];
  std::size_t e = doc.text.find('\n', b);
  if (e == std::string::npos) e = doc.text.size();
  if (e > b && doc.text[e - 1] == '\r') --e;
  return doc.text.substr(b, e - b);
}

Server::Value diagnostic(const Document& doc, int line, int col, int len, int severity, const std::string& message) {
  Server::Value d = Server::Value::object();
  d.set("range", range_on(doc_line(doc, line), line, col, len));
  d.set("severity", severity);
  d.set("source", "tmcl");
  d.set("message", message);
  return d;
}

}  // namespace

bool Server::is_test_file(const Document& doc) {
  const std::string_view ext = ".tmctest";
  return doc.path.size() > ext.size() && doc.path.compare(doc.path.size() - ext.size(), ext.size(), ext) == 0;
}

testrun::RunOptions Server::test_options() const {
  testrun::RunOptions o;
  o.target = settings_.target;
  o.asm_options.include_dirs = settings_.include_dirs;
  o.error_limit = 0;
  o.tool = "tmcl-lsp";
  return o;
}

// The test file's diagnostics; `failures` adds those of a run (tmcl.runTest).
Server::Value Server::test_diagnostics(Document& doc, const std::vector<testrun::Failure>& failures) {
  testrun::ProgramCache cache;
  testrun::TestFile test;
  std::vector<FileDiag> diags;
  std::string program_error;
  auto program = testrun::check_test_source(doc.path, doc.text, test_options(), cache, test, diags, program_error);
  Value list = Value::array();
  for (const FileDiag& d : diags) list.push(diagnostic(doc, d.line, d.col, d.len, 1, d.message));
  if (!program_error.empty()) {
    // The program's own diagnostics belong to it; here, its first error on the program line.
    std::string first = program_error.substr(0, program_error.find('\n'));
    list.push(diagnostic(doc, std::max(1, test.program_line), 0, 0, 1, "the program cannot be loaded: " + first));
  }
  for (const testrun::Failure& f : failures)
    list.push(diagnostic(doc, f.line, 0, 0, 1, f.message + (f.where.empty() ? "" : "\n" + f.where)));
  // Editing the program re-checks the test (check_includers).
  doc.reads.clear();
  if (program)
    for (const std::string& p : program->paths)
      if (!p.empty()) doc.reads.insert(p);
  return list;
}

Server::Reply Server::code_lens(const Value& params) {
  Reply err;
  Document* doc = find_document(params, err);
  if (!doc) return err;
  Reply r;
  r.result = Value::array();
  if (!is_test_file(*doc)) return r;
  Value& lens = r.result.push(Value::object());
  lens.set("range", range_on(doc_line(*doc, 1), 1, 1, 0));
  Value& cmd = lens.set("command", Value::object());
  cmd.set("title", "\xE2\x96\xB6 Run test");
  cmd.set("command", kRunTest);
  cmd.set("arguments", Value::array()).push(doc->uri);
  return r;
}

// tmcl.runTest URI: runs the open test file (its text as the editor has it) and answers with the
// outcome; the unmet expectations become diagnostics, a message says how it went.
Server::Reply Server::execute_command(const Value& params) {
  if (params["command"].as_string() != kRunTest)
    return {Value(), kInvalidParams, "unknown command '" + params["command"].as_string() + "' (the server has " + kRunTest + ")"};
  const std::string uri = params["arguments"].at(0).as_string();
  auto it = docs_.find(uri);
  if (it == docs_.end() || !is_test_file(it->second))
    return {Value(), kInvalidParams, std::string(kRunTest) + " needs the URI of an open test file (*.tmctest), not '" + uri + "'"};
  Document& doc = it->second;
  testrun::ProgramCache cache;
  const testrun::TestResult t = testrun::run_test_source(doc.path, doc.text, test_options(), cache);
  publish(doc, test_diagnostics(doc, t.failures));
  static const char* const kStatus[] = {"pass", "fail", "error", "skip"};
  std::string summary = std::string(t.status == testrun::TestResult::Pass   ? "PASS "
                                    : t.status == testrun::TestResult::Fail ? "FAIL "
                                    : t.status == testrun::TestResult::Skip ? "SKIP "
                                                                            : "ERROR ") +
                        doc.path;
  if (t.status == testrun::TestResult::Fail)
    summary += ": " + std::to_string(t.failures.size()) + (t.failures.size() == 1 ? " expectation" : " expectations") + " not met";
  if (t.status == testrun::TestResult::Skip) summary += " (" + t.skip_reason + ")";
  if (t.status == testrun::TestResult::Error) summary += ": the test cannot run (see its diagnostics)";
  Value n = Value::object();
  n.set("jsonrpc", "2.0");
  n.set("method", "window/showMessage");
  Value& p = n.set("params", Value::object());
  p.set("type", t.status == testrun::TestResult::Pass || t.status == testrun::TestResult::Skip ? 3 : 1);
  p.set("message", summary);
  out_.push_back(json::write(n));
  Reply r;
  r.result = Value::object();
  r.result.set("status", kStatus[t.status]);
  r.result.set("failures", static_cast<long long>(t.failures.size()));
  r.result.set("message", summary);
  return r;
}

}  // namespace tmcl::lsp
