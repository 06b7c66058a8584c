// The platform layer, files, on POSIX systems (os_files.hpp).
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "tmcl/fileio.hpp"
#include "tmcl/os_files.hpp"

#if __has_include(<sys/mman.h>)
#include <sys/mman.h>
#endif

namespace tmcl {
namespace os {

const int kOpenFlags = O_CLOEXEC;

std::string native_path(const std::string& path) { return path; }

std::vector<std::string> split_path_list(const std::string& list) {
  std::vector<std::string> dirs;
  for (std::size_t p = 0; p <= list.size();) {
    std::size_t q = std::min(list.find(':', p), list.size());
    if (q > p) dirs.push_back(list.substr(p, q - p));
    p = q + 1;
  }
  return dirs;
}
bool is_separator(char c) { return c == '/'; }
bool has_separator(std::string_view path) { return path.find('/') != std::string_view::npos; }
bool is_absolute(std::string_view path) { return !path.empty() && path[0] == '/'; }
std::size_t last_separator(std::string_view path) { return path.rfind('/'); }

std::string join_path(const std::string& folder, const std::string& name) {
  if (folder.empty()) return name;
  return folder.back() == '/' ? folder + name : folder + "/" + name;
}

std::string portable_path(std::string path) {
  std::replace(path.begin(), path.end(), '\\', '/');
  return path;
}

std::string normal_path(const std::string& path) { return std::filesystem::path(path).lexically_normal().generic_string(); }

bool is_device_name(std::string_view) { return false; }

bool sync_file(int fd) { return ::fsync(fd) == 0; }

bool replace_file(const std::string& from, const std::string& to) { return std::rename(from.c_str(), to.c_str()) == 0; }

std::string real_path(const std::string& path) {
  char* real = ::realpath(path.c_str(), nullptr);
  std::string out = real ? real : "";
  std::free(real);
  return out;
}

long long modified_ns(const struct stat& st) {
  return static_cast<long long>(st.st_mtim.tv_sec) * 1000000000LL + st.st_mtim.tv_nsec;
}

std::vector<std::string> config_dirs(const std::string& leaf) {
  std::vector<std::string> dirs;
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  const char* home = std::getenv("HOME");
  if (xdg && *xdg == '/') dirs.push_back(std::string(xdg) + "/tmcl/" + leaf);
  else if (home && *home) dirs.push_back(std::string(home) + "/.config/tmcl/" + leaf);
  return dirs;
}

}  // namespace os

void prefer_huge_pages(const void* data, std::size_t bytes) {
#ifdef MADV_HUGEPAGE
  constexpr std::uintptr_t kHuge = 2u << 20;
  if (bytes < 2 * kHuge) return;  // smaller buffers hold at most one huge page
  auto begin = (reinterpret_cast<std::uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
  auto end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kHuge - 1);
  if (end > begin) ::madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);  // advice: failure is harmless
#else
  (void)data;
  (void)bytes;
#endif
}

void prefer_huge_pages_for_next(std::size_t bytes) {
  if (void* block = std::malloc(bytes)) {
    prefer_huge_pages(block, bytes);
    std::free(block);
  }
}

}  // namespace tmcl
