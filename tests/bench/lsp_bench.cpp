// Language server speed (issue 16): a scripted client opens a 10,000-line program, then times
// (1) a one-character didChange until its publishDiagnostics is produced, (2) hover on a
// parameter number, (3) completion of an operand, (4) the semantic tokens of the whole file
// (the JSON reply written). Best of several runs, in milliseconds.
// Prints "figure<TAB>goal<TAB>measured" rows for tests/bench/run_all.sh.
#include <chrono>
#include <cstdio>
#include <string>

#include "tmcl/json.hpp"
#include "tmcl/lsp/server.hpp"

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main() {
  std::string text = "Speed = 51200\n";
  for (int i = 0; i < 2500; ++i) {
    std::string n = std::to_string(i);
    text += "L" + n + ":\n  SAP 4, 0, Speed  // speed\n  MVP ABS, 0, " + n + "\n  WAIT POS, 0, 0\n";
  }
  text += "  JA L0\n";
  tmcl::lsp::Server server;
  server.handle(R"({"jsonrpc":"2.0","id":1,"method":"initialize","params":{"capabilities":{},"initializationOptions":{"target":"usb-2-sd"}}})");
  server.handle(R"({"jsonrpc":"2.0","method":"textDocument/didOpen","params":{"textDocument":{"uri":"file:///bench.tmc","languageId":"tmcl","version":1,"text":)" +
                tmcl::json::quote(text) + "}}}");
  int lines = 0;
  for (char c : text) lines += c == '\n';
  double best_change = 1e9, best_hover = 1e9, best_completion = 1e9, best_tokens = 1e9;
  int version = 1;
  for (int run = 0; run < 20; ++run) {
    // Alternately insert and delete one character in an MVP operand on line 5000.
    std::string change = run % 2 == 0 ? R"({"range":{"start":{"line":4999,"character":14},"end":{"line":4999,"character":14}},"text":"1"})"
                                      : R"({"range":{"start":{"line":4999,"character":14},"end":{"line":4999,"character":15}},"text":""})";
    auto t0 = std::chrono::steady_clock::now();
    auto out = server.handle(R"({"jsonrpc":"2.0","method":"textDocument/didChange","params":{"textDocument":{"uri":"file:///bench.tmc","version":)" +
                             std::to_string(++version) + R"(},"contentChanges":[)" + change + "]}}");
    best_change = std::min(best_change, ms_since(t0));
    if (out.empty()) std::printf("no diagnostics published!\n");
    t0 = std::chrono::steady_clock::now();
    out = server.handle(R"({"jsonrpc":"2.0","id":2,"method":"textDocument/hover","params":{"textDocument":{"uri":"file:///bench.tmc"},"position":{"line":8998,"character":6}}})");
    best_hover = std::min(best_hover, ms_since(t0));
    if (out.empty() || out[0].find("Maximum positioning speed") == std::string::npos) std::printf("hover wrong: %s\n", out.empty() ? "" : out[0].c_str());
    t0 = std::chrono::steady_clock::now();
    out = server.handle(R"({"jsonrpc":"2.0","id":3,"method":"textDocument/completion","params":{"textDocument":{"uri":"file:///bench.tmc"},"position":{"line":8999,"character":6}}})");
    best_completion = std::min(best_completion, ms_since(t0));
    t0 = std::chrono::steady_clock::now();
    out = server.handle(R"({"jsonrpc":"2.0","id":4,"method":"textDocument/semanticTokens/full","params":{"textDocument":{"uri":"file:///bench.tmc"}}})");
    best_tokens = std::min(best_tokens, ms_since(t0));
    if (out.empty() || out[0].size() < 100000) std::printf("semantic tokens wrong: %.200s\n", out.empty() ? "" : out[0].c_str());
  }
  // Code actions in a copy with a misspelt mnemonic in every block: 2,500 errors, each with its
  // did-you-mean fix; a request for one line still turns every diagnostic into JSON.
  std::string typos = text;
  for (std::size_t at = 0; (at = typos.find("  SAP ", at)) != std::string::npos; at += 7) typos.replace(at, 6, "  SAPP ");
  server.handle(R"({"jsonrpc":"2.0","method":"textDocument/didOpen","params":{"textDocument":{"uri":"file:///typos.tmc","languageId":"tmcl","version":1,"text":)" +
                tmcl::json::quote(typos) + "}}}");
  double best_actions = 1e9;
  for (int run = 0; run < 20; ++run) {
    auto t0 = std::chrono::steady_clock::now();
    auto out = server.handle(R"({"jsonrpc":"2.0","id":4,"method":"textDocument/codeAction","params":{"textDocument":{"uri":"file:///typos.tmc"},)"
                             R"("range":{"start":{"line":4998,"character":3},"end":{"line":4998,"character":3}},"context":{"diagnostics":[]}}})");
    best_actions = std::min(best_actions, ms_since(t0));
    if (out.empty() || out[0].find("replace 'SAPP' with 'SAP'") == std::string::npos) std::printf("code action wrong: %s\n", out.empty() ? "" : out[0].c_str());
  }
  std::printf("lsp: diagnostics after a 1-character edit, %d-line file (ms)\t<= 20\t%.2f\n", lines, best_change);
  std::printf("lsp: hover on a parameter number, %d-line file (ms)\t<= 5\t%.3f\n", lines, best_hover);
  std::printf("lsp: completion of an operand, %d-line file (ms)\t<= 5\t%.3f\n", lines, best_completion);
  std::printf("lsp: semantic tokens of the whole %d-line file (ms)\t<= 20\t%.2f\n", lines, best_tokens);
  std::printf("lsp: code actions at a line, %d-line file with 2500 errors (ms)\t<= 5\t%.3f\n", lines, best_actions);
  return 0;
}
