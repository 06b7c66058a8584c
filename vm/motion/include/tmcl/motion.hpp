// The motion-core interface: everything an embedder needs to write a ramp generator for the VM.
//
// The VM owns the program; a motion core owns the motors. The VM never integrates motion itself:
// it forwards motion parameters (SAP/GAP/AAP on the numbers the core claims with owns()), motion
// commands (MVP, MVPA, ROR, ROL, RORA, ROLA, MST, RFS) and switch inputs, asks the core for the
// instant of its next observable event, and asks it to advance, in closed form, to an instant.
//
// Contract (the VM keeps it, a core may rely on it):
//   - Time is simulated, an integer count of microseconds (SimTime), starting at 0 after reset().
//   - Before any command, parameter access or query at instant t the VM has called advance(t),
//     so a core only ever needs to know "now" from the last advance().
//   - advance(t) never goes backwards; it appends every event in (last, t] in time order, each
//     stamped with its exact instant. An event caused by a command at instant t (e.g. an ideal
//     move that completes at once) is reported by the next advance(t) with the same instant.
//   - next_event() is the earliest instant > last advance (or == it, for events caused by a
//     command not yet collected) at which advance would report an event; kNever if none can
//     happen without new input. The VM sleeps until then, so a core must not under-report.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tmcl/profile.hpp"
#include "tmcl/sim_time.hpp"

namespace tmcl {

enum class MotionEventKind : std::uint8_t {
  TargetReached,    // position mode: the target is reached with zero speed (interrupt 3+motor)
  VelocityReached,  // velocity mode: the target speed is reached
  Stopped,          // the motor came to rest for another reason (stop switch, virtual stop, MST)
  Deviation,        // encoder deviation beyond axis parameter 212: motor stopped (interrupt 21+motor)
  ReferenceDone,    // a reference search completed
  SwitchChanged,    // a switch placed at a position (place_switch) closed or opened
  Stall,            // stop on stall (axis parameter 181): the load value reached 0, motor stopped (interrupt 15+motor)
  StepsLost,        // the shaft stands (a hard stop, a load of 100 % or more) while the counter runs on;
                    // `value` kStepsLostStallUnseen: stop on stall is on, but StealthChop hides the stall (E78)
  Rebased,          // a reference search made its reference point position 0: the register jumps
  CurrentChanged,   // coolStep changed the actual current (axis parameter 180) of a moving motor: `value`
  Contact,          // the shaft meets a hard stop (`input`: its side) or a load of 100 % or more (`value`:
                    // the load in %, 0 for a hard stop) and stands: the instant the shaft is held
};
std::string_view motion_event_name(MotionEventKind kind);
inline constexpr std::int32_t kStepsLostStallUnseen = 1;  // MotionEvent::value of a StepsLost

enum class SwitchInput : std::uint8_t { StopLeft, StopRight, Home };
std::string_view switch_input_name(SwitchInput input);  // "left", "right", "home"

struct MotionEvent {
  SimTime at;
  std::uint8_t motor;
  MotionEventKind kind;
  std::int32_t position;  // actual position at that instant
  // SwitchChanged only: which input, and whether it is now closed (active).
  SwitchInput input = SwitchInput::StopLeft;
  bool active = false;
  // CurrentChanged: the actual current (axis parameter 180) from then on; Stall: the load value
  // (206) the stall was measured at (0 for stallGuard2); Rebased: where the reference point was
  // before it became 0 (`position` is the motor's position in the new count).
  std::int32_t value = 0;
};
// The event as the trace and the recording show it: "left switch closed", else the kind's name.
std::string motion_event_text(const MotionEvent& ev);

// The physical value of a raw parameter value (MotionCore::physical).
struct PhysicalValue {
  double value;
  std::string_view unit;  // "pps", "pps²"
};

// Result of a parameter write the VM forwards to a core.
enum class ParamWrite : std::uint8_t { Ok, ReadOnly, OutOfRange };

enum class RfsAction : std::uint8_t { Start = 0, Stop = 1, Status = 2 };

// A motor's state at one instant, for recording and plotting (tmclrun --csv / --plot).
struct MotionSample {
  std::int64_t position;  // actual position (axis parameter 1, not wrapped to 32 bits)
  double velocity;        // pps
  double acceleration;    // pps²
  // Where the shaft is, in the position's counts, where a core keeps it apart from the counter
  // (steps lost at a hard stop, under a load, slipped: docs/motion.md, "Shaft and encoder").
  std::optional<std::int64_t> shaft = std::nullopt;
};

class MotionCore {
 public:
  virtual ~MotionCore() = default;
  virtual std::string_view name() const = 0;

