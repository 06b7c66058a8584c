// What the cores of the TMCM modules share beyond the ramp (ramp_motor.hpp): the limit switches
// with their stop functions and switch states, and the modules' reference search (RFS, 193-196)
// as a state machine driven by the switches. The TMC429 modules (motion_tmc429.cpp) and the
// TMCM-1260 (motion_tmc5160.cpp) describe both alike in their manuals; a core adds its units, its
// ramps and the parameter numbers where they differ. The TMC2300's `linear` core (motion_linear.cpp)
// uses it for the machine and the load model only (SwitchConfig::stop_switches false, no search).
// docs/motion.md explains every decision.
//
// Parameters this part gives a meaning: 0-3, 8-13, 193-196 (and the core's soft-stop flag and
// last-reference parameter, SwitchConfig), and where the profile declares an encoder (EncoderSpec)
// 207, 209, 210 and 212: the encoder counting the shaft (shaft.hpp) and the deviation stop.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "coolstep.hpp"
#include "ramp_motor.hpp"
#include "shaft.hpp"
#include "stall.hpp"

namespace tmcl::sw {

enum Param : int {
  kHomeState = 9,          // TMC429 modules: the reference (left or home) input; TMCM-1260: home
  kRightSwitchState = 10,
  kLeftSwitchState = 11,
  kRightStopDisable = 12,
  kLeftStopDisable = 13,
  kRfsMode = 193,          // 1-8; +64: the other end switch (1-4, TMCM-1260); +128: home inverted
  kRfsSpeed = 194,
  kRfsSwitchSpeed = 195,
  kRfsDistance = 196,      // between the end switches, after modes 2 and 3
  kSg1Threshold = 205,     // stallGuard 1 (TMCM-351): the stall detection threshold 1..7, 0 off
  kErrorFlags = 207,       // extended error flags: the deviation (and stall) stops
  kEncoderPosition = 209,
  kEncoderPrescaler = 210, // TMC429 modules: prescaler = value / 512; TMCM-1260: clear on null
  kMaxDeviation = 212,     // |XACTUAL - 209| beyond it stops the motor; 0: off
};

// What the profile declares of the module's encoder (motion-constant lines; docs/profiles.md).
struct EncoderSpec {
  bool present = false;            // `encoder 1`: 209 counts the shaft, 212 stops the motor
  std::int64_t prescaler_one = 0;  // `encoder-prescaler`: the 210 value of prescaler 1 (0: none,
                                   // the encoder is matched to the microsteps)
  std::int32_t prescaler_flags = 0;  // `encoder-prescaler-flags`: 210's bits that select functions
  std::int32_t deviation_flag = 0;   // `deviation-flag`: what a deviation stop sets in 207
  bool flags_clear_on_read = false;  // `error-flags-read-clears`: reading 207 clears it
  static EncoderSpec of(const Profile& profile);
};

enum class Goal : std::uint8_t { Idle, Position, Velocity, Halt, Search };

// The reference search's steps (docs/motion.md has a figure per mode):
//   FindFar  modes 2, 3: toward the far end switch at the search speed until it closes
//   Find     toward the switch at the search speed until it closes (modes 5, 6: the end switch
//            on the way reverses the search once)
//   Release  back at the switch speed until it opens: its near edge
//   Reenter  toward it again until it closes: the edge once more
//   Cross    on through it until it opens at its far edge (switches with two edges)
//   ToRef    to the reference point, which is then position 0
enum class SearchStep : std::uint8_t { Off, FindFar, Find, Release, Reenter, Cross, ToRef };
inline constexpr int kRefInput = 3;  // the reference input: the left or the home switch in series
inline constexpr int kNullInput = 4;  // modes 9, 10 (TMCM-1290): the encoder's null channel, not modelled

// A value of 193 taken apart.
struct SearchMode {
  int mode = 1;          // 1-8
  bool other = false;    // +64: modes 1-4 search the right switch (and 2, 3 the left one first)
  bool invert = false;   // +128: the home switch is closed outside its range
};

struct Search {
  SearchStep step = SearchStep::Off;
  SearchMode m;
  int input = 0;         // SwitchInput searched, or kRefInput
  int far = 1;           // modes 2, 3: the end switch searched first
  int dir = -1;          // direction of the current step
  int reverse_at = -1;   // modes 5, 6: the end switch that turns the search around (-1: none)
  bool both = false;     // the switch has a far edge: calibrate from both sides
  std::int64_t far_edge = 0, release = 0, reenter = 0;  // switching points (register counts)
};

struct Motor {
  ramp::RampMotor rm;
  std::array<std::int32_t, 256> p{};  // owned parameters, raw as written
  Goal goal = Goal::Idle;
  std::int32_t vt = 0;                // velocity-mode target, raw
  std::uint8_t timed = 0;             // bit (1 << SwitchInput): closed by a timed scenario line
  double trip_t = ramp::kInf;         // plan instant of a pending limit-switch stop
  Search search;
  shaft::Shaft shaft;                 // the rotor, apart from the counter (shaft.hpp)
  shaft::Encoder enc;                 // axis parameter 209, counting the shaft
  std::int32_t errors = 0;            // axis parameter 207: cleared by a motion command
  std::uint8_t halted_by = 0;         // the motor stopped by itself, its target kept: 1 a stall, 2 a deviation
                                      // (stop_reason); cleared by a motion command as 207 is
  stall::Axis sg;                     // hard stops, loads and the load value (stall_core.cpp)
  coolstep::State cool;               // coolStep's regulation (coolstep_core.cpp)
};

// Where the modules differ in what this part does.
struct SwitchConfig {
  int soft_stop;          // the flag choosing a ramp (1) or a hard stop (0) at a limit switch
  bool home_in_series;    // mode 3 searches the reference input (TMC429 modules: home in series with left)
  bool other_switch;      // 193 takes +64 (modes 1-4) and +128 only with modes 5-8 (TMCM-1260)
  int last_reference = 0; // parameter that keeps the reference point's former position (0: none)
  bool stop_switches = true;  // false: the module has no stop switches (TMC2300: placed ones only report)
  bool null_channel = false;  // 193 takes modes 9, 10: the encoder's null channel + / - (TMCM-1290)
  bool mode7_negative = false;  // mode 7 searches the home switch moving -, 8 moving + (TMCM-1290)
};

class SwitchCore : public ramp::RampCore<Motor> {
 public:
  SwitchCore(std::span<const int> owned, std::string_view home, bool chip_units, SwitchConfig cfg)
      : RampCore(owned, home, chip_units), cfg_(cfg) {}

