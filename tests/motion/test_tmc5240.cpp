// The tmc5240 core (TMCM-1290, TMCM-3216; TMCM-1290 manual 1.01) through its public API: its rows
// and ranges from the module's profile, EightPoint move times against the closed form (sections
// 1.3, 7.6: VSTART, A1 to V1, A2 to V2, AMAX to VMAX; DMAX to V2, D2 to V1, D1 to VSTOP; V1 = 0
// the plain trapezoid, V2 at or below V1 no A2/D2 phase), velocity mode on AMAX alone, the ramp
// wait time (21), the virtual stops (38-41) and the reference search's modes 7 to 10 (table 22).
#include <cmath>
#include <cstdlib>
#include <utility>

#include "check.hpp"
#include "helpers.hpp"

using mt::near;
using mt::us;
using tmcl::MotionEventKind;
using tmcl::ParamWrite;

namespace {

// The TMCM-1290 with plain settings: no EightPoint phases (V1 = 0), no start or stop speed, no
// ramp wait, hard stops, AMAX = DMAX = 51200 pps².
// (Named apart from test_tmc5160.cpp's Drive: a unity build puts both files in one unit.)
struct Drive5240 : mt::SwitchBench {
  explicit Drive5240(const char* profile = "tmcm-1290") : SwitchBench("tmc5240", profile, 1) {
    for (auto [param, value] : {std::pair{4, 51200}, {5, 51200}, {16, 0}, {17, 51200}, {19, 0}, {20, 0}, {21, 0},
                                {26, 0}, {35, 0}, {41, 0}, {12, 0}, {13, 0}})
      set(param, value);
  }
  // The EightPoint ramp of the tests below.
  void eightpoint(int vstart, int a1, int v1, int a2, int v2, int amax, int vmax, int dmax, int d2, int d1, int vstop) {
    for (auto [param, value] : {std::pair{19, vstart}, {15, a1}, {16, v1}, {34, a2}, {35, v2}, {5, amax}, {4, vmax},
                                {17, dmax}, {36, d2}, {18, d1}, {20, vstop}})
      set(param, value);
  }
};

// The ramp of the closed-form tests: three bands each way, VSTART 1000, VSTOP 2000.
constexpr double vs = 1000, a1 = 100000, v1 = 10000, a2 = 40000, v2 = 30000, amax = 20000, vmax = 60000, dmax = 25000,
                 d2 = 50000, d1 = 80000, ve = 2000;
void standard(Drive5240& b) { b.eightpoint(1000, 100000, 10000, 40000, 30000, 20000, 60000, 25000, 50000, 80000, 2000); }

// Time and distance of the accelerating and decelerating legs up to speed v (closed form).
double t_up(double v) {
  return (std::min(v, v1) - vs) / a1 + std::max(0.0, std::min(v, v2) - v1) / a2 + std::max(0.0, v - v2) / amax;
}
double s_up(double v) {
  auto s = [](double lo, double hi, double a) { return hi > lo ? (hi * hi - lo * lo) / (2 * a) : 0.0; };
  return s(vs, std::min(v, v1), a1) + s(v1, std::min(v, v2), a2) + s(v2, v, amax);
}
double t_down(double v) {
  return (std::min(v, v1) - ve) / d1 + std::max(0.0, std::min(v, v2) - v1) / d2 + std::max(0.0, v - v2) / dmax;
}
double s_down(double v) {
  auto s = [](double lo, double hi, double a) { return hi > lo ? (hi * hi - lo * lo) / (2 * a) : 0.0; };
  return s(ve, std::min(v, v1), d1) + s(v1, std::min(v, v2), d2) + s(v2, v, dmax);
}

}  // namespace