  // Power-on state for `motors` motors. Parameters the core owns start at the profile's
  // defaults (profile.axis_param(n)->default_value) where the profile lists them.
  virtual void reset(const Profile& profile, int motors) = 0;

  // Earliest instant of the next event (see the contract above); kNever when idle.
  virtual SimTime next_event() const = 0;
  // Advances every motor to instant `to` in closed form, appending the events on the way.
  virtual void advance(SimTime to, std::vector<MotionEvent>& events) = 0;

  // Axis parameters the core owns. The VM checks the profile's access and range first, then
  // forwards owned numbers here and keeps every other parameter in its own table.
  virtual bool owns(int param) const = 0;
  virtual ParamWrite set_param(int motor, int param, std::int32_t value) = 0;
  // The profile row whose range set_param checks an owned parameter against (the active
  // profile's, or that of the module the core models); nullptr: any value. For messages.
  virtual const ParamInfo* range(int param) const {
    (void)param;
    return nullptr;
  }
  // Reading may have effects (e.g. a flag cleared by reading), hence not const.
  virtual std::int32_t get_param(int motor, int param) = 0;

  virtual void move_absolute(int motor, std::int32_t target) = 0;  // MVP ABS/COORD, MVPA
  // MVP REL: to the actual position + offset, or where the module has axis parameter 127, from
  // where 127 says (docs/motion.md, "Relative moves"; the built-in cores share CoreSkeleton's rule).
  virtual void move_relative(int motor, std::int32_t offset) = 0;
  virtual void rotate(int motor, std::int32_t velocity) = 0;       // ROR (+), ROL (-), RORA, ROLA
  // Why the positioning just commanded cannot start, or which of its ramp settings the manual
  // forbids, naming the parameters (the VM's run-time warning `ramp-setting`); empty: none.
  virtual std::string move_problem(int motor) const {
    (void)motor;
    return {};
  }
  // Why the motor stands off its target though no command stopped it (a stop on stall, an encoder
  // deviation beyond 212), with the target it keeps: "stopped on stall (181) at position P; its
  // target T is kept"; empty: none (a WAIT POS that can never end says it).
  virtual std::string stop_reason(int motor) const {
    (void)motor;
    return {};
  }
  virtual void stop(int motor) = 0;                                // MST: soft stop
  // RFS START/STOP; STATUS returns 0 when no search is running (finished), non-zero otherwise.
  virtual std::int32_t reference_search(int motor, RfsAction action) = 0;

  virtual void set_switch(int motor, SwitchInput input, bool active) = 0;
  // A switch that belongs to the machine (scenario `switch left 0 at -20000`): `input` is closed
  // while the motor's physical position lies in [lo, hi] (INT64_MIN / INT64_MAX for an open end).
  // The physical position counts microsteps from where the motor stood at power-on: writing the
  // actual position (SAP 1) or a reference search moves the register, not the switch. A core that
  // places switches reports each closing and opening as a SwitchChanged event at its exact
  // instant, treats the input as closed while either this or set_switch says so, and returns
  // true; the default cannot place switches and returns false.
  virtual bool place_switch(int motor, SwitchInput input, std::int64_t lo, std::int64_t hi) {
    (void)motor, (void)input, (void)lo, (void)hi;
    return false;
  }
  virtual void encoder_slip(int motor, std::int32_t counts) = 0;  // encoder loses/gains counts
  // Whether a scenario's `slip` means something for motors of `profile` on this core: the core
  // models an encoder there. A scenario's slip line on a core that does not is a file error
  // (ScenarioOptions::encoder); the default models none.
  virtual bool models_encoder(const Profile& profile) const {
    (void)profile;
    return false;
  }

