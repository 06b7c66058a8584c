// The virtual module over its four transports (TCP on loopback, a pseudo-terminal, a
// socketpair standing in for stdio, a serial port: the slave of a pseudo-terminal, the host at
// its master): every scenario runs against a fresh server on each.
// Covers the manual's direct-mode reply table byte for byte, download/run/poll/stop/read-back,
// standalone + direct mode on shared variables, every status code, 138 events, reply
// suppression, addresses, 134/135/136 layouts, 137/255, a seeded random byte stream, torn
// frames and a flood of pipelined requests.
#include <fstream>
#include <random>

#include "check.hpp"
#include "client.hpp"
#include "data_file.hpp"

using namespace srvtest;
using tmcl::Instruction;
using tmcl::Op;
using tmcl::Transport;

namespace {

constexpr std::uint8_t H = 2, M = 1;  // host and module address

std::uint8_t op(Op o) { return static_cast<std::uint8_t>(o); }
Instruction I(Op o, int type, int motor, std::int32_t value) {
  return Instruction{op(o), static_cast<std::uint8_t>(type), static_cast<std::uint8_t>(motor), value};
}

// Expects the reply to a request to be exactly (status, op, value) from host 2 / module 1.
void expect(Link& l, std::uint8_t o, std::uint8_t type, std::uint8_t motor, std::int32_t value, std::uint8_t status,
            std::int32_t reply_value) {
  auto r = l.request(o, type, motor, value);
  CHECK(r.has_value());
  if (r) CHECK_EQ(hex(*r), hex(reply_bytes(H, M, status, o, reply_value)));
}

// A setter: status 100 (the value of a setter's reply is the VM's business, E38 and friends).
void set(Link& l, std::uint8_t o, std::uint8_t type, std::uint8_t motor, std::int32_t value) {
  auto r = l.request(o, type, motor, value);
  CHECK(r.has_value());
  if (r) CHECK_EQ(hex(Bytes(r->begin(), r->begin() + 4)), hex(Bytes{H, M, 100, o}));
}

std::uint8_t status_of(Link& l, std::uint8_t o, std::uint8_t type, std::uint8_t motor, std::int32_t value) {
  auto r = l.request(o, type, motor, value);
  return r ? (*r)[2] : 0;
}

std::int32_t get(Link& l, std::uint8_t o, std::uint8_t type, std::uint8_t motor) {
  auto r = l.request(o, type, motor, 0);
  CHECK(r.has_value());
  return r ? value_of(*r) : INT32_MIN;
}

void download(Link& l, const std::vector<Instruction>& prog, bool end_marker) {
  expect(l, 132, 0, 0, 0, 100, 0);
  for (const auto& ins : prog) expect(l, ins.op, ins.type, ins.motor, ins.value, 101, ins.value);
  if (end_marker) expect(l, 0, 0, 0, 0, 101, 0);
  expect(l, 133, 0, 0, 0, 100, 0);
}

// ---- scenarios ----

void conformance_rows(Server& s, Link& l) {
  (void)s;
  const auto lines = DATA_LINES("manual-direct-mode-replies.tsv");
  if (lines.empty()) return;  // already failed, naming the file
  int rows = 0;
  for (const std::string& line : lines) {
    if (line.rfind("manual\t", 0) == 0) continue;  // the header
    const std::vector<std::string> cols = ::tmcl_test::tsv_fields(line);
    if (cols.size() < 5) continue;
    ++rows;
    Bytes req = parse_hex(cols[3]), want = parse_hex(cols[4]);
    CHECK(l.send(req));
    auto got = l.recv(9);
    CHECK(got.has_value());
    if (got) CHECK_EQ(hex(*got) + "  <- " + cols[2], hex(want) + "  <- " + cols[2]);
    if (req[1] == 138) {
      // The row's second reply: status 128 when the motor arrives (after the next MVP).
      set(l, op(Op::SAP), 4, 0, 51200);
      set(l, op(Op::MVP), 0, 0, 2000);
      auto ev = l.recv(9, 5000);
      CHECK(ev.has_value());
      if (ev) CHECK_EQ(hex(*ev), std::string("02 01 80 8A 00 00 00 01 0E"));
    }
  }
  CHECK(rows >= 8);
}

void download_run_poll_stop_readback(Server& s, Link& l) {
  (void)s;
  const std::vector<Instruction> prog = {
      I(Op::SAP, 4, 0, 100000),   // 0: max speed
      I(Op::SAP, 5, 0, 200000),   // 1: max acceleration
      I(Op::MVP, 0, 0, 400000),   // 2: loop: out
      I(Op::WAIT, 1, 0, 0),       // 3: WAIT POS
      I(Op::MVP, 0, 0, 0),        // 4: back
      I(Op::WAIT, 1, 0, 0),       // 5
      I(Op::JA, 0, 0, 2),         // 6
  };
  download(l, prog, true);
  expect(l, 131, 0, 0, 0, 100, 0);
  CHECK_EQ(get(l, op(Op::GGP), 128, 0), 3);  // reset
  expect(l, 129, 0, 0, 0, 100, 0);
  CHECK_EQ(get(l, op(Op::GGP), 128, 0), 1);  // running
  // Poll the actual position while the motor moves: it must take intermediate values.
  std::int32_t lo = INT32_MAX, hi = INT32_MIN;
  int between = 0;
  const auto end = Clock::now() + std::chrono::milliseconds(1500);
  while (Clock::now() < end && between < 20) {
    std::int32_t p = get(l, op(Op::GAP), 1, 0);
    lo = std::min(lo, p);
    hi = std::max(hi, p);
    if (p > 0 && p < 400000) ++between;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  CHECK(between >= 3);
  CHECK(hi > lo);
  // 135 type 1: running, program counter inside the program.
  std::int32_t st = get(l, 135, 1, 0);
  CHECK_EQ(st >> 24, 1);
  CHECK((st & 0xFFFF) < 7);
  expect(l, 128, 0, 0, 0, 100, 0);
  CHECK_EQ(get(l, op(Op::GGP), 128, 0), 0);
  // The stopped program no longer drives the motor: once it rests it stays.
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  std::int32_t p1 = get(l, op(Op::GAP), 1, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  CHECK_EQ(get(l, op(Op::GAP), 1, 0), p1);
  // Read back with 134, type 0 (the classic layout) and types 1/2.
  for (std::size_t a = 0; a <= prog.size(); ++a) {
    auto r = l.request(134, 0, 0, static_cast<std::int32_t>(a));
    CHECK(r.has_value());
    if (!r) break;
    Instruction want = a < prog.size() ? prog[a] : Instruction{};
    auto e = tmcl::encode7(want);
    Bytes exp{H, e[0], e[1], e[2], e[3], e[4], e[5], e[6], 0};
    exp[8] = tmcl::sum8(exp.data(), 8);
    CHECK_EQ(hex(*r), hex(exp));
    CHECK_EQ(get(l, 134, 1, 0) >= 0, true);
  }
  auto r1 = l.request(134, 1, 0, 2);
  CHECK(r1 && value_of(*r1) == (4 | 0 << 8 | 0 << 16));
  auto r2 = l.request(134, 2, 0, 2);
  CHECK(r2 && value_of(*r2) == 400000);
  // A shorter download with an end marker truncates program memory there.
  download(l, {I(Op::STOP, 0, 0, 0)}, true);
  auto end1 = l.request(134, 0, 0, 1);
  CHECK(end1 && (*end1)[1] == 0);
}

void combined_mode_vars(Server& s, Link& l) {
  (void)s;
  // The program waits for the host to set variable 0, then answers in variable 1 and stops.
  download(l, {I(Op::GGP, 0, 2, 0), I(Op::JC, 0, 0, 0), I(Op::CALCV, 9, 1, 42), I(Op::STOP, 0, 0, 0)}, false);
  expect(l, 129, 1, 0, 0, 100, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  CHECK_EQ(get(l, op(Op::GGP), 128, 0), 1);  // still polling
  CHECK_EQ(get(l, op(Op::GGP), 1, 2), 0);
  CHECK_EQ(get(l, 135, 2, 0), 0);            // its accumulator (direct reads left it alone)
  set(l, op(Op::SGP), 0, 2, 7);
  std::int32_t v = 0;
  for (int i = 0; i < 200 && v != 42; ++i) {
    v = get(l, op(Op::GGP), 1, 2);
    if (v != 42) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  CHECK_EQ(v, 42);
  CHECK_EQ(get(l, op(Op::GGP), 128, 0), 0);  // it reached STOP
  CHECK_EQ(get(l, 135, 2, 0), 7);            // its accumulator holds what it read
}

void error_statuses(Server& s, Link& l) {
  (void)s;
  // 1: wrong checksum (answered once the line is quiet for the resynchronisation gap)
  Bytes bad = frame(M, op(Op::GAP), 1, 0, 0);
  bad[8] ^= 0x55;
  CHECK(l.send(bad));
  auto r = l.recv(9, 2000);
  CHECK(r.has_value());
  if (r) CHECK_EQ(hex(*r), hex(reply_bytes(H, M, 1, op(Op::GAP), 0)));
  CHECK_EQ(status_of(l, 99, 0, 0, 0), 2);             // 2: no such command
  CHECK_EQ(status_of(l, 160, 0, 0, 0), 2);
  CHECK_EQ(status_of(l, op(Op::GAP), 250, 0, 0), 3);  // 3: no axis parameter 250
  CHECK_EQ(status_of(l, 136, 7, 0, 0), 3);
  CHECK_EQ(status_of(l, op(Op::SAP), 4, 0, -1), 4);   // 4: speed out of range
  CHECK_EQ(status_of(l, 129, 1, 0, 5000), 4);         // 4: no such address
  CHECK_EQ(status_of(l, 255, 0, 0, 1), 4);            // 4: reset without 1234
  CHECK_EQ(status_of(l, 137, 0, 0, 1), 4);
  CHECK_EQ(status_of(l, op(Op::MVPXA), 0, 0, 0), 6);  // 6: not on the USB-2-SD
  CHECK_EQ(status_of(l, op(Op::GAP), 1, 0, 0), 100);
  CHECK_EQ(status_of(l, 132, 0, 0, 0), 100);
  CHECK_EQ(status_of(l, op(Op::ROR), 0, 0, 100), 101);  // stored, not executed
  CHECK_EQ(status_of(l, 133, 0, 0, 0), 100);
  CHECK_EQ(get(l, op(Op::GAP), 3, 0), 0);  // the ROR did not run
}

void events_138(Server& s, Link& l) {
  (void)s;
  set(l, op(Op::SAP), 4, 0, 200000);
  expect(l, 138, 2, 0, 1, 3, 1);  // wrong type
  expect(l, 138, 1, 0, 2, 4, 2);  // motor 1 does not exist
  // type 1: every MVP is announced
  expect(l, 138, 1, 0, 1, 100, 1);
  for (int target : {5000, 0}) {
    set(l, op(Op::MVP), 0, 0, target);
    auto ev = l.recv(9, 5000);
    CHECK(ev.has_value());
    if (ev) CHECK_EQ(hex(*ev), hex(reply_bytes(H, M, 128, 138, 1)));
    CHECK_EQ(get(l, op(Op::GAP), 1, 0), target);
  }
  // type 1 with mask 0 switches it off; type 0 announces the next MVP only
  expect(l, 138, 1, 0, 0, 100, 0);
  expect(l, 138, 0, 0, 1, 100, 1);
  set(l, op(Op::MVP), 0, 0, 3000);
  auto ev = l.recv(9, 5000);
  CHECK(ev && (*ev)[2] == 128);
  set(l, op(Op::MVP), 0, 0, 0);
  CHECK(l.silent(400));
  CHECK_EQ(get(l, op(Op::GAP), 1, 0), 0);
}

void suppression(Server& s, Link& l) {
  (void)s;
  CHECK(l.send(frame(M, op(Op::SGP), 255, 0, 1)));
  CHECK(l.silent(100));
  CHECK(l.send(frame(M, op(Op::SAP), 4, 0, 1000)));  // executed, not answered
  CHECK(l.send(frame(M, 136, 1, 0, 0)));
  CHECK(l.silent(100));
  CHECK_EQ(get(l, op(Op::GAP), 4, 0), 1000);  // GAP, GGP and GIO still answer
  CHECK_EQ(get(l, op(Op::GGP), 255, 0), 1);
  auto io = l.request(op(Op::GIO), 0, 0, 0);
  CHECK(io && (*io)[2] == 100);
  set(l, op(Op::SGP), 255, 0, 0);  // switched off: this reply is sent
}

void addresses(Server& s, Link& l) {
  (void)s;
  CHECK(l.send(frame(5, op(Op::GAP), 1, 0, 0)));  // another module: no reply
  CHECK(l.silent(100));
  set(l, op(Op::SGP), 66, 0, 7);  // now module 7
  CHECK(l.send(frame(M, op(Op::GAP), 1, 0, 0)));
  CHECK(l.silent(100));
  auto r = l.request(op(Op::GGP), 66, 0, 0, 7);
  CHECK(r.has_value());
  if (r) CHECK_EQ(hex(*r), hex(reply_bytes(H, 7, 100, op(Op::GGP), 7)));
  r = l.request(op(Op::SGP), 76, 0, 9, 7);  // host address 9 (the reply to this still goes to 2)
  CHECK(r && (*r)[0] == 2);
  r = l.request(op(Op::GGP), 76, 0, 0, 7);
  CHECK(r.has_value());
  if (r) CHECK_EQ(hex(*r), hex(reply_bytes(9, 7, 100, op(Op::GGP), 9)));
  CHECK(l.request(op(Op::SGP), 76, 0, 2, 7).has_value());
  CHECK(l.request(op(Op::SGP), 66, 0, 1, 7).has_value());
  expect(l, op(Op::GGP), 66, 0, 0, 100, 1);
}

void firmware_and_status(Server& s, Link& l) {
  (void)s;
  auto r = l.request(136, 0, 0, 0);
  CHECK(r.has_value());
  if (r) CHECK_EQ(std::string(r->begin() + 1, r->end()), std::string("0015V114"));
  if (r) CHECK_EQ((*r)[0], H);
  expect(l, 136, 1, 0, 0, 100, 0x000F010E);
  expect(l, 132, 0, 0, 10, 100, 10);
  expect(l, op(Op::STOP), 0, 0, 0, 101, 0);
  expect(l, 135, 0, 0, 0, 100, 4 << 24 | 11);  // download mode, pointer 11
  expect(l, 133, 0, 0, 0, 100, 0);
  expect(l, 135, 0, 0, 0, 100, 0 << 24 | 11);
  expect(l, op(Op::CALC), 9, 0, 77, 100, 77);  // accumulator := 77
  expect(l, 135, 2, 0, 0, 100, 77);
  expect(l, 135, 3, 0, 0, 100, 0);
  expect(l, 135, 4, 0, 0, 3, 0);
}

void factory_and_reset(Server& s, Link& l) {
  (void)s;
  set(l, op(Op::SGP), 5, 2, 123);
  set(l, op(Op::SAP), 4, 0, 777);
  expect(l, 255, 0, 0, 1234, 100, 1234);  // reply first, then the restart
  CHECK_EQ(get(l, op(Op::GGP), 5, 2), 0);
  CHECK(get(l, op(Op::GAP), 4, 0) != 777);
  set(l, op(Op::SGP), 0, 2, 55);
  set(l, op(Op::STGP), 0, 2, 0);  // into the EEPROM
  expect(l, 255, 0, 0, 1234, 100, 1234);
  CHECK_EQ(get(l, op(Op::GGP), 0, 2), 55);  // restored at power-up
  CHECK(l.send(frame(M, 137, 0, 0, 1234)));  // no reply (manual)
  CHECK(l.silent(150));
  expect(l, 255, 0, 0, 1234, 100, 1234);
  CHECK_EQ(get(l, op(Op::GGP), 0, 2), 0);  // the EEPROM was cleared
}

void random_stream(Server& s, Link& l) {
  (void)s;
  std::mt19937 rng(20240611);
  Bytes junk(30000);
  for (auto& b : junk) b = static_cast<std::uint8_t>(rng());
  const auto t0 = Clock::now();
  CHECK(l.send(junk, 10000));
  l.drain(150);  // replies to windows that looked like frames, status-1 answers
  CHECK(Clock::now() - t0 < std::chrono::seconds(15));
  // Recover a known state whatever the junk switched on, then it must answer valid frames.
  CHECK(l.send(frame(M, 133, 0, 0, 0)));
  CHECK(l.send(frame(M, op(Op::SGP), 255, 0, 0)));
  l.drain(150);
  for (int i = 0; i < 50; ++i) set(l, op(Op::SGP), static_cast<std::uint8_t>(i), 2, i * 3);
  for (int i = 0; i < 50; ++i) CHECK_EQ(get(l, op(Op::GGP), static_cast<std::uint8_t>(i), 2), i * 3);
}

void torn_frame(Server& s, Link& l) {
  Bytes f = frame(M, op(Op::GGP), 0, 2, 0);
  // Half a frame, then the connection goes away (stdio cannot: the next frame follows).
  CHECK(l.send(Bytes(f.begin(), f.begin() + 4)));
  if (s.opt.transport != Transport::Stdio) {
    l.close();
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    l = s.connect();
    CHECK(l.ok());
  }
  set(l, op(Op::SGP), 3, 2, 33);
  CHECK_EQ(get(l, op(Op::GGP), 3, 2), 33);
  // Garbage glued in front of a frame and between frames, in one write.
  Bytes mixed{0xFF, 0x01, 0x13};
  Bytes a = frame(M, op(Op::GGP), 3, 2, 0);
  mixed.insert(mixed.end(), a.begin(), a.end());
  mixed.push_back(0x42);
  mixed.insert(mixed.end(), a.begin(), a.end());
  CHECK(l.send(mixed));
  for (int i = 0; i < 2; ++i) {
    auto r = l.recv(9);
    CHECK(r.has_value());
    if (r) CHECK_EQ(hex(*r), hex(reply_bytes(H, M, 100, op(Op::GGP), 33)));
  }
}

void flood(Server& s, Link& l) {
  (void)s;
  constexpr int kN = 20000;
  Bytes all;
  all.reserve(kN * 9);
  for (int i = 0; i < kN; ++i) {
    Bytes f = frame(M, op(Op::CALC), 9, 0, i);  // CALC LOAD answers with its operand
    all.insert(all.end(), f.begin(), f.end());
  }
  // Write and read at the same time: the server stops reading when its replies pile up.
  std::size_t sent = 0, got = 0;
  Bytes in(kN * 9);
  const auto end = Clock::now() + std::chrono::seconds(20);
  while (got < in.size() && Clock::now() < end) {
    pollfd p{l.fd, static_cast<short>(POLLIN | (sent < all.size() ? POLLOUT : 0)), 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    if ((p.revents & POLLOUT) && sent < all.size()) {
      ssize_t n = ::write(l.fd, all.data() + sent, std::min<std::size_t>(all.size() - sent, 4096));
      if (n > 0) sent += static_cast<std::size_t>(n);
    }
    if (p.revents & POLLIN) {
      ssize_t n = ::read(l.fd, in.data() + got, in.size() - got);
      if (n > 0) got += static_cast<std::size_t>(n);
    }
  }
  CHECK_EQ(got, in.size());
  int wrong = 0;
  for (int i = 0; i < kN && (static_cast<std::size_t>(i) + 1) * 9 <= got; ++i) {
    Bytes r(in.begin() + i * 9, in.begin() + i * 9 + 9);
    if (r != reply_bytes(H, M, 100, op(Op::CALC), i)) ++wrong;
  }
  CHECK_EQ(wrong, 0);
  CHECK_EQ(get(l, 135, 2, 0), kN - 1);  // the accumulator holds the last one
}

using Scenario = void (*)(Server&, Link&);

void run(Transport t, Scenario sc) {
  ServerConfig cfg;
  cfg.transport = t;
  Server s(cfg);
  CHECK(s.is_ready);
  if (!s.is_ready) return;
  Link l = s.connect();
  CHECK(l.ok());
  if (!l.ok()) return;
  sc(s, l);
  l.close();
  CHECK_EQ(s.stop(), 0);
}

}  // namespace

#define ON_ALL_TRANSPORTS(name)                                 \
  TEST(tcp_##name) { run(Transport::Tcp, name); }               \
  TEST(pty_##name) { run(Transport::Pty, name); }               \
  TEST(stdio_##name) { run(Transport::Stdio, name); }          \
  TEST(serial_##name) { run(Transport::Serial, name); }

ON_ALL_TRANSPORTS(conformance_rows)
ON_ALL_TRANSPORTS(download_run_poll_stop_readback)
ON_ALL_TRANSPORTS(combined_mode_vars)
ON_ALL_TRANSPORTS(error_statuses)
ON_ALL_TRANSPORTS(events_138)
ON_ALL_TRANSPORTS(suppression)
ON_ALL_TRANSPORTS(addresses)
ON_ALL_TRANSPORTS(firmware_and_status)
ON_ALL_TRANSPORTS(factory_and_reset)
ON_ALL_TRANSPORTS(random_stream)
ON_ALL_TRANSPORTS(torn_frame)
ON_ALL_TRANSPORTS(flood)

// A serial line that goes away (an adapter unplugged; here the pseudo-terminal's master closed):
// the server says so and stops by itself with status 0, instead of spinning on the hang-up.
TEST(serial_line_gone_stops_the_server) {
  ServerConfig cfg;
  cfg.transport = Transport::Serial;
  Server s(cfg);
  CHECK(s.is_ready);
  if (!s.is_ready) return;
  ::close(s.line_master);
  s.line_master = -1;
  s.thread.join();  // it ends by itself (opt.max_wall_ms bounds a failure), nobody told it to stop
  CHECK_EQ(s.result, 0);
  CHECK(s.log.str().find("tmclrun: the serial line " + s.opt.serial_port + " is gone (unplugged?): stopping") !=
        std::string::npos);
}
