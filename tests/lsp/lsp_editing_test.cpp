// Protocol tests of the language server's editing aids (issue 16, part 1): semantic tokens (full
// and range), inlay hints, prepareRename, the project settings file .tmcl-lsp.json and include
// completion from the include folders. Each request also gets its bad inputs: an unknown document
// and positions or ranges outside the document.
#ifndef _WIN32
#include <sys/stat.h>  // mkfifo
#endif

#include <filesystem>
#include <fstream>

#include "lsp_client.hpp"
#include "os_test.hpp"

using tmcl::json::Value;
using namespace tmcl_lsp_test;

namespace {

const char* kEditUri = "file:///work/e.tmc";

// The semantic tokens of a response, decoded from relative to absolute positions:
// "line:char:length:type:modifiers" each, space-separated.
std::string decode(const Value& result) {
  const Value& d = result["data"];
  std::string out;
  long long line = 0, ch = 0;
  for (std::size_t i = 0; i + 4 < d.size(); i += 5) {
    line += d.at(i).as_int();
    ch = d.at(i).as_int() ? d.at(i + 1).as_int() : ch + d.at(i + 1).as_int();
    out += (out.empty() ? "" : " ") + std::to_string(line) + ":" + std::to_string(ch) + ":" + std::to_string(d.at(i + 2).as_int()) + ":" +
           std::to_string(d.at(i + 3).as_int()) + ":" + std::to_string(d.at(i + 4).as_int());
  }
  return out;
}

std::string doc(const std::string& uri) { return R"({"textDocument":{"uri":")" + uri + R"("}})"; }

std::string range(const std::string& uri, int l0, int c0, int l1, int c1) {
  return R"({"textDocument":{"uri":")" + uri + R"("},"range":{"start":{"line":)" + std::to_string(l0) + R"(,"character":)" +
         std::to_string(c0) + R"(},"end":{"line":)" + std::to_string(l1) + R"(,"character":)" + std::to_string(c1) + "}}}";
}

// A scratch folder for the settings tests, removed at the end.
struct TempDir {
  std::string path;
  TempDir() {
    path = tmcl_test::make_temp_dir("tmcl-lsp-test");
    CHECK(!path.empty());
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  void write(const std::string& name, const std::string& text) const {
    std::filesystem::create_directories(std::filesystem::path(path + "/" + name).parent_path());
    std::ofstream(path + "/" + name) << text;
  }
  std::string uri(const std::string& name = "") const { return tmcl::lsp::path_to_uri(path + (name.empty() ? "" : "/" + name)); }
};

std::string hover_text(Client& c, const std::string& uri, int line, int ch) {
  return c.request("textDocument/hover", pos(uri, line, ch))["result"]["contents"]["value"].as_string();
}

std::vector<std::string> messages(const Client& c, int type) {
  std::vector<std::string> out;
  for (const Value& n : c.notifications)
    if (n["method"].as_string() == "window/showMessage" && n["params"]["type"].as_int() == type) out.push_back(n["params"]["message"].as_string());
  return out;
}

}  // namespace

TEST(capabilities_declare_tokens_hints_and_prepare_rename) {
  Client c;
  Value r = c.request("initialize", R"({"processId":null,"capabilities":{}})");
  const Value& caps = r["result"]["capabilities"];
  CHECK_EQ(tmcl::json::write(caps["semanticTokensProvider"]),
           R"({"legend":{"tokenTypes":["keyword","enumMember","function","variable","number","comment","macro","string"],)"
           R"("tokenModifiers":["declaration","readonly"]},"full":true,"range":true})");
  CHECK(caps["inlayHintProvider"].as_bool());
  CHECK(caps["renameProvider"]["prepareProvider"].as_bool());
}

TEST(semantic_tokens_full) {
  Client c;
  start(c);
  c.open(kEditUri,
         "#include TMCLParam.tmc\n"   // 0
         "Speed = 1000 // fast\n"     // 1
         "Loop:\n"                    // 2
         "  SAP 4, 0, Speed\n"        // 3
         "  MVP ABS, 0, 100\n"        // 4
         "  JA loop\n"                // 5: names are case-insensitive
         "/* two\n"                   // 6
         "   lines */ STOP // \xC3\xA9!\n"  // 7: é is one UTF-16 unit
         "Stop = 3\n"                 // 8: a constant named like a mnemonic
         "  WAIT TICKS, 0, Stop\n"    // 9
         "  JA Nowhere\n");           // 10: undefined, no token
  Value r = c.request("textDocument/semanticTokens/full", doc(kEditUri))["result"];
  CHECK_EQ(decode(r),
           "0:0:8:6:0 0:9:13:7:0 "
           "1:0:5:3:3 1:8:4:4:0 1:13:7:5:0 "
           "2:0:4:2:1 "
           "3:2:3:0:0 3:6:1:4:0 3:9:1:4:0 3:12:5:3:2 "
           "4:2:3:0:0 4:6:3:1:0 4:11:1:4:0 4:14:3:4:0 "
           "5:2:2:0:0 5:5:4:2:0 "
           "6:0:6:5:0 7:0:11:5:0 7:12:4:0:0 7:17:5:5:0 "
           "8:0:4:3:3 8:7:1:4:0 "
           "9:2:4:0:0 9:7:5:1:0 9:14:1:4:0 9:17:4:3:2 "
           "10:2:2:0:0");
  // The encoding itself: the first tokens as the protocol sends them (relative positions).
  CHECK_EQ(tmcl::json::write(r["data"]).substr(0, 31), "[0,0,8,6,0,0,9,13,7,0,1,0,5,3,3");
}

TEST(semantic_tokens_range_and_bad_input) {
  Client c;
  start(c);
  c.open(kEditUri, "Loop:\n  SAP 4, 0, 1\n  MVP ABS, 0, 100\n  JA Loop\n");
  Value r = c.request("textDocument/semanticTokens/range", range(kEditUri, 1, 0, 2, 8))["result"];
  CHECK_EQ(decode(r), "1:2:3:0:0 1:6:1:4:0 1:9:1:4:0 1:12:1:4:0 2:2:3:0:0 2:6:3:1:0");
  CHECK_EQ(tmcl::json::write(r["data"]).substr(0, 12), "[1,2,3,0,0,0");  // relative to the document start
  Value unknown = c.request("textDocument/semanticTokens/full", doc("file:///nowhere.tmc"));
  CHECK_EQ(unknown["error"]["code"].as_int(), -32602);
  CHECK_EQ(unknown["error"]["message"].as_string(), "unknown document 'file:///nowhere.tmc' (not opened with didOpen)");
  Value outside = c.request("textDocument/semanticTokens/range", range(kEditUri, 0, 0, 99, 0));
  CHECK_EQ(outside["error"]["code"].as_int(), -32602);
  CHECK_EQ(outside["error"]["message"].as_string(), "position line 99 is outside the document (5 lines)");
  CHECK_EQ(c.request("textDocument/semanticTokens/range", doc(kEditUri))["error"]["message"].as_string(), "missing params.range");
  CHECK_EQ(c.request("textDocument/semanticTokens/range", range(kEditUri, 2, 0, 1, 0))["error"]["message"].as_string(),
           "params.range ends before it starts");
}

TEST(inlay_hints_name_bare_parameter_numbers) {
  Client c;
  start(c);
  c.open(kEditUri,
         "Speed = 4\n"                    // 0
         "  SAP 4, 0, 1000\n"             // 1
         "  GAP 4 /* x */ , 0\n"          // 2: a comment after the number is still bare
         "  SAP 4+1, 0, 5\n"              // 3: an expression: no hint
         "  SAP Speed, 0, 5\n"            // 4: a name says it already
         "  SGP 77, 0, 1\n"               // 5: bank 0
         "  SGP 0, 3, 10\n"               // 6: bank 3, read from the later operand
         "  EI 1\n"                       // 7: an interrupt vector
         "  SAP 999, 0, 1\n"              // 8: not a parameter of the target
         "  MVP ABS, 0, 4\n");            // 9: a position, not a parameter
  Value r = c.request("textDocument/inlayHint", range(kEditUri, 0, 0, 10, 0))["result"];
  std::string got;
  for (const Value& h : r.items())
    got += std::to_string(h["position"]["line"].as_int()) + ":" + std::to_string(h["position"]["character"].as_int()) + " " +
           h["label"].as_string() + " (" + std::to_string(h["kind"].as_int()) + ")\n";
  CHECK_EQ(got,
           "1:7 : Maximum positioning speed (2)\n"
           "2:7 : Maximum positioning speed (2)\n"
           "5:8 : Auto start mode (2)\n"
           "6:7 : Timer 0 period (ms) (2)\n"
           "7:6 : TI_TIMER1 (2)\n");
  // Only the range asked for.
  CHECK_EQ(c.request("textDocument/inlayHint", range(kEditUri, 5, 0, 6, 0))["result"].size(), 1u);
  CHECK_EQ(c.request("textDocument/inlayHint", range("file:///nowhere.tmc", 0, 0, 1, 0))["error"]["code"].as_int(), -32602);
  CHECK_EQ(c.request("textDocument/inlayHint", range(kEditUri, 0, 0, 50, 0))["error"]["message"].as_string(),
           "position line 50 is outside the document (11 lines)");
}

TEST(inlay_hints_follow_the_target) {
  Client c;
  start(c, R"({"target":"tmc2300-eval"})");
  c.open(kEditUri, "  SAP 4, 0, 1000\n");
  Value r = c.request("textDocument/inlayHint", range(kEditUri, 0, 0, 1, 0))["result"];
  CHECK_EQ(r.size(), 1u);
  const tmcl::ParamInfo* p = tmcl::find_profile("tmc2300-eval")->axis_param(4);
  CHECK(p != nullptr);
  CHECK_EQ(r.at(0)["label"].as_string(), ": " + std::string(p ? p->name : ""));
}

TEST(prepare_rename) {
  Client c;
  start(c);
  c.open(kEditUri,
         "Speed = 1000\n"                 // 0
         "Loop: SAP 4, 0, Speed // c\n"   // 1
         "  MVP ABS, 0, 100\n"            // 2
         "  JA loop\n"                    // 3
         "  JA Nowhere\n");               // 4
  auto prepare = [&](int line, int ch) { return c.request("textDocument/prepareRename", pos(kEditUri, line, ch)); };
  CHECK_EQ(tmcl::json::write(prepare(1, 18)["result"]),
           R"({"range":{"start":{"line":1,"character":16},"end":{"line":1,"character":21}},"placeholder":"Speed"})");
  CHECK_EQ(tmcl::json::write(prepare(3, 6)["result"]),
           R"({"range":{"start":{"line":3,"character":5},"end":{"line":3,"character":9}},"placeholder":"loop"})");
  CHECK_EQ(prepare(1, 1)["result"]["placeholder"].as_string(), "Loop");  // a label before a mnemonic
  auto refused = [&](int line, int ch) {
    Value e = prepare(line, ch);
    CHECK_EQ(e["error"]["code"].as_int(), -32803);
    return e["error"]["message"].as_string();
  };
  CHECK_EQ(refused(1, 7), "'SAP' is an instruction mnemonic: only labels and constants can be renamed");
  CHECK_EQ(refused(1, 10), "'4' is a number: only labels and constants can be renamed");
  CHECK_EQ(refused(1, 25), "this is a comment: only labels and constants can be renamed");
  CHECK_EQ(refused(2, 7), "'ABS' is a keyword of MVP: only labels and constants can be renamed");
  CHECK_EQ(refused(4, 7), "'Nowhere' is not a defined label or constant: only labels and constants can be renamed");
  CHECK_EQ(refused(2, 0), "nothing to rename here: only labels and constants can be renamed");
  CHECK_EQ(c.request("textDocument/prepareRename", pos("file:///nowhere.tmc", 0, 0))["error"]["code"].as_int(), -32602);
  CHECK_EQ(prepare(40, 0)["error"]["message"].as_string(), "position line 40 is outside the document (6 lines)");
  // Names are case-insensitive: renaming 'loop' renames 'Loop' too.
  Value edit = c.request("textDocument/rename", R"({"textDocument":{"uri":"file:///work/e.tmc"},"position":{"line":3,"character":6},"newName":"Again"})")["result"];
  CHECK_EQ(edit["changes"]["file:///work/e.tmc"].size(), 2u);
  // Changing only the case respells the name everywhere; it is not "already defined".
  edit = c.request("textDocument/rename", R"({"textDocument":{"uri":"file:///work/e.tmc"},"position":{"line":3,"character":6},"newName":"LOOP"})")["result"];
  CHECK_EQ(edit["changes"]["file:///work/e.tmc"].size(), 2u);
  // Hover on that label shows the label, not the instruction after it.
  CHECK_EQ(hover_text(c, kEditUri, 1, 1), "label `Loop`: address 0");
}

TEST(hover_reads_the_bank_after_the_parameter) {
  Client c;
  start(c);
  c.open(kEditUri, "  SGP 0, 3, 10\n");
  CHECK_EQ(hover_text(c, kEditUri, 0, 6).substr(0, 22), "0: Timer 0 period (ms)");
}

TEST(project_file_sets_target_and_include_folders) {
  TempDir dir;
  dir.write(".tmcl-lsp.json", R"({"target": "usb-2-sd", "includeDirs": ["lib"]})");
  dir.write("lib/mylib.inc", "Far = 5\n");
  dir.write("other.inc", "Near = 1\n");
  dir.write("notes.txt", "not an include file\n");
  Client c;
  Value r = c.request("initialize", R"({"processId":null,"capabilities":{},"rootUri":")" + dir.uri() + R"("})");
  CHECK(r.contains("result"));
  c.notify("initialized", "{}");
  std::string main = dir.uri("main.tmc");
  c.open(main, "#include mylib.inc\n  SAP 4, 0, Far\n");
  CHECK_EQ(c.last_diagnostics(main).size(), 0u);  // found in lib/, relative to the file
  CHECK_EQ(hover_text(c, main, 1, 6), "4: Maximum positioning speed, 0…16777215 pps, RW, default 51200 pps (usb-2-sd)");
  // Include completion: beside the document, then the include folders, then the bundled files.
  std::string other = dir.uri("new.tmc");
  c.open(other, "#include \n");
  Value items = c.request("textDocument/completion", pos(other, 0, 9))["result"];
  CHECK(items.size() >= 4u);
  CHECK_EQ(items.at(0)["label"].as_string(), "other.inc");
  CHECK_EQ(items.at(0)["detail"].as_string(), dir.path + "/other.inc");
  CHECK_EQ(items.at(1)["label"].as_string(), "mylib.inc");
  CHECK_EQ(items.at(1)["detail"].as_string(), dir.path + "/lib/mylib.inc");
  CHECK_EQ(items.at(2)["detail"].as_string(), "bundled include file");
  for (const Value& i : items.items()) CHECK(i["label"].as_string() != "notes.txt");
  CHECK(messages(c, 1).empty());
}

// An include folder that cannot be searched is a warning, as tmclasm's -I (issue 28, item 9),
// shown at the document's first line; the folders that exist are searched as before.
TEST(an_include_folder_that_does_not_exist_is_a_warning) {
  TempDir dir;
  dir.write(".tmcl-lsp.json", R"({"includeDirs": ["lib", "nothere"]})");
  dir.write("lib/mylib.inc", "Far = 5\n");
  Client c;
  c.request("initialize", R"({"processId":null,"capabilities":{},"rootUri":")" + dir.uri() + R"("})");
  c.notify("initialized", "{}");
  std::string main = dir.uri("main.tmc");
  c.open(main, "#include mylib.inc\n  SAP 4, 0, Far\n");
  Value d = c.last_diagnostics(main);
  CHECK_EQ(d.size(), 1u);
  CHECK_EQ(d.at(0)["message"].as_string(), "include folder '" + dir.path + "/nothere' (-I) does not exist");
  CHECK_EQ(d.at(0)["severity"].as_int(), 2);
  CHECK_EQ(d.at(0)["range"]["start"]["line"].as_int(), 0);
}

TEST(initialization_options_override_the_project_file) {
  TempDir dir;
  dir.write(".tmcl-lsp.json", R"({"target": "usb-2-sd", "includeDirs": ["lib"]})");
  Client c;
  c.request("initialize", R"({"processId":null,"capabilities":{},"rootUri":null,"workspaceFolders":[{"uri":")" + dir.uri() +
                              R"(","name":"w"}],"initializationOptions":{"target":"generic","includeDirs":[]}})");
  dir.write("lib/mylib.inc", "Far = 5\n");
  std::string main = dir.uri("main.tmc");
  c.open(main, "#include mylib.inc\n  SAP 4, 0, 1\n");
  CHECK_EQ(c.last_diagnostics(main).size(), 1u);  // lib/ is not searched
  CHECK(hover_text(c, main, 1, 6).find("(generic)") != std::string::npos);
}

