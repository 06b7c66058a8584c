// Closed-form ramp planning shared by the motion cores (tmc4361, linear): a plan is a list of
// constant-jerk segments computed once per command, evaluated at any instant without integrating.
// The mathematics and the decisions behind it are in docs/motion.md (from design/ramps.md).
//
// Conventions: seconds, microsteps, pps, pps², pps³, doubles. A plan's times are seconds after
// its origin (an integer microsecond the core keeps); its positions are relative to an integer
// base the core keeps, so the doubles stay small. Inside a segment the jerk is constant and the
// velocity never changes sign; jumps (start velocity, stop velocity, hard stop, the snap of a
// stopped motor onto its last step) are simply differences between one segment's end and the
// next one's start.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

namespace tmcl::ramp {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

struct Segment {
  double t0;   // start, seconds after the plan's origin
  double dur;  // kInf for the last segment of a plan
  double x0, v0, a0, j;
  int dir;     // +1 / -1: moving that way inside the segment; 0: at rest

  double x(double dt) const { return x0 + dt * (v0 + dt * (a0 / 2 + dt * j / 6)); }
  double v(double dt) const { return v0 + dt * (a0 + dt * j / 2); }
  double a(double dt) const { return a0 + dt * j; }
};

// The limits of one ramp in physical units. Inverse jerks: 0 = that bow phase is instant (the
// acceleration jumps); all four are 0 for trapezoid/SixPoint/EightPoint ramps, whose acceleration
// is constant between break velocities: astart/dfinal below vbreak (> 0), amid/dmid from vbreak
// up to vbreak2 (EightPoint: A2/D2 between V1 and V2; a band whose speeds are empty is skipped),
// amax/dmax above both.
struct Limits {
  double vmax = 0;
  double vstart = 0, vstop = 0;
  double amax = 0, astart = 0, vbreak = 0;
  double dmax = 0, dfinal = 0;
  double amid = 0, dmid = 0, vbreak2 = 0;
  double ij1 = 0, ij2 = 0, ij3 = 0, ij4 = 0;  // 1/BOW1 .. 1/BOW4
  // Seconds at rest after the speed reached 0 before the motor may move again (TZEROWAIT).
  double zero_wait = 0;
  bool s_curve() const { return ij1 > 0 || ij2 > 0 || ij3 > 0 || ij4 > 0; }
  bool mid_band() const { return vbreak2 > vbreak; }
  // The rates of the speed bands in use are > 0 (a zero acceleration would never get anywhere).
  bool rates() const;
  // ... and there is a speed to move at.
  bool can_move() const;
};

enum class EventKind : std::uint8_t { TargetReached, VelocityReached, Stopped, Deviation, ReferenceDone };
struct PlanEvent {
  double t;
  EventKind kind;
};

struct State {
  double t, x, v, a;
};

struct Plan {
  std::vector<Segment> segs;      // contiguous in time; the last one has dur == kInf
  std::vector<PlanEvent> events;  // sorted by t
  double t_rest = kInf;           // from this instant on the motor rests for good
  double rest_at = -kInf;         // ... and rests since this instant (its speed reached 0)

  void clear() {
    segs.clear();
    events.clear();
    t_rest = kInf;
    rest_at = -kInf;
  }
  // Index of the segment containing t (the last one whose t0 <= t).
  std::size_t find(double t) const;
  State at(double t) const;
};

// XACTUAL for a continuous position inside a segment moving `dir`: the last whole step passed,
// i.e. rounded toward where the segment came from (floor moving +, ceil moving -); tolerance 1e-6.
std::int64_t step_of(double x, int dir);

// Builds a plan from a start state. Each plan_* appends segments and events and leaves the
// builder at the state where it ends; finish_* appends the final infinite segment.
class Builder {
 public:
  Builder(Plan& plan, State start, int dir = 0) : plan_(plan), s_(start), last_dir_(dir) {}
  const State& state() const { return s_; }

  // Positioning: reach `target` (relative position, an integer) at rest, overshooting and coming
  // back when the current state cannot stop in time. Ends at rest; event TargetReached.
  void plan_position(const Limits& lim, double target);
  // Velocity mode: reach signed velocity `vt` and keep it (vt == 0: stop with the decel set).
  void plan_velocity(const Limits& lim, double vt);
  // Pieces of a plan a core composes itself (tmc429's soft approach): the legs of plan_velocity
  // to signed speed vt without its event and end (false, nothing added, when a needed rate is
  // 0); one constant-jerk piece in direction dir (a and j in the speed frame: a < 0 slows down);
  // a cruise at the current speed; the arrival on `target` at rest (TargetReached).
  bool ramp_to(const Limits& lim, double vt);
  void piece(double tau, double a, double j, int dir);
  void cruise(double tau, int dir);
  void arrive(double target, int dir);
  // Stops (events are the caller's): with the deceleration set and the stop-velocity cut-off,
  // with a linear deceleration (ignores bows), or at once.
  void stop_ramp(const Limits& lim);
  void stop_linear(double decel);
  void stop_hard();
  // A motor that cannot change speed (a needed rate is 0) keeps its speed for good.
  void coast();
  // The motor has rested `s` seconds when the plan starts (the ramp wait, Limits::zero_wait,
  // counts them: a move starts when the motor has rested that long).
  void rested(double s) { rest_at_ = -s; }

  void event(EventKind kind) { plan_.events.push_back({s_.t, kind}); }
  // Cuts the plan at instant t (a trip: switch, virtual stop, deviation) and continues from the
  // state there; events after t are dropped.
  void truncate(double t);
  void finish_rest();
  void finish_cruise();

 private:
  struct Piece {
    double tau, a, j;
  };
  struct Leg {
    Piece p[6];
    int n = 0;
    double t = 0, s = 0, u = 0;  // duration, distance, end speed (filled by sum())
    void add(double tau, double a, double j) {
      if (tau > 0) p[n++] = {tau, a, j};
    }
    void sum(double u0);
  };

  static double unwind(const Limits& lim, double u0, double a0);
  static void accel_leg(const Limits& lim, double u0, double a0, double u1, bool skip_b1, Leg& leg);
  static void decel_leg(const Limits& lim, double u0, double a0, double u1, bool skip_b4, Leg& leg);
  static void lead_leg(const Limits& lim, double u0, double a0, double vp, bool skip_b1, Leg& leg);
  // Distance of lead(u0,a0 -> vp) + final decel(vp -> vstop).
  static double reach(const Limits& lim, double u0, double a0, double vp, bool skip_b1);
  void plan_ahead(const Limits& lim, int dir, double u0, double a0, double dist, double target, bool skip_b1);
  void emit(const Leg& leg, int dir);
  void emit_cruise(double tau, int dir);
  void snap();
  void start_motion(int dir, double v);
  void wait_at_rest(const Limits& lim);

  Plan& plan_;
  State s_;
  int last_dir_ = 0;
  double rest_at_ = -kInf;  // the plan instant the motor came to rest (before 0: it rested already)
  bool moved_ = false;      // the plan moved the motor since it last came to rest
};

// Instant dt in [0, seg.dur] at which the segment's position reaches k (monotone segment), or a
// negative number when it does not within the segment.
double crossing(const Segment& seg, double k);

}  // namespace tmcl::ramp
