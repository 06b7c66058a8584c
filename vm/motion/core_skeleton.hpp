// What every built-in motion core shares, however its motors move: one M per motor (M holds the
// owned axis parameters in `p`), the owned parameters' power-on defaults and write ranges taken
// from the module profiles (the only source of both), the instant of the last advance, and the
// events a command causes at its own instant, reported by the next advance, and the one rule of
// MVP REL (move_relative) every core follows. RampCore
// (ramp_motor.hpp) adds motion planned in time on top; the ideal core, whose motors jump, adds
// its jumps (motion_ideal.cpp).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "tmcl/motion.hpp"
#include "tmcl/params.hpp"
#include "tmcl/profile.hpp"

namespace tmcl {

template <class M>
class CoreSkeleton : public MotionCore {
 public:
  // `owned`: the axis parameters the core owns (a static table); `home`: the profile of the
  // module the core models, whose rows stand in where the active profile has none. A core whose
  // parameters are in its chip's units (tmc429: `chip_units`) takes no row from a profile that
  // checks nothing (generic: its rows are the USB-2-SD's, in pps), only from its home profile.
  CoreSkeleton(std::span<const int> owned, std::string_view home, bool chip_units = false)
      : owned_(owned), home_(home), chip_units_(chip_units) {}

  // Power-on: every owned parameter at the profile's default, else the home profile's, else 0.
  void reset(const Profile& profile, int motors) override {
    const Profile* home = find_profile(home_);
    motors_.assign(static_cast<std::size_t>(motors), M{});
    range_.fill(nullptr);
    for (int n : owned_) {
      const ParamInfo* info = chip_units_ && profile.any_parameter ? nullptr : profile.axis_param(n);
      if (!info && home) info = home->axis_param(n);
      for (auto& m : motors_) m.p[static_cast<std::size_t>(n)] = info ? info->default_value : 0;
      // The VM checks a write against the active profile's range before the core sees it, except
      // under a profile that stands for any module (generic): there the module the core models
      // decides, from its own profile's row, so the core never holds a value its module would refuse.
      const ParamInfo* rule = profile.any_parameter ? nullptr : profile.axis_param(n);
      if (!rule && home) rule = home->axis_param(n);
      range_[static_cast<std::size_t>(n)] = rule;
    }
    // Parameter 127 where the module has it (under generic: the module the core models), owned
    // whether or not the core's table lists it, so move_relative always reads the value as set.
    relative_ = profile.any_parameter ? (home ? home->axis_param(kApRelativePositioningOption) : nullptr)
                                      : profile.axis_param(kApRelativePositioningOption);
    if (relative_) {
      range_[kApRelativePositioningOption] = relative_;
      for (auto& m : motors_) m.p[kApRelativePositioningOption] = relative_->default_value;
    }
    now_ = 0;
    pending_.clear();
  }
  bool owns(int param) const override {
    return (param == kApRelativePositioningOption && relative_) || std::find(owned_.begin(), owned_.end(), param) != owned_.end();
  }
  const ParamInfo* range(int param) const override { return range_row(param); }

  // MVP REL, one rule for every core (docs/motion.md, "Relative moves"): the new target is the
  // actual position + the offset, as the TMCL reference and every module's manual say ("an
  // offset to the actual position"; the TMC429 code of Trinamic's published firmware computes
  // XACTUAL + offset too), except on a module whose profile has axis parameter 127 (USB-2-SD,
  // TMCM-1260), which counts from where 127 says: 0 the last target, 1 the actual position,
  // 2 the encoder position (a core without an encoder: the actual position).
  void move_relative(int motor, std::int32_t offset) final {
    std::int64_t from = position(motor);
    if (relative_) {
      const std::int32_t option = at(motor).p[kApRelativePositioningOption];
      if (option == 0) from = get_param(motor, kApTargetPosition);
      if (option == 2 && owns(kApEncoderPosition)) from = get_param(motor, kApEncoderPosition);
    }
    move_absolute(motor, static_cast<std::int32_t>(static_cast<std::uint32_t>(static_cast<std::uint64_t>(from + offset))));
  }

 protected:
  M& at(int motor) { return motors_[static_cast<std::size_t>(motor)]; }

  // Whether an owned parameter may take value v: within the range of its profile row (above);
  // a parameter no profile lists takes any value.
  bool in_range(int param, std::int32_t v) const {
    const ParamInfo* r = range_row(param);
    return !r || accepts(*r, v);
  }
  const ParamInfo* range_row(int param) const {
    return param >= 0 && param < 256 ? range_[static_cast<std::size_t>(param)] : nullptr;
  }

  // An event a command caused now, reported by the next advance.
  MotionEvent& report_now(int motor, MotionEventKind kind, std::int32_t position) {
    return pending_.emplace_back(MotionEvent{now_, static_cast<std::uint8_t>(motor), kind, position});
  }
  SimTime next_pending() const { return pending_.empty() ? kNever : pending_.front().at; }
  // Moves the commands' events to `out` (all of them lie at or before now_).
  void take_pending(std::vector<MotionEvent>& out) {
    out.insert(out.end(), pending_.begin(), pending_.end());
    pending_.clear();
  }

  std::span<const int> owned_;
  std::string_view home_;
  bool chip_units_;
  std::vector<M> motors_;
  SimTime now_ = 0;

 private:
  std::array<const ParamInfo*, 256> range_{};  // per owned parameter: the profile row that bounds it
  const ParamInfo* relative_ = nullptr;        // the module's row of 127, if it has one
  std::vector<MotionEvent> pending_;           // caused by a command, reported by the next advance
};

}  // namespace tmcl
