// Parameters, variables, coordinates and I/O: access rules and ranges from the profile
// (standalone ignores what direct mode rejects, E3), global parameters 128-133, indexed variables
// (E8), coordinates and MVP COORD, SIO/GIO banks (E18), and reads that load the accumulator.
#include "check.hpp"
#include "machine.hpp"

using namespace vmtest;
using tmcl::Halt;
using tmcl::Op;

TEST(sap_gap_aap) {
  Machine m({I(Op::SAP, 4, 0, 51200), I(Op::GAP, 4, 0), I(Op::CALC, 2, 0, 2), I(Op::AAP, 4, 0), I(Op::GAP, 4, 0), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.acc, 102400);
  CHECK_EQ(m.vm.flags, tmcl::kFlagGreater);
}

TEST(sap_rules_in_standalone) {  // E3
  Machine m({I(Op::SAP, 4, 0, 2000000),  // out of range: ignored
             I(Op::SAP, 3, 0, 5),        // read-only: ignored
             I(Op::SAP, 99, 0, 5),       // unknown on this module: ignored
             I(Op::SAP, 4, 3, 5),        // no motor 3: ignored
             I(Op::CALC, 9, 0, 77), I(Op::GAP, 99, 0),  // unknown read: acc unchanged
             I(Op::STOP)});
  auto r = m.run();
  CHECK(r.halt == Halt::Stop);
  CHECK_EQ(m.vm.axis_param(0, 4), 1000);  // the profile default
  CHECK_EQ(m.vm.axis_param(0, 3), 0);
  CHECK_EQ(m.vm.acc, 77);
}

TEST(sap_target_moves_ideal_motor) {
  Machine m({I(Op::CALC, 9, 0, 1234), I(Op::AAP, 0, 0), I(Op::GAP, 1, 0), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.acc, 1234);
}

TEST(globals_banks) {
  Machine m({I(Op::SGP, 42, 2, 1234), I(Op::GGP, 42, 2), I(Op::CALC, 2, 0, 2), I(Op::AGP, 42, 2),
             I(Op::SGP, 77, 0, 1), I(Op::SGP, 77, 0, 5),  // out of range: ignored
             I(Op::SGP, 128, 0, 3),                        // read-only: ignored
             I(Op::SGP, 1, 1, 5),                          // bank 1 does not exist
             I(Op::GGP, 130, 0), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.vars[42], 2468);
  CHECK_EQ(m.vm.global_param(0, 77), 1);
  CHECK_EQ(m.vm.global_param(0, 128), 0);  // stopped now
  CHECK_EQ(m.vm.acc, 8);                   // GGP 130 is the address of the GGP itself
  CHECK_EQ(m.vm.eeprom.globals.at(77), 1); // auto-stored
}

TEST(application_status_while_running) {
  Machine m({I(Op::GGP, 128, 0), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.acc, 1);
}

TEST(random_is_seedable_and_deterministic) {  // E17
  Machine a({I(Op::SGP, 133, 0, 42), I(Op::GGP, 133, 0), I(Op::CALCX, 9), I(Op::GGP, 133, 0), I(Op::STOP)});
  Machine b({I(Op::SGP, 133, 0, 42), I(Op::GGP, 133, 0), I(Op::CALCX, 9), I(Op::GGP, 133, 0), I(Op::STOP)});
  a.run();
  b.run();
  CHECK_EQ(a.vm.acc, b.vm.acc);
  CHECK_EQ(a.vm.x, b.vm.x);
  CHECK(a.vm.acc != a.vm.x);
  CHECK(a.vm.acc >= 0);
}

TEST(indexed_variables) {  // E8
  Machine m({I(Op::CALC, 9, 0, 10), I(Op::CALCX, 9), I(Op::SIV, 0, 0, 55), I(Op::GIV), I(Op::CALC, 0, 0, 1), I(Op::CALCX, 10),
             I(Op::CALC, 9, 0, 11), I(Op::CALCX, 10), I(Op::AIV), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.vars[10], 55);
  CHECK_EQ(m.vm.vars[11], 56);
  for (std::int32_t bad : {-1, 256}) {
    Machine n({I(Op::CALC, 9, 0, bad), I(Op::CALCX, 9), I(Op::CALC, 9, 0, 9), I(Op::SIV, 0, 0, 1), I(Op::AIV), I(Op::GIV),
               I(Op::STOP)});
    n.run();
    CHECK_EQ(n.vm.acc, 9);
    CHECK(!n.vm.faulted());
    for (auto v : n.vm.vars) CHECK_EQ(v, 0);
  }
}

TEST(coordinates) {
  Machine m({I(Op::SCO, 1, 0, 1000), I(Op::GCO, 1, 0), I(Op::CALC, 0, 0, 1), I(Op::ACO, 2, 0), I(Op::MVP, 2, 0, 2),
             I(Op::CCO, 3, 0), I(Op::GCO, 3, 0), I(Op::SCO, 21, 0, 5),  // coordinate 21 does not exist
             I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.coords[0][1], 1000);
  CHECK_EQ(m.vm.coords[0][2], 1001);
  CHECK_EQ(m.vm.coords[0][3], 1001);
  CHECK_EQ(m.vm.acc, 1001);
  CHECK_EQ(m.vm.axis_param(0, 1), 1001);
}

// M32: the TMC2300-MOTOR-EVAL has no coordinates and no COORD type: MVP COORD answers "wrong
// type" (3) in direct mode; a module with coordinates answers "invalid value" (4) for one it lacks.
TEST(mvp_coord_where_the_module_refuses_it) {
  auto direct = [](const char* name, std::int32_t coord) {
    const tmcl::Profile& p = *tmcl::find_profile(name);
    auto core = tmcl::make_profile_motion_core(p);
    tmcl::Vm vm(p, *core);
    vm.power_on(nullptr);
    return vm.execute_direct(I(Op::MVP, 2, 0, coord)).status;
  };
  CHECK_EQ(direct("tmc2300-eval", 0), tmcl::kStatusWrongType);
  CHECK_EQ(direct("tmcm-1110", 30), tmcl::kStatusInvalidValue);
  CHECK_EQ(direct("tmcm-1110", 20), tmcl::kStatusOk);
}

TEST(cco_does_not_load_accumulator) {  // E9
  Machine m({I(Op::MVP, 0, 0, 42), I(Op::CALC, 9, 0, 5), I(Op::CCO, 4, 0), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.acc, 5);
  CHECK_EQ(m.vm.coords[0][4], 42);
  CHECK_EQ(m.vm.execute_direct(I(Op::CCO, 5, 0)).value, 42);
}

TEST(mvp_rel_uses_option_127) {
  Machine m({I(Op::MVP, 0, 0, 100), I(Op::MVP, 1, 0, 50), I(Op::GAP, 1, 0), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.acc, 150);
  Machine w({I(Op::MVP, 1, 0, 2147483647), I(Op::MVP, 1, 0, 1), I(Op::GAP, 1, 0), I(Op::STOP)});
  w.run();
  CHECK_EQ(w.vm.acc, -2147483647 - 1);  // 32-bit wrap
}

TEST(mvpa_rora_rola) {
  Machine m({I(Op::CALC, 9, 0, 300), I(Op::MVPA, 0, 0), I(Op::CALC, 9, 0, 100), I(Op::ROLA, 0, 0), I(Op::WAIT, 0, 0, 100),
             I(Op::MST, 0, 0), I(Op::GAP, 1, 0), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.acc, 200);  // 300 - 100 pps * 1 s
}

TEST(ror_out_of_range_ignored) {
  Machine m({I(Op::ROR, 0, 0, 2000000), I(Op::GAP, 2, 0), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.acc, 0);
}

TEST(sio_gio_banks) {  // E18
  Machine m({I(Op::SIO, 3, 2, 1), I(Op::SIO, 4, 2, 7), I(Op::GIO, 3, 2), I(Op::CALCX, 9), I(Op::SIO, 0, 0, 1),  // bank 0: no
             I(Op::GIO, 0, 1), I(Op::STOP)});
  tmcl::InputEvent a;
  a.kind = tmcl::InputEvent::Analog;
  a.index = 0;
  a.value = 512;
  m.vm.add_inputs({a});
  m.run();
  CHECK_EQ(m.vm.outputs[3], 1);
  CHECK_EQ(m.vm.outputs[4], 1);
  CHECK_EQ(m.vm.x, 1);
  CHECK_EQ(m.vm.acc, 512);
  CHECK_EQ(m.vm.inputs[0], 0);
}

TEST(reads_set_flags) {  // E2
  Machine m({I(Op::GGP, 5, 2), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.flags, tmcl::kFlagZero | tmcl::kFlagEqual);
}
