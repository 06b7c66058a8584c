// Virtual-module benchmark (issue 6): request/reply round trips per second over loopback TCP with
// one client — a GAP request, wait for its reply, the next request — against serve() running in
// a thread of this process, as PyTrinamic talks to it. Also the pipelined rate (16 requests in
// flight), which shows what the protocol engine itself costs. A real module on a 115200-baud
// line manages about 600 round trips per second. Loopback only; bounded by count and time.
// Prints "figure<TAB>goal<TAB>measured" rows for tests/bench/run_all.sh.
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <arpa/inet.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "tmcl/image.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/server.hpp"
#include "tmcl/vm.hpp"

namespace {

using Clock = std::chrono::steady_clock;

// Reads n bytes. Like a latency-sensitive host, the client polls the socket without sleeping for
// up to 200 us before it blocks, so a round trip measures the server and the kernel, not the
// client's own wake-up (the echo baseline uses the same reader, so the comparison stays fair).
bool read_exact(int fd, std::uint8_t* p, std::size_t n) {
  std::size_t got = 0;
  auto spin_until = Clock::now() + std::chrono::microseconds(200);
  while (got < n) {
    ssize_t k = ::recv(fd, p + got, n - got, MSG_DONTWAIT);
    if (k < 0 && (errno == EAGAIN || errno == EWOULDBLOCK) && Clock::now() < spin_until) continue;
    if (k < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) k = ::recv(fd, p + got, n - got, 0);
    if (k <= 0) {
      pollfd pf{fd, POLLIN, 0};
      if (k < 0 && errno == EINTR) continue;
      if (k == 0 || ::poll(&pf, 1, 2000) <= 0) return false;
      continue;
    }
    got += static_cast<std::size_t>(k);
  }
  return true;
}

// The kernel's ceiling on this machine: the same ping-pong against a bare echo thread that
// spins on a non-blocking socket the way serve() does (no protocol, no VM): it reads without
// sleeping for 100 us after each message and only then sleeps in poll().
double echo_baseline() {
  int lfd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof a;
  if (::bind(lfd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || ::listen(lfd, 1) != 0) return -1;
  ::getsockname(lfd, reinterpret_cast<sockaddr*>(&a), &len);
  std::thread echo([lfd] {
    int c = ::accept(lfd, nullptr, nullptr);
    int one = 1;
    ::setsockopt(c, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    std::uint8_t b[512];
    auto spin_until = Clock::now();
    for (;;) {
      ssize_t k = ::recv(c, b, sizeof b, MSG_DONTWAIT);
      if (k == 0) break;
      if (k < 0) {
        if (errno != EAGAIN) break;
        if (Clock::now() < spin_until) continue;
        pollfd pf{c, POLLIN, 0};
        ::poll(&pf, 1, 1);
        continue;
      }
      spin_until = Clock::now() + std::chrono::microseconds(100);
      if (::send(c, b, static_cast<std::size_t>(k), MSG_NOSIGNAL) != k) break;
    }
    ::close(c);
  });
  int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  int one = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  double rate = -1;
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0) {
    std::uint8_t m[9] = {1, 6, 1, 0, 0, 0, 0, 0, 8};
    int n = 0;
    const auto t0 = Clock::now();
    while (n < 300000) {
      if (::send(fd, m, 9, MSG_NOSIGNAL) != 9 || !read_exact(fd, m, 9)) break;
      if ((++n & 1023) == 0 && std::chrono::duration<double>(Clock::now() - t0).count() > 2.0) break;
    }
    rate = n / std::chrono::duration<double>(Clock::now() - t0).count();
  }
  ::close(fd);
  echo.join();
  ::close(lfd);
  return rate;
}

}  // namespace

int main() {
  const tmcl::Profile* profile = tmcl::find_profile("usb-2-sd");
  auto core = tmcl::make_motion_core(profile->default_motion);
  tmcl::Vm vm(*profile, *core);
  vm.power_on(nullptr);

  int stop_pipe[2];
  if (::pipe(stop_pipe) != 0) return 1;
  tmcl::ServeOptions opt;
  opt.port = 0;
  opt.handle_signals = false;
  opt.quiet = true;
  opt.stop_fd = stop_pipe[0];
  opt.max_wall_ms = 60000;
  std::mutex mu;
  std::condition_variable cv;
  std::string ready;
  opt.on_ready = [&](const std::string& s) {
    std::lock_guard<std::mutex> g(mu);
    ready = s;
    cv.notify_all();
  };
  std::thread server([&] { tmcl::serve(vm, opt); });
  {
    std::unique_lock<std::mutex> g(mu);
    if (!cv.wait_for(g, std::chrono::seconds(5), [&] { return !ready.empty(); })) return 1;
  }
  const int port = std::stoi(ready.substr(ready.rfind(':') + 1));
  int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  int one = 1;
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) return 1;

  const auto req = tmcl::datagram(1, tmcl::Instruction{6, 1, 0, 0});  // GAP 1, 0: actual position
  std::uint8_t reply[9 * 16];

  // Ping-pong: one request in flight. Bounded: 300000 round trips or 3 s.
  auto measure_pingpong = [&](int max_n, double max_s) {
    int n = 0;
    const auto t0 = Clock::now();
    double s = 0;
    while (n < max_n) {
      if (::send(fd, req.data(), req.size(), MSG_NOSIGNAL) != 9 || !read_exact(fd, reply, 9)) return -1.0;
      ++n;
      if ((n & 1023) == 0 && (s = std::chrono::duration<double>(Clock::now() - t0).count()) > max_s) break;
    }
    s = std::chrono::duration<double>(Clock::now() - t0).count();
    return n / s;
  };
  measure_pingpong(20000, 0.5);  // warm up
  const double pingpong = measure_pingpong(300000, 3.0);

  // Pipelined: 16 requests per write, 16 replies read back.
  std::vector<std::uint8_t> batch;
  for (int i = 0; i < 16; ++i) batch.insert(batch.end(), req.begin(), req.end());
  int n = 0;
  const auto t0 = Clock::now();
  while (n < 2000000) {
    if (::send(fd, batch.data(), batch.size(), MSG_NOSIGNAL) != static_cast<ssize_t>(batch.size()) ||
        !read_exact(fd, reply, sizeof reply))
      break;
    n += 16;
    if ((n & 16383) == 0 && std::chrono::duration<double>(Clock::now() - t0).count() > 3.0) break;
  }
  const double pipelined = n / std::chrono::duration<double>(Clock::now() - t0).count();

  ::close(fd);
  [[maybe_unused]] ssize_t w = ::write(stop_pipe[1], "x", 1);
  server.join();

  std::printf("server: round trips/s, loopback TCP, one request in flight\t>= 100000\t%.0f\n", pingpong);
  std::printf("server: requests/s, loopback TCP, 16 in flight\t(info)\t%.0f\n", pipelined);
  std::printf("server: bare TCP echo round trips/s on this machine (ceiling)\t(info)\t%.0f\n", echo_baseline());
  return pingpong > 0 ? 0 : 1;
}
