// The EEPROM: STGP/RSGP, STAP/RSAP, SCO/GCO bank-255 forms, global 84/85, auto-stored bank 0,
// power-up restore, the file format (round trip, corruption, atomic save) (E16), program memory
// in the EEPROM (E55).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "check.hpp"
#include "os_test.hpp"
#include "machine.hpp"
#include "tmcl/eeprom.hpp"

using namespace vmtest;
using tmcl::Op;

TEST(stgp_rsgp_user_variables) {
  Machine m({I(Op::SGP, 3, 2, 99), I(Op::STGP, 3, 2), I(Op::SGP, 3, 2, 1), I(Op::RSGP, 3, 2), I(Op::SGP, 60, 2, 5),
             I(Op::STGP, 60, 2),  // only 0..55 are backed: ignored
             I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.vars[3], 99);
  CHECK_EQ(m.vm.eeprom.vars.size(), 1u);
  CHECK(m.vm.eeprom_dirty);
}

TEST(stap_rsap_axis_parameters) {
  Machine m({I(Op::SAP, 4, 0, 5000), I(Op::STAP, 4, 0), I(Op::SAP, 4, 0, 7), I(Op::RSAP, 4, 0), I(Op::SAP, 140, 0, 3),
             I(Op::RSAP, 140, 0),  // never stored: the factory default
             I(Op::STAP, 0, 0),    // not EEPROM-backed on this module: ignored
             I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.axis_param(0, 4), 5000);
  CHECK_EQ(m.vm.axis_param(0, 140), 8);
  CHECK_EQ(m.vm.eeprom.axis.size(), 1u);
}

TEST(coordinate_eeprom_forms) {
  Machine m({I(Op::SCO, 1, 0, 11), I(Op::SCO, 2, 0, 22), I(Op::SCO, 0, 255, 0), I(Op::SCO, 1, 0, 0), I(Op::SCO, 2, 0, 0),
             I(Op::GCO, 2, 255), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.coords[0][1], 0);
  CHECK_EQ(m.vm.coords[0][2], 22);
  CHECK_EQ(m.vm.eeprom.coords.size(), 20u);  // all but coordinate 0
}

TEST(power_on_restores) {
  tmcl::EepromImage img;
  img.vars[3] = 33;
  img.globals[84] = 1;
  img.axis[{0, 4}] = 4444;
  img.coords[{0, 5}] = 55;
  Machine m({I(Op::STOP)});
  m.vm.power_on(&img);
  CHECK_EQ(m.vm.vars[3], 33);
  CHECK_EQ(m.vm.axis_param(0, 4), 4444);
  CHECK_EQ(m.vm.coords[0][5], 55);
  img.globals[85] = 1;  // do not restore user variables
  img.globals[84] = 0;  // coordinates in RAM only
  m.vm.power_on(&img);
  CHECK_EQ(m.vm.vars[3], 0);
  CHECK_EQ(m.vm.coords[0][5], 0);
}

TEST(global_84_writes_coordinates_through) {
  Machine m({I(Op::SGP, 84, 0, 1), I(Op::SCO, 4, 0, 40), I(Op::SCO, 0, 0, 1), I(Op::STOP)});
  m.run();
  CHECK_EQ(m.vm.eeprom.coords.size(), 1u);  // coordinate 0 stays in RAM
}

TEST(file_round_trip_and_corruption) {
  tmcl::EepromImage img;
  img.profile = "test";
  img.vars[0] = -5;
  img.globals[77] = 1;
  img.axis[{0, 4}] = 100;
  img.coords[{0, 20}] = 2147483647;
  std::string text = tmcl::eeprom_to_text(img);
  tmcl::EepromImage back;
  std::string err;
  CHECK(tmcl::eeprom_from_text(text, "e.txt", back, err));
  CHECK(back == img);
  std::string bad = text;
  bad[bad.find("-5")] = '+';
  CHECK(!tmcl::eeprom_from_text(bad, "e.txt", back, err));
  CHECK(err.find("e.txt:3:7: error:") != std::string::npos);
  bad = text;
  bad.replace(bad.find("100"), 3, "101");
  CHECK(!tmcl::eeprom_from_text(bad, "e.txt", back, err));
  CHECK(err.find("checksum mismatch") != std::string::npos);
  CHECK(!tmcl::eeprom_from_text(text.substr(0, text.size() - 15), "e.txt", back, err));
  CHECK(!tmcl::eeprom_from_text("tmcl-eeprom 2\n", "e.txt", back, err));
  CHECK(err.find("version 2") != std::string::npos);
  CHECK(!tmcl::eeprom_from_text("", "e.txt", back, err));
  CHECK(!tmcl::eeprom_from_text("hello\n", "e.txt", back, err));
}

// Every bad line is reported in one go, each with its line, column and length for a caret, in
// line order, so a hand-edited file is mended in one pass (the golden case eeprom-errors shows
// the rendered text).
TEST(text_reports_every_error) {
  const std::string text =
      "tmcl-eeprom 1\nprofile generic\nvar 1 x\nglobl 7 1\nvar 2 3\nvar 2 4\naxis 0 1\ncheck 00000000\n";
  tmcl::EepromImage back;
  std::vector<tmcl::FileDiag> diags;
  CHECK(!tmcl::eeprom_from_text(text, "e.txt", back, diags));
  CHECK_EQ(diags.size(), 5u);
  if (diags.size() == 5) {
    CHECK_EQ(diags[0].line, 3);
    CHECK_EQ(diags[0].col, 7);
    CHECK_EQ(diags[0].len, 1);
    CHECK_EQ(diags[1].line, 4);
    CHECK(diags[1].message.find("did you mean 'global'?") != std::string::npos);
    CHECK_EQ(diags[2].line, 6);
    CHECK(diags[2].message.find("already set on line 5") != std::string::npos);
    CHECK_EQ(diags[3].line, 7);
    CHECK(diags[3].message.find("expected 'axis MOTOR PARAM VALUE'") != std::string::npos);
    CHECK_EQ(diags[4].line, 8);
    CHECK(diags[4].message.find("checksum mismatch") != std::string::npos);
  }
  // Sealing ignores the checksum but not the records.
  diags.clear();
  CHECK(!tmcl::eeprom_from_text(text, "e.txt", back, diags, false));
  CHECK_EQ(diags.size(), 4u);
  // The string form renders them all, capped like the assembler's.
  std::string err;
  CHECK(!tmcl::eeprom_from_text(text, "e.txt", back, err));
  CHECK(err.find("e.txt:3:7: error:") != std::string::npos);
  CHECK(err.find("e.txt:8:7: error:") != std::string::npos);
}

TEST(file_save_is_atomic_and_loads) {
  const std::string dir = tmcl_test::make_temp_dir("tmcl-eeprom");
  CHECK(!dir.empty());
  std::string path = dir + "/e.eeprom";
  tmcl::EepromImage img, back;
  bool existed = true;
  std::string err;
  CHECK(tmcl::load_eeprom_file(path, back, existed, err));  // missing: empty, not an error
  CHECK(!existed);
  img.vars[1] = 7;
  CHECK(tmcl::save_eeprom_file(path, img, err));
  CHECK(tmcl::load_eeprom_file(path, back, existed, err));
  CHECK(existed);
  CHECK_EQ(back.vars.at(1), 7);
  CHECK(!std::filesystem::exists(path + ".tmp"));  // no temporary left behind
  CHECK(!tmcl::save_eeprom_file(dir + "/no/such/dir/e", img, err));
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
}

// Bank 0 in direct mode: only parameters the module auto-stores have an EEPROM copy to store
// or restore; read-only, plain read-write and computed ones answer "wrong type" (3).
TEST(bank0_store_and_restore_need_an_eeprom_copy) {
  const tmcl::Profile& usb = *tmcl::find_profile("usb-2-sd");
  Machine m({I(Op::STOP)}, usb);
  CHECK_EQ(m.vm.execute_direct(I(Op::STGP, 86, 0)).status, 100);      // step pulse length, auto-stored
  CHECK_EQ(m.vm.execute_direct(I(Op::SGP, 86, 0, 40)).status, 100);
  CHECK_EQ(m.vm.execute_direct(I(Op::RSGP, 86, 0)).status, 100);
  CHECK_EQ(m.vm.execute_direct(I(Op::GGP, 86, 0)).value, 40);         // auto-stored: SGP wrote the copy too
  CHECK_EQ(m.vm.execute_direct(I(Op::STGP, 255, 0)).status, 3);       // read-write, not stored
  CHECK_EQ(m.vm.execute_direct(I(Op::RSGP, 128, 0)).status, 3);       // read-only
  CHECK_EQ(m.vm.execute_direct(I(Op::STGP, 200, 0)).status, 3);       // not a parameter here
  Machine g({I(Op::STOP)}, tmcl::generic_profile());
  CHECK_EQ(g.vm.execute_direct(I(Op::STGP, 200, 0)).status, 100);     // generic: any number
  CHECK_EQ(g.vm.execute_direct(I(Op::STGP, 132, 0)).status, 3);       // computed by the VM
  CHECK_EQ(g.vm.execute_direct(I(Op::RSGP, 130, 0)).status, 3);
}

namespace {
// A stored value, or INT32_MIN for none (a failed check, not an exception).
std::int32_t stored(const std::map<int, std::int32_t>& records, int key) {
  auto it = records.find(key);
  return it != records.end() ? it->second : INT32_MIN;
}
}  // namespace

// Bank 3 (the interrupt settings) in the EEPROM: the TMCM profiles give them E (errata M2), so
// STGP stores and RSGP restores them, and power-up restores them like bank 0 (a timer period
// starts its timer).
TEST(bank3_store_restore_and_power_cycle_on_a_tmcm_module) {
  const tmcl::Profile& tmcm = *tmcl::find_profile("tmcm-1110");
  Machine m({I(Op::STOP)}, tmcm);
  CHECK_EQ(m.vm.execute_direct(I(Op::SGP, 0, 3, 250)).status, 100);   // timer 0 period
  CHECK_EQ(m.vm.execute_direct(I(Op::STGP, 0, 3)).status, 100);
  CHECK_EQ(m.vm.execute_direct(I(Op::SGP, 27, 3, 2)).status, 100);    // left stop switch 0 edge
  CHECK_EQ(m.vm.execute_direct(I(Op::STGP, 27, 3)).status, 100);
  CHECK(m.vm.eeprom_dirty);
  CHECK_EQ(m.vm.eeprom.bank3.size(), 2u);
  CHECK(m.vm.eeprom.globals.empty());                                 // not bank 0's parameter 0 or 27
  CHECK_EQ(m.vm.execute_direct(I(Op::SGP, 0, 3, 7)).status, 100);
  CHECK_EQ(m.vm.execute_direct(I(Op::RSGP, 0, 3)).status, 100);
  CHECK_EQ(m.vm.execute_direct(I(Op::GGP, 0, 3)).value, 250);
  CHECK_EQ(m.vm.timers[0].period_ms, 250u);                          // the restored period runs
  CHECK_EQ(m.vm.execute_direct(I(Op::SGP, 39, 3, 3)).status, 100);
  CHECK_EQ(m.vm.execute_direct(I(Op::RSGP, 39, 3)).status, 100);     // never stored: factory default
  CHECK_EQ(m.vm.execute_direct(I(Op::GGP, 39, 3)).value, 0);

  // Power cycle: the stored settings come back, the timer runs from power-up.
  const tmcl::EepromImage image = m.vm.eeprom;
  Machine n({I(Op::VECT, 0, 0, 5), I(Op::EI, 0), I(Op::EI, 255), I(Op::WAIT, 0, 0, 100), I(Op::STOP),
             I(Op::GGP, 0, 2), I(Op::CALC, 0, 0, 1), I(Op::AGP, 0, 2), I(Op::RETI)},
            tmcm);
  n.vm.power_on(&image);
  n.vm.start(0);
  CHECK_EQ(n.vm.bank3[0], 250);
  CHECK_EQ(n.vm.bank3[27], 2);
  CHECK_EQ(n.vm.bank3[39], 0);
  auto r = n.run();
  CHECK(r.halt == tmcl::Halt::Stop);
  CHECK_EQ(n.vm.vars[0], 4);                  // at 250, 500, 750 and 1000 ms
}

// Every bundled module whose profile gives a bank-3 parameter E stores it; the others refuse
// as for bank 0: a parameter without E is a wrong type (3), a module without bank 3 has no such
// bank (invalid value, 4), generic stores any number.
TEST(bank3_store_follows_the_profile_on_every_module) {
  int with_e = 0;
  for (const tmcl::Profile* p : tmcl::all_profiles()) {
    if (p->any_parameter) continue;
    for (const tmcl::ParamInfo& g : p->bank3) {
      Machine m({I(Op::STOP)}, *p);
      const std::uint8_t want = (g.access & (tmcl::kEeprom | tmcl::kAutoStore)) ? 100 : 3;
      CHECK_EQ(m.vm.execute_direct(I(Op::STGP, g.number, 3)).status, want);
      CHECK_EQ(m.vm.execute_direct(I(Op::RSGP, g.number, 3)).status, want);
      CHECK_EQ(m.vm.eeprom.bank3.size(), want == 100 ? 1u : 0u);
      with_e += want == 100;
    }
  }
  CHECK(with_e > 0);
  const tmcl::Profile& usb = *tmcl::find_profile("usb-2-sd");  // bank 3 is RW there
  Machine u({I(Op::SGP, 0, 3, 10), I(Op::STGP, 0, 3), I(Op::STOP)}, usb);
  u.run();
  CHECK(u.vm.eeprom.bank3.empty());
  CHECK(!u.vm.eeprom_dirty);
  CHECK_EQ(u.vm.execute_direct(I(Op::STGP, 0, 3)).status, 3);
  Machine e({I(Op::STOP)}, *tmcl::find_profile("tmc2300-eval"));  // no bank 3
  CHECK_EQ(e.vm.execute_direct(I(Op::STGP, 0, 3)).status, 4);
  CHECK_EQ(e.vm.execute_direct(I(Op::RSGP, 0, 3)).status, 4);
  Machine t({I(Op::STOP)});  // the test profile: bank 3 RW
  CHECK_EQ(t.vm.execute_direct(I(Op::STGP, 28, 3)).status, 3);
  CHECK_EQ(t.vm.execute_direct(I(Op::STGP, 29, 3)).status, 3);   // not a parameter here
  Machine g({I(Op::SGP, 1, 3, 20), I(Op::STGP, 1, 3), I(Op::STOP)}, tmcl::generic_profile());
  g.run();
  CHECK_EQ(stored(g.vm.eeprom.bank3, 1), 20);
  CHECK_EQ(g.vm.execute_direct(I(Op::STGP, 200, 3)).status, 100);  // generic: any number
}

// A standalone program on a TMCM module: STGP/RSGP of bank 3 run (they were ignored before).
TEST(bank3_stgp_in_a_program) {
  Machine m({I(Op::SGP, 1, 3, 40), I(Op::STGP, 1, 3), I(Op::SGP, 1, 3, 0), I(Op::RSGP, 1, 3), I(Op::STOP)},
            *tmcl::find_profile("tmcm-351"));
  m.run();
  CHECK_EQ(m.vm.bank3[1], 40);
  CHECK_EQ(stored(m.vm.eeprom.bank3, 1), 40);
}

// A bank-3 parameter a user's profile marks A is stored by every SGP, as bank 0's are.
TEST(bank3_auto_stored_in_a_users_profile) {
  static const tmcl::ParamInfo bank3[] = {{0, "timer 0", 0, 4294967295LL, tmcl::kRead | tmcl::kWrite | tmcl::kAutoStore, 0, ""}};
  static const tmcl::Profile p = [] {
    tmcl::Profile q = test_profile();
    q.bank3 = bank3;
    return q;
  }();
  Machine m({I(Op::SGP, 0, 3, 30), I(Op::STOP)}, p);
  m.run();
  CHECK_EQ(stored(m.vm.eeprom.bank3, 0), 30);
  CHECK(m.vm.eeprom_dirty);
}

// The file keeps bank 3 as `global3` records, after bank 0's; a file without them (every file
// written before them) reads as it did.
TEST(file_round_trip_with_bank3) {
  tmcl::EepromImage img;
  img.profile = "tmcm-1110";
  img.globals[77] = 1;
  img.bank3[0] = 250;
  img.bank3[27] = -1;
  img.axis[{0, 4}] = 100;
  const std::string text = tmcl::eeprom_to_text(img);
  CHECK(text.find("global 77 1\nglobal3 0 250\nglobal3 27 -1\naxis 0 4 100\n") != std::string::npos);
  tmcl::EepromImage back;
  std::string err;
  CHECK(tmcl::eeprom_from_text(text, "e.txt", back, err));
  CHECK(back == img);
  // A file of the first format: no global3 lines, same checksum rule.
  const std::string old_file = "tmcl-eeprom 1\nprofile generic\nvar 0 2\nglobal 77 1\naxis 0 4 53200\ncoord 0 1 -20\n"
                               "coord 1 1 0\ncoord 2 1 0\ncoord 3 1 0\ncoord 4 1 0\ncoord 5 1 0\ncheck c5be0db5\n";
  CHECK(tmcl::eeprom_from_text(old_file, "old.txt", back, err));
  CHECK(back.bank3.empty());
  CHECK_EQ(stored(back.globals, 77), 1);
  // Hand-edited records are checked like the others: duplicates, numbers, a misspelt keyword.
  std::vector<tmcl::FileDiag> diags;
  CHECK(!tmcl::eeprom_from_text("tmcl-eeprom 1\nprofile x\nglobal3 0 1\nglobal3 0 2\nglobal3 256 1\nglobl3 1 1\n",
                                "e.txt", back, diags, false));
  CHECK_EQ(diags.size(), 3u);
  if (diags.size() == 3) {
    CHECK(diags[0].message.find("duplicate record: global3 0 is already set on line 3") != std::string::npos);
    CHECK(diags[1].message.find("bad parameter number '256'") != std::string::npos);
    CHECK(diags[2].message.find("did you mean 'global3'?") != std::string::npos);
  }
}

// Program memory in the EEPROM (E55): `program` records round-trip; a file written before them
// (here the one golden case serve/eeprom-bank3 pins, byte for byte) still loads, with no program;
// a gap, a bad opcode and a duplicate address are errors naming their line.
TEST(file_program_records) {
  tmcl::EepromImage img;
  img.profile = "tmcm-1110";
  img.globals[77] = 1;
  img.program = {{9, 1, 2, 5}, {0, 0, 0, 0}, {28, 0, 0, -1}};  // an opcode-0 word inside is kept
  const std::string text = tmcl::eeprom_to_text(img);
  CHECK(text.find("global 77 1\nprogram 0 9 1 2 5\nprogram 1 0 0 0 0\nprogram 2 28 0 0 -1\ncheck ") != std::string::npos);
  tmcl::EepromImage back;
  std::string err;
  CHECK(tmcl::eeprom_from_text(text, "e.txt", back, err));
  CHECK(back == img);
  const std::string old = "tmcl-eeprom 1\nprofile tmcm-1110\nglobal3 0 250\nglobal3 27 2\ncheck 26c9a35b\n";
  CHECK(tmcl::eeprom_from_text(old, "old.eeprom", back, err));
  CHECK(back.program.empty());
  CHECK_EQ(back.bank3.at(0), 250);
  std::vector<tmcl::FileDiag> diags;
  const std::string bad = "tmcl-eeprom 1\nprofile tmcm-1110\nprogram 0 9 1 2 5\nprogram 2 28 0 0 0\nprogram 3 256 0 0 0\n"
                          "program 0 1 0 0 0\n";
  CHECK(!tmcl::eeprom_from_text(bad, "bad.eeprom", back, diags, false));
  CHECK_EQ(diags.size(), 3u);
  if (diags.size() == 3) {
    CHECK_EQ(diags[0].line, 4);
    CHECK_EQ(diags[0].message, std::string("program record for address 2, but address 1 has none (program memory runs from "
                                           "address 0 without a gap)"));
    CHECK_EQ(diags[1].line, 5);
    CHECK_EQ(diags[1].message, std::string("malformed EEPROM record 'program 3 256 0 0 0': bad opcode '256' (0..255)"));
    CHECK_EQ(diags[2].line, 6);
    CHECK_EQ(diags[2].message, std::string("duplicate record: program 0 is already set on line 3"));
  }
}

// A download's end and a run with an EEPROM file store the program where the profile keeps it in
// EEPROM; a module with program RAM stores nothing.
TEST(store_program_follows_the_profile) {
  Machine eeprom({I(Op::SGP, 1, 2, 5), I(Op::STOP)}, *tmcl::find_profile("tmcm-1110"));
  CHECK(eeprom.vm.program_in_eeprom());
  eeprom.vm.store_program();
  CHECK_EQ(eeprom.vm.eeprom.program.size(), 2u);
  CHECK(eeprom.vm.eeprom_dirty);
  Machine ram({I(Op::SGP, 1, 2, 5), I(Op::STOP)}, *tmcl::find_profile("usb-2-sd"));
  CHECK(!ram.vm.program_in_eeprom());
  ram.vm.store_program();
  CHECK(ram.vm.eeprom.program.empty());
  CHECK(!ram.vm.eeprom_dirty);
  // Power-up keeps the image's program in the EEPROM (what the server's 255 goes through).
  tmcl::EepromImage img = eeprom.vm.eeprom;
  eeprom.vm.power_on(&img);
  CHECK_EQ(eeprom.vm.eeprom.program.size(), 2u);
}
