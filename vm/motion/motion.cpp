// The motion-core registry (tmclrun --motion NAME: the built-in cores of motion_cores.def, and an
// embedder's) and event names.
#include <algorithm>
#include <map>
#include <mutex>

#include "tmcl/motion.hpp"

namespace tmcl {
namespace {

struct Registry {
  std::mutex lock;
  std::map<std::string, MotionFactory, std::less<>> factories;
  Registry() {
#define TMCL_MOTION_CORE(name) factories.emplace(#name, [] { return make_##name##_motion_core(); });
#include "tmcl/motion_cores.def"
#undef TMCL_MOTION_CORE
  }
};

Registry& registry() {
  static Registry r;
  return r;
}

}  // namespace

std::string_view motion_event_name(MotionEventKind kind) {
  switch (kind) {
    case MotionEventKind::TargetReached: return "target reached";
    case MotionEventKind::VelocityReached: return "velocity reached";
    case MotionEventKind::Stopped: return "stopped";
    case MotionEventKind::Deviation: return "deviation";
    case MotionEventKind::ReferenceDone: return "reference search done";
    case MotionEventKind::SwitchChanged: return "switch changed";
    case MotionEventKind::Stall: return "stall";
    case MotionEventKind::StepsLost: return "steps lost";
    case MotionEventKind::Rebased: return "position re-based";
    case MotionEventKind::CurrentChanged: return "coolStep current";
    case MotionEventKind::Contact: return "contact";
  }
  return "?";
}

std::string_view switch_input_name(SwitchInput input) {
  switch (input) {
    case SwitchInput::StopLeft: return "left";
    case SwitchInput::StopRight: return "right";
    case SwitchInput::Home: return "home";
  }
  return "?";
}

std::string motion_event_text(const MotionEvent& ev) {
  if (ev.kind == MotionEventKind::Stall) return "stall: load value " + std::to_string(ev.value) + ", stopped";
  if (ev.kind == MotionEventKind::StepsLost)
    return ev.value == kStepsLostStallUnseen
               ? "steps lost: the shaft stands, the position counter runs on (StealthChop: stallGuard2 sees no stall)"
               : "steps lost: the shaft stands, the position counter runs on";
  if (ev.kind == MotionEventKind::Rebased)
    return "position re-based: the reference point, " + std::to_string(ev.value) + " before, is 0 now";
  if (ev.kind == MotionEventKind::CurrentChanged) return "coolStep: actual current " + std::to_string(ev.value);
  if (ev.kind == MotionEventKind::Contact)
    return ev.value > 0 ? "contact: the shaft meets a load of " + std::to_string(ev.value) + " %"
                        : "contact: the shaft meets the " + std::string(switch_input_name(ev.input)) + " hard stop";
  if (ev.kind != MotionEventKind::SwitchChanged) return std::string(motion_event_name(ev.kind));
  return std::string(switch_input_name(ev.input)) + " switch " + (ev.active ? "closed" : "opened");
}

void register_motion_core(std::string name, MotionFactory factory) {
  Registry& r = registry();
  std::lock_guard<std::mutex> g(r.lock);
  r.factories[std::move(name)] = std::move(factory);
}

std::unique_ptr<MotionCore> make_motion_core(std::string_view name) {
  Registry& r = registry();
  std::lock_guard<std::mutex> g(r.lock);
  auto it = r.factories.find(name);
  if (it == r.factories.end()) return nullptr;
  return it->second();
}

std::unique_ptr<MotionCore> make_profile_motion_core(const Profile& profile, std::string* note) {
  if (auto core = make_motion_core(profile.default_motion)) return core;
  std::string_view use = profile.fallback_motion.empty() ? std::string_view("ideal") : profile.fallback_motion;
  auto core = make_motion_core(use);
  if (!core) use = "ideal", core = make_ideal_motion_core();
  if (note)
    *note = "motion core '" + std::string(profile.default_motion) + "' (the default for " + std::string(profile.name) +
            ") is not built in; using '" + std::string(use) + "'";
  return core;
}

std::vector<std::string> motion_core_names() {
  Registry& r = registry();
  std::lock_guard<std::mutex> g(r.lock);
  std::vector<std::string> names;
  for (const auto& [name, f] : r.factories) names.push_back(name);
  return names;
}

}  // namespace tmcl