// Hover agrees with the assembler: generic accepts every parameter number (no warning), so a
// number its tables do not name is not "not a parameter"; a module's unknown number is.
TEST(hover_on_a_parameter_number_the_tables_do_not_name) {
  Client c;
  start(c, R"({"target":"generic"})");
  const std::string uri = "file:///work/unknown.tmc";
  c.open(uri, "SAP 6, 0, 1\nSAP 193, 0, 1\nSGP 200, 0, 1\n");
  CHECK_EQ(c.last_diagnostics(uri).size(), 0u);
  CHECK_EQ(hover_text(c, uri, 0, 4), "axis parameter 6: no name or range known; generic accepts every parameter number "
                                     "(the target setting picks a module's table)");
  CHECK(hover_text(c, uri, 1, 5).find("generic accepts every parameter number") != std::string::npos);
  CHECK_EQ(hover_text(c, uri, 2, 5).substr(0, 37), "global parameter 200 of bank 0: no na");
  Client d;
  start(d, R"({"target":"usb-2-sd"})");
  d.open(uri, "SAP 6, 0, 1\n");
  CHECK_EQ(d.last_diagnostics(uri).size(), 1u);  // -Wtarget: the module has no axis parameter 6
  CHECK_EQ(hover_text(d, uri, 0, 4), "axis parameter 6: not a parameter of usb-2-sd");
}

