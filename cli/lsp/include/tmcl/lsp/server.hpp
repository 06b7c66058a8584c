// The TMCL language server (tmcl-lsp, docs/lsp.md): JSON-RPC 2.0 over Content-Length framed
// messages, the LSP lifecycle, open documents with full and incremental sync, and the features
// (diagnostics, hover, definition, references, completion, document symbols, formatting,
// semantic tokens, inlay hints, rename, a project settings file), all
// computed by the assembler library on the editor's text. The Server is transport-free: it takes
// one message body and returns the bodies to send, so tests drive it directly.
#pragma once

#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/format.hpp"
#include "tmcl/json.hpp"
#include "tmcl/testrun.hpp"

namespace tmcl::lsp {

// Error codes of responses: JSON-RPC 2.0's, and the LSP's own (RequestFailed, ServerNotInitialized).
inline constexpr int kParseError = -32700;
inline constexpr int kInvalidRequest = -32600;
inline constexpr int kMethodNotFound = -32601;
inline constexpr int kInvalidParams = -32602;
inline constexpr int kServerNotInitialized = -32002;
inline constexpr int kRequestFailed = -32803;

// ---- framing --------------------------------------------------------------------------------
// "Content-Length: N\r\n\r\n" + body.
std::string frame(std::string_view body);

// Reads framed messages from a file descriptor. A malformed header is reported (error set) and
// skipped up to the next blank line, so the server can answer it and go on.
class Reader {
 public:
  explicit Reader(int fd) : fd_(fd) {}
  enum class Status { Message, BadHeader, End };
  Status next(std::string& body, std::string& error);

 private:
  bool fill();
  int fd_;
  std::string buf_;
  bool eof_ = false;
};

// ---- the server -------------------------------------------------------------------------------
struct Document {
  std::string uri;
  std::string path;
  std::string text;
  std::int64_t version = 0;
  std::vector<std::size_t> line_starts;  // byte offset of each line
  std::vector<SourceToken> tokens;       // of text (tokenize)
  std::shared_ptr<AsmResult> result;     // the last assembly of this document as a root file
  std::set<std::string> reads;           // paths that assembly read (for re-checking includers)
};

struct Settings {
  std::string target = "generic";         // -t: a target name or a profile file
  std::vector<std::string> include_dirs;  // -I
};

class Server {
 public:
  using Value = json::Value;
  Server();
  // Handles one message body; returns the message bodies to send, in order.
  std::vector<std::string> handle(std::string_view body);
  bool exited() const { return exited_; }
  int exit_code() const { return shutdown_ ? 0 : 1; }
  const Document* document(const std::string& uri) const;

 private:
  struct Reply {  // a result, or an error (code != 0)
    Value result;
    int code = 0;
    std::string message;
  };

  Reply dispatch(const std::string& method, const Value& params, bool is_request);
  Reply initialize(const Value& params);
  void open(const Value& params);
  Reply change(const Value& params);
  void check(Document& doc);
  void publish(const Document& doc, Value diagnostics);  // textDocument/publishDiagnostics
  void check_includers(const std::string& path);
  Value diagnostics_of(const Document& doc) const;
  Value diagnostic_json(const Diagnostic& d, const AsmResult& r) const;
  // Where a diagnostic is shown in the root file: one in an included file at its #include line.
  SourceLoc shown_at(const Diagnostic& d, const AsmResult& r) const;

  // Features (features.cpp).
  Reply hover(const Value& params);
  Reply definition(const Value& params);
  Reply references(const Value& params);
  Reply completion(const Value& params);
  Reply document_symbols(const Value& params);
  Reply formatting(const Value& params);
  Reply rename(const Value& params);
  Reply workspace_symbols(const Value& params);
  Reply signature_help(const Value& params);
  Reply folding_ranges(const Value& params);
  Reply semantic_tokens(const Value& params, bool in_range);  // tokens.cpp
  Reply inlay_hints(const Value& params);                     // hints.cpp
  Reply prepare_rename(const Value& params);                  // hints.cpp

  // Settings (settings.cpp): the project file .tmcl-lsp.json in the workspace root, overridden by
  // initializationOptions; read at initialize and when the client says the file changed.
  Reply configure(const Value& initialize_params);
  Reply load_settings();
  void watched_files_changed(const Value& params);
  void watch_settings_file();  // asks the client to report changes (dynamic registration)
  void complete_include(const Document& doc, Value& items) const;
  Reply code_actions(const Value& params);  // actions.cpp

  // Test files, *.tmctest (testfiles.cpp): diagnostics, a "Run test" code lens, tmcl.runTest.
  static bool is_test_file(const Document& doc);
  testrun::RunOptions test_options() const;
  Value test_diagnostics(Document& doc, const std::vector<testrun::Failure>& failures);
  Reply code_lens(const Value& params);
  Reply execute_command(const Value& params);

  // The prologue every request about a document shares: the document, and with a position
  // the byte offset and the token there; or, when either is missing, the error reply.
  struct Target {
    Document* doc = nullptr;
    std::size_t offset = 0;
    const SourceToken* token = nullptr;  // under (or just before) the position; may be null
    Reply error;
    explicit operator bool() const { return doc != nullptr; }
  };
  Target target(const Value& params, bool with_position);

  // Finding the document and the token a request is about; errors as replies.
  Document* find_document(const Value& params, Reply& err);
  bool position(const Document& doc, const Value& params, std::size_t& offset, Reply& err) const;
  const SourceToken* token_at(const Document& doc, std::size_t offset) const;
  Value range_of(const Document& doc, std::size_t offset, std::size_t len) const;
  Value location_of(const SourceLoc& loc, const AsmResult& r) const;
  bool range_param(const Document& doc, const Value& params, std::size_t& begin, std::size_t& end, Reply& err) const;
  // The target of a document: what its first line names (// tmcl-target: NAME), else the
  // settings' target; the settings' alone for the other.
  const Profile& profile(const Document& doc) const;
  const Profile& settings_profile() const;
  const Symbol* symbol(const Document& doc, std::string_view name) const;

  std::map<std::string, Document> docs_;
  std::vector<std::string> out_;  // notifications produced while handling a message
  Settings settings_;
  Value init_options_;         // initializationOptions as received
  std::string settings_file_;  // the project file's path ("" without a workspace root)
  bool can_watch_ = false;     // the client registers file watchers dynamically
  bool initialized_ = false;
  bool shutdown_ = false;
  bool exited_ = false;
};

// The legend of the semantic tokens (token types and modifiers), as the capabilities declare it.
json::Value semantic_token_legend();

// file:///a%20b/c.tmc <-> /a b/c.tmc
std::string uri_to_path(std::string_view uri);
std::string path_to_uri(std::string_view path);

// Byte offset of (line, UTF-16 character) in text with these line starts, clamped to the line;
// and the UTF-16 character of a byte offset within its line.
std::size_t offset_of(std::string_view text, const std::vector<std::size_t>& starts, std::size_t line, std::size_t character);
std::size_t utf16_column(std::string_view line, std::size_t bytes);

}  // namespace tmcl::lsp
