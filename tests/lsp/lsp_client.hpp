// The scripted LSP client of the language server's protocol tests: it drives a Server in process
// (no pipes), keeps the notifications it sends, and builds the usual request parameters.
#pragma once

#include <string>
#include <vector>

#include "check.hpp"
#include "tmcl/json.hpp"
#include "tmcl/lsp/server.hpp"

namespace tmcl_test {

using tmcl::json::Value;

struct Client {
  tmcl::lsp::Server server;
  int next_id = 1;
  std::vector<Value> notifications;
  Value last;  // the last response (replies are read through references into it)

  // Sends a request; returns its response (notifications sent meanwhile are kept).
  const Value& request(const std::string& method, const std::string& params) {
    int id = next_id++;
    std::string body = R"({"jsonrpc":"2.0","id":)" + std::to_string(id) + R"(,"method":")" + method + R"(","params":)" + params + "}";
    return send(body, id);
  }
  void notify(const std::string& method, const std::string& params) {
    send(R"({"jsonrpc":"2.0","method":")" + method + R"(","params":)" + params + "}", -1);
  }
  const Value& send(const std::string& body, int id) {
    Value& response = last;
    response = Value();
    for (const std::string& out : server.handle(body)) {
      Value v;
      tmcl::json::Error e;
      if (!tmcl::json::parse(out, v, e)) tmcl_test::fail(__FILE__, __LINE__, "server sent bad JSON: " + out);
      if (v.contains("method")) notifications.push_back(v);
      else if (v["id"].as_int(-2) == id || id == 0) response = v;
    }
    return response;
  }
  void open(const std::string& uri, const std::string& text) {
    notify("textDocument/didOpen", R"({"textDocument":{"uri":")" + uri + R"(","languageId":"tmcl","version":1,"text":)" +
                                       tmcl::json::quote(text) + "}}");
  }
  Value last_diagnostics(const std::string& uri) {
    for (auto it = notifications.rbegin(); it != notifications.rend(); ++it)
      if ((*it)["params"]["uri"].as_string() == uri) return (*it)["params"]["diagnostics"];
    return Value();
  }
};

inline std::string pos(const std::string& uri, int line, int ch) {
  return R"({"textDocument":{"uri":")" + uri + R"("},"position":{"line":)" + std::to_string(line) + R"(,"character":)" +
         std::to_string(ch) + "}}";
}

inline void start(Client& c, const std::string& options = R"({"target":"usb-2-sd"})") {
  Value r = c.request("initialize", R"({"processId":null,"capabilities":{},"initializationOptions":)" + options + "}");
  CHECK(r["result"]["capabilities"]["hoverProvider"].as_bool());
  c.notify("initialized", "{}");
}

}  // namespace tmcl_test