TEST(bad_project_file_is_reported_and_ignored) {
  TempDir dir;
  dir.write(".tmcl-lsp.json", "{\"target\": \"usb-2-sd\",\n \"includeDirs\": [\"lib\",]}\n");
  Client c;
  c.request("initialize", R"({"processId":null,"capabilities":{},"rootUri":")" + dir.uri() + R"("})");
  std::vector<std::string> errors = messages(c, 1);
  CHECK_EQ(errors.size(), 1u);
  CHECK_EQ(errors.empty() ? "" : errors[0], dir.path + "/.tmcl-lsp.json:2:24: error: expected a value, found ']'" +
                                                " (the file is ignored: target generic, no include folders)");
  std::string main = dir.uri("main.tmc");
  c.open(main, "  SAP 4, 0, 1\n");
  CHECK(hover_text(c, main, 0, 6).find("(generic)") != std::string::npos);
  // An unknown target and an unknown key.
  Client d;
  dir.write(".tmcl-lsp.json", R"({"target": "usb-3-sd", "colour": "red"})");
  d.request("initialize", R"({"processId":null,"capabilities":{},"rootPath":")" + dir.path + R"("})");
  errors = messages(d, 1);
  CHECK_EQ(errors.size(), 1u);
  const std::string bad_target = errors.empty() ? "" : errors[0];
  CHECK_EQ(bad_target, dir.path + "/.tmcl-lsp.json: error: \"target\": unknown target 'usb-3-sd'; did you mean 'usb-2-sd'? (see tmclasm "
                       "--list-targets; or a profile file, docs/profiles.md) (the file is ignored: target generic, no include folders)");
  // Not an object.
  Client e;
  dir.write(".tmcl-lsp.json", "[1]");
  e.request("initialize", R"({"processId":null,"capabilities":{},"rootUri":")" + dir.uri() + R"("})");
  CHECK_EQ(messages(e, 1).size(), 1u);
#ifndef _WIN32  // Windows has no named pipes among the files of a folder
  // A named pipe would block a reader until someone writes: it is refused, not opened.
  std::filesystem::remove(dir.path + "/.tmcl-lsp.json");
  CHECK(mkfifo((dir.path + "/.tmcl-lsp.json").c_str(), 0600) == 0);
  Client g;
  g.request("initialize", R"({"processId":null,"capabilities":{},"rootUri":")" + dir.uri() + R"("})");
  errors = messages(g, 1);
  CHECK_EQ(errors.empty() ? "" : errors[0], dir.path + "/.tmcl-lsp.json: error: not a regular file (the file is ignored: target generic, no include folders)");
  std::filesystem::remove(dir.path + "/.tmcl-lsp.json");
#endif
  dir.write(".tmcl-lsp.json", R"({"target": "usb-2-sd", "colour": "red"})");
  Client f;
  f.request("initialize", R"({"processId":null,"capabilities":{},"rootUri":")" + dir.uri() + R"("})");
  CHECK_EQ(messages(f, 1).size(), 0u);
  std::vector<std::string> warnings = messages(f, 2);
  CHECK_EQ(warnings.size(), 1u);
  CHECK_EQ(warnings.empty() ? "" : warnings[0], dir.path + "/.tmcl-lsp.json: warning: unknown setting \"colour\" (known: target, includeDirs)");
}

