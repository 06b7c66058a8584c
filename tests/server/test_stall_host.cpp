// Stall detection seen from a host (issue 34): tmclrun --serve as a TMCM-1110 with a scenario
// load, driven over TCP the way a host program drives a module, with no program of its own.
// A calibration loop raises the stallGuard2 threshold 174 until the load value 206 under the
// load is non-zero, and must end where the model (vm/motion/stall.hpp) says a module would; a
// timed load comes at its instant of the serving clock even when no request arrives then.
#include <fstream>

#include "check.hpp"
#include "child.hpp"

using namespace srvtest;

namespace {

std::string scenario_file(const std::string& name, const std::string& text) {
  char dir[] = "/tmp/tmcl-stall-host-XXXXXX";
  const std::string path = std::string(::mkdtemp(dir) ? dir : "/tmp") + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// tmclrun serving a TMCM-1110 over TCP with `scenario`, listening.
Child serve_tmcm1110(const std::string& scenario) {
  Child c = spawn_tmclrun({"-t", "tmcm-1110", "--serve", "tcp:127.0.0.1:0", "--scenario", scenario, "--max-wall-time", "60s"});
  CHECK(c.line.rfind("listening on 127.0.0.1:", 0) == 0);
  return c;
}

}  // namespace

// The host's loop, as Trinamic's host library calibrates stallGuard2: run at the working speed
// under the load, start 174 at its lowest (-64) and raise it one step at a time until 206 reads
// more than 0. The model's reading (stall.hpp) is
//   round(no_load(f, cs) * (1 - P/100) + 8 * sgt), held within 0..1023,
//   no_load(f, cs) = 250 + 500 * (cs + 1)/32 * f / (f + 500).
// Here f = 400 (ROR, TMC429 units) * 30.5176 pps / 16 microsteps = 762.94 fullsteps/s, cs = 16
// (run current 128 of 0..255 in 32 steps), so no_load = 250 + 265.625 * 0.60412 = 410.47; under
// P = 90 %: 41.047 + 8 * sgt, which rounds to 0 for sgt <= -6 (-6.95) and to 1 at sgt = -5
// (1.047). The loop must end at 174 = -5 with 206 = 1.
TEST(a_hosts_calibration_loop_ends_where_the_model_says) {
  Child c = serve_tmcm1110(scenario_file("load.txt", "at 0s load 0 = 90%\n"));
  {
    Link l = connect_to(c.line);
    CHECK(l.ok());
    ask(l, kSap, 140, 0, 4);  // 16 microsteps: a fullstep is 16
    ask(l, kRor, 0, 0, 400);
    sleep_ms(100);            // at speed (1000 is 465661 pps²: 26 ms)
    int sgt = -64;
    std::int32_t load = 0;
    for (; sgt <= 63; ++sgt) {
      ask(l, kSap, 174, 0, sgt);
      sleep_ms(10);  // several fullsteps (1.3 ms each): a measurement with the new threshold
      load = ask(l, kGap, 206, 0, 0);
      if (load > 0) break;
    }
    CHECK_EQ(sgt, -5);
    CHECK_EQ(load, 1);
    // Raising it further raises the reading by 8 a step, as the model says.
    ask(l, kSap, 174, 0, 0);
    sleep_ms(10);
    CHECK_EQ(ask(l, kGap, 206, 0, 0), 41);
  }
  ::kill(c.pid, SIGTERM);
  CHECK_EQ(reap(c), 0);
}

// `at 300ms load 0 = 100%` on the serving clock: the host starts the motor with stop on stall
// (181) and asks nothing until long after; the motor has stopped at the load's instant (the
// first fullstep measured after it), not when the next request came.
TEST(a_timed_load_comes_on_the_serving_clock) {
  Child c = serve_tmcm1110(scenario_file("timed.txt", "at 300ms load 0 = 100%\n"));
  {
    Link l = connect_to(c.line);
    CHECK(l.ok());
    ask(l, kSap, 140, 0, 4);
    ask(l, kSap, 181, 0, 200);
    // The tick timer (ms) before and after the ROR: it started between the two, however long a
    // loaded machine made the requests take.
    const auto kGgp = static_cast<std::uint8_t>(tmcl::Op::GGP);
    const std::int32_t t0 = ask(l, kGgp, 132, 0, 0);
    ask(l, kRor, 0, 0, 400);
    const std::int32_t t1 = ask(l, kGgp, 132, 0, 0);
    sleep_ms(800);
    CHECK_EQ(ask(l, kGap, 3, 0, 0), 0);          // stopped on stall ...
    CHECK_EQ(ask(l, kGap, 208, 0, 0) & 1, 1);    // ... flagged
    // ... at 300 ms: 12207 pps from the ROR (the ramp to it costs 160 microsteps), within the
    // tick timer's millisecond on each side and a fullstep.
    const double earliest = 12207.03 * (0.300 - (t1 + 1) / 1000.0) - 160 - 16;
    const double latest = 12207.03 * (0.300 - t0 / 1000.0) - 160 + 16;
    const std::int32_t at = ask(l, kGap, 1, 0, 0);
    CHECK(at >= earliest && at <= latest);
    if (!(at >= earliest && at <= latest)) std::fprintf(stderr, "  stopped at %d, expected %.0f to %.0f\n", at, earliest, latest);
  }
  ::kill(c.pid, SIGTERM);
  CHECK_EQ(reap(c), 0);
}
