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
  rec_.mark(now_, motor, Mark::StopSwitch, std::string(which) + " switch " + (active ? "on" : "off"),
            inner_.sample_at(motor, now_).position);
}

void RecordingTrace::interrupt_enter(const Vm& vm, int vector, std::int32_t from_pc) {
  if (inner_) inner_->interrupt_enter(vm, vector, from_pc);
  const InterruptVector* v = vm.profile->vector(vector);
  rec_.mark(vm.now, -1, Mark::Interrupt, v ? std::string(v->name) : "interrupt " + std::to_string(vector));
}

}  // namespace tmcl
