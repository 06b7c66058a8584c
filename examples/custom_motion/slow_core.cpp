// The `slow` example core (slow_core.hpp). Each motor is a line p(t) = p0 + dir * speed * (t - t0)
// in microseconds, so the instant it reaches its target is known exactly: ceil(distance / speed).
#include "slow_core.hpp"

#include <algorithm>
#include <cstdlib>
#include <vector>

namespace {

using namespace tmcl;

struct Motor {
  std::int64_t p0 = 0;  // position at t0
  SimTime t0 = 0;
  int dir = 0;          // -1, 0, +1
  std::int32_t speed = 1000;
  std::int32_t target = 0;
  bool rotating = false;
  SimTime arrive = kNever;  // position mode: instant of arrival
  bool reported = true;
};

class SlowCore final : public MotionCore {
 public:
  std::string_view name() const override { return "slow"; }
  void reset(const Profile& profile, int motors) override {
    motors_.assign(static_cast<std::size_t>(motors), Motor{});
    if (const ParamInfo* p = profile.axis_param(4))
      for (auto& m : motors_) m.speed = std::max<std::int32_t>(1, p->default_value);
    now_ = 0;
  }
  SimTime next_event() const override {
    SimTime t = kNever;
    for (const auto& m : motors_)
      if (!m.reported) t = std::min(t, m.arrive);
    return t;
  }
  void advance(SimTime to, std::vector<MotionEvent>& out) override {
    now_ = std::max(now_, to);
    for (std::size_t i = 0; i < motors_.size(); ++i) {
      Motor& m = motors_[i];
      if (!m.reported && m.arrive <= now_) {
        m.reported = true;
        out.push_back({m.arrive, static_cast<std::uint8_t>(i), MotionEventKind::TargetReached, m.target});
      }
    }
  }
  bool owns(int p) const override { return p == 0 || p == 1 || p == 2 || p == 3 || p == 4 || p == 8; }
  ParamWrite set_param(int motor, int param, std::int32_t value) override {
    Motor& m = at(motor);
    switch (param) {
      case 0: move_absolute(motor, value); return ParamWrite::Ok;
      case 2: rotate(motor, value); return ParamWrite::Ok;
      case 4:
        if (value <= 0) return ParamWrite::OutOfRange;
        rebase(m);
        m.speed = value;
        if (!m.rotating && !m.reported) move_absolute(motor, m.target);  // the rest at the new speed
        return ParamWrite::Ok;
      default: return ParamWrite::ReadOnly;
    }
  }
  std::int32_t get_param(int motor, int param) override {
    Motor& m = at(motor);
    switch (param) {
      case 0: return m.target;
      case 1: return position(motor);
      case 2: case 3: return m.dir * m.speed * (moving(m) ? 1 : 0);
      case 4: return m.speed;
      case 8: return target_reached(motor);
      default: return 0;
    }
  }
  void move_absolute(int motor, std::int32_t target) override {
    Motor& m = at(motor);
    rebase(m);
    m.target = target;
    m.rotating = false;
    std::int64_t d = static_cast<std::int64_t>(target) - m.p0;
    m.dir = d > 0 ? 1 : d < 0 ? -1 : 0;
    m.arrive = now_ + (std::llabs(d) * 1000000 + m.speed - 1) / m.speed;  // rounded up
    m.reported = false;
  }
  // MVP REL counts from the actual position, as the TMCL reference says (docs/motion.md).
  void move_relative(int motor, std::int32_t offset) override { move_absolute(motor, position(motor) + offset); }
  void rotate(int motor, std::int32_t velocity) override {
    Motor& m = at(motor);
    rebase(m);
    m.rotating = velocity != 0;
    m.dir = velocity > 0 ? 1 : velocity < 0 ? -1 : 0;
    m.arrive = kNever;
    m.reported = true;
  }
  void stop(int motor) override { rotate(motor, 0); }
  std::int32_t reference_search(int, RfsAction) override { return 0; }
  void set_switch(int, SwitchInput, bool) override {}
  void encoder_slip(int, std::int32_t) override {}
  std::int32_t position(int motor) const override { return static_cast<std::int32_t>(pos(motors_[static_cast<std::size_t>(motor)], now_)); }
  bool target_reached(int motor) const override {
    const Motor& m = motors_[static_cast<std::size_t>(motor)];
    return !m.rotating && now_ >= m.arrive;
  }
  bool reference_done(int) const override { return true; }
  MotionSample sample_at(int motor, SimTime t) const override {
    const Motor& m = motors_[static_cast<std::size_t>(motor)];
    bool mv = m.rotating || t < m.arrive;
    return {pos(m, t), mv ? static_cast<double>(m.dir * m.speed) : 0.0, 0.0};
  }

 private:
  Motor& at(int motor) { return motors_[static_cast<std::size_t>(motor)]; }
  bool moving(const Motor& m) const { return m.rotating || now_ < m.arrive; }
  static std::int64_t pos(const Motor& m, SimTime t) {
    if (m.dir == 0) return m.p0;
    std::int64_t p = m.p0 + m.dir * (static_cast<std::int64_t>(m.speed) * (t - m.t0) / 1000000);
    if (!m.rotating) p = m.dir > 0 ? std::min<std::int64_t>(p, m.target) : std::max<std::int64_t>(p, m.target);
    return p;
  }
  void rebase(Motor& m) {
    m.p0 = pos(m, now_);
    m.t0 = now_;
  }
  std::vector<Motor> motors_;
  SimTime now_ = 0;
};

}  // namespace

std::unique_ptr<tmcl::MotionCore> make_slow_motion_core() { return std::make_unique<SlowCore>(); }