  void reset(const Profile& profile, int motors) override;
  void advance(SimTime to, std::vector<MotionEvent>& out) override;
  ParamWrite set_param(int motor, int param, std::int32_t value) override;
  std::int32_t get_param(int motor, int param) override;
  void move_absolute(int motor, std::int32_t target) override;
  void rotate(int motor, std::int32_t velocity) override;
  void stop(int motor) override;
  std::int32_t reference_search(int motor, RfsAction action) override;
  bool reference_done(int motor) const override;
  void set_switch(int motor, SwitchInput input, bool active) override;
  // The shaft slips `counts` microsteps against the counter (scenario `slip`); the encoder sees it.
  void encoder_slip(int motor, std::int32_t counts) override;
  bool models_encoder(const Profile& profile) const override;
  std::string stop_reason(int motor) const override;
  // The sample with the shaft where it has parted from the counter (the plot draws it).
  MotionSample sample_at(int motor, SimTime t) const override;
  std::optional<std::int32_t> sample_param(int motor, int param, SimTime t) const override;
  // 205, stallGuard 1's threshold, is the core's only where the profile names that measurement
  // (`motion-constant stallguard 1`, stall_core.cpp); elsewhere the VM keeps it, if the module has it.
  bool owns(int param) const override {
    return (param != kSg1Threshold || guard_ == stall::Guard::SG1) && RampCore::owns(param);
  }
  // ---- loads, stalls and lost steps (stall_core.cpp; docs/motion.md)
  SimTime next_event() const override;
  bool place_hard_stop(int motor, SwitchInput side, std::int64_t position) override;
  bool set_load(int motor, int percent) override;
  bool place_load(int motor, std::int64_t lo, std::int64_t hi, int percent) override;

