// Recording a run for tmclrun --csv/--plot without touching the VM: a MotionCore decorator that
// samples the real core before every advance and marks commands and switch changes, and a
// TraceSink tee that marks interrupts (and passes everything on to the text trace, if any).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tmcl/motion_plot.hpp"
#include "tmcl/vm.hpp"

namespace tmcl {

class RecordingCore final : public MotionCore {
 public:
  RecordingCore(MotionCore& inner, MotionRecorder& recorder) : inner_(inner), rec_(recorder) {}

  std::string_view name() const override { return inner_.name(); }
  void reset(const Profile& profile, int motors) override;
  SimTime next_event() const override { return inner_.next_event(); }
  void advance(SimTime to, std::vector<MotionEvent>& events) override;
  bool owns(int param) const override { return inner_.owns(param); }
  const ParamInfo* range(int param) const override { return inner_.range(param); }
  ParamWrite set_param(int motor, int param, std::int32_t value) override;
  std::int32_t get_param(int motor, int param) override { return inner_.get_param(motor, param); }
  void move_absolute(int motor, std::int32_t target) override;
  void move_relative(int motor, std::int32_t offset) override;
  void rotate(int motor, std::int32_t velocity) override;
  void stop(int motor) override;
  std::int32_t reference_search(int motor, RfsAction action) override;
  void set_switch(int motor, SwitchInput input, bool active) override;
  void encoder_slip(int motor, std::int32_t counts) override { inner_.encoder_slip(motor, counts); }
  std::int32_t position(int motor) const override { return inner_.position(motor); }
  bool target_reached(int motor) const override { return inner_.target_reached(motor); }
  bool reference_done(int motor) const override { return inner_.reference_done(motor); }
  MotionSample sample_at(int motor, SimTime t) const override { return inner_.sample_at(motor, t); }
  std::optional<std::int32_t> sample_param(int motor, int param, SimTime t) const override {
    return inner_.sample_param(motor, param, t);
  }
  bool place_switch(int motor, SwitchInput input, std::int64_t lo, std::int64_t hi) override {
    return inner_.place_switch(motor, input, lo, hi);
  }
  bool place_hard_stop(int motor, SwitchInput side, std::int64_t position) override {
    const bool ok = inner_.place_hard_stop(motor, side, position);
    if (ok) rec_.hard_stop(motor, side, position);  // drawn as a line on the position panel
    return ok;
  }
  bool set_load(int motor, int percent) override { return inner_.set_load(motor, percent); }
  bool place_load(int motor, std::int64_t lo, std::int64_t hi, int percent) override {
    return inner_.place_load(motor, lo, hi, percent);
  }
  std::optional<PhysicalValue> physical(int motor, int param, std::int32_t raw) const override {
    return inner_.physical(motor, param, raw);
  }
  std::string units_note() const override { return inner_.units_note(); }

  // Samples up to `at` (the end of the run).
  void finish(SimTime at) { rec_.sample_until(inner_, at); }
  // The units a core in chip units had at power-on and, for each change during the run (a
  // divisor written: also a mark "units: ..."), from when on the new ones held, joined by `sep`:
  // the CSV's comment lines, the plot's title. Empty for a core in pps.
  std::string units_history(std::string_view sep) const;
  // For the plot's title: "; TMC429 units" (the note's name), with ", changes marked" when they
  // changed during the run; empty for a core in pps. Never longer with more changes.
  std::string units_title() const;

 private:
  void issued(int motor, std::string label);
  std::string motor_units(int motor) const;
  MotionCore& inner_;
  MotionRecorder& rec_;
  SimTime now_ = 0;  // the last advance: commands and switches happen at this instant
  std::vector<std::pair<SimTime, std::string>> units_;  // the units note from each instant on
  std::vector<std::string> motor_units_;                 // each motor's units as last marked
};

class RecordingTrace final : public TraceSink {
 public:
  RecordingTrace(TraceSink* inner, MotionRecorder& recorder) : inner_(inner), rec_(recorder) {}
  void instruction(const Vm& vm, SimTime at, std::int32_t pc, const Instruction& ins) override {
    if (inner_) inner_->instruction(vm, at, pc, ins);
  }
  void interrupt_enter(const Vm& vm, int vector, std::int32_t from_pc) override;
  void interrupt_leave(const Vm& vm, std::int32_t to_pc) override {
    if (inner_) inner_->interrupt_leave(vm, to_pc);
  }
  void motion_event(const Vm& vm, const MotionEvent& ev) override {
    if (inner_) inner_->motion_event(vm, ev);
  }
  void wait_end(const Vm& vm, std::int32_t pc, bool timeout) override {
    if (inner_) inner_->wait_end(vm, pc, timeout);
  }
  void input_event(const Vm& vm, const std::string& what) override {
    if (inner_) inner_->input_event(vm, what);
  }
  void warning(const Vm& vm, const RuntimeWarning& w) override {
    if (inner_) inner_->warning(vm, w);
  }

 private:
  TraceSink* inner_;
  MotionRecorder& rec_;
};

}  // namespace tmcl
