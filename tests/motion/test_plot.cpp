// Recorder, CSV and SVG: golden CSV files for the manuals' example programs (driven through the
// core API the way tmclrun runs them), and a structural check of the SVG.
// TMCL_UPDATE_GOLDEN=1 rewrites the golden files for review in git diff.
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "check.hpp"
#include "helpers.hpp"
#include "tmcl/motion_plot.hpp"

using mt::Bench;

namespace {

// A tiny program runner: the motion part of a TMCL program as a list of steps.
struct Runner {
  Bench b;
  tmcl::MotionRecorder rec;
  explicit Runner(const char* core, const char* profile, tmcl::SimTime period) : b(core, profile), rec(1, period) {}
  void advance(tmcl::SimTime t) {
    rec.sample_until(*b.core, t);
    std::size_t n = b.events.size();
    b.to(t);
    for (std::size_t i = n; i < b.events.size(); ++i) rec.motion_event(b.events[i]);
  }
  void wait_pos() {
    while (!b.core->target_reached(0)) advance(b.core->next_event());
  }
  void mvp(std::int32_t target) {
    rec.mark(b.now, 0, tmcl::Mark::MoveIssued, "MVP ABS, 0, " + std::to_string(target), b.core->position(0));
    b.core->move_absolute(0, target);
  }
};

void compare_golden(const std::string& name, const std::string& text) {
  std::string path = std::string(TMCL_MOTION_GOLDEN_DIR) + "/" + name;
  if (std::getenv("TMCL_UPDATE_GOLDEN")) {
    std::ofstream(path) << text;
    return;
  }
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  CHECK(in.good() || !ss.str().empty());
  CHECK(ss.str() == text);
  if (ss.str() != text) std::fprintf(stderr, "golden mismatch: %s (TMCL_UPDATE_GOLDEN=1 rewrites it)\n", path.c_str());
}

}  // namespace

// USB-2-SD manual, section 7.2: SAP 4, 0, 50000 / SAP 5, 0, 10000 / MVP ABS 5000 / WAIT POS /
// MVP ABS 0 / WAIT POS (one pass of the main loop).
TEST(golden_usb2sd_main_loop) {
  Runner r("tmc4361", "usb-2-sd", 20000);
  r.b.set(4, 50000);
  r.b.set(5, 10000);
  r.mvp(5000);
  r.wait_pos();
  r.mvp(0);
  r.wait_pos();
  r.advance(r.b.now + 100000);
  std::ostringstream csv;
  tmcl::write_csv(csv, r.rec);
  compare_golden("usb2sd_main_loop.csv", csv.str());
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

// USB-2-SD manual, section 7.6, Func2: ROL 0, 500 / WAIT TICKS, 0, 100 / MST 0.
TEST(golden_usb2sd_rol_mst) {
  Runner r("tmc4361", "usb-2-sd", 1000);
  r.rec.mark(0, 0, tmcl::Mark::MoveIssued, "ROL 0, 500", 0);
  r.b.core->rotate(0, -500);
  r.advance(1000000);
  r.rec.mark(r.b.now, 0, tmcl::Mark::MoveIssued, "MST 0", r.b.core->position(0));
  r.b.core->stop(0);
  r.advance(r.b.core->next_event());
  r.advance(r.b.now + 5000);
  std::ostringstream csv;
  tmcl::write_csv(csv, r.rec);
  compare_golden("usb2sd_rol_mst.csv", csv.str());
}

// TMC2300-MOTOR-EVAL manual, section 6.2 (its main loop, speeds within the module's range).
TEST(golden_tmc2300_main_loop) {
  Runner r("linear", "tmc2300-eval", 50000);
  r.b.set(4, 20000);
  r.b.set(5, 10000);
  r.mvp(5000);
  r.wait_pos();
  r.mvp(0);
  r.wait_pos();
  std::ostringstream csv;
  tmcl::write_csv(csv, r.rec);
  compare_golden("tmc2300_main_loop.csv", csv.str());
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
