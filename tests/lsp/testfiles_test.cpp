// Test files (*.tmctest) in the language server (cli/lsp/testfiles.cpp): their diagnostics on
// open and on change, the program's problems on the program line, the "Run test" code lens, the
// tmcl.runTest command with its outcome as diagnostics and a message, and TMCL requests on a test
// file answered with nothing instead of a crash.

#include <cstdlib>
#include <fstream>

#include "os_test.hpp"
#include "lsp_client.hpp"

using tmcl::json::Value;
using namespace tmcl_lsp_test;

namespace {

// A folder with prog.tmc in it (test files name their program relative to themselves).
std::string folder() {
  static const std::string dir = [] {
    std::string d = tmcl_test::make_temp_dir("tmcl-lsp-testfiles");
    std::ofstream(d + "/prog.tmc") << "        CALC LOAD, 5\nloop:   SGP 1, 2, 7\n        STOP\n";
    return d;
  }();
  return dir;
}

std::string uri(const std::string& name) { return tmcl::lsp::path_to_uri(folder() + "/" + name); }

void open_test(Client& c, const std::string& name, const std::string& text) {
  c.notify("textDocument/didOpen", R"({"textDocument":{"uri":")" + uri(name) + R"(","languageId":"tmcltest","version":1,"text":)" +
                                       tmcl::json::quote(text) + "}}");
}

std::string run_test(Client& c, const std::string& u) {
  return tmcl::json::write(c.request("workspace/executeCommand", R"({"command":"tmcl.runTest","arguments":[")" + u + R"("]})"));
}

std::string messages(const Value& diags) {
  std::string s;
  for (const Value& d : diags.items())
    s += std::to_string(d["range"]["start"]["line"].as_int()) + ":" + std::to_string(d["range"]["start"]["character"].as_int()) +
         "-" + std::to_string(d["range"]["end"]["character"].as_int()) + " " + d["message"].as_string() + "\n";
  return s;
}

}  // namespace

TEST(testfile_capabilities) {
  Client c;
  Value r = c.request("initialize", R"({"processId":null,"capabilities":{}})");
  CHECK_EQ(tmcl::json::write(r["result"]["capabilities"]["codeLensProvider"]), R"({"resolveProvider":false})");
  CHECK_EQ(tmcl::json::write(r["result"]["capabilities"]["executeCommandProvider"]), R"({"commands":["tmcl.runTest"]})");
}

TEST(testfile_diagnostics_on_open_and_change) {
  Client c;
  start(c, "{}");
  open_test(c, "a.tmctest", "program prog.tmc\nexpect at end acc = 5\nexpcet at end v[1] = 7\nexpect at end pc = lop\n");
  CHECK_EQ(messages(c.last_diagnostics(uri("a.tmctest"))),
           "2:0-6 unknown line 'expcet' (program, target, motion, instr-time, max-time, define, skip, at, switch, hardstop, load, expect); did you "
           "mean 'expect'?\n"
           "3:19-22 no register, label or constant named 'lop'; did you mean 'loop'?\n");
  c.notify("textDocument/didChange", R"({"textDocument":{"uri":")" + uri("a.tmctest") +
                                         R"(","version":2},"contentChanges":[{"text":"program prog.tmc\nexpect at end acc = 5\n"}]})");
  CHECK_EQ(c.last_diagnostics(uri("a.tmctest")).size(), 0u);
  // A program that is not there: on the program line.
  open_test(c, "b.tmctest", "# b\nprogram nowhere.tmc\nexpect at end acc = 5\n");
  const std::string b = messages(c.last_diagnostics(uri("b.tmctest")));
  CHECK(b.rfind("1:0-19 the program cannot be loaded: ", 0) == 0);
  CHECK(b.find("nowhere.tmc") != std::string::npos);
}