TEST(project_file_is_watched_and_read_again) {
  TempDir dir;
  Client c;
  c.request("initialize", R"({"processId":null,"rootUri":")" + dir.uri() +
                              R"(","capabilities":{"workspace":{"didChangeWatchedFiles":{"dynamicRegistration":true}}}})");
  c.notify("initialized", "{}");
  CHECK(!c.notifications.empty());
  if (c.notifications.empty()) return;
  const Value& reg = c.notifications.back();
  CHECK_EQ(reg["method"].as_string(), "client/registerCapability");
  CHECK_EQ(tmcl::json::write(reg["params"]),
           R"({"registrations":[{"id":"tmcl-lsp-settings","method":"workspace/didChangeWatchedFiles",)"
           R"("registerOptions":{"watchers":[{"globPattern":"**/.tmcl-lsp.json"}]}}]})");
  CHECK(c.send(R"({"jsonrpc":"2.0","id":"tmcl-lsp-watch","result":null})", 0).is_null());  // the client's answer is ignored
  std::string main = dir.uri("main.tmc");
  c.open(main, "  SAP 6, 0, 16\n");
  CHECK_EQ(c.last_diagnostics(main).size(), 0u);  // generic: any parameter number
  dir.write(".tmcl-lsp.json", R"({"target": "usb-2-sd"})");
  c.notify("workspace/didChangeWatchedFiles", R"({"changes":[{"uri":")" + dir.uri(".tmcl-lsp.json") + R"(","type":1}]})");
  CHECK_EQ(c.last_diagnostics(main).size(), 1u);  // re-checked for usb-2-sd
  std::filesystem::remove(dir.path + "/.tmcl-lsp.json");
  c.notify("workspace/didChangeWatchedFiles", R"({"changes":[{"uri":")" + dir.uri(".tmcl-lsp.json") + R"(","type":3}]})");
  CHECK_EQ(c.last_diagnostics(main).size(), 0u);  // back to the defaults
  // A client without dynamic registration is not asked.
  Client d;
  d.request("initialize", R"({"processId":null,"rootUri":")" + dir.uri() + R"(","capabilities":{}})");
  d.notify("initialized", "{}");
  CHECK(d.notifications.empty());
}

