// Direct mode: execute_direct's status codes and values; reads leave the accumulator alone;
// the reply values of tests/data/manual-direct-mode-replies.tsv (E14).
#include "check.hpp"
#include "machine.hpp"

using namespace vmtest;
using tmcl::Op;

TEST(direct_reads_do_not_touch_accumulator) {
  Machine m({I(Op::STOP)});
  m.vm.acc = 17;
  m.vm.flags = tmcl::kFlagLower;
  auto r = m.vm.execute_direct(I(Op::SAP, 4, 0, 51200));
  CHECK_EQ(r.status, 100);
  r = m.vm.execute_direct(I(Op::GAP, 4, 0));
  CHECK_EQ(r.status, 100);
  CHECK_EQ(r.value, 51200);
  CHECK_EQ(m.vm.acc, 17);
  CHECK_EQ(m.vm.flags, tmcl::kFlagLower);
  r = m.vm.execute_direct(I(Op::GGP, 130, 0));
  CHECK_EQ(r.status, 100);
}

TEST(direct_status_codes) {
  Machine m({I(Op::STOP)});
  CHECK_EQ(m.vm.execute_direct(Instruction{99, 0, 0, 0}).status, 2);     // no such command
  CHECK_EQ(m.vm.execute_direct(Instruction{128, 0, 0, 0}).status, 2);    // control: the server's
  CHECK_EQ(m.vm.execute_direct(I(Op::UF0)).status, 6);                   // not on this module
  CHECK_EQ(m.vm.execute_direct(I(Op::UF1)).status, 6);                   // no user functions
  CHECK_EQ(m.vm.execute_direct(I(Op::SAP, 99, 0, 1)).status, 3);         // unknown parameter
  CHECK_EQ(m.vm.execute_direct(I(Op::SAP, 3, 0, 1)).status, 3);          // read-only
  CHECK_EQ(m.vm.execute_direct(I(Op::SAP, 4, 0, -1)).status, 4);         // out of range
  CHECK_EQ(m.vm.execute_direct(I(Op::SAP, 4, 7, 1)).status, 4);          // no such motor
  CHECK_EQ(m.vm.execute_direct(I(Op::SGP, 1, 1, 1)).status, 4);          // no bank 1
  CHECK_EQ(m.vm.execute_direct(I(Op::CALC, 12, 0, 1)).status, 3);        // no such operation
  CHECK_EQ(m.vm.execute_direct(I(Op::EI, 100)).status, 3);               // no such interrupt
  CHECK_EQ(m.vm.execute_direct(I(Op::STGP, 60, 2)).status, 3);           // not EEPROM-backed
}

TEST(direct_flow_commands_have_no_effect) {
  Machine m({I(Op::STOP), I(Op::STOP)});
  auto r = m.vm.execute_direct(I(Op::JA, 0, 0, 1));
  CHECK_EQ(r.status, 100);
  CHECK_EQ(m.vm.pc, 0);
  r = m.vm.execute_direct(I(Op::WAIT, 0, 0, 100));
  CHECK_EQ(r.status, 100);
  CHECK(!m.vm.wait.active);
}

TEST(direct_manual_reply_values) {
  Machine m({I(Op::STOP)});
  CHECK_EQ(m.vm.execute_direct(I(Op::CALC, 2, 0, -5000)).value, -5000);
  CHECK_EQ(m.vm.execute_direct(I(Op::CALCVV, 1, 65, 42)).value, 0);
  CHECK_EQ(m.vm.execute_direct(I(Op::CALCVA, 1, 27)).value, 0);
  CHECK_EQ(m.vm.execute_direct(I(Op::CALCAV, 1, 27)).value, 0);
  CHECK_EQ(m.vm.execute_direct(I(Op::CALCVX, 1, 27)).value, 0);
  CHECK_EQ(m.vm.execute_direct(I(Op::CALCXV, 1, 27)).value, 0);
  CHECK_EQ(m.vm.execute_direct(I(Op::CALCV, 1, 27, 5000)).value, 5000);
}

TEST(direct_and_program_share_state) {
  Machine m({I(Op::WAIT, 0, 0, 10), I(Op::GGP, 7, 2), I(Op::STOP)});
  auto r = m.vm.run({UINT64_MAX, 50'000});
  CHECK(r.halt == tmcl::Halt::TimeLimit);
  CHECK_EQ(m.vm.execute_direct(I(Op::SGP, 7, 2, 123)).status, 100);
  m.vm.run({});
  CHECK_EQ(m.vm.acc, 123);
}

TEST(motion_event_listener) {
  Machine m({I(Op::MVP, 0, 0, 10), I(Op::MVP, 0, 0, 20), I(Op::STOP)});
  std::vector<std::int32_t> reached;
  m.vm.on_motion_event = [&](const tmcl::Vm&, const tmcl::MotionEvent& ev) {
    if (ev.kind == tmcl::MotionEventKind::TargetReached) reached.push_back(ev.position);
  };
  m.run();
  CHECK_EQ(reached.size(), 2u);
  CHECK_EQ(reached.back(), 20);
}