TEST(testfile_code_lens_and_run_test) {
  Client c;
  start(c, "{}");
  open_test(c, "pass.tmctest", "program prog.tmc\nexpect at end acc = 5\nexpect at end v[1] = 7\n");
  CHECK_EQ(tmcl::json::write(c.request("textDocument/codeLens", R"({"textDocument":{"uri":")" + uri("pass.tmctest") + R"("}})")["result"]),
           R"([{"range":{"start":{"line":0,"character":0},"end":{"line":0,"character":1}},"command":{"title":")" "\xE2\x96\xB6" R"( Run test",)"
           R"("command":"tmcl.runTest","arguments":[")" + uri("pass.tmctest") + R"("]}}])");
  CHECK_EQ(run_test(c, uri("pass.tmctest")),
           R"({"jsonrpc":"2.0","id":3,"result":{"status":"pass","failures":0,"message":"PASS )" + folder() + R"(/pass.tmctest"}})");
  CHECK_EQ(c.notifications.back()["method"].as_string(), "window/showMessage");
  CHECK_EQ(c.notifications.back()["params"]["type"].as_int(), 3);
  CHECK_EQ(c.last_diagnostics(uri("pass.tmctest")).size(), 0u);

  open_test(c, "fail.tmctest", "program prog.tmc\nexpect at end acc = 6\nexpect at end v[1] = 7\nexpect at end halted fault\n");
  const std::string r = run_test(c, uri("fail.tmctest"));
  CHECK(r.find(R"("status":"fail","failures":2,"message":"FAIL )" + folder() + "/fail.tmctest: 2 expectations not met") != std::string::npos);
  CHECK_EQ(c.notifications.back()["params"]["type"].as_int(), 1);
  CHECK_EQ(messages(c.last_diagnostics(uri("fail.tmctest"))),
           "1:0-21 expected acc = 6 at the end, got 5\nthe program was at " + folder() + "/prog.tmc:3 (loop+1): STOP\n"
           "3:0-26 expected the run to end with fault, but the run ended at 0.000060s (STOP at " + folder() +
               "/prog.tmc:3)\nthe program was at " + folder() + "/prog.tmc:3 (loop+1): STOP\n");
  // An edit brings the file's own diagnostics back (the run's are stale).
  c.notify("textDocument/didChange", R"({"textDocument":{"uri":")" + uri("fail.tmctest") +
                                         R"(","version":2},"contentChanges":[{"text":"program prog.tmc\n"}]})");
  CHECK_EQ(c.last_diagnostics(uri("fail.tmctest")).size(), 0u);
}

TEST(testfile_bad_commands_and_tmcl_requests) {
  Client c;
  start(c, "{}");
  open_test(c, "t.tmctest", "program prog.tmc\nexpect at end acc = 5\n");
  c.open(uri("prog.tmc"), "CALC LOAD, 5\nSTOP\n");
  CHECK_EQ(tmcl::json::write(c.request("textDocument/codeLens", R"({"textDocument":{"uri":")" + uri("prog.tmc") + R"("}})")["result"]), "[]");
  CHECK_EQ(c.request("workspace/executeCommand", R"({"command":"tmcl.fly","arguments":[]})")["error"]["message"].as_string(),
           "unknown command 'tmcl.fly' (the server has tmcl.runTest)");
  CHECK_EQ(c.request("workspace/executeCommand", R"({"command":"tmcl.runTest","arguments":[")" + uri("prog.tmc") + R"("]})")["error"]["code"].as_int(),
           -32602);
  // TMCL's requests on a test file: nothing to say, and no crash.
  for (const char* m : {"textDocument/hover", "textDocument/definition", "textDocument/references", "textDocument/completion",
                        "textDocument/rename", "textDocument/prepareRename", "textDocument/signatureHelp"})
    CHECK(c.request(m, pos(uri("t.tmctest"), 0, 2))["result"].is_null());
  CHECK(c.request("textDocument/semanticTokens/full", R"({"textDocument":{"uri":")" + uri("t.tmctest") + R"("}})")["result"].is_null());
  // Saving the program checks the test files that run it again.
  const std::size_t before = c.notifications.size();
  c.notify("textDocument/didSave", R"({"textDocument":{"uri":")" + uri("prog.tmc") + R"("}})");
  bool republished = false;
  for (std::size_t i = before; i < c.notifications.size(); ++i)
    republished = republished || c.notifications[i]["params"]["uri"].as_string() == uri("t.tmctest");
  CHECK(republished);
}
