// Unit tests of the platform layer's input relay (os_net.hpp, pollable_input): what os::poll waits
// on for a file descriptor delivers that file's input and nothing else, even when the caller
// closes the descriptor and the C library hands its number to the next file opened (on Windows
// a thread relays the input; a DAP test session that ended before the thread saw the end of its
// file once lost the next session's requests to it: CI, the Windows step under Wine).
#include "check.hpp"
#include "tmcl/os_net.hpp"

#include <cstdio>
#include <string>

namespace {

std::FILE* file_with(const std::string& name, const std::string& text) {
  std::FILE* f = std::fopen(name.c_str(), "wb+");
  if (!f) return nullptr;
  std::fwrite(text.data(), 1, text.size(), f);
  std::rewind(f);
  return f;
}

// Everything readable from `fd` up to its end, waiting with os::poll as the DAP adapter does.
std::string drain(int fd) {
  std::string got;
  char buf[256];
  for (;;) {
    pollfd p = tmcl::os::poll_entry(fd, POLLIN);
    if (tmcl::os::poll(&p, 1, 5000) <= 0) return got + "<timeout>";
    const long n = tmcl::os::read_some(fd, buf, sizeof buf);
    if (n <= 0) return got;
    got.append(buf, static_cast<std::size_t>(n));
  }
}

}  // namespace

TEST(pollable_input_delivers_the_file_it_was_given) {
  std::FILE* f = file_with("os_net_test_a.txt", "first file\n");
  CHECK(f != nullptr);
  if (!f) return;
  const int polled = tmcl::os::pollable_input(::fileno(f));
  CHECK(polled >= 0);
  CHECK_EQ(drain(polled), std::string("first file\n"));
  tmcl::os::release_pollable_input(polled, ::fileno(f));
  std::fclose(f);
  std::remove("os_net_test_a.txt");
}

#ifdef _WIN32
// The descriptor closed at once and its number reused: the relay still reads the first file. Many
// rounds, because without a duplicate of its own the thread reads whichever file holds the number
// when it gets round to reading.
TEST(pollable_input_keeps_its_file_when_the_caller_closes_the_descriptor) {
  for (int round = 0; round < 40; ++round) {
    std::FILE* a = file_with("os_net_test_a.txt", "first file\n");
    CHECK(a != nullptr);
    if (!a) return;
    const int fd = ::fileno(a);
    const int polled = tmcl::os::pollable_input(fd);
    CHECK(polled >= 0);
    std::fclose(a);
    std::FILE* b = file_with("os_net_test_b.txt", "second file\n");
    CHECK(b != nullptr);
    if (!b) return;
    const bool reused = ::fileno(b) == fd;
    const std::string got = drain(polled);
    tmcl::os::release_pollable_input(polled, fd);
    std::fclose(b);
    if (got != "first file\n") {
      CHECK_EQ(got, std::string("first file\n"));
      std::fprintf(stderr, "round %d, descriptor %s\n", round, reused ? "reused" : "not reused");
      break;
    }
  }
  std::remove("os_net_test_a.txt");
  std::remove("os_net_test_b.txt");
}
#endif
