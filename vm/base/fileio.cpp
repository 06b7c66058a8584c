// Whole-file reading and crash-safe writing (temporary file + rename, fsync on request). What
// differs between systems is in the platform layer (os_files.hpp).
#include "tmcl/fileio.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tmcl/os_files.hpp"

namespace tmcl {

namespace {
std::string size_text(std::size_t bytes) {
  if (bytes % (1u << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  if (bytes % (1u << 10) == 0) return std::to_string(bytes >> 10) + " KiB";
  return std::to_string(bytes) + " bytes";
}
}  // namespace

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> out;
  for (std::size_t pos = 0; pos < text.size();) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    out.push_back(text.substr(pos, end - pos));
    if (!out.back().empty() && out.back().back() == '\r') out.back().pop_back();
    pos = end + 1;
  }
  return out;
}

bool read_file(const std::string& path, std::vector<std::uint8_t>& out, std::string& error, std::size_t max_bytes) {
  int fd = path == "-" ? 0 : ::open(os::native_path(path).c_str(), O_RDONLY | os::kOpenFlags);
  if (fd < 0) {
    error = "cannot open '" + path + "': " + std::strerror(errno);
    return false;
  }
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) {
    error = "'" + path + "' is a directory";
    ::close(fd);
    return false;
  }
  out.clear();
  std::uint8_t buf[65536];
  while (true) {
    ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      error = "cannot read '" + path + "': " + std::strerror(errno);
      if (fd != 0) ::close(fd);
      return false;
    }
    if (n == 0) break;
    if (out.size() + static_cast<std::size_t>(n) > max_bytes) {
      error = "'" + path + "' is larger than the limit of " + size_text(max_bytes);
      if (fd != 0) ::close(fd);
      return false;
    }
    out.insert(out.end(), buf, buf + n);
  }
  if (fd != 0) ::close(fd);
  return true;
}

static bool write_all(int fd, const std::vector<std::uint8_t>& data) {
  std::size_t done = 0;
  while (done < data.size()) {
    // At most 1 GiB a call: Windows' write() counts in an unsigned int.
    const auto chunk = static_cast<unsigned>(std::min<std::size_t>(data.size() - done, 1u << 30));
    ssize_t n = ::write(fd, data.data() + done, chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

bool flush_stdout(std::string& error) {
  if (std::fflush(stdout) == 0 && !std::ferror(stdout)) return true;
  error = std::string("cannot write standard output: ") + std::strerror(errno);
  return false;
}

bool write_file_atomic(const std::string& path, const std::vector<std::uint8_t>& data, std::string& error,
                       bool durable) {
  if (path == "-") {
    if (!write_all(1, data)) {
      error = std::string("cannot write to standard output: ") + std::strerror(errno);
      return false;
    }
    return true;
  }
  // A device or pipe (-o /dev/null, a FIFO; NUL on Windows) is written into, never replaced by a
  // regular file.
  const std::string native = os::native_path(path);
  struct stat st {};
  if (native != path || os::is_device_name(native) || (::stat(native.c_str(), &st) == 0 && !S_ISREG(st.st_mode))) {
    if (S_ISDIR(st.st_mode)) {
      error = "cannot write '" + path + "': it is a directory";
      return false;
    }
    int dev = ::open(native.c_str(), O_WRONLY | os::kOpenFlags);
    bool ok = dev >= 0 && write_all(dev, data);
    if (!ok) error = "cannot write '" + path + "': " + std::strerror(errno);
    if (dev >= 0) ::close(dev);
    return ok;
  }
  std::string tmp = path + ".tmp." + std::to_string(::getpid());
  int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | os::kOpenFlags, 0666);
  if (fd < 0) {
    error = "cannot write '" + path + "': " + std::strerror(errno);
    return false;
  }
  bool ok = write_all(fd, data) && (!durable || os::sync_file(fd));
  int saved = errno;
  ok = (::close(fd) == 0) && ok;
  if (!ok || !os::replace_file(tmp, path)) {
    if (ok) saved = errno;
    ::unlink(tmp.c_str());
    error = "cannot write '" + path + "': " + std::strerror(saved);
    return false;
  }
  return true;
}

}  // namespace tmcl
