// The server's settings (docs/lsp.md, "Settings"): the project file .tmcl-lsp.json in the
// workspace root — target and include directories, relative ones taken from the file's folder —
// overridden by the client's initializationOptions. The file is read at initialize and again when
// the client reports it changed (workspace/didChangeWatchedFiles, for which the server registers
// a watcher when the client allows it); a bad file is reported with window/showMessage, naming
// the file and the place, and ignored. Also here: the files an #include can name, for completion.
#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "context.hpp"
#include "tmcl/lsp/server.hpp"
#include "tmcl/targets.hpp"
#include "tmcl/os_files.hpp"

namespace tmcl::lsp {

namespace {

constexpr int kMessageError = 1;    // MessageType.Error
constexpr int kMessageWarning = 2;  // MessageType.Warning
constexpr int kFileKind = 17;       // CompletionItemKind.File
constexpr const char* kProjectFile = ".tmcl-lsp.json";

json::Value show_message(int type, std::string text) {
  json::Value n = json::Value::object();
  n.set("jsonrpc", "2.0");
  n.set("method", "window/showMessage");
  json::Value& p = n.set("params", json::Value::object());
  p.set("type", type);
  p.set("message", std::move(text));
  return n;
}

std::string folder_of(const std::string& path) {
  std::size_t slash = tmcl::os::last_separator(path);
  return slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
}

// Reads the project file into `s`; false with `error` ("FILE:LINE:COL: error: ...") when it is bad.
// Unknown keys are not an error (a newer version may know them) but get a warning.
bool read_project_file(const std::string& path, Settings& s, std::string& error, std::vector<std::string>& warnings) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {  // a FIFO would block the server in open()
    error = path + ": error: not a regular file";
    return false;
  }
  DiskReader disk;
  std::string text;
  if (!disk.read(path, text)) {
    error = path + ": error: " + disk.last_error();
    return false;
  }
  json::Value v;
  json::Error e;
  if (!json::parse(text, v, e)) {
    error = path + ":" + std::to_string(e.line) + ":" + std::to_string(e.column) + ": error: " + e.message;
    return false;
  }
  if (!v.is_object()) {
    error = path + ": error: expected a JSON object like {\"target\": \"usb-2-sd\", \"includeDirs\": [\"lib\"]}";
    return false;
  }
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string& key = v.key(i);
    const json::Value& item = v.at(i);
    if (key == "target") {
      // A profile file named by a relative path is found from the project file's folder.
      std::string target = item.is_string() ? item.as_string() : std::string();
      if (tmcl::os::has_separator(target) && !tmcl::os::is_absolute(target)) target = tmcl::os::join_path(folder_of(path), target);
      const TargetResult t = resolve_target(target);
      if (!item.is_string() || !t.profile) {
        error = path + ": error: \"target\": " + (item.is_string() ? t.message(1) : "a target name or a profile file, not " + json::write(item));
        return false;
      }
      s.target = target;
    } else if (key == "includeDirs") {
      if (!item.is_array()) {
        error = path + ": error: \"includeDirs\" must be an array of folder names";
        return false;
      }
      for (const json::Value& dir : item.items()) {
        if (!dir.is_string() || dir.as_string().empty()) {
          error = path + ": error: \"includeDirs\" must hold folder names, not " + json::write(dir);
          return false;
        }
        const std::string& d = dir.as_string();
        s.include_dirs.push_back(tmcl::os::is_absolute(d) ? d : tmcl::os::join_path(folder_of(path), d));
      }
    } else {
      warnings.push_back(path + ": warning: unknown setting \"" + key + "\" (known: target, includeDirs)");
    }
  }
  return true;
}

}  // namespace

// At initialize: where the project file is (the workspace root: rootUri, else the first workspace
// folder, else rootPath), whether the client can watch it, and the settings.
Server::Reply Server::configure(const Value& params) {
  init_options_ = params["initializationOptions"];
  std::string root;
  if (params["rootUri"].is_string()) root = uri_to_path(params["rootUri"].as_string());
  else if (params["workspaceFolders"].at(0)["uri"].is_string()) root = uri_to_path(params["workspaceFolders"].at(0)["uri"].as_string());
  else if (params["rootPath"].is_string()) root = params["rootPath"].as_string();
  while (root.size() > 1 && tmcl::os::is_separator(root.back())) root.pop_back();
  settings_file_ = root.empty() ? "" : tmcl::os::join_path(root, kProjectFile);
  can_watch_ = params["capabilities"]["workspace"]["didChangeWatchedFiles"]["dynamicRegistration"].as_bool();
  return load_settings();
}