 protected:
  // The module has coolStep (coolstep_core.cpp): 180 is its regulated current scale.
  bool has_coolstep() const { return cool_on_; }
  // ---- what a core says
  // pps per velocity unit of `m` now (1 for a core in pps).
  virtual double vunit(const Motor& m) const = 0;
  // The largest speed (raw) the velocity register holds.
  virtual std::int32_t max_speed() const = 0;
  // The ramp of the motor's goal (Position or Velocity) at its parameters.
  virtual ramp::Limits ramp_limits(const Motor& m) const = 0;
  // The ramp of a reference-search step at `speed` (raw): a velocity ramp to it, or (the last
  // step, `positioning`) the positioning ramp with it as the top speed.
  virtual ramp::Limits search_limits(const Motor& m, std::int32_t speed, bool positioning) const = 0;
  // Plans a positioning to the target (parameter 0); the default is the plain positioning ramp.
  virtual void plan_position(Motor& m, ramp::Builder& b, const ramp::Limits& lim) const;
  // Writes of the parameters the shared part leaves to the core: the default checks the range,
  // stores the value and re-plans when it changed.
  virtual ParamWrite set_other(Motor& m, int param, std::int32_t value);
  // Parameter 2 as read, and parameter 9 (see kHomeState).
  virtual std::int32_t target_speed(const Motor& m, const ramp::State& s) const;
  virtual bool home_state(const Motor& m) const { return closed(m, 2); }
  // After a re-plan has been cut at its first limit-switch trip (m.trip_t): a core's own stops
  // (the TMC5240's virtual stops) cut it earlier with stop_at(); the default has none.
  virtual void scan_stops(Motor&, const ramp::Limits&) {}

  // ---- the shared machinery, for the cores
  // A reading in whole units, toward zero as the chip's registers hold it.
  static std::int32_t units(double v);
  bool closed(const Motor& m, int input) const;
  // Re-plans motor m from its state now toward its goal; then the first limit-switch trip cuts it.
  // `vscale` multiplies the speed now (a chip whose velocity unit just changed: tmc429). A
  // re-plan not `by_command` (a parameter, a switch) keeps a cruise's "velocity reached" quiet.
  void replan(Motor& m, double vscale = 1, bool by_command = false);
  void abort_search(Motor& m) { m.search.step = SearchStep::Off; }
  // Cuts the plan at plan instant t and stops there as at a limit switch (its soft-stop flag);
  // the next re-plan after t keeps that stop (m.trip_t).
  void stop_at(Motor& m, double t, const ramp::Limits& lim);
  const EncoderSpec& encoder_spec() const { return enc_spec_; }
  // ---- the shaft (shaft.hpp), for the cores and for what blocks or slips a rotor
  // The counter in the machine's frame (XACTUAL + phys), and the shaft's place, now.
  std::int64_t commanded(const Motor& m) const { return m.rm.xactual(now_) + m.rm.phys; }
  std::int64_t shaft_at(const Motor& m) const { return m.shaft.at(commanded(m)); }
  // Steps lost now: the counter moved `steps` the shaft did not follow.
  void lose_steps(Motor& m, std::int64_t steps) { m.shaft.lose(steps); }
  // The shaft stands from now (a hard stop, a stall without stop) / follows again from now.
  void hold_shaft(Motor& m) { m.shaft.hold(commanded(m)); }
  void release_shaft(Motor& m) { m.shaft.release(commanded(m)); }
  // After the shaft or the encoder changed apart from the plan: a moving motor is re-planned (the
  // deviation scan finds the new trip), one at rest stops with a deviation now if beyond 212.
  // `stop_at_rest`: a slip, not a write of 209 or 210 (a program re-aligning the encoder).
  void shaft_changed(Motor& m, bool stop_at_rest);
  // XACTUAL - 209 as a function of the register position, for the deviation stop.
  shaft::Deviation deviation(const Motor& m) const { return {m.rm.phys, m.shaft, m.enc}; }
  // ---- the load value and stop on stall (stall_core.cpp)
  // Starts a new plan now: first brings the load value up to now (what the old plan measured).
  ramp::Builder restart(Motor& m, double vscale = 1);
  // Before a write of `param`: a parameter the load value depends on brings it up to now.
  void stall_input(Motor& m, int param);
  // 206 and 208 as read; false when `param` is neither (or the module has no stallGuard2).
  // 206 and 208 as read at `at` (now_ or, for a sample, an instant before the next event).
  bool stall_param(const Motor& m, int param, std::int32_t& value, SimTime at) const;
  void set_goal(Motor& m, Goal goal) {
    abort_search(m);
    m.goal = goal;
    m.trip_t = ramp::kInf;
  }

