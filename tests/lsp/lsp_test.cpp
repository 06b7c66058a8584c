// Protocol tests of the language server (cli/lsp/): a scripted client sends every request the
// server offers and every kind of bad input, and checks the exact replies. The Reader is tested
// on a pipe with good, bad and truncated frames.
#include <cstdio>

#include "lsp_client.hpp"
#include "os_test.hpp"

using tmcl::json::Value;
using namespace tmcl_lsp_test;

namespace {

const char* kUri = "file:///work/t.tmc";
const char* kProgram =
    "Speed = 1000\n"
    "Loop:\n"
    "  SAP 4, 0, Speed\n"
    "  MVP ABS, 0, 100\n"
    "  JA Lop\n";

}  // namespace

TEST(lifecycle) {
  Client c;
  Value early = c.request("textDocument/hover", pos(kUri, 0, 0));
  CHECK_EQ(early["error"]["code"].as_int(), -32002);
  start(c);
  CHECK_EQ(tmcl::json::write(c.request("initialize", "{}")["error"]["code"]), "-32600");
  CHECK_EQ(tmcl::json::write(c.request("initialize", "{}")["error"]["code"]), "-32600");
  Value s = c.request("shutdown", "null");
  CHECK(s.contains("result") && s["result"].is_null());
  CHECK_EQ(c.request("textDocument/hover", pos(kUri, 0, 0))["error"]["code"].as_int(), -32600);
  CHECK(!c.server.exited());
  c.notify("exit", "null");
  CHECK(c.server.exited());
  CHECK_EQ(c.server.exit_code(), 0);
  Client d;
  d.notify("exit", "null");
  CHECK_EQ(d.server.exit_code(), 1);  // exit without shutdown
}