TEST(tmc5240_is_the_tmcm1290s_core_with_its_rows_and_ranges) {
  for (const char* name : {"tmcm-1290", "tmcm-3216"}) {
    const tmcl::Profile* p = tmcl::find_profile(name);
    CHECK(p != nullptr);
    if (!p) continue;
    CHECK(p->default_motion == "tmc5240");
    mt::Bench d("tmc5240", name, p->motors);
    CHECK_EQ(d.get(4), p->axis_param(4)->default_value);
    CHECK_EQ(d.get(34), p->axis_param(34)->default_value);
    CHECK(!d.core->physical(0, 4, 1000));  // pps already: no chip units
    // 193: modes 1-10, +64 with 1-4, +128 with 5-8; 9 and 10 alone (table 22).
    for (int v : {1, 4, 5, 8, 9, 10, 65, 68, 133, 136})
      CHECK(d.core->set_param(0, 193, v) == ParamWrite::Ok);
    for (int v : {0, 11, 69, 73, 74, 137, 138, 129})
      CHECK(d.core->set_param(0, 193, v) == ParamWrite::OutOfRange);
    for (int ro : {3, 8, 40, 196, 197}) CHECK(d.core->set_param(0, ro, 0) == ParamWrite::ReadOnly);
    CHECK(d.core->set_param(0, 34, 116) == ParamWrite::OutOfRange);  // A2: 117..7629278
    CHECK(d.core->set_param(0, 35, 1000001) == ParamWrite::OutOfRange);  // V2: 0..1000000
  }
  CHECK_EQ(tmcl::find_profile("tmcm-3216")->motors, 3);
}

// Section 1.3: every band of a long move, and the move's time to the microsecond.
TEST(tmc5240_eightpoint_move_times_match_the_closed_form) {
  Drive5240 b;
  standard(b);
  const double dist = 400000;
  const double total = t_up(vmax) + (dist - s_up(vmax) - s_down(vmax)) / vmax + t_down(vmax);
  b.core->move_absolute(0, 400000);
  auto v_at = [&](double t) { return b.core->sample_at(0, static_cast<tmcl::SimTime>(std::llround(t * 1e6))).velocity; };
  CHECK(near(v_at(0.05), vs + a1 * 0.05, 0, 1));                              // A1 to V1
  CHECK(near(v_at(t_up(v1) + 0.1), v1 + a2 * 0.1, 0, 1));                      // A2 to V2
  CHECK(near(v_at(t_up(v2) + 0.5), v2 + amax * 0.5, 0, 1));                    // AMAX to VMAX
  CHECK(near(v_at(t_up(vmax) + 0.1), vmax, 0, 1e-6));                          // cruise
  const double t_dec = total - t_down(vmax);
  CHECK(near(v_at(t_dec + 0.2), vmax - dmax * 0.2, 0, 1));                     // DMAX to V2
  CHECK(near(v_at(total - t_down(v2) + 0.1), v2 - d2 * 0.1, 0, 1));            // D2 to V1
  CHECK(near(v_at(total - 0.05), ve + d1 * 0.05, 0, 1));                       // D1 to VSTOP
  CHECK_EQ(b.next(), us(total));
  CHECK(b.last().kind == MotionEventKind::TargetReached);
  CHECK_EQ(b.core->position(0), 400000);
  CHECK_EQ(b.get(8), 1);
}

// Short moves: the peak speed lies in the A2 band or in the AMAX band, from the closed form
// s_up(vp) + s_down(vp) = distance, quadratic in vp² inside one band: vp² = lo² + (distance -
// s_up(lo) - s_down(lo)) / (1/2a + 1/2d), lo the band's lower edge, a and d its rates.
TEST(tmc5240_short_moves_peak_in_the_band_the_closed_form_says) {
  struct Band {
    double lo, hi, a, d;
    std::int32_t target;
  };
  for (const Band& band : {Band{v1, v2, a2, d2, 15000}, Band{v2, vmax, amax, dmax, -60000}}) {
    Drive5240 b;
    standard(b);
    const double dist = std::abs(band.target);
    const double vp = std::sqrt(band.lo * band.lo + (dist - s_up(band.lo) - s_down(band.lo)) / (1 / (2 * band.a) + 1 / (2 * band.d)));
    CHECK(vp > band.lo && vp < band.hi);
    b.core->move_absolute(0, band.target);
    CHECK_EQ(b.next(), us(t_up(vp) + t_down(vp)));
    CHECK_EQ(b.core->position(0), band.target);
  }
}

