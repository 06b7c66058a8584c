// The protocol engine (TmclModule) without any I/O: framing and resynchronisation byte by byte,
// the 17-byte and quiet-gap rules, download bookkeeping, option handling. Fast and exact: the
// transports test the same behaviour end to end in test_transports.cpp.
#include "check.hpp"
#include "frames.hpp"
#include "tmcl/server.hpp"

using namespace srvtest;
using tmcl::Instruction;
using tmcl::Op;

namespace {

struct Engine {
  std::unique_ptr<tmcl::MotionCore> core = tmcl::make_ideal_motion_core();
  tmcl::Vm vm{*tmcl::find_profile("usb-2-sd"), *core};
  tmcl::TmclModule module;
  explicit Engine(tmcl::ProtocolOptions o = {}) : module(vm, o) {}
  Bytes feed(const Bytes& b) {
    module.receive(b.data(), b.size());
    Bytes out = module.output();
    module.output().clear();
    return out;
  }
};

Bytes cat(std::initializer_list<Bytes> parts) {
  Bytes r;
  for (const auto& p : parts) r.insert(r.end(), p.begin(), p.end());
  return r;
}

// The status byte of a reply, by value (a reference into a temporary would dangle).
std::uint8_t st(const Bytes& b) { return b.size() >= 3 ? b[2] : 0; }

}  // namespace

TEST(frame_split_byte_by_byte) {
  Engine e;
  Bytes f = frame(1, kGgp, 0, 2, 0);
  Bytes out;
  for (auto b : f) {
    Bytes o = e.feed({b});
    out.insert(out.end(), o.begin(), o.end());
  }
  CHECK_EQ(hex(out), hex(reply_bytes(2, 1, 100, kGgp, 0)));
}

TEST(garbage_before_frame_is_skipped_silently) {
  Engine e;
  Bytes out = e.feed(cat({{0x01, 0x99, 0x01}, frame(1, kGgp, 0, 2, 0)}));
  CHECK_EQ(hex(out), hex(reply_bytes(2, 1, 100, kGgp, 0)));
  CHECK_EQ(e.module.counters().skipped_bytes, 3u);
  CHECK(!e.module.window_pending());
}

TEST(corrupted_frame_then_frame_gives_status_1_then_reply) {
  Engine e;
  Bytes bad = frame(1, kGgp, 0, 2, 0);
  bad[5] ^= 1;
  Bytes out = e.feed(cat({bad, frame(1, kGgp, 1, 2, 0)}));
  CHECK_EQ(hex(out), hex(cat({reply_bytes(2, 1, 1, kGgp, 0), reply_bytes(2, 1, 100, kGgp, 0)})));
}

TEST(lone_corrupted_frame_waits_for_the_gap) {
  Engine e;
  Bytes bad = frame(1, kGgp, 0, 2, 0);
  bad[8] ^= 0x80;
  CHECK(e.feed(bad).empty());
  CHECK(e.module.window_pending());
  e.module.gap_elapsed();
  CHECK_EQ(hex(e.module.output()), hex(reply_bytes(2, 1, 1, kGgp, 0)));
  CHECK(!e.module.window_pending());
}

TEST(corrupted_frame_for_another_module_is_not_answered) {
  Engine e;
  Bytes bad = frame(3, kGgp, 0, 2, 0);
  bad[8] ^= 0x80;
  CHECK(e.feed(bad).empty());
  e.module.gap_elapsed();
  CHECK(e.module.output().empty());
  CHECK(e.feed(frame(3, kGgp, 0, 2, 0)).empty());  // valid, but not ours
  CHECK_EQ(e.module.counters().foreign, 1u);
}

TEST(torn_frame_then_new_connection) {
  Engine e;
  Bytes f = frame(1, kGgp, 0, 2, 0);
  CHECK(e.feed(Bytes(f.begin(), f.begin() + 5)).empty());
  e.module.drop_partial();
  CHECK_EQ(hex(e.feed(f)), hex(reply_bytes(2, 1, 100, kGgp, 0)));
}

