// What the unit tests need of the operating system, written once so that it is the same on Linux
// and on Windows (the cross build runs the unit tests under Wine, tests/windows/run.sh):
// a fresh scratch folder, setting and clearing environment variables, a temporary file, a stream
// whose text the test reads back, and a pipe (in place of POSIX's mkdtemp, setenv, tmpfile,
// open_memstream and pipe).
#pragma once

#ifdef _WIN32
#include <fcntl.h>
#include <io.h>
#include <process.h>
#include <sys/stat.h>
#else
#include <unistd.h>
#endif

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <cstdint>
#include <random>
#include <string>
#include <system_error>

namespace tmcl_test {

// A new, empty folder in the system's temporary folder, named PREFIX-<random>; "" when none
// could be made. Spelled with '/' on every system ("C:/Users/u/AppData/Local/Temp/PREFIX-..." on
// Windows), so that a test's `dir + "/name"` is the path the tools compose. The caller removes
// it (std::filesystem::remove_all) when it wants it gone.
inline std::string make_temp_dir(const std::string& prefix) {
  std::error_code ec;
  const std::filesystem::path base = std::filesystem::temp_directory_path(ec);
  if (ec) return "";
  std::random_device seed;
  std::mt19937_64 random(seed() ^ static_cast<std::uint64_t>(std::filesystem::file_time_type::clock::now().time_since_epoch().count()));
  for (int attempt = 0; attempt < 100; ++attempt) {
    char name[32];
    std::snprintf(name, sizeof name, "-%012llx", static_cast<unsigned long long>(random() & 0xffffffffffffULL));
    const std::filesystem::path dir = base / (prefix + name);
    if (std::filesystem::create_directory(dir, ec) && !ec) return dir.generic_string();
  }
  return "";
}

inline void set_env(const char* name, const char* value) {
#ifdef _WIN32
  ::_putenv_s(name, value);
#else
  ::setenv(name, value, 1);
#endif
}

inline void unset_env(const char* name) {
#ifdef _WIN32
  ::_putenv_s(name, "");  // an empty value removes the variable on Windows
#else
  ::unsetenv(name);
#endif
}

// A pipe: fds[0] reads what fds[1] writes, byte for byte (binary on Windows too).
inline bool make_pipe(int fds[2]) {
#ifdef _WIN32
  return ::_pipe(fds, 1 << 16, _O_BINARY) == 0;
#else
  return ::pipe(fds) == 0;
#endif
}

inline bool write_all(int fd, const std::string& bytes) {
  for (std::size_t done = 0; done < bytes.size();) {
#ifdef _WIN32
    const int n = ::_write(fd, bytes.data() + done, static_cast<unsigned>(bytes.size() - done));
#else
    const auto n = ::write(fd, bytes.data() + done, bytes.size() - done);
#endif
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

inline void close_fd(int fd) {
#ifdef _WIN32
  ::_close(fd);
#else
  ::close(fd);
#endif
}

// A temporary file open for reading and writing, removed when closed; nullptr when none could
// be made. std::tmpfile() on POSIX. Under Wine, tmpfile() (a name in the drive's root, opened
// without O_EXCL) fails with EACCES now and then while other processes make temporary files too,
// as ctest -j2 runs them (a DAP test session then got no input, or crashed on a null FILE*: CI's
// Windows step): here a name of this process's own in the current folder, created exclusively.
inline std::FILE* scratch_file() {
#ifdef _WIN32
  static unsigned counter = 0;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::string name = "tmcl-scratch-" + std::to_string(::_getpid()) + "-" + std::to_string(counter++) + ".tmp";
    const int fd = ::_open(name.c_str(), _O_CREAT | _O_EXCL | _O_RDWR | _O_BINARY | _O_TEMPORARY, _S_IREAD | _S_IWRITE);
    if (fd < 0) continue;
    if (std::FILE* f = ::_fdopen(fd, "w+b")) return f;
    ::_close(fd);
    return nullptr;
  }
  return nullptr;
#else
  return std::tmpfile();
#endif
}

// A stream to hand to code that writes to a FILE*, and the text written to it: text() closes it.
class CapturedFile {
 public:
  CapturedFile() : file_(scratch_file()) {}
  CapturedFile(const CapturedFile&) = delete;
  CapturedFile& operator=(const CapturedFile&) = delete;
  ~CapturedFile() {
    if (file_) std::fclose(file_);
  }
  std::FILE* get() const { return file_; }
  std::string text() {
    std::string out;
    if (!file_) return out;
    std::rewind(file_);
    char buf[4096];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, file_)) > 0;) out.append(buf, n);
    std::fclose(file_);
    file_ = nullptr;
    return out;
  }

 private:
  std::FILE* file_;
};

}  // namespace tmcl_test
