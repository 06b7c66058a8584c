// Recording a run's motion and writing it as CSV (tmclrun --csv FILE --sample DURATION) or as an
// SVG plot of position, velocity and acceleration against time (tmclrun --plot FILE.svg).
//
// Wiring into a run loop:
//   MotionRecorder rec(vm.motors, sample_period);
//   before every motion->advance(t):        rec.sample_until(*motion, t);
//   for every MotionEvent the VM handles:   rec.motion_event(ev);
//   when the program issues a move:         rec.mark(now, motor, Mark::MoveIssued, "MVP ABS 5000", pos);
//   when an interrupt is taken:             rec.mark(now, motor, Mark::Interrupt, "TI_TIMER0");
//   when a stop switch changes:             rec.mark(now, motor, Mark::StopSwitch, "left 0 = 1");
//   at the end:                             rec.sample_until(*motion, now); write_csv(...); write_svg(...);
// Samples come from MotionCore::sample_at, which looks ahead in closed form, so the VM never has
// to wake up for a sample.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "tmcl/motion.hpp"
#include "tmcl/plot.hpp"

namespace tmcl {

// A scenario's hard stop (RecordingCore::place_hard_stop): a line on the motor's position panel
// and a comment line in the CSV.
struct RecordedHardStop {
  int motor;
  SwitchInput side;
  std::int64_t position;
};
// A re-base of a motor's position count (a reference search's, SAP 1): from `at` on every position
// in that count is `delta` more than before. The walls stay; their lines follow the count.
struct RecordedRebase {
  SimTime at;
  int motor;
  std::int64_t delta;
};

class MotionRecorder {
 public:
  // period > 0: one sample of every motor at 0, period, 2*period, ...
  MotionRecorder(int motors, SimTime period);

  // Samples every motor at each grid instant in (last sampled, to] (and at 0 the first time).
  // Call it before the core advances to `to`, i.e. while its plan is still the one that holds.
  void sample_until(const MotionCore& core, SimTime to);
  void mark(SimTime at, int motor, Mark kind, std::string label, std::optional<std::int64_t> position = {});
  // A core's event: target reached becomes a TargetReached mark, the others Other marks.
  void motion_event(const MotionEvent& ev);
  void hard_stop(int motor, SwitchInput side, std::int64_t position) { hard_stops_.push_back({motor, side, position}); }
  // The motor's count re-based at `at` (motion_event does it for a reference search's; the
  // recording core for SAP 1).
  void rebase(SimTime at, int motor, std::int64_t delta) {
    if (delta != 0) rebases_.push_back({at, motor, delta});
  }

  // Axis parameters sampled with the motion, each drawn as a panel of its own (tmclrun
  // --plot-series 206,180): call before the first sample. plot_series_name names those it can.
  void sample_params(std::vector<int> params) { params_ = std::move(params); }
  const std::vector<int>& sampled_params() const { return params_; }
  // param_samples()[(i * motors() + m) * sampled_params().size() + k]: parameter k of motor m at
  // times()[i], empty where the core cannot say it (MotionCore::sample_param).
  const std::vector<std::optional<std::int32_t>>& param_samples() const { return param_samples_; }

  // Which motors write_csv and write_svg show, in order (tmclrun: shown_motors, vm_output.hpp);
  // every recorded one until it is called.
  void show_motors(std::vector<int> motors) { shown_ = std::move(motors); }
  std::vector<int> shown_motors() const;

  int motors() const { return motors_; }
  SimTime period() const { return period_; }
  const std::vector<SimTime>& times() const { return times_; }
  // samples()[i * motors() + m]: motor m at times()[i].
  const std::vector<MotionSample>& samples() const { return samples_; }
  const std::vector<RecordedMark>& marks() const { return marks_; }
  const std::vector<RecordedHardStop>& hard_stops() const { return hard_stops_; }
  const std::vector<RecordedRebase>& rebases() const { return rebases_; }

 private:
  int motors_;
  SimTime period_;
  SimTime next_ = 0;
  std::vector<SimTime> times_;
  std::vector<MotionSample> samples_;
  std::vector<RecordedMark> marks_;
  std::vector<RecordedHardStop> hard_stops_;
  std::vector<RecordedRebase> rebases_;
  std::vector<int> params_;
  std::vector<std::optional<std::int32_t>> param_samples_;
  std::optional<std::vector<int>> shown_;
};

// CSV: a comment line, a header, then rows in time order; sample rows have an empty event column,
// event rows an empty velocity and acceleration. Stable text (fixed decimals) for golden files.
// `units_note` (MotionCore::units_note: a core in chip units) follows as comment lines (tmclrun
// passes the units at power-on and, one line each, from when on each change held), then one
// comment line per hard stop of a shown motor ("# hard stop left -20000 (motor 0)"), and one per
// re-base of that motor's count after it ("# hard stop left -20000 (motor 0) at 0 from 1.094612 s,
// the position count re-based").
void write_csv(std::ostream& out, const MotionRecorder& rec, std::string_view units_note = {});

// The axis parameters a plot can draw as a series (--plot-series) and their names: 206 "load
// value", 180 "actual current"; empty for any other.
std::string_view plot_series_name(int param);

// The SVG of plot.hpp: three stacked panels (position, velocity, acceleration) over a shared
// time axis, one colour per quantity, one dash pattern per motor, event markers and a legend;
// then one panel per sampled parameter (sample_params).
void write_svg(std::ostream& out, const MotionRecorder& rec, const PlotOptions& options = {});

}  // namespace tmcl
