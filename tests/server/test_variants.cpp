// The firmware variants of the virtual module (FirmwareVariants, errata S24-S27): each default
// and each variant, on the protocol engine without I/O. tmclctl's `debug --probe` reports which
// of them a module has (tests/host/test_debug_probe.cpp).
#include "check.hpp"
#include "frames.hpp"
#include "tmcl/server.hpp"

using namespace srvtest;
using tmcl::Instruction;
using tmcl::Op;

namespace {

Instruction instr(Op op, int type, int motor, std::int32_t value) {
  return Instruction{static_cast<std::uint8_t>(op), static_cast<std::uint8_t>(type), static_cast<std::uint8_t>(motor), value};
}

// (Named apart from test_protocol.cpp's Engine: a unity build puts both files in one unit.)
// 0: CALC LOAD 4711; 1: WAIT TICKS 0, 10 (100 ms); 2: CALC ADD 1; 3: STOP.
struct VariantEngine {
  std::unique_ptr<tmcl::MotionCore> core = tmcl::make_ideal_motion_core();
  tmcl::Vm vm{*tmcl::find_profile("usb-2-sd"), *core};
  tmcl::TmclModule module;
  explicit VariantEngine(tmcl::FirmwareVariants v = {}) : module(vm, options(v)) {
    vm.load({instr(Op::CALC, tmcl::kw::CalcA::LOAD, 0, 4711), instr(Op::WAIT, tmcl::kw::Wait::TICKS, 0, 10),
             instr(Op::CALC, tmcl::kw::CalcA::ADD, 0, 1), instr(Op::STOP, 0, 0, 0)});
  }
  static tmcl::ProtocolOptions options(tmcl::FirmwareVariants v) {
    tmcl::ProtocolOptions o;
    o.variants = v;
    return o;
  }
  Bytes feed(const Bytes& b) {
    module.receive(b.data(), b.size());
    return take();
  }
  Bytes take() {
    Bytes out = module.output();
    module.output().clear();
    return out;
  }
};

constexpr std::uint8_t kStep = 130, kStatus = 135, kRead = 134, kReset = 131, kGap = static_cast<std::uint8_t>(Op::GAP);

tmcl::FirmwareVariants variant(bool tmcl::FirmwareVariants::*field) {
  tmcl::FirmwareVariants v;
  v.*field = true;
  return v;
}

}  // namespace

TEST(step_during_wait_answers_at_once_by_default) {
  VariantEngine e;
  e.feed(frame(1, kReset, 0, 0, 0));
  CHECK_EQ(hex(e.feed(frame(1, kStep, 0, 0, 0))), hex(reply_bytes(2, 1, 100, kStep, 0)));  // CALC
  CHECK_EQ(hex(e.feed(frame(1, kStep, 0, 0, 0))), hex(reply_bytes(2, 1, 100, kStep, 0)));  // enters the WAIT
  CHECK_EQ(value_of(e.feed(frame(1, kStatus, 1, 0, 0))), 2 << 24 | 1 << 16 | 1);          // step, waiting, pc 1
  CHECK_EQ(hex(e.feed(frame(1, kStep, 0, 0, 0))), hex(reply_bytes(2, 1, 100, kStep, 0)));  // still waiting
  CHECK_EQ(value_of(e.feed(frame(1, kStatus, 1, 0, 0))), 2 << 24 | 1 << 16 | 1);
  e.module.advance(e.vm.now + 200000);
  // The wait is over: this step leaves the WAIT and runs nothing after it (the manuals: "only
  // the next instruction"; errata S11).
  CHECK_EQ(hex(e.feed(frame(1, kStep, 0, 0, 0))), hex(reply_bytes(2, 1, 100, kStep, 0)));
  CHECK_EQ(value_of(e.feed(frame(1, kStatus, 1, 0, 0))), 2 << 24 | 2);
  CHECK_EQ(e.vm.acc, 4711);
  e.feed(frame(1, kStep, 0, 0, 0));
  CHECK_EQ(e.vm.acc, 4712);
}

TEST(step_waits_variant_answers_when_the_wait_is_over) {
  VariantEngine e(variant(&tmcl::FirmwareVariants::step_waits));
  e.feed(frame(1, kReset, 0, 0, 0));
  e.feed(frame(1, kStep, 0, 0, 0));
  const tmcl::SimTime t0 = e.vm.now;
  CHECK(e.feed(frame(1, kStep, 0, 0, 0)).empty());    // held: the WAIT runs
  CHECK(e.feed(frame(1, kStatus, 1, 0, 0)).empty());  // read only after the step's reply
  CHECK(!e.module.window_pending());                  // not a corrupted frame either
  CHECK(e.module.next_wakeup() <= t0 + 100000);
  e.module.advance(t0 + 50000);
  CHECK(e.take().empty());
  e.module.advance(t0 + 200000);
  // The step's reply, then the status that waited behind it: past the WAIT, no wait, pc 2.
  CHECK_EQ(hex(e.take()), hex(reply_bytes(2, 1, 100, kStep, 0)) + " " + hex(reply_bytes(2, 1, 100, kStatus, 2 << 24 | 2)));
  CHECK_EQ(e.vm.acc, 4711);  // no instruction after the WAIT ran
  CHECK(e.vm.status == tmcl::AppStatus::Step);
  CHECK_EQ(hex(e.feed(frame(1, kStep, 0, 0, 0))), hex(reply_bytes(2, 1, 100, kStep, 0)));  // CALC ADD: at once
  CHECK_EQ(e.vm.acc, 4712);
}

