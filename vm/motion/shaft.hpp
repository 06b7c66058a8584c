// The shaft of a TMCM module's motor, kept apart from its position counter, and the encoder that
// watches the shaft (the `tmc429` and `tmc5160` cores; docs/motion.md, "Shaft and encoder").
//
// An open-loop module counts the microsteps it commands (XACTUAL, axis parameter 1); the shaft
// follows them only while nothing stops it. Three positions, all in microsteps:
//   register   XACTUAL as the program reads it (SAP 1 and a reference search move it)
//   commanded  XACTUAL + RampMotor::phys: the counter in the machine's frame (from power-on;
//              SAP 1 does not move it, the scenario's switches are placed in it)
//   shaft      where the rotor really is, in the same frame: commanded + offset, or `held_at`
//              while the shaft is blocked (a hard stop) and the counter runs on
// The shaft moves apart from the counter in two ways:
//   lose(n)    the counter moved n microsteps the shaft did not follow (steps lost in one go)
//   hold/release  the shaft stands (at a hard stop, in a stall without stop) while the counter
//              goes on: every commanded step in between is lost; release() makes it follow again
//   slip(n)    the shaft moved n microsteps by itself (a scenario's `slip M = N` line)
// The encoder counts the shaft: 209 = floor(shaft * num / den) + off, num/den the prescaler
// (TMCM-1110 manual 5.4.1: prescaler = 210 / 512); writing 209 sets the count. Only the cores
// decide when a shaft holds or slips; this file knows no time, no ramp and no module.
#pragma once

#include <cstdint>
#include <optional>

namespace tmcl::shaft {

// floor(a / b) for b > 0.
inline std::int64_t floor_div(std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

struct Shaft {
  std::int64_t offset = 0;  // shaft - commanded while following: the steps lost and slipped so far
  bool held = false;        // blocked: stands at held_at whatever the counter does
  std::int64_t held_at = 0;

  std::int64_t at(std::int64_t commanded) const { return held ? held_at : commanded + offset; }
  // The counter moved `steps` (signed) that the shaft did not follow.
  void lose(std::int64_t steps) {
    if (!held) offset -= steps;
  }
  // The shaft moved `steps` (signed) on its own.
  void slip(std::int64_t steps) {
    if (held)
      held_at += steps;
    else
      offset += steps;
  }
  // From now the shaft stands where it is while the counter runs on.
  void hold(std::int64_t commanded) {
    held_at = at(commanded);
    held = true;
  }
  // From now the shaft follows the counter again, from where it stands.
  void release(std::int64_t commanded) {
    if (!held) return;
    offset = held_at - commanded;
    held = false;
  }
  // Shaft steps per commanded step: 1 while following, 0 while held.
  int follows() const { return held ? 0 : 1; }
};

// The encoder on a shaft: the count it shows (209) for a shaft position, through the prescaler.
struct Encoder {
  std::int64_t off = 0;  // 209 = floor(shaft * num / den) + off
  std::int64_t num = 1, den = 1;  // the prescaler, num / den (den > 0; num 0: the count stands)

  std::int64_t read(std::int64_t shaft) const { return floor_div(shaft * num, den) + off; }
  // SAP 209: the count becomes `value` where the shaft is.
  void set(std::int64_t shaft, std::int64_t value) { off = value - floor_div(shaft * num, den); }
  // A new prescaler counts on from the count shown now (the count does not jump).
  void rescale(std::int64_t shaft, std::int64_t new_num, std::int64_t new_den) {
    const std::int64_t shown = read(shaft);
    num = new_num, den = new_den > 0 ? new_den : 1;
    set(shaft, shown);
  }
};

// The deviation the module checks against 212 (manuals: "when the actual position (parameter 1)
// and the encoder position (parameter 209) differ more than set here"): XACTUAL - 209, as a
// function of the register position x while the counter moves and the shaft follows or stands.
struct Deviation {
  std::int64_t to_commanded = 0;  // commanded = x + to_commanded (RampMotor::phys)
  Shaft shaft;
  Encoder enc;

  std::int64_t at(std::int64_t x) const { return x - enc.read(shaft.at(x + to_commanded)); }
  // The first register position reached moving `dir` (+1, -1) from x0 (x0 itself included) at
  // which |deviation| > max; nullopt when none within 2^40 microsteps. The deviation is monotone
  // in x (it changes by 1 - (encoder steps) per counter step, the encoder's steps all >= 0 or all
  // <= 0 per counter step), so a bisection finds the exact step.
  std::optional<std::int64_t> trip(std::int64_t x0, int dir, std::int64_t max) const;
};

}  // namespace tmcl::shaft
