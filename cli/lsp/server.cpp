// The language server's core: framing, JSON-RPC dispatch and the LSP lifecycle, documents with
// full and incremental sync, and diagnostics (the assembler's, and the control-flow analysis'
// when that library is built), re-published for every open file that includes a changed one.
// Bad input never ends the server: it gets the protocol's error response.
#include "tmcl/lsp/server.hpp"
#include "tmcl/targets.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#if __has_include("tmcl/analysis.hpp")
#include "tmcl/analysis.hpp"
#include "tmcl/os_files.hpp"
#define TMCL_LSP_ANALYSIS 1
#endif

namespace tmcl::lsp {

namespace {

constexpr std::size_t kMaxMessage = 256u << 20;  // a bigger Content-Length is an error, not an allocation

int hex_digit(char c) {
  return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
}

// The files an assembly reads: open documents from the editor's text, the rest from disk.
class OverlayReader final : public FileOverlay {
 public:
  explicit OverlayReader(const std::map<std::string, Document>& docs) : docs_(docs) {}

 private:
  bool serve(const std::string& path, std::string& out) override {
    for (const auto& [uri, d] : docs_)
      if (d.path == path) {
        out = d.text;
        return true;
      }
    return false;
  }
  const std::map<std::string, Document>& docs_;
};

void index_lines(Document& d) {
  d.line_starts.assign(1, 0);
  for (std::size_t i = 0; i < d.text.size(); ++i)
    if (d.text[i] == '\n') d.line_starts.push_back(i + 1);
  d.tokens = tokenize(d.text);
}

}  // namespace

// ---- framing --------------------------------------------------------------------------------

std::string frame(std::string_view body) {
  return "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + std::string(body);
}

bool Reader::fill() {
  if (eof_) return false;
  char chunk[65536];
  for (;;) {
    ssize_t n = ::read(fd_, chunk, sizeof chunk);
    if (n > 0) {
      buf_.append(chunk, static_cast<std::size_t>(n));
      return true;
    }
    if (n < 0 && errno == EINTR) continue;
    eof_ = true;
    return false;
  }
}

Reader::Status Reader::next(std::string& body, std::string& error) {
  std::size_t end;
  while ((end = buf_.find("\r\n\r\n")) == std::string::npos) {
    if (buf_.size() > 65536) {  // no header end in sight: drop what we have
      error = "message header longer than 64 KiB without a blank line";
      buf_.clear();
      return Status::BadHeader;
    }
    if (!fill()) return Status::End;
  }
  std::string header = buf_.substr(0, end);
  buf_.erase(0, end + 4);
  std::optional<std::size_t> length;
  std::size_t p = 0;
  while (p <= header.size()) {
    std::size_t nl = header.find("\r\n", p);
    std::string line = header.substr(p, nl == std::string::npos ? std::string::npos : nl - p);
    p = nl == std::string::npos ? header.size() + 1 : nl + 2;
    std::size_t colon = line.find(':');
    if (colon == std::string::npos) {
      error = "malformed header line '" + line + "' (expected 'Name: value')";
      return Status::BadHeader;
    }
    std::string name = line.substr(0, colon);
    for (auto& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    std::string value = line.substr(colon + 1);
    while (!value.empty() && value.front() == ' ') value.erase(0, 1);
    if (name == "content-length") {
      std::size_t n = 0;
      bool digits = !value.empty();
      for (char c : value) {
        if (c < '0' || c > '9' || n > kMaxMessage) digits = false;
        else n = n * 10 + static_cast<std::size_t>(c - '0');
      }
      if (!digits || n > kMaxMessage) {
        error = "bad Content-Length '" + value + "' (expected a byte count up to 256 MiB)";
        return Status::BadHeader;
      }
      length = n;
    }
  }
  if (!length) {
    error = "message header without Content-Length";
    return Status::BadHeader;
  }
  while (buf_.size() < *length)
    if (!fill()) {
      error = "input ended inside a message body";
      return Status::End;
    }
  body = buf_.substr(0, *length);
  buf_.erase(0, *length);
  return Status::Message;
}

// ---- URIs and positions -------------------------------------------------------------------------

std::string uri_to_path(std::string_view uri) {
  if (uri.substr(0, 7) != "file://") return std::string(uri);
  uri.remove_prefix(7);
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex_digit(uri[i + 1]) >= 0 && hex_digit(uri[i + 2]) >= 0) {
      out += static_cast<char>(hex_digit(uri[i + 1]) * 16 + hex_digit(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  // "file:///C:/work/a.tmc" (VS Code: "file:///c%3A/work/a.tmc") names C:/work/a.tmc on Windows.
  if (out.size() > 1 && out[0] == '/' && out[1] != '/' && !tmcl::os::is_separator(out[1]) && tmcl::os::is_absolute(out.substr(1)))
    out.erase(0, 1);
  return out;
}

std::string path_to_uri(std::string_view path) {
  std::string out = "file://";
  if (!path.empty() && !tmcl::os::is_separator(path[0]) && tmcl::os::is_absolute(path)) out += '/';  // file:///C:/...
  for (char c : path) {
    if (c != '/' && tmcl::os::is_separator(c)) c = '/';  // Windows' '\'
    auto u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || c == '/' || c == '-' || c == '_' || c == '.' || c == '~') {
      out += c;
    } else {
      static const char* hex = "0123456789ABCDEF";
      out += '%';
      out += hex[u >> 4];
      out += hex[u & 15];
    }
  }
  return out;
}

// UTF-16 units of the bytes before `bytes` in `line`: a 4-byte UTF-8 sequence is two units,
// other sequences one; a byte that starts no valid sequence counts as one unit.
std::size_t utf16_column(std::string_view line, std::size_t bytes) {
  std::size_t units = 0;
  for (std::size_t i = 0; i < bytes && i < line.size();) {
    auto c = static_cast<unsigned char>(line[i]);
    std::size_t n = c < 0x80 ? 1 : c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC0 ? 2 : 1;
    bool valid = i + n <= line.size();
    for (std::size_t k = 1; valid && k < n; ++k) valid = (static_cast<unsigned char>(line[i + k]) & 0xC0) == 0x80;
    if (!valid) n = 1;
    units += n == 4 ? 2 : 1;
    i += n;
  }
  return units;
}

std::size_t offset_of(std::string_view text, const std::vector<std::size_t>& starts, std::size_t line, std::size_t character) {
  std::size_t begin = starts[line];
  std::size_t end = line + 1 < starts.size() ? starts[line + 1] - 1 : text.size();
  if (end > begin && text[end - 1] == '\r') --end;
  std::size_t i = begin, units = 0;
  while (i < end && units < character) {
    auto c = static_cast<unsigned char>(text[i]);
    std::size_t n = c < 0x80 ? 1 : c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC0 ? 2 : 1;
    if (i + n > end) n = 1;
    units += n == 4 ? 2 : 1;
    i += n;
  }
  return i;
}

// ---- the server ---------------------------------------------------------------------------------

Server::Server() = default;

const Document* Server::document(const std::string& uri) const {
  auto it = docs_.find(uri);
  return it == docs_.end() ? nullptr : &it->second;
}

const Profile& Server::settings_profile() const {
  const Profile* p = resolve_target(settings_.target).profile;
  return p ? *p : generic_profile();
}

const Profile& Server::profile(const Document& doc) const {
  return doc.result && doc.result->profile ? *doc.result->profile : settings_profile();
}

std::vector<std::string> Server::handle(std::string_view body) {
  out_.clear();
  std::vector<std::string> replies;
  Value msg;
  json::Error perr;
  auto error_reply = [](const Value& id, int code, const std::string& message) {
    Value r = Value::object();
    r.set("jsonrpc", "2.0");
    r.set("id", id);
    Value& e = r.set("error", Value::object());
    e.set("code", code);
    e.set("message", message);
    return json::write(r);
  };
  if (!json::parse(body, msg, perr)) {
    replies.push_back(error_reply(Value(), kParseError, "malformed JSON at " + perr.to_string()));
    return replies;
  }
  const Value* id = msg.find("id");
  bool is_request = id && (id->is_int() || id->is_string());
  if (!msg.is_object() || !msg["method"].is_string() || (id && !is_request && !id->is_null())) {
    // A response from the client (we send no requests) is ignored; anything else is invalid.
    if (msg.is_object() && !msg.contains("method") && (msg.contains("result") || msg.contains("error"))) return replies;
    replies.push_back(error_reply(is_request ? *id : Value(), kInvalidRequest,
                                  "invalid request: expected an object with a string \"method\" and an integer or string \"id\""));
    return replies;
  }
  std::string method = msg["method"].as_string();
  Reply r = dispatch(method, msg["params"], is_request);
  if (is_request) {
    if (r.code != 0) {
      replies.push_back(error_reply(*id, r.code, r.message));
    } else {
      Value resp = Value::object();
      resp.set("jsonrpc", "2.0");
      resp.set("id", *id);
      resp.set("result", std::move(r.result));
      replies.push_back(json::write(resp));
    }
  }
  for (auto& n : out_) replies.push_back(std::move(n));
  out_.clear();
  return replies;
}

Server::Reply Server::dispatch(const std::string& method, const Value& params, bool is_request) {
  Reply r;
  if (method == "exit") {
    exited_ = true;
    return r;
  }
  if (!initialized_ && method != "initialize") {
    if (is_request) r = {Value(), kServerNotInitialized, "the server is not initialized yet (send initialize first)"};
    return r;
  }
  if (shutdown_) {
    if (is_request) r = {Value(), kInvalidRequest, "the server is shut down; only exit is accepted"};
    return r;
  }
  if (method == "initialize") {
    if (initialized_) return {Value(), kInvalidRequest, "initialize was already received"};
    return initialize(params);
  }
  if (method == "initialized") {
    watch_settings_file();
    return r;
  }
  if (method == "shutdown") {
    shutdown_ = true;
    return r;
  }
  if (method == "textDocument/didOpen") {
    open(params);
    return r;
  }
  if (method == "textDocument/didChange") return change(params);
  if (method == "textDocument/didSave") {
    Reply err;
    if (Document* d = find_document(params, err)) {
      check(*d);
      check_includers(d->path);
    }
    return r;
  }
  if (method == "textDocument/didClose") {
    Reply err;
    if (Document* d = find_document(params, err)) {
      Value n = Value::object();
      n.set("jsonrpc", "2.0");
      n.set("method", "textDocument/publishDiagnostics");
      Value& p = n.set("params", Value::object());
      p.set("uri", d->uri);
      p.set("diagnostics", Value::array());
      out_.push_back(json::write(n));
      std::string path = d->path;
      docs_.erase(d->uri);
      check_includers(path);  // includers read it from disk again
    }
    return r;
  }
  if (method == "textDocument/hover") return hover(params);
  if (method == "textDocument/definition" || method == "textDocument/declaration") return definition(params);
  if (method == "textDocument/references") return references(params);
  if (method == "textDocument/completion") return completion(params);
  if (method == "textDocument/documentSymbol") return document_symbols(params);
  if (method == "textDocument/formatting") return formatting(params);
  if (method == "textDocument/rename") return rename(params);
  if (method == "workspace/symbol") return workspace_symbols(params);
  if (method == "textDocument/signatureHelp") return signature_help(params);
  if (method == "textDocument/foldingRange") return folding_ranges(params);
  if (method == "textDocument/semanticTokens/full") return semantic_tokens(params, false);
  if (method == "textDocument/semanticTokens/range") return semantic_tokens(params, true);
  if (method == "textDocument/inlayHint") return inlay_hints(params);
  if (method == "textDocument/prepareRename") return prepare_rename(params);
  if (method == "workspace/didChangeWatchedFiles") {
    watched_files_changed(params);
    return r;
  }
  if (method == "textDocument/codeAction") return code_actions(params);
  if (method == "textDocument/codeLens") return code_lens(params);
  if (method == "workspace/executeCommand") return execute_command(params);
  if (!is_request) return r;  // unknown notifications ($/cancelRequest, ...) are ignored
  return {Value(), kMethodNotFound, "unknown method '" + method + "'"};
}

Server::Reply Server::initialize(const Value& params) {
  initialized_ = true;
  Reply r = configure(params);  // settings.cpp
  if (r.code) return r;
  Value caps = Value::object();
  Value& sync = caps.set("textDocumentSync", Value::object());
  sync.set("openClose", true);
  sync.set("change", 2);
  sync.set("save", Value::object()).set("includeText", false);
  caps.set("hoverProvider", true);
  caps.set("definitionProvider", true);
  caps.set("declarationProvider", true);
  caps.set("referencesProvider", true);
  caps.set("documentSymbolProvider", true);
  caps.set("documentFormattingProvider", true);
  caps.set("renameProvider", Value::object()).set("prepareProvider", true);
  Value& tokens = caps.set("semanticTokensProvider", Value::object());
  tokens.set("legend", semantic_token_legend());
  tokens.set("full", true);
  tokens.set("range", true);
  caps.set("inlayHintProvider", true);
  caps.set("workspaceSymbolProvider", true);
  caps.set("foldingRangeProvider", true);
  caps.set("codeActionProvider", Value::object()).set("codeActionKinds", Value::array()).push("quickfix");
  caps.set("codeLensProvider", Value::object()).set("resolveProvider", false);
  caps.set("executeCommandProvider", Value::object()).set("commands", Value::array()).push("tmcl.runTest");
  caps.set("signatureHelpProvider", Value::object()).set("triggerCharacters", Value::array()).push(",");
  Value& comp = caps.set("completionProvider", Value::object());
  comp.set("triggerCharacters", Value::array()).push(" ");
  comp["triggerCharacters"];
  r.result = Value::object();
  r.result.set("capabilities", std::move(caps));
  Value& info = r.result.set("serverInfo", Value::object());
  info.set("name", "tmcl-lsp");
  return r;
}

Document* Server::find_document(const Value& params, Reply& err) {
  const Value& uri = params["textDocument"]["uri"];
  if (!uri.is_string()) {
    err = {Value(), kInvalidParams, "missing params.textDocument.uri"};
    return nullptr;
  }
  auto it = docs_.find(uri.as_string());
  if (it == docs_.end()) {
    err = {Value(), kInvalidParams, "unknown document '" + uri.as_string() + "' (not opened with didOpen)"};
    return nullptr;
  }
  return &it->second;
}

void Server::open(const Value& params) {
  const Value& td = params["textDocument"];
  if (!td["uri"].is_string() || !td["text"].is_string()) return;
  Document& d = docs_[td["uri"].as_string()];
  d.uri = td["uri"].as_string();
  d.path = uri_to_path(d.uri);
  d.text = td["text"].as_string();
  d.version = td["version"].as_int();
  index_lines(d);
  check(d);
  check_includers(d.path);
}

Server::Reply Server::change(const Value& params) {
  Reply err;
  Document* d = find_document(params, err);
  if (!d) return err;
  for (const Value& c : params["contentChanges"].items()) {
    if (!c["text"].is_string()) continue;
    const Value& range = c["range"];
    if (!range.is_object()) {
      d->text = c["text"].as_string();
    } else {
      auto at = [&](const Value& pos) {
        auto line = static_cast<std::size_t>(std::max<std::int64_t>(0, pos["line"].as_int()));
        if (line >= d->line_starts.size()) return d->text.size();
        return offset_of(d->text, d->line_starts, line, static_cast<std::size_t>(std::max<std::int64_t>(0, pos["character"].as_int())));
      };
      std::size_t a = at(range["start"]), b = at(range["end"]);
      if (b < a) std::swap(a, b);
      d->text.replace(a, b - a, c["text"].as_string());
    }
    index_lines(*d);
  }
  d->version = params["textDocument"]["version"].as_int(d->version);
  check(*d);
  check_includers(d->path);
  return {};
}

void Server::check(Document& doc) {
  if (is_test_file(doc)) return publish(doc, test_diagnostics(doc, {}));
  AsmOptions opts;
  // A first line that names a target wins over the settings: the assembler reads it, and says
  // there when it names none that can be used.
  opts.profile = target_comment(doc.text) ? nullptr : &settings_profile();
  opts.include_dirs = settings_.include_dirs;
  opts.error_limit = 0;
  OverlayReader reader(docs_);
  auto r = std::make_shared<AsmResult>(assemble({doc.path}, opts, reader));
#ifdef TMCL_LSP_ANALYSIS
  if (r->ok()) {
    analyze(analysis_input(*r), r->diags, AnalysisOptions{});
  }
#endif
  doc.reads.clear();
  for (const auto& f : r->sources.files) doc.reads.insert(f.path);
  doc.result = std::move(r);
  publish(doc, diagnostics_of(doc));
}

void Server::publish(const Document& doc, Value diagnostics) {
  Value n = Value::object();
  n.set("jsonrpc", "2.0");
  n.set("method", "textDocument/publishDiagnostics");
  Value& p = n.set("params", Value::object());
  p.set("uri", doc.uri);
  p.set("version", static_cast<long long>(doc.version));
  p.set("diagnostics", std::move(diagnostics));
  out_.push_back(json::write(n));
}

void Server::check_includers(const std::string& path) {
  for (auto& [uri, d] : docs_)
    if (d.path != path && d.reads.count(path)) check(d);
}

Server::Value Server::location_of(const SourceLoc& loc, const AsmResult& r) const {
  Value l = Value::object();
  const SourceFile& f = r.sources.files[static_cast<std::size_t>(loc.file)];
  l.set("uri", path_to_uri(f.path));
  std::string_view line = f.line(loc.line);
  auto col = static_cast<std::size_t>(std::max(0, loc.col - 1));
  Value range = Value::object();
  Value& s = range.set("start", Value::object());
  s.set("line", std::max(0, loc.line - 1));
  s.set("character", static_cast<long long>(utf16_column(line, col)));
  Value& e = range.set("end", Value::object());
  e.set("line", std::max(0, loc.line - 1));
  e.set("character", static_cast<long long>(utf16_column(line, col + static_cast<std::size_t>(std::max(0, loc.len)))));
  l.set("range", std::move(range));
  return l;
}

// Every diagnostic of the document's assembly.
Server::Value Server::diagnostics_of(const Document& doc) const {
  Value list = Value::array();
  const AsmResult& r = *doc.result;
  for (const Diagnostic* d : r.diags.sorted(r.sources)) list.push(diagnostic_json(*d, r));
  return list;
}

namespace {
// The #include line of the file that includes the one `at` is in.
SourceLoc includer_of(const SourceLoc& at, const AsmResult& r) {
  const SourceFile& f = r.sources.files[static_cast<std::size_t>(at.file)];
  const SourceFile& up = r.sources.files[static_cast<std::size_t>(f.includer)];
  return SourceLoc{f.includer, f.include_line, 1, static_cast<int>(up.line(f.include_line).size())};
}
}  // namespace

SourceLoc Server::shown_at(const Diagnostic& d, const AsmResult& r) const {
  SourceLoc at = d.loc.file < 0 ? SourceLoc{0, 1, 1, 0} : d.loc;
  while (r.sources.files[static_cast<std::size_t>(at.file)].includer >= 0) at = includer_of(at, r);
  return at;
}

// One diagnostic. One in an included file is shown at the #include line of this document that
// leads to it, with its real place as related information.
Server::Value Server::diagnostic_json(const Diagnostic& diag, const AsmResult& r) const {
  const Diagnostic* d = &diag;
  Value item = Value::object();
  Value related = Value::array();
  SourceLoc at = d->loc;
  if (at.file < 0) {
    at = SourceLoc{0, 1, 1, 0};
  }
  // Walk up the include chain to the root file (includer -1).
  while (r.sources.files[static_cast<std::size_t>(at.file)].includer >= 0) {
    const SourceFile& f = r.sources.files[static_cast<std::size_t>(at.file)];
    Value rel = Value::object();
    rel.set("location", location_of(at, r));
    rel.set("message", "in " + f.name + ": " + d->message);
    related.push(std::move(rel));
    at = includer_of(at, r);
  }
  Value loc = location_of(at, r);
  item.set("range", loc["range"]);
  item.set("severity", d->severity == Severity::Error ? 1 : d->severity == Severity::Warning ? 2 : 3);
  if (!d->name.empty()) item.set("code", d->name);
  item.set("source", "tmcl");
  item.set("message", d->message);
  for (const Diagnostic& note : d->notes) {
    if (note.loc.file < 0) continue;
    Value rel = Value::object();
    rel.set("location", location_of(note.loc, r));
    rel.set("message", note.message);
    related.push(std::move(rel));
  }
  if (related.size()) item.set("relatedInformation", std::move(related));
  return item;
}

}  // namespace tmcl::lsp
