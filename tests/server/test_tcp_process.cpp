// TCP-only rules and the server as a separate process: one client at a time (a second one is
// told it is refused, the next one after a disconnect is served), IPv6 loopback, and
// SIGTERM/SIGINT shutting tmclrun --serve down cleanly with the EEPROM file saved.
#include <fstream>

#include "check.hpp"
#include "child.hpp"
#include "client.hpp"

using namespace srvtest;
using tmcl::Op;
using tmcl::Transport;

namespace {

// The refused connection reads the refusal line, then the end of the stream (no reset, which
// could destroy the line before it is read), never a reply: also when it sent a request first.
bool refused(Link& l) {
  if (!l.ok()) return false;
  l.send(frame(1, kGgp, 0, 2, 0));
  std::string got;
  const auto end = Clock::now() + std::chrono::seconds(5);
  for (;;) {
    pollfd p{l.fd, POLLIN, 0};
    if (Clock::now() > end) return false;
    if (const int rc = ::poll(&p, 1, 100); rc <= 0) {
      if (rc < 0 && errno != EINTR) return false;
      continue;
    }
    char b[256];
    const ssize_t n = ::read(l.fd, b, sizeof b);
    if (n > 0) got.append(b, static_cast<std::size_t>(n));
    if (n == 0) break;  // the server closed its side
    if (n < 0 && errno != EAGAIN) return false;  // a reset
  }
  if (got != tmcl::kBusyRefusal) std::fprintf(stderr, "  refused client read '%s'\n", got.c_str());
  return got == tmcl::kBusyRefusal;
}

}  // namespace

TEST(tcp_second_client_is_refused_and_next_is_served) {
  ServerConfig cfg;
  Server s(cfg);
  CHECK(s.is_ready);
  Link a = s.connect();
  auto r = a.request(kSgp, 9, 2, 9);
  CHECK(r && (*r)[2] == 100);
  Link b = s.connect();
  CHECK(refused(b));
  b.close();
  Link b2 = s.connect();  // and the next one, while the first client stays
  CHECK(refused(b2));
  r = a.request(kGgp, 9, 2, 0);  // the first client is undisturbed
  CHECK(r && value_of(*r) == 9);
  a.close();
  Link c = s.connect();
  r = c.request(kGgp, 9, 2, 0);  // state survives connections
  CHECK(r && value_of(*r) == 9);
  CHECK(s.log.str().find("refused a second client") != std::string::npos);
  c.close();
  CHECK_EQ(s.stop(), 0);
}

TEST(tcp_ipv6_loopback) {
  ServerConfig cfg;
  cfg.host = "::1";
  Server s(cfg);
  if (!s.is_ready || s.ready[0] != '[') {
    std::fprintf(stderr, "note: no IPv6 loopback here, skipped (%s)\n", s.log.str().c_str());
    return;
  }
  Link l = s.connect();
  CHECK(l.ok());
  auto r = l.request(136, 1, 0, 0);
  CHECK(r && value_of(*r) == 0x000F010E);
}

namespace {

Child spawn(const std::string& spec, const std::string& eeprom) {
  return spawn_tmclrun({"-t", "usb-2-sd", "--serve", spec, "--eeprom", eeprom, "--max-wall-time", "30s"});
}

}  // namespace

TEST(signals_shut_down_cleanly_and_save_the_eeprom) {
  char dir[] = "/tmp/tmcl-server-test-XXXXXX";
  CHECK(::mkdtemp(dir) != nullptr);
  const std::string eeprom = std::string(dir) + "/module.eeprom";

  Child c = spawn("tcp:127.0.0.1:0", eeprom);
  CHECK(c.line.rfind("listening on 127.0.0.1:", 0) == 0);
  {
    Link l = connect_to(c.line);
    CHECK(l.ok());
    auto r = l.request(kSgp, 4, 2, 4711);
    CHECK(r && (*r)[2] == 100);
    r = l.request(kStgp, 4, 2, 0);
    CHECK(r && (*r)[2] == 100);
    CHECK(l.send(Bytes{1, 2, 3}));  // a torn frame in flight does not delay the shutdown
  }
  ::kill(c.pid, SIGTERM);
  CHECK_EQ(reap(c), 0);
  std::ifstream in(eeprom);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text.find("var 4 4711") != std::string::npos);

  // Restarted with the same file: the value is back; SIGINT works the same way.
  Child d = spawn("tcp:127.0.0.1:0", eeprom);
  {
    Link l = connect_to(d.line);
    auto r = l.request(kGgp, 4, 2, 0);
    CHECK(r && value_of(*r) == 4711);
    ::kill(d.pid, SIGINT);
    CHECK_EQ(reap(d), 0);
  }
  ::unlink(eeprom.c_str());
  ::rmdir(dir);
}

TEST(autostart_runs_the_preloaded_program) {
  ServerConfig cfg;
  cfg.program = {tmcl::Instruction{static_cast<std::uint8_t>(Op::WAIT), 0, 0, 100000},
                 tmcl::Instruction{static_cast<std::uint8_t>(Op::STOP), 0, 0, 0}};
  cfg.autostart = true;
  Server s(cfg);
  Link l = s.connect();
  auto r = l.request(kGgp, 128, 0, 0);
  CHECK(r && value_of(*r) == 1);  // running (waiting)
  r = l.request(135, 1, 0, 0);
  CHECK(r && value_of(*r) == (1 << 24 | 1 << 16 | 0));  // running, in a WAIT, at address 0
}

TEST(simulated_time_follows_the_wall_clock_scaled) {
  ServerConfig cfg;
  cfg.time_scale = 50;
  Server s(cfg);
  Link l = s.connect();
  auto a = l.request(kGgp, 132, 0, 0);  // tick timer, milliseconds
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  auto b = l.request(kGgp, 132, 0, 0);
  CHECK(a && b);
  if (a && b) {
    const std::int32_t d = value_of(*b) - value_of(*a);  // about 200 ms * 50 = 10 s
    CHECK(d >= 9000);
    CHECK(d <= 20000);
  }
}