TEST(malformed_params_get_answers) {
  Client c;
  start(c);
  c.open(kEditUri, "Loop:\n  SAP 4, 0, 1\n  JA Loop\n");
  const char* methods[] = {"textDocument/semanticTokens/full", "textDocument/semanticTokens/range", "textDocument/inlayHint",
                           "textDocument/prepareRename"};
  const std::string bad[] = {
      "null", "[]", R"({"textDocument":5})", R"({"textDocument":{"uri":"file:///work/e.tmc"},"position":{"line":-1,"character":0}})",
      R"({"textDocument":{"uri":"file:///work/e.tmc"},"position":{"line":"1","character":0}})",
      R"({"textDocument":{"uri":"file:///work/e.tmc"},"range":{"start":{"line":0,"character":0},"end":{"line":2147483648,"character":0}}})",
      R"({"textDocument":{"uri":"file:///work/e.tmc"},"range":{"start":{"line":0},"end":{"line":1,"character":0}}})",
      R"({"textDocument":{"uri":"file:///work/e.tmc"},"range":[0,1]})",
  };
  for (const char* m : methods)
    for (const std::string& p : bad) {
      Value r = c.request(m, p);
      bool full = std::string(m) == "textDocument/semanticTokens/full";
      // Only the full tokens need nothing but the document; everything else is InvalidParams.
      if (full && p.find("file:///work/e.tmc") != std::string::npos) CHECK(r["result"]["data"].size() > 0u);
      else CHECK_EQ(r["error"]["code"].as_int(), -32602);
    }
  // The server still answers.
  CHECK(c.request("textDocument/semanticTokens/full", doc(kEditUri))["result"]["data"].size() > 0u);
  Value w = c.request("workspace/didChangeWatchedFiles", R"({"changes":5})");  // a notification sent as a request
  CHECK(w.contains("result"));
  c.notify("workspace/didChangeWatchedFiles", R"({"changes":[{"uri":5},{"type":1}]})");
  CHECK(!c.server.exited());
}

