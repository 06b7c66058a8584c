// tmcl-lsp: the TMCL language server on standard input and output (docs/lsp.md). Reads framed
// JSON-RPC messages, hands each to tmcl::lsp::Server, writes its replies; all logic is in cli/lsp/.
// Exit status: 0 after shutdown and exit, 1 on exit without shutdown or end of input, 64 usage.
#include <unistd.h>

#include <cerrno>

#include <cstdio>
#include <cstring>
#include <string>

#include "tmcl/lsp/server.hpp"
#include "tmcl/version.hpp"

namespace {

const char* kUsage = R"(usage: tmcl-lsp [--stdio]
The TMCL language server: speaks the Language Server Protocol on standard input and output.
Editors start it themselves (docs/editors.md); settings come from .tmcl-lsp.json in the
workspace root and from initializationOptions, which win
({"target": "usb-2-sd", "includeDirs": ["lib"]}, docs/lsp.md).

options:
  --stdio    talk over standard input and output (the default and only transport)
  --help     show this help
  --version  show the version

exit status: 0 after shutdown and exit, 1 when the input ends or exit comes without shutdown,
             64 usage error, 74 standard output could not be written
)";

bool write_all(const std::string& s) {
  std::size_t done = 0;
  while (done < s.size()) {
    ssize_t n = ::write(1, s.data() + done, s.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (a == "--version") {
      std::puts(tmcl::version_line("tmcl-lsp").c_str());
      return 0;
    }
    if (a == "--stdio") continue;
    std::fprintf(stderr, "tmcl-lsp: unknown option '%s'\n(see tmcl-lsp --help)\n", a.c_str());
    return 64;
  }
  tmcl::lsp::Server server;
  tmcl::lsp::Reader reader(0);
  std::string body, error;
  for (;;) {
    auto status = reader.next(body, error);
    if (status == tmcl::lsp::Reader::Status::End) return 1;
    std::vector<std::string> out;
    if (status == tmcl::lsp::Reader::Status::BadHeader) {
      out.push_back(R"({"jsonrpc":"2.0","id":null,"error":{"code":-32700,"message":)" + tmcl::json::quote(error) + "}}");
    } else {
      out = server.handle(body);
    }
    for (const auto& m : out)
      if (!write_all(tmcl::lsp::frame(m))) return 74;
    if (server.exited()) return server.exit_code();
  }
}