// The project file, then initializationOptions over it. An unknown target in the options fails
// (InvalidParams); a bad project file is reported and ignored.
Server::Reply Server::load_settings() {
  Settings s;
  if (!settings_file_.empty() && ::access(settings_file_.c_str(), F_OK) == 0) {
    std::string error;
    std::vector<std::string> warnings;
    if (!read_project_file(settings_file_, s, error, warnings)) {
      s = Settings{};
      out_.push_back(json::write(show_message(kMessageError, error + " (the file is ignored: target generic, no include folders)")));
    }
    for (std::string& w : warnings) out_.push_back(json::write(show_message(kMessageWarning, std::move(w))));
  }
  const Value& o = init_options_;
  if (o["target"].is_string()) {
    const TargetResult t = resolve_target(o["target"].as_string());
    if (!t.profile) return {Value(), kInvalidParams, t.message(1)};
    s.target = o["target"].as_string();
  }
  if (o["includeDirs"].is_array()) {
    s.include_dirs.clear();
    for (const Value& dir : o["includeDirs"].items())
      if (dir.is_string()) s.include_dirs.push_back(dir.as_string());
  }
  settings_ = std::move(s);
  return {};
}

void Server::watch_settings_file() {
  if (!can_watch_ || settings_file_.empty()) return;
  Value req = Value::object();
  req.set("jsonrpc", "2.0");
  req.set("id", "tmcl-lsp-watch");  // the client's answer is ignored like every response
  req.set("method", "client/registerCapability");
  Value& reg = req.set("params", Value::object()).set("registrations", Value::array()).push(Value::object());
  reg.set("id", "tmcl-lsp-settings");
  reg.set("method", "workspace/didChangeWatchedFiles");
  reg.set("registerOptions", Value::object()).set("watchers", Value::array()).push(Value::object()).set("globPattern", std::string("**/") + kProjectFile);
  out_.push_back(json::write(req));
}

// The project file changed (created, changed or deleted): read the settings again and re-check
// every open document. Another changed file re-checks the open documents that include it.
void Server::watched_files_changed(const Value& params) {
  bool reload = false;
  for (const Value& change : params["changes"].items()) {
    std::string path = uri_to_path(change["uri"].as_string());
    if (!settings_file_.empty() && path == settings_file_) reload = true;
    else check_includers(path);
  }
  if (!reload) return;
  load_settings();  // the options were checked at initialize
  for (auto& [uri, d] : docs_) check(d);
}

// Include files the assembler would find: beside the document, in each include folder, bundled
// (docs/language.md, "Includes"), in that order; a name found earlier hides a later one.
void Server::complete_include(const Document& doc, Value& items) const {
  std::vector<std::string> seen;  // lower-case names
  auto add = [&](const std::string& name, std::string detail) {
    std::string key = lower(name);
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) return;
    seen.push_back(key);
    Value& i = items.push(Value::object());
    i.set("label", name);
    i.set("kind", kFileKind);
    i.set("detail", std::move(detail));
  };
  std::vector<std::string> dirs{folder_of(doc.path)};
  dirs.insert(dirs.end(), settings_.include_dirs.begin(), settings_.include_dirs.end());
  for (const std::string& dir : dirs) {
    std::vector<std::string> names;
    std::error_code ec;
    for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      std::string name = it->path().filename().string();
      std::string ext = lower(it->path().extension().string());
      if ((ext == ".inc" || ext == ".tmc" || ext == ".tmcl") && it->is_regular_file(ec) && it->path() != std::filesystem::path(doc.path))
        names.push_back(name);
    }
    std::sort(names.begin(), names.end());
    for (const std::string& n : names) add(n, tmcl::os::join_path(dir, n));
  }
  for (const auto& [name, text] : bundled_includes()) add(name, "bundled include file");
}

}  // namespace tmcl::lsp