TEST(torn_frame_without_disconnect_resynchronises) {
  Engine e;
  Bytes f = frame(1, kGgp, 0, 2, 0);
  CHECK(e.feed(Bytes(f.begin(), f.begin() + 5)).empty());
  CHECK_EQ(hex(e.feed(f)), hex(reply_bytes(2, 1, 100, kGgp, 0)));
}

TEST(download_end_marker_and_pointer) {
  Engine e;
  e.feed(frame(1, 132, 0, 0, 0));
  for (int i = 0; i < 5; ++i) {
    CHECK_EQ(st(e.feed(frame(1, static_cast<std::uint8_t>(Op::STOP), 0, 0, i))), 101);
  }
  CHECK(e.module.download_mode());
  CHECK_EQ(e.vm.program_size, 0);  // not reloaded word by word
  e.feed(frame(1, 133, 0, 0, 0));
  CHECK_EQ(e.vm.program_size, 5);
  e.feed(frame(1, 132, 0, 0, 2));
  e.feed(frame(1, 0, 0, 0, 0));  // end marker at 2
  e.feed(frame(1, 133, 0, 0, 0));
  CHECK_EQ(e.vm.program_size, 2);
  // 577 words on the USB-2-SD: the 578th store is refused
  e.feed(frame(1, 132, 0, 0, 576));
  CHECK_EQ(st(e.feed(frame(1, static_cast<std::uint8_t>(Op::STOP), 0, 0, 0))), 101);
  CHECK_EQ(st(e.feed(frame(1, static_cast<std::uint8_t>(Op::STOP), 0, 0, 0))), 4);
  CHECK_EQ(st(e.feed(frame(1, 132, 0, 0, 577))), 4);
}

TEST(address_overrides_and_locked_eeprom) {
  tmcl::ProtocolOptions o;
  o.module_address = 5;
  o.host_address = 9;
  o.eeprom_locked = true;
  Engine e(o);
  CHECK(e.feed(frame(1, kGgp, 0, 2, 0)).empty());
  CHECK_EQ(hex(e.feed(frame(5, kGgp, 66, 0, 0))), hex(reply_bytes(9, 5, 100, kGgp, 5)));
  CHECK_EQ(st(e.feed(frame(5, static_cast<std::uint8_t>(Op::STGP), 0, 2, 0))), 5);
  CHECK_EQ(st(e.feed(frame(5, static_cast<std::uint8_t>(Op::STAP), 4, 0, 0))), 5);
  CHECK_EQ(st(e.feed(frame(5, static_cast<std::uint8_t>(Op::SGP), 77, 0, 1))), 5);  // auto-stored
  CHECK_EQ(st(e.feed(frame(5, static_cast<std::uint8_t>(Op::SGP), 0, 2, 1))), 100);  // RAM only
  CHECK_EQ(st(e.feed(frame(5, 132, 0, 0, 0))), 5);
  CHECK_EQ(st(e.feed(frame(5, 137, 0, 0, 1234))), 5);
  // after a software reset the overrides still hold
  e.feed(frame(5, 255, 0, 0, 1234));
  CHECK(e.module.take_power_cycle());
  CHECK_EQ(hex(e.feed(frame(5, kGgp, 76, 0, 0))), hex(reply_bytes(9, 5, 100, kGgp, 9)));
}

// A user's profile may mark a bank-3 parameter A (stored by every SGP): with the EEPROM locked
// that SGP writes the EEPROM, so it is refused as bank 0's auto-stored parameters are.
TEST(locked_eeprom_refuses_sgp_of_an_auto_stored_bank3_parameter) {
  static const tmcl::ParamInfo bank3[] = {{0, "timer 0", 0, 4294967295LL, tmcl::kRead | tmcl::kWrite | tmcl::kAutoStore, 0, ""}};
  static const tmcl::Profile profile = [] {
    tmcl::Profile q = *tmcl::find_profile("usb-2-sd");
    q.bank3 = bank3;
    return q;
  }();
  auto core = tmcl::make_ideal_motion_core();
  tmcl::Vm vm(profile, *core);
  tmcl::ProtocolOptions o;
  o.eeprom_locked = true;
  tmcl::TmclModule m(vm, o);
  Bytes f = frame(1, static_cast<std::uint8_t>(Op::SGP), 0, 3, 100);
  m.receive(f.data(), f.size());
  CHECK_EQ(st(m.output()), 5);
  CHECK(vm.eeprom.bank3.empty());
}

