// tmcl-lsp: the TMCL language server on standard input and output (docs/lsp.md). Reads framed
// JSON-RPC messages, hands each to tmcl::lsp::Server, writes its replies; all logic is in cli/lsp/.
// Its one option is declared in a table like every tool's (tmcl/options.hpp).
// Exit status: 0 after shutdown and exit, 1 on exit without shutdown or end of input, 64 usage.
#include <unistd.h>

#include <cerrno>

#include <cstdio>
#include <cstring>
#include <string>

#include "tmcl/lsp/server.hpp"
#include "tmcl/options.hpp"
#include "tmcl/os_console.hpp"

namespace {

const char* kUsage = R"(usage: tmcl-lsp [--stdio]
The TMCL language server: speaks the Language Server Protocol on standard input and output.
Editors start it themselves (editors.md); settings come from .tmcl-lsp.json in the
workspace root and from initializationOptions, which win
({"target": "usb-2-sd", "includeDirs": ["lib"]}, lsp.md).

options:
)";

const char* kEpilogue = R"(
exit status: 0 after shutdown and exit, 1 when the input ends or exit comes without shutdown,
             64 usage error, 74 standard output could not be written

documentation: the .md files named above are in share/doc/tmcl/ of the installation
               (/usr/share/doc/tmcl/ from the Debian package); also man tmcl-lsp
)";

// The options, declared once (tmcl/options.hpp): --help, the man-page check and completion follow.
tmcl::cli::Tool command_line() {
  tmcl::cli::Tool t;
  t.name = "tmcl-lsp";
  t.usage = kUsage;
  t.epilogue = kEpilogue;
  t.column = 13;
  t.options = {{"--stdio", "", "talk over standard input and output (the default and only transport)", {}}};
  t.operands = [](const std::vector<std::string>&, const std::vector<std::string>&) { return tmcl::cli::Values(); };
  return t;
}

int usage_error(const std::string& msg) {
  std::fprintf(stderr, "tmcl-lsp: %s\n(see tmcl-lsp --help)\n", msg.c_str());
  return 64;
}

bool write_all(const std::string& s) {
  std::size_t done = 0;
  while (done < s.size()) {
    const auto chunk = static_cast<unsigned>(std::min<std::size_t>(s.size() - done, 1u << 30));  // Windows: unsigned
    ssize_t n = ::write(1, s.data() + done, chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  tmcl::os::init_console();  // Windows: bytes as they are, UTF-8 (os_console.hpp)
  const tmcl::cli::Result cl = tmcl::cli::parse(command_line(), argc, argv);
  if (cl.status == tmcl::cli::Result::Status::Done) return 0;
  if (cl.status == tmcl::cli::Result::Status::Error) return usage_error(cl.error);
  if (!cl.operands.empty()) return usage_error("unexpected argument '" + cl.operands[0] + "' (editors start tmcl-lsp without any)");
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