TEST(diagnostics_on_open_and_incremental_change) {
  Client c;
  start(c);
  c.open(kUri, kProgram);
  Value d = c.last_diagnostics(kUri);
  CHECK_EQ(d.size(), 1u);
  CHECK_EQ(d.at(0)["message"].as_string(), "use of undefined symbol 'Lop'");
  CHECK_EQ(tmcl::json::write(d.at(0)["range"]), R"({"start":{"line":4,"character":5},"end":{"line":4,"character":8}})");
  CHECK_EQ(d.at(0)["severity"].as_int(), 1);
  // Insert the missing "o": an incremental change.
  c.notify("textDocument/didChange", R"({"textDocument":{"uri":"file:///work/t.tmc","version":2},"contentChanges":[)"
                                     R"({"range":{"start":{"line":4,"character":6},"end":{"line":4,"character":6}},"text":"o"}]})");
  CHECK_EQ(c.last_diagnostics(kUri).size(), 0u);
  CHECK_EQ(c.server.document(kUri)->text.substr(c.server.document(kUri)->text.size() - 8), "JA Loop\n");
  CHECK_EQ(c.notifications.back()["params"]["version"].as_int(), 2);
  // A full replacement, then a warning with its name as the code.
  c.notify("textDocument/didChange", R"({"textDocument":{"uri":"file:///work/t.tmc","version":3},"contentChanges":[)"
                                     R"({"text":"  SAP 4, 0, 99999999\n"}]})");
  Value w = c.last_diagnostics(kUri);
  CHECK_EQ(w.size(), 1u);
  CHECK(w.at(0)["severity"].as_int() <= 2);
  c.notify("textDocument/didClose", R"({"textDocument":{"uri":"file:///work/t.tmc"}})");
  CHECK_EQ(c.last_diagnostics(kUri).size(), 0u);
  CHECK(c.server.document(kUri) == nullptr);
}

// The language server runs the same analysis, and honours the same per-line suppressions.
TEST(analysis_warnings_and_allow_comments) {
  Client c;
  start(c);
  const char* uri = "file:///work/wear.tmc";
  c.open(uri, "loop: STGP 0, 2\n  WAIT TICKS, 0, 1\n  JA loop\n");
  Value d = c.last_diagnostics(uri);
  CHECK_EQ(d.size(), 1u);
  CHECK_EQ(d.at(0)["code"].as_string(), "eeprom-wear");
  c.notify("textDocument/didChange", R"({"textDocument":{"uri":"file:///work/wear.tmc","version":2},"contentChanges":[)"
                                     R"({"text":"loop: STGP 0, 2 // tmcl: allow eeprom-wear\n  WAIT TICKS, 0, 1\n  JA loop\n"}]})");
  CHECK_EQ(c.last_diagnostics(uri).size(), 0u);
}

TEST(hover) {
  Client c;
  start(c);
  c.open(kUri, kProgram);
  CHECK_EQ(c.request("textDocument/hover", pos(kUri, 2, 6))["result"]["contents"]["value"].as_string(),
           "4: Maximum positioning speed, 0…16777215 pps, RW, default 51200 pps (usb-2-sd)");
  CHECK_EQ(c.request("textDocument/hover", pos(kUri, 2, 3))["result"]["contents"]["value"].as_string(),
           "```tmcl\nSAP <axis parameter>, <motor>, <value>\n```\nSet axis parameter (opcode 5)");
  CHECK_EQ(c.request("textDocument/hover", pos(kUri, 2, 12))["result"]["contents"]["value"].as_string(),
           "constant `Speed` = 1000");
  CHECK(c.request("textDocument/hover", pos(kUri, 3, 0))["result"].is_null());  // blank before MVP
  // Units come from the profile; a parameter the manual gives none for has none.
  c.open("file:///work/units.tmc", "  SAP 14, 0, 1\n  SGP 0, 3, 1000\n  SAP 1, 0, 0\n");
  CHECK_EQ(c.request("textDocument/hover", pos("file:///work/units.tmc", 0, 7))["result"]["contents"]["value"].as_string(),
           "14: Ramp type, 0…1, RW, default 0 (usb-2-sd)");
  CHECK_EQ(c.request("textDocument/hover", pos("file:///work/units.tmc", 1, 6))["result"]["contents"]["value"].as_string(),
           "0: Timer 0 period (ms), 0…4294967295 ms, RW, default 0 ms (usb-2-sd)");
  CHECK_EQ(c.request("textDocument/hover", pos("file:///work/units.tmc", 2, 6))["result"]["contents"]["value"].as_string(),
           "1: Actual position, -2147483648…2147483647 \u03bcsteps, RW, default 0 \u03bcsteps (usb-2-sd)");
}

TEST(definition_references_symbols_completion_formatting) {
  Client c;
  start(c);
  c.open(kUri, std::string(kProgram) + "  JA Loop\n");
  Value def = c.request("textDocument/definition", pos(kUri, 5, 6))["result"];
  CHECK_EQ(tmcl::json::write(def), R"({"uri":"file:///work/t.tmc","range":{"start":{"line":1,"character":0},"end":{"line":1,"character":4}}})");
  Value refs = c.request("textDocument/references",
                         R"({"textDocument":{"uri":"file:///work/t.tmc"},"position":{"line":1,"character":1},"context":{"includeDeclaration":false}})")["result"];
  CHECK_EQ(refs.size(), 1u);
  CHECK_EQ(refs.at(0)["range"]["start"]["line"].as_int(), 5);
  Value syms = c.request("textDocument/documentSymbol", R"({"textDocument":{"uri":"file:///work/t.tmc"}})")["result"];
  CHECK_EQ(syms.size(), 2u);
  Value comp = c.request("textDocument/completion", pos(kUri, 3, 6))["result"];
  CHECK_EQ(comp.at(0)["label"].as_string(), "ABS");
  Value mn = c.request("textDocument/completion", pos(kUri, 3, 2))["result"];
  CHECK(mn.size() > 40);
  Value params = c.request("textDocument/completion", pos(kUri, 2, 6))["result"];
  CHECK_EQ(params.at(0)["label"].as_string(), "0");
  c.open("file:///work/u.tmc", "loop: sap 4,0,1\nja loop\n");
  Value f = c.request("textDocument/formatting", R"({"textDocument":{"uri":"file:///work/u.tmc"},"options":{"tabSize":2,"insertSpaces":true}})")["result"];
  CHECK_EQ(f.size(), 1u);
  CHECK_EQ(f.at(0)["newText"].as_string(), "loop:\n  SAP 4, 0, 1\n  JA loop\n");
  c.open("file:///work/bad.tmc", "sap 4, 0, 1@\n");
  Value bad = c.request("textDocument/formatting", R"({"textDocument":{"uri":"file:///work/bad.tmc"},"options":{}})");
  CHECK_EQ(bad["error"]["code"].as_int(), -32803);
}

TEST(bad_input_gets_error_responses) {
  Client c;
  start(c);
  c.open(kUri, kProgram);
  Value r = c.send("{bad json", 0);
  CHECK_EQ(r["error"]["code"].as_int(), -32700);
  CHECK(r["id"].is_null());
  CHECK_EQ(c.send(R"([1,2])", 0)["error"]["code"].as_int(), -32600);
  CHECK_EQ(c.send(R"({"jsonrpc":"2.0","id":{"x":1},"method":"shutdown"})", 0)["error"]["code"].as_int(), -32600);
  CHECK_EQ(c.request("no/such", "{}")["error"]["code"].as_int(), -32601);
  CHECK_EQ(c.request("textDocument/hover", pos("file:///nowhere.tmc", 0, 0))["error"]["message"].as_string(),
           "unknown document 'file:///nowhere.tmc' (not opened with didOpen)");
  CHECK_EQ(c.request("textDocument/hover", pos(kUri, 99, 0))["error"]["message"].as_string(),
           "position line 99 is outside the document (6 lines)");
  CHECK_EQ(c.request("textDocument/hover", R"({"textDocument":{"uri":"file:///work/t.tmc"}})")["error"]["code"].as_int(), -32602);
  CHECK(c.request("textDocument/hover", pos(kUri, 2, 500)).contains("result"));  // a column past the end clamps
  c.notify("$/cancelRequest", R"({"id":1})");  // unknown notifications are ignored
  CHECK(!c.server.exited());
}

TEST(rename_and_workspace_symbols) {
  Client c;
  start(c);
  c.open("file:///work/lib2.inc", "Far = 100\n");
  c.open("file:///work/main2.tmc", "#include lib2.inc\nHome:\n  MVP ABS, 0, Far\n  JA Home\n");
  Value edit = c.request("textDocument/rename", R"({"textDocument":{"uri":"file:///work/main2.tmc"},"position":{"line":2,"character":14},"newName":"Distance"})")["result"];
  CHECK_EQ(tmcl::json::write(edit),
           R"({"changes":{"file:///work/main2.tmc":[{"range":{"start":{"line":2,"character":14},"end":{"line":2,"character":17}},"newText":"Distance"}],)"
           R"("file:///work/lib2.inc":[{"range":{"start":{"line":0,"character":0},"end":{"line":0,"character":3}},"newText":"Distance"}]}})");
  CHECK_EQ(c.request("textDocument/rename", R"({"textDocument":{"uri":"file:///work/main2.tmc"},"position":{"line":1,"character":1},"newName":"MVP"})")["error"]["message"].as_string(),
           "'MVP' is not a valid label or constant name");
  CHECK_EQ(c.request("textDocument/rename", R"({"textDocument":{"uri":"file:///work/main2.tmc"},"position":{"line":1,"character":1},"newName":"Far"})")["error"]["message"].as_string(),
           "'Far' is already defined");
  CHECK_EQ(c.request("textDocument/rename", R"({"textDocument":{"uri":"file:///work/main2.tmc"},"position":{"line":2,"character":3},"newName":"X"})")["error"]["code"].as_int(), -32602);
  Value ws = c.request("workspace/symbol", R"({"query":"hom"})")["result"];
  CHECK_EQ(ws.size(), 1u);
  CHECK_EQ(ws.at(0)["name"].as_string(), "Home");
}

TEST(signature_help) {
  Client c;
  start(c);
  c.open(kUri, kProgram);
  Value sh = c.request("textDocument/signatureHelp", pos(kUri, 3, 11))["result"];  // "  MVP ABS, |0, 100"
  CHECK_EQ(sh["signatures"].at(0)["label"].as_string(), "MVP <move type>, <motor>, <position>");
  CHECK_EQ(sh["activeParameter"].as_int(), 1);
  CHECK_EQ(tmcl::json::write(sh["signatures"].at(0)["parameters"].at(1)["label"]), "[17,24]");
  CHECK(c.request("textDocument/signatureHelp", pos(kUri, 1, 2))["result"].is_null());  // a label line
}

TEST(folding_ranges) {
  Client c;
  start(c);
  c.open("file:///work/f.tmc", "/* a\n   b */\nStart:\n  SAP 4, 0, 1\n  STOP\n\nSub:\n  RSUB\n");
  Value f = c.request("textDocument/foldingRange", R"({"textDocument":{"uri":"file:///work/f.tmc"}})")["result"];
  CHECK_EQ(tmcl::json::write(f), R"([{"startLine":0,"endLine":1,"kind":"comment"},{"startLine":2,"endLine":4},{"startLine":6,"endLine":7}])");
}

TEST(includers_are_rechecked) {
  Client c;
  start(c);
  c.open("file:///work/lib.inc", "Far = 100\n");
  c.open("file:///work/main.tmc", "#include lib.inc\n  MVP ABS, 0, Far\n");
  CHECK_EQ(c.last_diagnostics("file:///work/main.tmc").size(), 0u);
  c.notify("textDocument/didChange", R"({"textDocument":{"uri":"file:///work/lib.inc","version":2},"contentChanges":[{"text":"Near = 1\n"}]})");
  Value d = c.last_diagnostics("file:///work/main.tmc");
  CHECK_EQ(d.size(), 1u);
  CHECK_EQ(d.at(0)["message"].as_string(), "use of undefined symbol 'Far'");
}

TEST(framing_on_a_pipe) {
  int fds[2];
  CHECK(tmcl_test::make_pipe(fds));
  std::string input = tmcl::lsp::frame("{}") + "Content-Length: x\r\n\r\n" + "Content-Type: a\r\ncontent-length: 2\r\n\r\n[]" +
                      "Content-Length: 10\r\n\r\n{";
  CHECK(tmcl_test::write_all(fds[1], input));
  tmcl_test::close_fd(fds[1]);
  tmcl::lsp::Reader reader(fds[0]);
  std::string body, error;
  CHECK(reader.next(body, error) == tmcl::lsp::Reader::Status::Message);
  CHECK_EQ(body, "{}");
  CHECK(reader.next(body, error) == tmcl::lsp::Reader::Status::BadHeader);
  CHECK_EQ(error, "bad Content-Length 'x' (expected a byte count up to 256 MiB)");
  CHECK(reader.next(body, error) == tmcl::lsp::Reader::Status::Message);
  CHECK_EQ(body, "[]");
  CHECK(reader.next(body, error) == tmcl::lsp::Reader::Status::End);
  CHECK_EQ(error, "input ended inside a message body");
  tmcl_test::close_fd(fds[0]);
}

TEST(positions_count_utf16) {
  CHECK_EQ(tmcl::lsp::utf16_column("// \xC3\xA9x", 5), 4u);
  CHECK_EQ(tmcl::lsp::utf16_column("// \xF0\x9F\x98\x80x", 7), 5u);
  CHECK_EQ(tmcl::lsp::uri_to_path("file:///a%20b/c.tmc"), "/a b/c.tmc");
  CHECK_EQ(tmcl::lsp::path_to_uri("/a b/c.tmc"), "file:///a%20b/c.tmc");
#ifdef _WIN32
  // A drive's path: VS Code writes the colon as %3A; both spellings name the file.
  CHECK_EQ(tmcl::lsp::uri_to_path("file:///c%3A/work/a.tmc"), "c:/work/a.tmc");
  CHECK_EQ(tmcl::lsp::uri_to_path("file:///C:/work/a.tmc"), "C:/work/a.tmc");
  CHECK_EQ(tmcl::lsp::path_to_uri("C:\\work\\a b.tmc"), "file:///C%3A/work/a%20b.tmc");
#else
  CHECK_EQ(tmcl::lsp::uri_to_path("file:///c%3A/work/a.tmc"), "/c:/work/a.tmc");  // a folder named "c:"
  CHECK_EQ(tmcl::lsp::path_to_uri("/a\\b"), "file:///a%5Cb");
#endif
}
