// The EEPROM: STGP/RSGP, STAP/RSAP, SCO/GCO bank-255 forms, global 84/85, auto-stored bank 0,
// power-up restore, the file format (round trip, corruption, atomic save) (E16).
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