// A phase whose speed is 0 is skipped: V2 = 0 (or V2 <= V1) is the SixPoint ramp of A1/AMAX and
// DMAX/D1; V1 = 0 is the plain trapezoid of AMAX and DMAX whatever V2 says (7.6: it "switches
// off the EightPoint ramp"), however small A1, A2, D1, D2 are.
TEST(tmc5240_phases_whose_speed_is_zero_are_skipped) {
  const double dist = 300000;
  {
    Drive5240 b;
    b.eightpoint(1000, 100000, 10000, 117, 0, 20000, 60000, 25000, 117, 80000, 2000);
    const double sa = (v1 * v1 - vs * vs) / (2 * a1) + (vmax * vmax - v1 * v1) / (2 * amax);
    const double sd = (vmax * vmax - v1 * v1) / (2 * dmax) + (v1 * v1 - ve * ve) / (2 * d1);
    const double total = (v1 - vs) / a1 + (vmax - v1) / amax + (dist - sa - sd) / vmax + (vmax - v1) / dmax + (v1 - ve) / d1;
    b.core->move_absolute(0, 300000);
    CHECK_EQ(b.next(), us(total));
    Drive5240 c;  // V2 below V1: the same
    c.eightpoint(1000, 100000, 10000, 117, 5000, 20000, 60000, 25000, 117, 80000, 2000);
    c.core->move_absolute(0, 300000);
    CHECK_EQ(c.next(), us(total));
  }
  {
    Drive5240 b;
    b.eightpoint(1000, 117, 0, 117, 30000, 20000, 60000, 25000, 117, 117, 2000);
    const double sa = (vmax * vmax - vs * vs) / (2 * amax), sd = (vmax * vmax - ve * ve) / (2 * dmax);
    const double total = (vmax - vs) / amax + (dist - sa - sd) / vmax + (vmax - ve) / dmax;
    b.core->move_absolute(0, 300000);
    CHECK_EQ(b.next(), us(total));
    CHECK_EQ(b.core->position(0), 300000);
  }
}

// 7.6's note: velocity mode ramps with AMAX (5) alone, from and to standstill; a reversal waits
// the ramp wait time (21, 32 µs units) at standstill.
TEST(tmc5240_velocity_mode_uses_amax_and_waits_at_a_reversal) {
  Drive5240 b;
  standard(b);
  b.set(21, 3125);  // 0.1 s
  b.core->rotate(0, 40000);
  CHECK_EQ(b.next(), us(40000.0 / amax));
  CHECK(b.last().kind == MotionEventKind::VelocityReached);
  const tmcl::SimTime t0 = b.now;
  b.core->rotate(0, -40000);  // down with AMAX, 0.1 s at rest, up with AMAX
  CHECK_EQ(b.next(), t0 + us(2 * 40000.0 / amax + 0.1));
  CHECK(b.last().kind == MotionEventKind::VelocityReached);
  CHECK_EQ(b.get(3), -40000);
  auto v_at = [&](double t) { return b.core->sample_at(0, t0 + static_cast<tmcl::SimTime>(std::llround(t * 1e6))).velocity; };
  CHECK_EQ(v_at(2.0 + 0.05), 0.0);  // resting within the wait
  CHECK(near(v_at(2.1 + 0.5), -amax * 0.5, 0, 1));
}

// The ramp wait holds a new move until the motor has rested 21 since its last stop; a motor that
// has rested longer starts at once.
TEST(tmc5240_ramp_wait_time_holds_the_next_move) {
  Drive5240 b;
  b.set(21, 15625);  // 0.5 s
  const double t1 = mt::move_time(10000, 51200, 51200);
  b.core->move_absolute(0, 10000);
  CHECK_EQ(b.next(), us(t1));
  const tmcl::SimTime stop = b.now;  // the stop was at t1, reported at the next microsecond
  b.to(stop + 200000);  // 0.2 s at rest, then a move back: it starts 0.5 s after the stop
  b.core->move_absolute(0, 0);
  CHECK_EQ(b.next(), us(t1 + 0.5 + t1));
  CHECK_EQ(b.core->position(0), 0);
  b.to(b.now + 600000);  // rested longer than the wait: no hold
  const tmcl::SimTime t = b.now;
  b.core->move_absolute(0, 10000);
  CHECK_EQ(b.next(), t + us(t1));
  // A target behind a moving motor: it stops, waits, comes back.
  Drive5240 c;
  c.set(21, 3125);  // 0.1 s
  c.core->rotate(0, 51200);
  c.to(2000000);  // at 51200 pps since 1 s: at 76800
  c.core->move_absolute(0, 0);
  CHECK(c.until(MotionEventKind::TargetReached));
  const double back = mt::move_time(76800 + 25600, 51200, 51200);  // stopped at 102400
  CHECK_EQ(c.now, 2000000 + us(1.0 + 0.1 + back));
}

