// The golden CSVs of the motion recorder: prints the CSV of one named run of a core, driven
// through the core API (recording.hpp), for the golden runner (tests/golden/motion/). The runs
// are the manuals' example programs' motion, without the VM around them.
// usage: motion_csv usb2sd-main-loop | usb2sd-rol-mst | tmc2300-main-loop
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>

#include "recording.hpp"

namespace {

std::string csv_of(const tmcl::MotionRecorder& rec) {
  std::ostringstream csv;
  tmcl::write_csv(csv, rec);
  return csv.str();
}

}  // namespace

int main(int argc, char** argv) {
  std::string name = argc == 2 ? argv[1] : "";
  std::string csv;
  if (name == "usb2sd-main-loop") {
    mt::Runner r("tmc4361", "usb-2-sd", 20000);
    mt::usb2sd_main_loop(r);
    csv = csv_of(r.rec);
  } else if (name == "usb2sd-rol-mst") {  // USB-2-SD manual, section 7.6, Func2: ROL 0, 500 / WAIT TICKS, 0, 100 / MST 0
    mt::Runner r("tmc4361", "usb-2-sd", 1000);
    r.rec.mark(0, 0, tmcl::Mark::MoveIssued, "ROL 0, 500", 0);
    r.b.core->rotate(0, -500);
    r.advance(1000000);
    r.rec.mark(r.b.now, 0, tmcl::Mark::MoveIssued, "MST 0", r.b.core->position(0));
    r.b.core->stop(0);
    r.advance(r.b.core->next_event());
    r.advance(r.b.now + 5000);
    csv = csv_of(r.rec);
  } else if (name == "tmc2300-main-loop") {  // TMC2300-MOTOR-EVAL manual, section 6.2 (speeds within range)
    mt::Runner r("linear", "tmc2300-eval", 50000);
    r.b.set(4, 20000);
    r.b.set(5, 10000);
    r.mvp(5000);
    r.wait_pos();
    r.mvp(0);
    r.wait_pos();
    csv = csv_of(r.rec);
  } else {
    std::fprintf(stderr, "usage: motion_csv usb2sd-main-loop | usb2sd-rol-mst | tmc2300-main-loop\n");
    return 64;
  }
  if (tmcl_test::failures() != 0) return 70;  // a parameter the core refused (helpers.hpp)
  std::cout << csv;
  return 0;
}