// The target's profile everywhere: hover, completion and diagnostics of a TMCM module; a first
// line that names a target wins over the settings; the setting may name a profile file.
TEST(hover_completion_and_diagnostics_follow_the_module) {
  Client c;
  start(c, R"({"target":"tmcm-1110"})");
  c.open(kEditUri, "  SAP 154, 0, 3\n  SAP 4, 0, 5000\n  SAP \n");
  CHECK_EQ(hover_text(c, kEditUri, 0, 6), "154: Pulse divisor, 0…13, RWE, default 3 (tmcm-1110)");
  Value d = c.last_diagnostics(kEditUri);
  CHECK_EQ(d.size(), 2u);  // the range of 4, and the unfinished SAP
  CHECK(d.at(0)["message"].as_string().find("0 to 2047") != std::string::npos);
  Value items = c.request("textDocument/completion", pos(kEditUri, 2, 6))["result"];
  bool divisor = false;
  for (const Value& i : items.items()) divisor = divisor || (i["label"].as_string() == "154" && i["detail"].as_string().find("Pulse divisor") != std::string::npos);
  CHECK(divisor);
}

// A parameter whose row the profile calls not simulated says so, and why (the profile's
// not-simulated= reason, which tmclrun's note gives at run time); a simulated one says nothing.
TEST(hover_of_a_parameter_tmclrun_does_not_simulate_says_why) {
  Client c;
  start(c, R"({"target":"tmcm-1110"})");
  c.open(kEditUri, "  SAP 213, 0, 1\n  SAP 4, 0, 100\n");
  CHECK_EQ(hover_text(c, kEditUri, 0, 6), "213: Group index, 0…255, RW, default 0 (tmcm-1110)\n\n"
                                          "not simulated by tmclrun: group moves are not modelled");
  CHECK(hover_text(c, kEditUri, 1, 6).find("not simulated") == std::string::npos);
}