 private:
  bool decode(std::int32_t value, SearchMode& out) const;
  void switch_stop(Motor& m, ramp::Builder& b, const ramp::Limits& lim);
  void scan_trips(Motor& m, const ramp::Limits& lim);
  void scan_deviation(Motor& m);
  void set_prescaler(Motor& m);
  bool deviation_on(const Motor& m) const { return enc_spec_.present && m.p[kMaxDeviation] > 0; }
  std::int64_t encoder(const Motor& m) const { return m.enc.read(shaft_at(m)); }
  std::int32_t search_speed(const Motor& m) const;
  std::int32_t switch_speed(const Motor& m) const;
  bool search_closed(const Motor& m, int input) const;
  void start_search(Motor& m);
  void search_step(Motor& m, bool stop_first, double vscale = 1);
  void turn_around(Motor& m);
  bool release_blocked(const Motor& m, int input, int dir) const;
  void search_switch(Motor& m, int input, bool now_closed, std::int64_t edge, int dir);
  void search_met(Motor& m, std::int64_t edge);
  bool far_edge(const Motor& m, int input, int dir) const;
  void reference_at(Motor& m, std::int64_t a, std::int64_t b);

  SwitchConfig cfg_;
  EncoderSpec enc_spec_;

  // ---- stall_core.cpp
  void reset_stall(const Profile& profile);  // from reset(): which stallGuard2 the module has
  bool sg_on_ = false;    // the module has stallGuard2 (its profile lists 174)
  bool flags208_ = false; // ... and flags a stall in 208 bit 0
  std::int64_t current_steps_ = 256;  // the run current's range (6) in 32 steps of the current scale
  struct Window;
  SimTime next_mech(const Motor& m) const;
  void on_mech(Motor& m, std::vector<MotionEvent>& out);
  void commit(Motor& m);
  bool last_reading(const Motor& m, int& value, SimTime at) const;
  int current_scale(const Motor& m) const;
  double fullstep(const Motor& m) const;
  double period(const Motor& m) const;
  int load_at(const Motor& m, double shaft_pos) const;
  double shaft_pos(const Motor& m, const ramp::Segment& seg, double t) const;
  double contact(const Motor& m, const ramp::Segment& seg, double t1, double t2, int& why) const;
  double first_stall(const Motor& m, const ramp::Segment& seg, double t1, double t2) const;
  bool stops_on_stall(const Motor& m) const;
  // ---- the other drivers' measurements (stallGuard 1, StallGuard4; stall_core.cpp, errata E74, E75)
  stall::Guard guard_ = stall::Guard::None;  // which measurement the module makes
  std::int32_t stall_flag207_ = 0;           // what a stop on stall sets in 207 (`stall-flag`)
  bool measuring(const Motor& m) const;
  // StealthChop switched by speed (the TMC5160: 186, 187): stallGuard2 measures only at or above
  // this speed (pps; 0: at every speed). Errata E78.
  bool stealth_by_speed_ = false;
  double stealth_below(const Motor& m) const;
  bool measures_at(const Motor& m, double pps) const { return measuring(m) && pps + 1e-9 >= stealth_below(m); }
  int measure(const Motor& m, double f, int load) const;
  int reading_at(const Motor& m, double f, int cs, int load) const;
  double stall_below(const Motor& m, int load) const;
  int stall_reading(const Motor& m, int value) const;
  // stallGuard 1 measures at a constant speed only ("no stall detection while the motor is being
  // accelerated or decelerated", TMCM-351 manual 7.3); the others on every moving segment.
  bool steady_enough(const ramp::Segment& seg) const {
    return guard_ != stall::Guard::SG1 || (seg.a0 == 0 && seg.j == 0);
  }

  // ---- coolstep_core.cpp: the actual current 180 (docs/motion.md, "coolStep")
  // What a walk over the measurements of a plan found (cool_walk).
  struct CoolWalk {
    coolstep::State st;     // the regulation after the walk
    int value = 0;          // the last measurement's reading (206), when `measured`
    bool measured = false;
    double stop = -1;       // search: the plan instant it stopped at (a change of the scale, or the cap)
  };
  void reset_cool(const Profile& profile);
  static bool cool_input(int param);
  bool cool_param(Motor& m, int param, std::int32_t value, ParamWrite& result);
  std::int32_t actual_current(const Motor& m) const;
  coolstep::Settings cool_settings(const Motor& m) const;
  bool cool_active(const Motor& m) const;
  bool regulates(const Motor& m, double pps) const;
  int scale_of(std::int32_t current) const;
  int reading_scale(const Motor& m) const;
  void cool_walk(const Motor& m, double s_lo, double s_hi, bool search, CoolWalk& w) const;
  double next_cool(const Motor& m) const;
  bool cool_on_ = false;  // the module has coolStep: its profile lists 172 (and the load value)
};

}  // namespace tmcl::sw
