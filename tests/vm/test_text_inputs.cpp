// The text a user types: decimal numbers (numbers.hpp), durations with h and fractions, scenario
// files reporting every error with its column, and EEPROM files sealed after a hand edit.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "check.hpp"
#include "os_test.hpp"
#include "tmcl/duration.hpp"
#include "tmcl/eeprom.hpp"
#include "tmcl/numbers.hpp"
#include "tmcl/scenario.hpp"

using tmcl::NumberStatus;

namespace {
NumberStatus dec(const char* text, std::int64_t scale, std::int64_t& out, bool fraction = true) {
  return tmcl::parse_decimal(text, tmcl::Decimal{INT64_MIN, INT64_MAX, scale, fraction, true}, out);
}
}  // namespace

TEST(decimal_numbers) {
  std::int64_t v = 0;
  CHECK(dec("0", 1, v) == NumberStatus::Ok && v == 0);
  CHECK(dec("-2147483648", 1, v) == NumberStatus::Ok && v == -2147483648LL);
  CHECK(dec("+7", 1, v) == NumberStatus::Ok && v == 7);
  CHECK(dec("1.5", 1000, v) == NumberStatus::Ok && v == 1500);
  CHECK(dec("0.25", 1000, v) == NumberStatus::Ok && v == 250);
  CHECK(dec("1.500000000000000000000000", 2, v) == NumberStatus::Ok && v == 3);  // trailing zeros are free
  CHECK(dec("1.0000005", 1000, v) == NumberStatus::Inexact);
  CHECK(dec("0.5", 1, v) == NumberStatus::Inexact);
  CHECK(dec("1.5", 1, v, false) == NumberStatus::Fraction);
  CHECK(dec("", 1, v) == NumberStatus::Empty);
  for (const char* bad : {"-", "1.", ".5", "1..5", "1e3", "0x10", " 1", "1 ", "1_000", "--1"})
    CHECK(dec(bad, 1, v) == NumberStatus::Malformed);
  CHECK(dec("9223372036854775807", 1, v) == NumberStatus::Ok && v == INT64_MAX);
  CHECK(dec("-9223372036854775808", 1, v) == NumberStatus::Ok && v == INT64_MIN);
  CHECK(dec("9223372036854775808", 1, v) == NumberStatus::OutOfRange);
  CHECK(dec("99999999999999999999999", 1, v) == NumberStatus::OutOfRange);
  CHECK(dec("3000000000", 3'600'000'000, v) == NumberStatus::OutOfRange);
  CHECK(tmcl::parse_decimal("-1", tmcl::Decimal{0, 10, 1, false, false}, v) == NumberStatus::Negative);
  CHECK(tmcl::parse_decimal("11", tmcl::Decimal{0, 10, 1, false, false}, v) == NumberStatus::OutOfRange);
  CHECK(tmcl::parse_int("-5", -10, 10, v) && v == -5);
  CHECK(!tmcl::parse_int("1.0", -10, 10, v));
}

TEST(durations_with_hours_and_fractions) {
  CHECK_EQ(tmcl::parse_duration("1h").value_or(-1), 3'600'000'000LL);
  CHECK_EQ(tmcl::parse_duration("1.5s").value_or(-1), 1'500'000);
  CHECK_EQ(tmcl::parse_duration("0.25ms").value_or(-1), 250);
  CHECK_EQ(tmcl::parse_duration("0.5min").value_or(-1), 30'000'000);
  CHECK_EQ(tmcl::parse_duration("0.0").value_or(-1), 0);
  std::string err;
  CHECK(!tmcl::parse_duration("5x", err));
  CHECK_EQ(err, std::string("unknown unit 'x' in '5x'; use us, ms, s, min or h"));
  CHECK(!tmcl::parse_duration("1.0000005ms", err));
  CHECK_EQ(err, std::string("1.0000005ms is not a whole number of microseconds"));
  CHECK(!tmcl::parse_duration("10", err));
  CHECK(err.find("needs a unit") != std::string::npos);
  CHECK(!tmcl::parse_duration("-1s", err));
  CHECK(err.find("negative") != std::string::npos);
  CHECK(!tmcl::parse_duration("", err));
  CHECK(!tmcl::parse_duration("1e3s", err));
  CHECK(err.find("malformed number '1e3'") != std::string::npos);
  CHECK(!tmcl::parse_duration("3000000000h", err));
  CHECK(err.find("too long") != std::string::npos);
}

TEST(scenario_reports_every_error_with_its_column) {
  std::vector<tmcl::InputEvent> ev;
  std::vector<tmcl::FileDiag> diags;
  tmcl::ScenarioOptions o;
  o.motors = 1;
  o.module = "usb-2-sd";
  const char* text =
      "at 10ms input 0 = 1\n"
      "at 1s inptu 0 = 1\n"      // did you mean
      "at 1x input 0 = 1\n"      // unit
      "at 2s left 1 = 1\n"       // no motor 1
      "at 2s input 9 = 1\n"      // input range
      "at 2s input 0 = 1.5\n"    // not an integer
      "at 3s input 0 1\n"        // shape
      "at 1.5s analog 2 = -512 # fine\n";
  CHECK(!tmcl::parse_scenario(text, "s.txt", ev, diags, o));
  CHECK_EQ(diags.size(), 6u);
  CHECK_EQ(ev.size(), 2u);  // the good lines are still read
  if (diags.size() == 6) {
    CHECK_EQ(diags[0].line, 2);
    CHECK_EQ(diags[0].col, 7);
    CHECK(diags[0].message.find("did you mean 'input'?") != std::string::npos);
    CHECK_EQ(diags[1].col, 4);
    CHECK_EQ(diags[2].message, std::string("usb-2-sd has no motor 1 (0..0)"));
    CHECK_EQ(diags[3].col, 13);
    CHECK_EQ(diags[4].col, 17);
  }
  if (ev.size() == 2) CHECK_EQ(ev[1].at, 1'500'000);
  std::string err;
  ev.clear();
  o.error_limit = 2;
  CHECK(!tmcl::parse_scenario(text, "s.txt", ev, err, o));
  CHECK(err.rfind("s.txt:2:7: error: unknown input 'inptu'", 0) == 0);
  CHECK(err.find(" at 1s inptu 0 = 1\n       ^~~~~\n") != std::string::npos);
  CHECK(err.find("s.txt: note: 4 more errors not shown") != std::string::npos);
}

TEST(eeprom_seal_mends_a_hand_edited_file) {
  const std::string dir = tmcl_test::make_temp_dir("tmcl-seal");
  CHECK(!dir.empty());
  std::string path = dir + "/e.eeprom";
  tmcl::EepromImage img;
  img.profile = "usb-2-sd";
  img.vars[1] = 5;
  std::string err;
  CHECK(tmcl::save_eeprom_file(path, img, err));
  {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    std::string text = s.str();
    text.insert(text.find("check"), "var 0 -7\n");  // an edit, and a record out of order
    std::ofstream(path) << text;
  }
  tmcl::EepromImage back;
  bool existed = false;
  CHECK(!tmcl::load_eeprom_file(path, back, existed, err));
  CHECK(err.find("checksum mismatch); if you edited it on purpose, run 'tmclrun --eeprom-seal FILE'") != std::string::npos);
  CHECK(tmcl::seal_eeprom_file(path, err));
  CHECK(tmcl::load_eeprom_file(path, back, existed, err));
  CHECK_EQ(back.vars.size(), 2u);
  CHECK_EQ(back.vars[0], -7);
  // A record the reader cannot understand is refused, checksum or not.
  std::ofstream(path, std::ios::app) << "var x 1\n";
  CHECK(!tmcl::seal_eeprom_file(path, err));
  CHECK(err.find("malformed EEPROM record 'var x 1'") != std::string::npos);
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
}