// A bundled module is known to the server by its profile file alone (docs/profiles.md, "A new
// bundled profile"): the TMCM-6214's first line, hover, completion, its six motors and the names
// of its generated include file.
TEST(a_module_known_by_its_profile_file_alone) {
  Client c;
  start(c, R"({"target":"usb-2-sd"})");
  c.open(kEditUri, "// tmcl-target: tmcm-6214\n#include TMCM-6214.inc\n  SAP 40, 5, 100\n  SAP AP_DeviationAction, 5, 1\n  SAP \n");
  const std::string h = hover_text(c, kEditUri, 2, 6);
  CHECK(h.find("40: Position compare start") == 0);
  CHECK(h.find("(tmcm-6214)") != std::string::npos);
  Value d = c.last_diagnostics(kEditUri);
  CHECK_EQ(d.size(), 1u);  // the unfinished SAP only: 40 and 240 exist, and motor 5
  Value items = c.request("textDocument/completion", pos(kEditUri, 4, 6))["result"];
  bool compare = false;
  for (const Value& i : items.items())
    compare = compare || (i["label"].as_string() == "40" && i["detail"].as_string().find("Position compare start") != std::string::npos);
  CHECK(compare);
}

// The assembler's check of what the module's EEPROM keeps (STAP/RSAP/STGP/RSGP) is the server's too.
TEST(a_store_of_what_the_eeprom_does_not_keep_is_a_diagnostic) {
  Client c;
  start(c, R"({"target":"tmcm-1110"})");
  c.open(kEditUri, "  STAP 4, 0\n  RSAP 8, 0\n  STGP 77, 0\n  STGP 132, 0\n");
  Value d = c.last_diagnostics(kEditUri);
  CHECK_EQ(d.size(), 2u);  // 8 and 132; 4 has E, 77 is A
  CHECK_EQ(d.at(0)["range"]["start"]["line"].as_int(), 1);
  CHECK(d.at(0)["message"].as_string().find("axis parameter 8 (Target position reached) is not stored in the EEPROM of TMCM-1110") == 0);
  CHECK_EQ(d.at(1)["range"]["start"]["line"].as_int(), 3);
  CHECK(d.at(1)["message"].as_string().find("global parameter 132 (TMCL tick timer) is not stored in the EEPROM") == 0);
}