TEST(control_commands_missing_from_profile_are_status_6) {
  auto core = tmcl::make_linear_motion_core();
  tmcl::Vm vm(*tmcl::find_profile("tmc2300-eval"), *core);
  tmcl::TmclModule m(vm);
  Bytes f = frame(1, 138, 1, 0, 1);
  m.receive(f.data(), f.size());
  CHECK_EQ(m.output().size(), 9u);
  if (m.output().size() == 9) CHECK_EQ(m.output()[2], 6);
  // no global 76 on this module: the host address is the default 2
  CHECK_EQ(m.output()[0], 2);
}

TEST(step_executes_one_instruction) {
  Engine e;
  e.vm.load({Instruction{static_cast<std::uint8_t>(Op::CALC), 0, 0, 5}, Instruction{static_cast<std::uint8_t>(Op::CALC), 0, 0, 5},
             Instruction{static_cast<std::uint8_t>(Op::STOP), 0, 0, 0}});
  e.feed(frame(1, 131, 0, 0, 0));
  e.feed(frame(1, 130, 0, 0, 0));
  CHECK_EQ(e.vm.acc, 5);
  CHECK_EQ(e.vm.pc, 1);
  CHECK(e.vm.status == tmcl::AppStatus::Step);
  e.module.advance(e.vm.now + 1000000);  // a stepped program does not run on by itself
  CHECK_EQ(e.vm.acc, 5);
  e.feed(frame(1, 130, 0, 0, 0));
  CHECK_EQ(e.vm.acc, 10);
  CHECK_EQ(value_of(e.feed(frame(1, 135, 1, 0, 0))), 2 << 24 | 2);
}

TEST(parse_serve_spec_forms) {
  tmcl::ServeOptions o;
  std::string err;
  CHECK(tmcl::parse_serve_spec("tcp:127.0.0.1:2001", o, err));
  CHECK(o.transport == tmcl::Transport::Tcp && o.host == "127.0.0.1" && o.port == 2001);
  CHECK(tmcl::parse_serve_spec("tcp:[::1]:0", o, err));
  CHECK(o.host == "::1" && o.port == 0);
  CHECK(tmcl::parse_serve_spec("tcp:4000", o, err));
  CHECK(o.host == "127.0.0.1" && o.port == 4000);
  CHECK(tmcl::parse_serve_spec("pty", o, err) && o.transport == tmcl::Transport::Pty);
  CHECK(tmcl::parse_serve_spec("stdio", o, err) && o.transport == tmcl::Transport::Stdio);
  CHECK(!tmcl::parse_serve_spec("tcp:::1:80", o, err));
  CHECK(!tmcl::parse_serve_spec("tcp:host:99999", o, err));
  CHECK(!tmcl::parse_serve_spec("serial", o, err));
  CHECK(!err.empty());
  // A serial port: COMn and \\.\COMn on every system (they open only on Windows), a device path,
  // and ":BAUD" for another rate than 9600.
  CHECK(tmcl::parse_serve_spec("COM5", o, err));
  CHECK(o.transport == tmcl::Transport::Serial && o.serial_port == "COM5" && o.serial_baud == 9600);
  CHECK(tmcl::parse_serve_spec("\\\\.\\COM12:115200", o, err));
  CHECK(o.serial_port == "\\\\.\\COM12" && o.serial_baud == 115200);
  CHECK(tmcl::parse_serve_spec("/dev/ttyUSB0:57600", o, err));
  CHECK(o.serial_port == "/dev/ttyUSB0" && o.serial_baud == 57600);
  err.clear();
  CHECK(!tmcl::parse_serve_spec("COM5:1234", o, err));
  CHECK(err.find("'1234' is not a baud rate") != std::string::npos);
  CHECK(tmcl::parse_serve_spec("Com7", o, err) && o.serial_port == "Com7");  // as tmclctl takes it
  CHECK(!tmcl::parse_serve_spec("COM", o, err));
  CHECK(!tmcl::parse_serve_spec("com5x", o, err));
}
