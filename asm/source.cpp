// Reading source files from disk (or standard input) for the assembler.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <iterator>
#include <sys/stat.h>

#include "internal.hpp"

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
  out.clear();
  char buf[65536];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) {
    out.append(buf, n);
    if (out.size() > detail::kMaxFileBytes) break;  // the caller reports the size limit
  }
  bool ok = !std::ferror(f);
  if (!ok) error_ = "read error";
  std::fclose(f);
  return ok;
}

bool MemoryReader::read(const std::string& path, std::string& out) {
  auto it = files.find(path);
  if (it == files.end()) return false;
  out = it->second;
  return true;
}

}  // namespace tmcl
