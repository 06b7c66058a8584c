// Protocol tests of the language server's code actions (cli/lsp/actions.cpp) and of the
// analysis' notes as related information: every did-you-mean fix the assembler attaches, "add
// RETI" and "remove unreachable code" from the analysis, which diagnostics a request's range or
// context selects, and that applying an action's edit makes its warning go away.
#include "check.hpp"
#include "lsp_client.hpp"

using tmcl::json::Value;
using tmcl_lsp_test::Client;
using tmcl_lsp_test::start;

namespace {

std::string actions_params(const std::string& uri, int l0, int c0, int l1, int c1, const std::string& context = "{\"diagnostics\":[]}") {
  return R"({"textDocument":{"uri":")" + uri + R"("},"range":{"start":{"line":)" + std::to_string(l0) + R"(,"character":)" +
         std::to_string(c0) + R"(},"end":{"line":)" + std::to_string(l1) + R"(,"character":)" + std::to_string(c1) +
         R"(}},"context":)" + context + "}";
}

Value actions(Client& c, const std::string& uri, int l0, int c0, int l1, int c1, const std::string& context = "{\"diagnostics\":[]}") {
  return c.request("textDocument/codeAction", actions_params(uri, l0, c0, l1, c1, context))["result"];
}

// The one edit of an action, as JSON text: {"uri":[{"range":...,"newText":...}]}.
std::string edit_of(const Value& action) { return tmcl::json::write(action["edit"]["changes"]); }

// Applies the action's one edit to the open document `uri` as an incremental change.
void apply(Client& c, const std::string& uri, const Value& action, int version) {
  const Value& edit = action["edit"]["changes"][uri].at(0);
  Value change = Value::object();
  change.set("range", edit["range"]);
  change.set("text", edit["newText"]);
  c.notify("textDocument/didChange", R"({"textDocument":{"uri":")" + uri + R"(","version":)" + std::to_string(version) +
                                         R"(},"contentChanges":[)" + tmcl::json::write(change) + "]}");
}

bool has_code(const Value& diags, const std::string& code) {
  for (const Value& d : diags.items())
    if (d["code"].as_string() == code) return true;
  return false;
}

}  // namespace

TEST(capability_is_announced) {
  Client c;
  Value r = c.request("initialize", R"({"processId":null,"capabilities":{}})");
  CHECK_EQ(tmcl::json::write(r["result"]["capabilities"]["codeActionProvider"]), R"({"codeActionKinds":["quickfix"]})");
}

