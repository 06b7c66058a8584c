// Recorder, CSV and SVG: the CSV format on one move and a structural check of the SVG. The golden
// CSVs of the manuals' example programs are golden cases (tests/golden/motion/, motion_csv.cpp).
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "check.hpp"
#include "recording.hpp"
#include "tmcl/motion_recording.hpp"

using mt::Runner;

// USB-2-SD manual, section 7.2, one pass of the main loop: the SVG has its three panels and marks.
TEST(svg_usb2sd_main_loop) {
  Runner r("tmc4361", "usb-2-sd", 20000);
  mt::usb2sd_main_loop(r);
  std::ostringstream svg;
  tmcl::write_svg(svg, r.rec, {"USB-2-SD: MVP ABS 5000, MVP ABS 0", 1100, 780});
  std::string s = svg.str();
  CHECK(s.rfind("<svg", 0) == 0);
  CHECK(s.find("</svg>") != std::string::npos);
  CHECK(s.find("position [µsteps]") != std::string::npos);
  CHECK(s.find("velocity [pps]") != std::string::npos);
  CHECK(s.find("acceleration [pps²]") != std::string::npos);
  CHECK(s.find("time [s]") != std::string::npos);
  std::size_t polylines = 0, pos = 0;
  while ((pos = s.find("<polyline", pos)) != std::string::npos) ++polylines, ++pos;
  CHECK_EQ(polylines, std::size_t{3});
  CHECK(s.find("move issued: MVP ABS, 0, 5000") != std::string::npos);
  CHECK(s.find("target reached") != std::string::npos);
  if (std::getenv("TMCL_PLOT_OUT")) std::ofstream(std::getenv("TMCL_PLOT_OUT")) << s;
}

TEST(csv_format) {
  Runner r("tmc4361", "usb-2-sd", 250000);
  r.mvp(100000);
  r.wait_pos();
  std::ostringstream csv;
  tmcl::write_csv(csv, r.rec);
  std::string s = csv.str();
  CHECK(s.find("time_s,motor,position,velocity_pps,acceleration_pps2,event\n") != std::string::npos);
  CHECK(s.find("0.000000,0,0,,,\"move issued: MVP ABS, 0, 100000\"\n") != std::string::npos);
  CHECK(s.find("1.000000,0,25600,51200.000,0.000,\n") != std::string::npos);
  CHECK(s.find("2.953125,0,100000,,,target reached\n") != std::string::npos);
}

TEST(svg_many_motors_and_empty) {
  tmcl::MotionRecorder empty(1, 1000);
  std::ostringstream svg;
  tmcl::write_svg(svg, empty);
  CHECK(svg.str().find("</svg>") != std::string::npos);
}

// A title that would run past the width (a core in chip units names its divisors there) is set
// smaller; a short one keeps its size.
TEST(svg_long_title_fits) {
  tmcl::MotionRecorder rec(1, 1000);
  std::ostringstream short_svg, long_svg;
  tmcl::write_svg(short_svg, rec, {"p.tmc on usb-2-sd (tmc4361 motion)", 1100, 780});
  CHECK(short_svg.str().find("font-size=\"19\" font-weight=\"bold\" fill=\"#222\">p.tmc on") != std::string::npos);
  const std::string title(200, 'x');
  tmcl::write_svg(long_svg, rec, {title, 1100, 780});
  CHECK(long_svg.str().find("font-size=\"10\" font-weight=\"bold\" fill=\"#222\">" + title) != std::string::npos);
  std::ostringstream mid;
  tmcl::write_svg(mid, rec, {std::string(120, 'x'), 1100, 780});
  CHECK(mid.str().find("font-size=\"13\" font-weight=\"bold\"") != std::string::npos);  // (1100 - 96 - 16) / 72
}

// The recording of a core in chip units: a rotation's speed in units and pps; a placed switch's
// events as marks that name the switch; the CSV's units line.
TEST(recording_in_chip_units) {
  auto core = tmcl::make_motion_core("tmc429");
  core->reset(*tmcl::find_profile("generic"), 1);
  tmcl::MotionRecorder rec(1, 100000);
  tmcl::RecordingCore rc(*core, rec);
  CHECK(rc.place_switch(0, tmcl::SwitchInput::StopLeft, INT64_MIN, -3000));
  rc.rotate(0, -1000);
  std::vector<tmcl::MotionEvent> ev;
  for (int i = 0; i < 4 && rc.next_event() != tmcl::kNever; ++i) rc.advance(rc.next_event(), ev);
  std::ostringstream csv;
  tmcl::write_csv(csv, rec, rc.units_note());
  const std::string s = csv.str();
  CHECK(s.find("move issued: rotate at -1000 (-30517.578 pps)") != std::string::npos);
  CHECK(s.find(",0,-3000,,,left switch closed\n") != std::string::npos);
  CHECK(s.find("\n# TMC429 units: pulse divisor 3, ramp divisor 7: velocity 1 = 30.5176 pps, acceleration 1 = 465.661 pps²\n") !=
        std::string::npos);
}
