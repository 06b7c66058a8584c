// Recorder, CSV and SVG: the CSV format on one move and a structural check of the SVG. The golden
// CSVs of the manuals' example programs are golden cases (tests/golden/motion/, motion_csv.cpp).
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "check.hpp"
#include "recording.hpp"

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