TEST(first_line_target_wins_over_the_settings) {
  Client c;
  start(c, R"({"target":"usb-2-sd"})");
  c.open(kEditUri, "// tmcl-target: pd60-1260\n  SAP 4, 0, 5000\n  SAP 153, 0, 1\n");
  CHECK(hover_text(c, kEditUri, 1, 6).find("(tmcm-1260)") != std::string::npos);
  Value d = c.last_diagnostics(kEditUri);
  CHECK_EQ(d.size(), 1u);  // 5000 pps is fine there; 153 does not exist
  CHECK(d.at(0)["message"].as_string().find("axis parameter 153 does not exist on TMCM-1260") != std::string::npos);
  // A name that is no target: an error on the first line, at the name.
  c.open("file:///work/f.tmc", "// tmcl-target: tmcm-9999\n  STOP\n");
  d = c.last_diagnostics("file:///work/f.tmc");
  CHECK_EQ(d.size(), 1u);
  CHECK_EQ(d.at(0)["range"]["start"]["line"].as_int(), 0);
  CHECK_EQ(d.at(0)["range"]["start"]["character"].as_int(), 16);
}

// A module based on another (tmcm-3351 on tmcm-3312): hover, completion and diagnostics are its own.
TEST(hover_and_completion_of_the_tmcm3351) {
  Client c;
  start(c, R"({"target":"generic"})");
  c.open(kEditUri, "// tmcl-target: tmcm-3351\n  SAP 22, 2, 512000\n  SGP 46, 3, 1\n  SAP 255, 0, 1\n  SAP \n");
  CHECK_EQ(hover_text(c, kEditUri, 1, 6), "22: Bow 1, 0…2147483647 pps³, RW, default 512000 pps³ (tmcm-3351)");
  Value d = c.last_diagnostics(kEditUri);
  CHECK_EQ(d.size(), 2u);  // 255 is the USB-2-SD's, not this module's; the unfinished SAP. Input 7 (46) is the TMCM-3351's.
  CHECK(d.at(0)["message"].as_string().find("axis parameter 255 does not exist on TMCM-3351") != std::string::npos);
  Value items = c.request("textDocument/completion", pos(kEditUri, 4, 6))["result"];
  bool closed_loop = false;
  for (const Value& i : items.items()) closed_loop = closed_loop || (i["label"].as_string() == "129" && i["detail"].as_string().find("Closed loop") != std::string::npos);
  CHECK(closed_loop);
}

TEST(the_target_setting_may_be_a_profile_file) {
  TempDir dir;
  dir.write("profiles/mine.profile",
            "tmcl-profile 1\nname mine\nfirmware 4242V100\nmotors 1\nprogram-memory 100\ncommands 1-6 128-137 255\n"
            "axis 4 \"My speed\" 0..100 RW default=7\n");
  dir.write(".tmcl-lsp.json", R"({"target": "profiles/mine.profile"})");
  Client c;
  c.request("initialize", R"({"processId":null,"capabilities":{},"rootUri":")" + dir.uri() + R"("})");
  CHECK(messages(c, 1).empty());
  const std::string main = dir.uri("main.tmc");
  c.open(main, "  SAP 4, 0, 1\n");
  CHECK_EQ(hover_text(c, main, 0, 6), "4: My speed, 0…100, RW, default 7 (mine)");
  // A malformed profile file is reported like a bad setting, naming its first error.
  dir.write("profiles/mine.profile", "tmcl-profile 1\nmotors x\n");
  Client e;
  e.request("initialize", R"({"processId":null,"capabilities":{},"rootUri":")" + dir.uri() + R"("})");
  auto errors = messages(e, 1);
  CHECK_EQ(errors.size(), 1u);
  CHECK(!errors.empty() && errors[0].find("mine.profile:2:8: error: expected a motor count") != std::string::npos);
}