// 38-41: a virtual stop stops a motor that reaches it moving toward it (hard with 26 = 0, with
// the ramp beyond it with 26 = 1), 40 says which one it is at, motion away from it is free.
TEST(tmc5240_virtual_stops_stop_the_motor) {
  {
    Drive5240 b;
    b.set(39, 30000);
    b.set(41, 2);
    b.core->move_absolute(0, 50000);
    CHECK(b.until(MotionEventKind::Stopped));
    CHECK_EQ(b.core->position(0), 30000);
    CHECK_EQ(b.get(40), 2);
    CHECK_EQ(b.get(8), 0);
    CHECK_EQ(b.count(MotionEventKind::TargetReached), 0);
    b.core->move_absolute(0, 60000);  // further: it does not move
    b.to(b.now + 500000);
    CHECK_EQ(b.core->position(0), 30000);
    b.core->move_absolute(0, 0);  // away: free
    CHECK(b.until(MotionEventKind::TargetReached));
    CHECK_EQ(b.core->position(0), 0);
    CHECK_EQ(b.get(40), 0);
  }
  {  // soft: stops with DMAX beyond the left stop; the left stop alone is enabled
    Drive5240 b;
    b.set(26, 1);
    b.set(38, -20000);
    b.set(39, 100);
    b.set(41, 1);
    b.core->rotate(0, -20000);
    CHECK(b.until(MotionEventKind::Stopped));
    CHECK_EQ(b.core->position(0), -20000 - static_cast<std::int32_t>(std::floor(20000.0 * 20000.0 / (2 * 51200))));
    CHECK_EQ(b.get(40), 1);
  }
  {  // disabled (41 = 0): the motor passes
    Drive5240 b;
    b.set(39, 30000);
    b.core->move_absolute(0, 50000);
    CHECK(b.until(MotionEventKind::TargetReached));
    CHECK_EQ(b.core->position(0), 50000);
    CHECK_EQ(b.get(40), 0);
  }
}

// Table 22 and 7.1.7: mode 7 searches the home switch moving -, 8 moving + (the TMCM-1260's
// are the other way round); 9 and 10 the encoder's null channel, which is not modelled: the
// search runs on at the search speed until RFS STOP.
TEST(tmc5240_rfs_modes_7_to_10) {
  for (auto [mode, dir] : {std::pair{7, -1}, {8, 1}}) {
    Drive5240 b;
    b.set(193, mode);
    b.set(194, 20000);
    b.set(195, 2000);
    b.place(tmcl::SwitchInput::Home, dir * 10000, dir * 10000 + 400);
    CHECK_EQ(b.core->reference_search(0, tmcl::RfsAction::Start), 0);
    CHECK(b.until(MotionEventKind::ReferenceDone));
    CHECK_EQ(b.core->position(0), 0);
  }
  for (auto [mode, dir] : {std::pair{9, 1}, {10, -1}}) {
    Drive5240 b;
    b.set(193, mode);
    b.set(194, 20000);
    b.core->reference_search(0, tmcl::RfsAction::Start);
    b.to(3000000);
    CHECK(!b.core->reference_done(0));
    CHECK_EQ(b.get(3), dir * 20000);
    b.core->reference_search(0, tmcl::RfsAction::Stop);
    CHECK(b.until(MotionEventKind::Stopped));
  }
}

// The TMCM-3216's three axes are three such ramps, apart: each its own parameters and plan, the
// events in time order.
TEST(tmc5240_three_axes_of_the_tmcm3216_move_apart) {
  mt::Bench b("tmc5240", "tmcm-3216", 3);
  for (int m = 0; m < 3; ++m)
    for (auto [param, value] : {std::pair{4, 51200}, {5, 51200}, {16, 0}, {17, 51200}, {19, 0}, {20, 0}, {21, 0}})
      b.set(param, value, m);
  b.set(4, 25600, 2);
  b.core->move_absolute(2, 40000);
  b.core->move_absolute(0, 10000);
  b.to(10000000);
  CHECK_EQ(b.events.size(), std::size_t{2});
  CHECK_EQ(b.events[0].motor, 0);
  CHECK_EQ(b.events[0].at, us(mt::move_time(10000, 51200, 51200)));
  CHECK_EQ(b.events[1].motor, 2);
  CHECK_EQ(b.events[1].at, us(mt::move_time(40000, 25600, 51200)));
  CHECK_EQ(b.core->position(0), 10000);
  CHECK_EQ(b.core->position(1), 0);
  CHECK_EQ(b.core->position(2), 40000);
}