TEST(did_you_mean_fixes_come_from_the_diagnostics) {
  Client c;
  start(c);
  const std::string uri = "file:///work/dym.tmc";
  c.open(uri,
         "#inclde x\n"                // 0: unknown directive
         "Loop:\n"                    // 1
         "  SAPP 4, 0, 1\n"           // 2: unknown mnemonic
         "  MVP ABSS, 0, 1\n"         // 3: unknown keyword
         "  JA Lop\n"                 // 4: undefined label
         "  #include \"TMCLParm.tmc\"\n");  // 5: include file not found
  CHECK_EQ(c.last_diagnostics(uri).size(), 5u);
  Value a = actions(c, uri, 2, 3, 2, 3);  // a cursor inside SAPP
  CHECK_EQ(a.size(), 1u);
  CHECK_EQ(a.at(0)["title"].as_string(), "replace 'SAPP' with 'SAP'");
  CHECK_EQ(a.at(0)["kind"].as_string(), "quickfix");
  CHECK(a.at(0)["isPreferred"].as_bool());
  CHECK_EQ(a.at(0)["diagnostics"].at(0)["message"].as_string(), "unknown instruction mnemonic 'SAPP'");
  CHECK_EQ(edit_of(a.at(0)),
           R"({"file:///work/dym.tmc":[{"range":{"start":{"line":2,"character":2},"end":{"line":2,"character":6}},"newText":"SAP"}]})");
  a = actions(c, uri, 3, 0, 3, 0);  // the start of the line touches nothing: ABSS starts at 6
  CHECK_EQ(a.size(), 0u);
  a = actions(c, uri, 3, 0, 3, 16);  // the whole line
  CHECK_EQ(a.size(), 1u);
  CHECK_EQ(a.at(0)["title"].as_string(), "replace 'ABSS' with 'ABS'");
  CHECK_EQ(tmcl::json::write(a.at(0)["edit"]["changes"][uri].at(0)["range"]),
           R"({"start":{"line":3,"character":6},"end":{"line":3,"character":10}})");
  a = actions(c, uri, 4, 8, 4, 8);  // the cursor just after Lop
  CHECK_EQ(a.size(), 1u);
  CHECK_EQ(a.at(0)["title"].as_string(), "replace 'Lop' with 'Loop'");
  a = actions(c, uri, 0, 0, 0, 0);
  CHECK_EQ(a.size(), 1u);
  CHECK_EQ(a.at(0)["title"].as_string(), "replace '#inclde' with '#include'");
  // The include name is replaced between its quotes.
  a = actions(c, uri, 5, 12, 5, 12);
  CHECK_EQ(a.size(), 1u);
  CHECK_EQ(a.at(0)["title"].as_string(), "replace 'TMCLParm.tmc' with 'TMCLParam.tmc'");
  CHECK_EQ(tmcl::json::write(a.at(0)["edit"]["changes"][uri].at(0)["range"]),
           R"({"start":{"line":5,"character":12},"end":{"line":5,"character":24}})");
  // Several lines at once: every fix in the range.
  CHECK_EQ(actions(c, uri, 0, 0, 5, 0).size(), 4u);
  // A diagnostic the client lists in the context counts even outside the range.
  std::string listed = R"({"diagnostics":[)" + tmcl::json::write(c.last_diagnostics(uri).at(0)) + "]}";
  a = actions(c, uri, 1, 0, 1, 0, listed);
  CHECK_EQ(a.size(), 1u);
  // Only other kinds asked for: nothing.
  CHECK_EQ(actions(c, uri, 2, 3, 2, 3, R"({"diagnostics":[],"only":["refactor"]})").size(), 0u);
  CHECK_EQ(actions(c, uri, 2, 3, 2, 3, R"({"diagnostics":[],"only":["quickfix"]})").size(), 1u);
}

TEST(applying_a_did_you_mean_fix_clears_the_error) {
  Client c;
  start(c);
  const std::string uri = "file:///work/fix.tmc";
  c.open(uri, "Loop:\n  SAPP 4, 0, 1\n  JA Loop\n");
  Value a = actions(c, uri, 1, 2, 1, 2);
  CHECK_EQ(a.size(), 1u);
  apply(c, uri, a.at(0), 2);
  CHECK_EQ(c.server.document(uri)->text, "Loop:\n  SAP 4, 0, 1\n  JA Loop\n");
  CHECK_EQ(c.last_diagnostics(uri).size(), 0u);
  // A parameter name from a bundled include file, misspelt.
  const std::string named = "file:///work/named.tmc";
  c.open(named, "#include TMCLParam.tmc\n  SAP MaxPositioningSped, 0, 1\n");
  a = actions(c, named, 1, 10, 1, 10);
  CHECK_EQ(a.size(), 1u);
  CHECK_EQ(a.at(0)["title"].as_string(), "replace 'MaxPositioningSped' with 'APMaxPositioningSpeed'");
  apply(c, named, a.at(0), 2);
  CHECK_EQ(c.last_diagnostics(named).size(), 0u);
}

TEST(add_reti_where_a_handler_runs_on) {
  Client c;
  start(c);
  const std::string uri = "file:///work/reti.tmc";
  c.open(uri,
         "  VECT 0, Handler\n"
         "  EI 0\n"
         "  EI 255\n"
         "  CSUB Sub\n"
         "Loop:\n"
         "  JA Loop\n"
         "Handler:\n"
         "\tMVP ABS, 0, 100  // moves\n"  // 7: the handler's last instruction
         "Sub:\n"
         "  RSUB\n");
  Value d = c.last_diagnostics(uri);
  CHECK(has_code(d, "reti"));
  Value a = actions(c, uri, 7, 1, 7, 1);
  CHECK_EQ(a.size(), 1u);
  CHECK_EQ(a.at(0)["title"].as_string(), "add RETI");
  CHECK_EQ(a.at(0)["diagnostics"].at(0)["code"].as_string(), "reti");
  // On its own line after the instruction, indented as the formatter indents instructions.
  CHECK_EQ(edit_of(a.at(0)),
           R"({"file:///work/reti.tmc":[{"range":{"start":{"line":8,"character":0},"end":{"line":8,"character":0}},"newText":"  RETI\n"}]})");
  apply(c, uri, a.at(0), 2);
  CHECK(!has_code(c.last_diagnostics(uri), "reti"));
  CHECK_EQ(c.last_diagnostics(uri).size(), 0u);
  // No fix for a warning without one: the line of "JA Loop" has none.
  CHECK_EQ(actions(c, uri, 5, 0, 5, 9).size(), 0u);
}

TEST(add_reti_at_the_end_of_a_handler_that_ends_the_program) {
  Client c;
  start(c);
  const std::string uri = "file:///work/end.tmc";
  c.open(uri, "  VECT 0, Handler\n  EI 0\n  EI 255\nLoop:\n  JA Loop\nHandler:\n  MVP ABS, 0, 100\n");
  // The warning is at the assembler's STOP, which has no line: shown on the first line.
  Value d = c.last_diagnostics(uri);
  CHECK_EQ(d.size(), 1u);
  CHECK_EQ(d.at(0)["message"].as_string(), "STOP ends the program inside interrupt handler 'Handler', without RETI");
  std::string listed = R"({"diagnostics":[)" + tmcl::json::write(d.at(0)) + "]}";
  Value a = actions(c, uri, 6, 4, 6, 4, listed);
  CHECK_EQ(a.size(), 1u);
  CHECK_EQ(edit_of(a.at(0)),
           R"({"file:///work/end.tmc":[{"range":{"start":{"line":7,"character":0},"end":{"line":7,"character":0}},"newText":"  RETI\n"}]})");
  apply(c, uri, a.at(0), 2);
  CHECK_EQ(c.last_diagnostics(uri).size(), 0u);
  // Without a final newline the RETI goes on a new line after the last one.
  c.open("file:///work/end2.tmc", "  VECT 0, H\n  EI 0\n  EI 255\nL:\n  JA L\nH:\n  MVP ABS, 0, 100");
  listed = R"({"diagnostics":[)" + tmcl::json::write(c.last_diagnostics("file:///work/end2.tmc").at(0)) + "]}";
  a = actions(c, "file:///work/end2.tmc", 6, 0, 6, 0, listed);
  CHECK_EQ(edit_of(a.at(0)),
           R"({"file:///work/end2.tmc":[{"range":{"start":{"line":6,"character":17},"end":{"line":6,"character":17}},"newText":"\n  RETI"}]})");
}

TEST(remove_unreachable_code) {
  Client c;
  start(c);
  const std::string uri = "file:///work/dead.tmc";
  c.open(uri,
         "  JA Start\n"
         "  MVP ABS, 0, 1   // dead\n"  // 1: the run starts
         "Dead:\n"
         "  // more\n"
         "\n"
         "  MVP ABS, 0, 2\n"  // 5: the run ends
         "Start:\n"
         "  STOP\n");
  Value d = c.last_diagnostics(uri);
  CHECK_EQ(d.size(), 1u);
  CHECK_EQ(d.at(0)["code"].as_string(), "unreachable");
  CHECK_EQ(actions(c, uri, 0, 0, 0, 5).size(), 0u);  // not on the warning's line
  Value a = actions(c, uri, 1, 3, 1, 3);
  CHECK_EQ(a.size(), 1u);
  CHECK_EQ(a.at(0)["title"].as_string(), "remove unreachable code");
  // Exactly the lines of the run; the label stays (something may still name it).
  CHECK_EQ(edit_of(a.at(0)),
           R"({"file:///work/dead.tmc":[{"range":{"start":{"line":1,"character":0},"end":{"line":6,"character":0}},"newText":"Dead:\n"}]})");
  apply(c, uri, a.at(0), 2);
  CHECK_EQ(c.server.document(uri)->text, "  JA Start\nDead:\nStart:\n  STOP\n");
  CHECK_EQ(c.last_diagnostics(uri).size(), 0u);
  // One instruction; a label in front of it stays on its own line.
  c.open("file:///work/one.tmc", "  JA S\nX: MVP ABS, 0, 1\nS:\n  STOP\n");
  a = actions(c, "file:///work/one.tmc", 1, 4, 1, 4);
  CHECK_EQ(edit_of(a.at(0)),
           R"({"file:///work/one.tmc":[{"range":{"start":{"line":1,"character":0},"end":{"line":2,"character":0}},"newText":"X:\n"}]})");
  // A constant inside the run would go with it: no fix then, only the warning.
  c.open("file:///work/const.tmc", "  JA S\n  MVP ABS, 0, 1\nK = 3\n  MVP ABS, 0, K\nS:\n  STOP\n");
  CHECK(has_code(c.last_diagnostics("file:///work/const.tmc"), "unreachable"));
  CHECK_EQ(actions(c, "file:///work/const.tmc", 1, 0, 3, 0).size(), 0u);
}

TEST(fix_in_an_included_file_edits_that_file) {
  Client c;
  start(c);
  c.open("file:///work/tail.inc", "  JA Out\n  MVP ABS, 0, 1\nOut:\n");
  c.open("file:///work/top.tmc", "#include tail.inc\n  STOP\n");
  Value d = c.last_diagnostics("file:///work/top.tmc");
  CHECK_EQ(d.size(), 1u);
  Value a = actions(c, "file:///work/top.tmc", 0, 3, 0, 3);  // shown on the #include line
  CHECK_EQ(a.size(), 1u);
  CHECK_EQ(edit_of(a.at(0)),
           R"({"file:///work/tail.inc":[{"range":{"start":{"line":1,"character":0},"end":{"line":2,"character":0}},"newText":""}]})");
}

TEST(bad_code_action_requests) {
  Client c;
  start(c);
  c.open("file:///work/x.tmc", "  STOP\n");
  CHECK_EQ(c.request("textDocument/codeAction", actions_params("file:///work/none.tmc", 0, 0, 0, 0))["error"]["code"].as_int(), -32602);
  Value no_range = c.request("textDocument/codeAction", R"({"textDocument":{"uri":"file:///work/x.tmc"},"context":{}})");
  CHECK_EQ(no_range["error"]["message"].as_string(), "missing params.range (start and end line/character)");
  CHECK_EQ(actions(c, "file:///work/x.tmc", 0, 0, 0, 0, "null").size(), 0u);  // no context: fine, nothing to fix
}

// The analysis' notes (where a subroutine starts, where it is called from) are related
// information at their own places, in whichever file that is.
TEST(analysis_notes_are_related_information) {
  Client c;
  start(c);
  c.open("file:///work/sub.inc", "Sub:\n  MVP ABS, 0, 1\n  RETI\n");
  c.open("file:///work/calls.tmc", "  CSUB Sub\n  STOP\n#include sub.inc\n");
  Value d = c.last_diagnostics("file:///work/calls.tmc");
  CHECK_EQ(d.size(), 2u);  // the STOP is unreachable too: the ignored RETI runs on
  CHECK_EQ(d.at(1)["code"].as_string(), "reti");
  CHECK_EQ(d.at(1)["range"]["start"]["line"].as_int(), 2);  // the #include line
  const Value& rel = d.at(1)["relatedInformation"];
  CHECK_EQ(rel.size(), 3u);
  CHECK_EQ(rel.at(0)["location"]["uri"].as_string(), "file:///work/sub.inc");  // the warning's own place
  CHECK_EQ(rel.at(0)["location"]["range"]["start"]["line"].as_int(), 2);
  CHECK_EQ(rel.at(1)["message"].as_string(), "subroutine 'Sub' starts here");
  CHECK_EQ(tmcl::json::write(rel.at(1)["location"]),
           R"({"uri":"file:///work/sub.inc","range":{"start":{"line":1,"character":2},"end":{"line":1,"character":5}}})");
  CHECK_EQ(rel.at(2)["message"].as_string(), "called from here");
  CHECK_EQ(tmcl::json::write(rel.at(2)["location"]),
           R"({"uri":"file:///work/calls.tmc","range":{"start":{"line":0,"character":2},"end":{"line":0,"character":6}}})");
}
