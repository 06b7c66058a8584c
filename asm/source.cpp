// Reading source files from disk (or standard input) for the assembler, and what every loaded
// source goes through before it is parsed.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <sys/stat.h>

#include "internal.hpp"
#include "tmcl/fileio.hpp"
#include "tmcl/os_files.hpp"

namespace tmcl {

bool DiskReader::read(const std::string& path, std::string& out) {
  if (path == "-") {
    out.assign(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
    return !std::cin.bad();
  }
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    error_ = std::strerror(errno);
    return false;
  }
  if (S_ISDIR(st.st_mode)) {
    error_ = "it is a directory";
    return false;
  }
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) {
    error_ = std::strerror(errno);
    return false;
  }
  // Read straight into a string of the file's size: growing it by doubling would touch (and
  // fault in) twice the memory. A file that grows meanwhile is read on in chunks.
  out.clear();
  std::size_t expected = S_ISREG(st.st_mode) ? static_cast<std::size_t>(st.st_size) : 0;
  if (expected > detail::kMaxFileBytes) expected = detail::kMaxFileBytes + 1;  // the caller reports the limit
  out.reserve(expected);
  prefer_huge_pages(out.data(), out.capacity());
  out.resize(expected);
  std::size_t got = expected > 0 ? std::fread(out.data(), 1, expected, f) : 0;
  out.resize(got);
  char buf[65536];
  std::size_t n;
  while (out.size() <= detail::kMaxFileBytes && (n = std::fread(buf, 1, sizeof buf, f)) > 0) out.append(buf, n);
  bool ok = !std::ferror(f);
  if (!ok) error_ = "read error";
  std::fclose(f);
  return ok;
}

namespace detail {

bool drop_bom(std::string& text) {
  if (text.rfind("\xEF\xBB\xBF", 0) != 0) return false;
  text.erase(0, 3);
  return true;
}

std::string include_key(const std::string& path) {
  return std::filesystem::path(path).lexically_normal().generic_string();
}

bool find_include(const std::string& written, const std::string& including_path, const AsmOptions& options,
                  FileReader& reader, FoundInclude& found, std::vector<std::string>* searched) {
  namespace fs = std::filesystem;
  // TMCL-IDE programs are written on Windows: "lib\motor.inc" names a folder on every system.
  const std::string name = os::portable_path(written);
  auto tried = [searched](const std::string& folder, const char* why) {
    if (searched) searched->push_back("'" + (folder.empty() ? std::string(".") : folder) + "' (" + why + ")");
  };
  auto try_path = [&](const std::string& p) {
    if (p == "-" || !reader.read(p, found.text)) return false;  // "-" is standard input, never an include
    found.path = p;
    found.key = include_key(p);
    return true;
  };
  if (os::is_absolute(name)) return try_path(name);
  if (including_path.rfind("<bundled>/", 0) != 0 && including_path != "-") {
    const std::size_t sep = os::last_separator(including_path);
    const std::string folder = sep == std::string::npos ? "" : including_path.substr(0, sep == 0 ? 1 : sep);
    if (try_path(os::join_path(folder, name))) return true;
    tried(folder, "the including file's folder");
  }
  for (const auto& dir : options.include_dirs) {
    if (try_path(os::join_path(dir, name))) return true;
    tried(dir, "-I");
  }
  for (const auto& [bname, btext] : bundled_includes()) {
    if (upper(bname) == upper(name)) {
      found.text = std::string(btext);
      found.path = "<bundled>/" + bname;
      found.key = found.path;
      return true;
    }
  }
  return false;
}

int first_long_line(const SourceFile& f) {
  const auto& starts = f.line_starts;
  for (std::size_t l = 0; l < starts.size(); ++l) {
    std::size_t end = l + 1 < starts.size() ? starts[l + 1] : f.text.size();
    if (end - starts[l] > kMaxLineBytes) return static_cast<int>(l + 1);
  }
  return 0;
}

}  // namespace detail

std::string DiskReader::folder_problem(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return errno == ENOENT ? "does not exist" : std::strerror(errno);
  return S_ISDIR(st.st_mode) ? std::string() : "is not a folder";
}

std::string MemoryReader::folder_problem(const std::string& path) {
  std::string prefix = path.empty() || path.back() == '/' ? path : path + "/";
  auto it = files.lower_bound(prefix);
  return it != files.end() && it->first.rfind(prefix, 0) == 0 ? std::string() : "does not exist";
}

bool MemoryReader::read(const std::string& path, std::string& out) {
  auto it = files.find(path);
  if (it == files.end()) return false;
  out = it->second;
  return true;
}

}  // namespace tmcl