TEST(step_waits_variant_answers_a_step_without_wait_at_once) {
  VariantEngine e(variant(&tmcl::FirmwareVariants::step_waits));
  e.feed(frame(1, kReset, 0, 0, 0));
  CHECK_EQ(hex(e.feed(frame(1, kStep, 0, 0, 0))), hex(reply_bytes(2, 1, 100, kStep, 0)));
  CHECK_EQ(e.vm.pc, 1);
}

TEST(direct_read_leaves_a_by_default_and_loads_it_with_the_variant) {
  for (bool on : {false, true}) {
    VariantEngine e(on ? variant(&tmcl::FirmwareVariants::direct_read_sets_a) : tmcl::FirmwareVariants{});
    e.feed(frame(1, kReset, 0, 0, 0));
    e.feed(frame(1, kStep, 0, 0, 0));  // A = 4711
    e.feed(frame(1, 128, 0, 0, 0));
    const std::int32_t speed = value_of(e.feed(frame(1, kGap, 4, 0, 0)));
    CHECK(speed != 4711);
    CHECK_EQ(value_of(e.feed(frame(1, kStatus, 2, 0, 0))), on ? speed : 4711);
  }
}

TEST(direct_read_variant_leaves_a_running_program_alone) {
  VariantEngine e(variant(&tmcl::FirmwareVariants::direct_read_sets_a));
  e.feed(frame(1, kReset, 0, 0, 0));
  e.feed(frame(1, 129, 0, 0, 0));
  e.module.advance(e.vm.now + 1000);  // in the WAIT, running
  e.feed(frame(1, kGap, 4, 0, 0));
  CHECK_EQ(value_of(e.feed(frame(1, kStatus, 2, 0, 0))), 4711);
}

TEST(status_after_reset_is_3_by_default_and_0_with_the_variant) {
  for (bool on : {false, true}) {
    VariantEngine e(on ? variant(&tmcl::FirmwareVariants::reset_reports_stopped) : tmcl::FirmwareVariants{});
    e.feed(frame(1, kReset, 0, 0, 0));
    CHECK_EQ(value_of(e.feed(frame(1, kStatus, 0, 0, 0))) >> 24, on ? 0 : 3);
    CHECK_EQ(value_of(e.feed(frame(1, kGgp, 128, 0, 0))), on ? 0 : 3);
  }
}

TEST(read_past_memory_is_status_4_by_default_and_opcode_0_with_the_variant) {
  for (bool on : {false, true}) {
    VariantEngine e(on ? variant(&tmcl::FirmwareVariants::read_past_memory_zero) : tmcl::FirmwareVariants{});
    const int memory = e.vm.profile->program_memory;  // 577 on the USB-2-SD
    CHECK_EQ(memory, 577);
    const Bytes past = e.feed(frame(1, kRead, 0, 0, memory));
    if (on)
      CHECK_EQ(hex(past), hex(Bytes{2, 0, 0, 0, 0, 0, 0, 0, 2}));  // the special reply of opcode 0
    else
      CHECK_EQ(hex(past), hex(reply_bytes(2, 1, 4, kRead, memory)));
    CHECK_EQ(hex(e.feed(frame(1, kRead, 0, 0, -1))), hex(reply_bytes(2, 1, 4, kRead, -1)));  // never a negative address
  }
}

TEST(firmware_variant_names) {
  tmcl::FirmwareVariants v;
  std::string error;
  CHECK(tmcl::parse_firmware_variants("step-waits,reset-reports-stopped", v, error));
  CHECK(v.step_waits && v.reset_reports_stopped && !v.direct_read_sets_a && !v.read_past_memory_zero);
  CHECK(!tmcl::parse_firmware_variants("step-wait", v, error));
  CHECK_EQ(error, std::string("unknown firmware variant 'step-wait' (known: step-waits, direct-read-sets-a, "
                              "reset-reports-stopped, read-past-memory-zero)"));
  CHECK(!tmcl::parse_firmware_variants("", v, error));
  CHECK_EQ(tmcl::firmware_variant_table().size(), 4u);
}
