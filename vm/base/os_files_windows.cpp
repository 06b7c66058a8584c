// The platform layer, files, on Windows (os_files.hpp): binary, non-inherited opens, MoveFileEx
// for the atomic replace (rename() there fails when the target exists), %APPDATA% for the
// configuration. File names are UTF-8 throughout: the tools' manifest
// (cli/windows/utf8.manifest) makes UTF-8 the process's code page for every narrow call.
#include <fcntl.h>
#include <io.h>
#include <windows.h>

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <filesystem>

#include "tmcl/fileio.hpp"
#include "tmcl/os_files.hpp"

namespace tmcl {
namespace os {

const int kOpenFlags = O_BINARY | O_NOINHERIT;

std::string native_path(const std::string& path) { return path == "/dev/null" ? "NUL" : path; }

std::vector<std::string> split_path_list(const std::string& list) {
  std::vector<std::string> dirs;
  std::string cur;
  for (char c : list) {
    const bool drive = c == ':' && cur.size() == 1 && std::isalpha(static_cast<unsigned char>(cur[0]));
    if (c == ';' || (c == ':' && !drive)) {
      if (!cur.empty()) dirs.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!cur.empty()) dirs.push_back(cur);
  return dirs;
}
bool is_separator(char c) { return c == '/' || c == '\\'; }
bool has_separator(std::string_view path) { return path.find_first_of("/\\") != std::string_view::npos; }
bool is_absolute(std::string_view path) {
  if (!path.empty() && is_separator(path[0])) return true;  // "\a" (the current drive) and "\\server\share"
  return path.size() >= 2 && path[1] == ':' && std::isalpha(static_cast<unsigned char>(path[0]));
}
std::size_t last_separator(std::string_view path) { return path.find_last_of("/\\"); }

std::string join_path(const std::string& folder, const std::string& name) {
  if (folder.empty()) return name;
  if (is_separator(folder.back()) || (folder.size() == 2 && folder[1] == ':')) return folder + name;  // "C:" + "a" is C:a
  const bool backslashes = folder.find('\\') != std::string::npos && folder.find('/') == std::string::npos;
  return folder + (backslashes ? "\\" : "/") + name;
}

std::string portable_path(std::string path) { return path; }

std::string normal_path(const std::string& path) {
  const std::filesystem::path normal = std::filesystem::path(path).lexically_normal();  // '\' throughout
  return path.find('\\') != std::string::npos ? normal.string() : normal.generic_string();
}

bool is_device_name(std::string_view path) {
  if (path.substr(0, 4) == "\\\\.\\") path.remove_prefix(4);
  if (!path.empty() && path.back() == ':') path.remove_suffix(1);
  std::string name;
  for (char c : path) name += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (name == "NUL" || name == "CON" || name == "AUX" || name == "PRN") return true;
  return name.size() == 4 && (name.substr(0, 3) == "COM" || name.substr(0, 3) == "LPT") && name[3] >= '1' && name[3] <= '9';
}

bool sync_file(int fd) { return ::_commit(fd) == 0; }

bool replace_file(const std::string& from, const std::string& to) {
  if (::MoveFileExA(from.c_str(), to.c_str(), MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH)) return true;
  switch (::GetLastError()) {
    case ERROR_FILE_NOT_FOUND:
    case ERROR_PATH_NOT_FOUND: errno = ENOENT; break;
    case ERROR_ACCESS_DENIED:
    case ERROR_SHARING_VIOLATION: errno = EACCES; break;
    case ERROR_DISK_FULL: errno = ENOSPC; break;
    default: errno = EIO; break;
  }
  return false;
}

std::string real_path(const std::string& path) {
  char full[MAX_PATH * 4];
  return ::_fullpath(full, path.c_str(), sizeof full) ? std::string(full) : std::string();
}

long long modified_ns(const struct stat& st) { return static_cast<long long>(st.st_mtime) * 1000000000LL; }

std::vector<std::string> config_dirs(const std::string& leaf) {
  std::vector<std::string> dirs;
  if (const char* appdata = std::getenv("APPDATA"); appdata && *appdata) dirs.push_back(std::string(appdata) + "\\tmcl\\" + leaf);
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  const char* home = std::getenv("HOME");  // ~ is %USERPROFILE% where HOME is not set
  if (!home || !*home) home = std::getenv("USERPROFILE");
  if (xdg && *xdg) dirs.push_back(std::string(xdg) + "/tmcl/" + leaf);
  else if (home && *home) dirs.push_back(std::string(home) + "/.config/tmcl/" + leaf);
  return dirs;
}

}  // namespace os

void prefer_huge_pages(const void*, std::size_t) {}  // large pages need a privilege users lack
void prefer_huge_pages_for_next(std::size_t) {}

}  // namespace tmcl