  // The machine's mechanics (scenario `hardstop` and `load` lines; docs/motion.md, "Loads, stalls
  // and lost steps"), in the physical frame of place_switch: a mechanical end on `side` (StopLeft:
  // the shaft cannot go below `position`; StopRight: above it); from now on a load of `percent` %
  // of the motor's holding torque (100 and above: the motor stalls); a load of `percent` % while
  // the shaft is in [lo, hi]. A core that models them returns true; the default cannot, and the
  // VM ends the run with a fault naming the core and the scenario line.
  virtual bool place_hard_stop(int motor, SwitchInput side, std::int64_t position) {
    (void)motor, (void)side, (void)position;
    return false;
  }
  virtual bool set_load(int motor, int percent) {
    (void)motor, (void)percent;
    return false;
  }
  virtual bool place_load(int motor, std::int64_t lo, std::int64_t hi, int percent) {
    (void)motor, (void)lo, (void)hi, (void)percent;
    return false;
  }

  virtual std::int32_t position(int motor) const = 0;  // actual position (axis parameter 1)
  virtual bool target_reached(int motor) const = 0;    // WAIT POS condition
  virtual bool reference_done(int motor) const = 0;    // WAIT RFS condition

  // The state of `motor` at instant t >= the last advance(), assuming no further input: a core
  // in closed form can look ahead, which lets a recorder sample at any period without waking
  // the VM. The default knows only the position now and reports no motion.
  virtual MotionSample sample_at(int motor, SimTime t) const {
    (void)t;
    return {position(motor), 0.0, 0.0};
  }
  // What GAP of axis parameter `param` would read at instant t (the last advance() <= t <= the
  // next event), where the core can say it without advancing: the plot's optional series
  // (tmclrun --plot-series). The default: nothing (the plot leaves the line out).
  virtual std::optional<std::int32_t> sample_param(int motor, int param, SimTime t) const {
    (void)motor, (void)param, (void)t;
    return std::nullopt;
  }

  // For cores whose parameters are in a chip's units (tmc429): the physical value that the raw
  // value of a velocity or acceleration parameter stands for on `motor` now (parameter 2 for the
  // speeds of ROR/ROL). nullopt for a parameter that is not a rate, and for cores in pps.
  virtual std::optional<PhysicalValue> physical(int motor, int param, std::int32_t raw) const {
    (void)motor, (void)param, (void)raw;
    return std::nullopt;
  }
  // One line saying the units in force ("TMC429 units: ..."), for the title of a plot and the
  // head of a CSV; empty for cores in pps.
  virtual std::string units_note() const { return {}; }

  // A copy of the core with its whole state, for the debugger's checkpoints (reverse execution,
  // cli/debug). nullptr (the default) when the core cannot be copied: the debugger then says
  // that reverse execution needs a core that can.
  virtual std::unique_ptr<MotionCore> clone() const { return nullptr; }
};

// Motion-core registry: --motion NAME. Built-in cores register themselves; an embedder may add
// its own before creating a VM.
using MotionFactory = std::function<std::unique_ptr<MotionCore>()>;
void register_motion_core(std::string name, MotionFactory factory);
// nullptr when no core has that name.
std::unique_ptr<MotionCore> make_motion_core(std::string_view name);
// Registered names, sorted.
std::vector<std::string> motion_core_names();
// The core a module's profile names (`motion NAME`); while that core is not built in (a profile
// may name one a newer tmcl has), its `fallback=` core, else `ideal`, with `note` saying so.
std::unique_ptr<MotionCore> make_profile_motion_core(const Profile& profile, std::string* note = nullptr);

// The built-in cores' factories: make_ideal_motion_core(), make_tmc4361_motion_core(), ... one
// for each line of motion_cores.def, which says what each core is.
#define TMCL_MOTION_CORE(name) std::unique_ptr<MotionCore> make_##name##_motion_core();
#include "tmcl/motion_cores.def"
#undef TMCL_MOTION_CORE

}  // namespace tmcl
