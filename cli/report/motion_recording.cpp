// Recording decorator and trace tee for tmclrun --csv/--plot (see motion_recording.hpp).
#include "tmcl/motion_recording.hpp"

#include <cstdio>

#include "tmcl/params.hpp"

namespace tmcl {

void RecordingCore::advance(SimTime to, std::vector<MotionEvent>& events) {
  rec_.sample_until(inner_, to);  // while the core's plan still holds
  std::size_t first = events.size();
  inner_.advance(to, events);
  for (std::size_t i = first; i < events.size(); ++i) rec_.motion_event(events[i]);
  now_ = to;
}

void RecordingCore::reset(const Profile& profile, int motors) {
  inner_.reset(profile, motors);
  now_ = 0;
  units_.clear();
  motor_units_.clear();
  if (std::string note = inner_.units_note(); !note.empty()) {
    units_.emplace_back(0, std::move(note));
    for (int m = 0; m < motors; ++m) motor_units_.push_back(motor_units(m));
  }
}

// One motor's units, from what the core converts: "velocity 1 = 7.62939 pps, acceleration 1 =
// 116.415 pps²".
std::string RecordingCore::motor_units(int motor) const {
  std::string text;
  for (auto [param, what] : {std::pair{int{kApTargetSpeed}, "velocity"}, std::pair{int{kApMaxAcceleration}, "acceleration"}})
    if (auto p = inner_.physical(motor, param, 1)) {
      char buf[96];
      std::snprintf(buf, sizeof buf, "%s%s 1 = %.6g %s", text.empty() ? "" : ", ", what, p->value, std::string(p->unit).c_str());
      text += buf;
    }
  return text;
}

ParamWrite RecordingCore::set_param(int motor, int param, std::int32_t value) {
  const std::int32_t before = param == kApActualPosition ? inner_.position(motor) : 0;
  const ParamWrite r = inner_.set_param(motor, param, value);
  // SAP 1 re-bases the motor's count: the walls stay where they are, at other counts now.
  if (param == kApActualPosition && r == ParamWrite::Ok) rec_.rebase(now_, motor, std::int64_t{inner_.position(motor)} - before);
  if (units_.empty()) return r;  // a core in pps
  if (std::string note = inner_.units_note(); note != units_.back().second) {
    // A mark (a CSV row) for each motor whose units changed, with its own units: the row's motor
    // is the one it is about.
    for (std::size_t m = 0; m < motor_units_.size(); ++m) {
      const int mi = static_cast<int>(m);
      if (std::string mine = motor_units(mi); mine != motor_units_[m]) {
        rec_.mark(now_, mi, Mark::Other, "units: " + mine, inner_.sample_at(mi, now_).position);
        motor_units_[m] = std::move(mine);
      }
    }
    units_.emplace_back(now_, std::move(note));
  }
  return r;
}

std::string RecordingCore::units_history(std::string_view sep) const {
  std::string text;
  for (std::size_t i = 0; i < units_.size(); ++i) {
    if (i == 0) {
      text = units_[i].second;
      continue;
    }
    char at[48];
    std::snprintf(at, sizeof at, "from %.6f s: ", static_cast<double>(units_[i].first) * 1e-6);
    text.append(sep).append(at).append(units_[i].second);
  }
  return text;
}

std::string RecordingCore::units_title() const {
  if (units_.empty()) return {};
  const std::string& first = units_.front().second;
  return "; " + first.substr(0, first.find(':')) + (units_.size() > 1 ? ", changes marked" : "");
}

void RecordingCore::issued(int motor, std::string label) {
  rec_.mark(now_, motor, Mark::MoveIssued, std::move(label), inner_.sample_at(motor, now_).position);
}

void RecordingCore::move_absolute(int motor, std::int32_t target) {
  inner_.move_absolute(motor, target);
  issued(motor, "move to " + std::to_string(target));
}

void RecordingCore::move_relative(int motor, std::int32_t offset) {
  inner_.move_relative(motor, offset);
  issued(motor, "move by " + std::to_string(offset));
}

void RecordingCore::rotate(int motor, std::int32_t velocity) {
  inner_.rotate(motor, velocity);
  std::string speed = std::to_string(velocity) + " pps";
  if (auto p = inner_.physical(motor, kApTargetSpeed, velocity)) {  // a core in chip units
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3f %s", p->value, std::string(p->unit).c_str());
    speed = std::to_string(velocity) + " (" + buf + ")";
  }
  issued(motor, "rotate at " + speed);
}

void RecordingCore::stop(int motor) {
  inner_.stop(motor);
  issued(motor, "stop");
}

std::int32_t RecordingCore::reference_search(int motor, RfsAction action) {
  std::int32_t r = inner_.reference_search(motor, action);
  if (action != RfsAction::Status) issued(motor, action == RfsAction::Start ? "reference search" : "stop search");
  return r;
}

void RecordingCore::set_switch(int motor, SwitchInput input, bool active) {
  inner_.set_switch(motor, input, active);
  const char* which = input == SwitchInput::StopLeft ? "left" : input == SwitchInput::StopRight ? "right" : "home";
  rec_.mark(now_, motor, input == SwitchInput::Home ? Mark::HomeSwitch : Mark::StopSwitch,
            std::string(which) + " switch " + (active ? "on" : "off"),
            inner_.sample_at(motor, now_).position);
}

void RecordingTrace::interrupt_enter(const Vm& vm, int vector, std::int32_t from_pc) {
  if (inner_) inner_->interrupt_enter(vm, vector, from_pc);
  const InterruptVector* v = vm.profile->vector(vector);
  rec_.mark(vm.now, -1, Mark::Interrupt, v ? std::string(v->name) : "interrupt " + std::to_string(vector));
}

}  // namespace tmcl
