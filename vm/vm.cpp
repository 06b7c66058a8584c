// The VM's life cycle and its slow path: power-up, program loading, interrupts, timers, external
// inputs, motion events and the choice of the next instant to wake up at. The run loop and the
// instruction semantics are in vm_exec.cpp; parameter access in vm_params.cpp; the motion commands in
// vm_motion.cpp.
#include <algorithm>
#include <bit>

#include "tmcl/interrupts.hpp"
#include "tmcl/params.hpp"
#include "tmcl/vm.hpp"
#include "vm_ops.hpp"

namespace tmcl {

std::string_view halt_name(Halt h) {
  switch (h) {
    case Halt::Stop: return "stop";
    case Halt::Fault: return "fault";
    case Halt::StepLimit: return "max-steps";
    case Halt::TimeLimit: return "max-time";
    case Halt::Blocked: return "blocked";
    case Halt::NotRunning: return "not-running";
    case Halt::Break: return "break";
    case Halt::Interrupted: return "interrupted";
  }
  return "?";
}

Vm::Vm(const Profile& p, MotionCore& core) : profile(&p), motion(&core) {
  load({});
  power_on(nullptr);
}

void Vm::load(const std::vector<Instruction>& prog) {
  program = prog;
  program_size = static_cast<std::int32_t>(prog.size());
  program.push_back(Instruction{});  // sentinel: running past the end faults
  decode_all();
  source_of.clear();
  if (!executed.empty()) count_coverage();  // counting goes on, sized to the new program
}

void Vm::count_coverage() {
  executed.assign(program.size(), 0);
  taken.assign(program.size(), 0);
}

void Vm::decode_all() {
  code_.resize(program.size());
  for (std::size_t i = 0; i + 1 < program.size(); ++i) code_[i] = ops::decode_for_run(program[i], program[i + 1], program_size, *profile);
  code_.back() = Instruction{};
  for (std::size_t i = 0; i < traps.size() && i + 1 < program.size(); ++i)
    if (traps[i]) set_trap(static_cast<std::int32_t>(i), true);
}

void Vm::set_trap(std::int32_t address, bool on) {
  if (address < 0 || address >= program_size) return;
  auto a = static_cast<std::size_t>(address);
  if (traps.size() < program.size()) traps.resize(program.size(), 0);
  traps[a] = on ? 1 : 0;
  const bool next_trapped = a + 1 < traps.size() && traps[a + 1];
  code_[a] = on ? Instruction{} : ops::decode_for_run(program[a], next_trapped ? Instruction{} : program[a + 1], program_size, *profile);
  // A CALC fused with the DJNZ after it would run a trapped DJNZ without stopping: unfuse it.
  if (a > 0 && !traps[a - 1])
    code_[a - 1] = ops::decode_for_run(program[a - 1], on ? Instruction{} : program[a], program_size, *profile);
}

void Vm::power_on(const EepromImage* image) {
  const int motors = profile->motors;
  motion->reset(*profile, motors);
  pc = acc = x = 0;
  flags = errors = 0;
  sp = dsp = 0;
  stack.fill(0);
  data_stack.fill(0);
  status = AppStatus::Stopped;
  wait = WaitState{};
  vars.fill(0);
  bank0.fill(0);
  bank3.fill(0);
  for (const auto& g : profile->bank0) bank0[g.number & 255] = g.default_value;
  for (const auto& g : profile->bank3) bank3[g.number & 255] = g.default_value;
  axis.assign(static_cast<std::size_t>(motors), {});
  axis_written.assign(static_cast<std::size_t>(motors), {});
  for (auto& a : axis) {
    a.fill(0);
    for (const auto& ap : profile->axis_params) a[ap.number & 255] = ap.default_value;
  }
  for (auto& marked : not_simulated_params_) marked.reset();
  for (int t = 0; t < 3; ++t)
    for (const ParamInfo& p : t == 0 ? profile->axis_params : t == 1 ? profile->bank0 : profile->bank3)
      if (!p.not_simulated.empty()) not_simulated_params_[static_cast<std::size_t>(t)].set(p.number & 255);
  coords.assign(static_cast<std::size_t>(motors), std::vector<std::int32_t>(static_cast<std::size_t>(profile->coords), 0));
  inputs.fill(0);
  analog.fill(0);
  outputs.fill(0);
  settings.fill(0);
  for (const auto& port : profile->ports) {  // what an input reads until a scenario sets it (E53)
    if (port.kind == PortKind::Bits) continue;
    auto& bank = port.output ? (port.bank == 2 ? outputs : settings) : (port.bank == 1 ? analog : inputs);
    bank[port.number] = port.default_value;
  }
  switches.assign(static_cast<std::size_t>(motors), MotorSwitches{});
  vectors.fill(-1);
  enabled.fill(0);
  pending.fill(0);
  global_enable = false;
  in_handler = false;
  saved = InterruptContext{};
  timers.fill(Timer{});
  now = 0;
  steps = 0;
  tick_offset_ms = 0;
  random_state = 1;
  halt_pc = -1;
  fault_set_ = false;
  fault_message_.clear();
  warnings.clear();
  warnings_total = 0;
  notes.clear();
  input_next = 0;
  next_check_ = 0;
  unplaceable_.clear();
  for (const auto& p : placed) apply_input(p);

  eeprom = image ? *image : EepromImage{};
  eeprom.profile = std::string(profile->name);
  eeprom_dirty = false;
  if (!image) return;
  // What a module restores at power-up: banks 0 and 3 (a timer period starts its timer), axis
  // parameters, user variables (unless global 85 says not to), coordinates (when global 84 says
  // they live in the EEPROM).
  for (const auto& [param, value] : image->globals)
    if (param >= 0 && param < 256) bank0[static_cast<std::size_t>(param)] = value;
  for (const auto& [param, value] : image->bank3)
    if (param >= 0 && param < 256) set_bank3(param, value);
  for (const auto& [key, value] : image->axis) {
    auto [motor, param] = key;
    if (!motor_ok(motor) || param < 0 || param > 255) continue;
    if (motion->owns(param))
      (void)motion->set_param(motor, param, value);
    else
      axis[static_cast<std::size_t>(motor)][static_cast<std::size_t>(param)] = value;
  }
  if (bank0[kGpDoNotRestoreUserVars] == 0)
    for (const auto& [n, value] : image->vars)
      if (n >= 0 && n < 256) vars[static_cast<std::size_t>(n)] = value;
  if (bank0[kGpCoordinatesInEeprom] != 0)
    for (const auto& [key, value] : image->coords) {
      auto [motor, n] = key;
      if (motor_ok(motor) && n > 0 && n < profile->coords)
        coords[static_cast<std::size_t>(motor)][static_cast<std::size_t>(n)] = value;
    }
}

bool Vm::program_in_eeprom() const { return profile->program_store == ProgramStore::Eeprom; }

void Vm::store_program() {
  if (!program_in_eeprom()) return;
  std::vector<Instruction> words(program.begin(), program.begin() + program_size);
  if (eeprom.program == words) return;
  eeprom.program = std::move(words);
  eeprom_dirty = true;
}

void Vm::start(std::int32_t address) {
  pc = address;
  status = AppStatus::Running;
  halt_pc = -1;
  fault_set_ = false;
  fault_message_.clear();
  next_check_ = 0;
}

RunResult Vm::step() {
  const bool waiting = wait.active;
  start(pc);
  // A one-microsecond window: a WAIT is entered (or checked) but never jumps time ahead. A WAIT
  // in progress is the instruction this step runs: it is checked once and, when over, left, but
  // the instruction after it is the next step's (errata S11).
  Limits lim{waiting ? steps : steps + 1, now + 1};
  lim.to_instruction = waiting;
  RunResult r = run(lim);
  if (status == AppStatus::Running) status = AppStatus::Step;
  return r;
}

void Vm::stop_application() {
  if (status == AppStatus::Running || status == AppStatus::Step) status = AppStatus::Stopped;
}

void Vm::reset_application() {
  reset_interpreter();
  pc = 0;
  halt_pc = -1;
  status = AppStatus::Reset;
}

void Vm::reset_interpreter() {
  acc = x = 0;
  flags = errors = 0;
  sp = dsp = 0;
  wait = WaitState{};
  in_handler = false;
  saved = InterruptContext{};
  pending.fill(0);
  next_check_ = 0;
}

void Vm::add_inputs(std::vector<InputEvent> events) {
  // The lines already applied stay in front, in their order: a power-on replays the queue from
  // its start (a debugger's `run` again after a change by hand). Only those to come are sorted.
  for (auto& e : events) {
    if (!e.placed_kind()) {
      inputs_queue.push_back(e);
      continue;
    }
    placed.push_back(e);
    apply_input(e);
  }
  std::stable_sort(inputs_queue.begin() + static_cast<std::ptrdiff_t>(input_next), inputs_queue.end(),
                   [](const InputEvent& a, const InputEvent& b) { return a.at < b.at; });
  next_check_ = 0;
}

void Vm::apply_due_inputs() {
  sync_motion();
  while (input_next < inputs_queue.size() && inputs_queue[input_next].at <= now) apply_input(inputs_queue[input_next++]);
}

std::string Vm::where(std::int32_t address) const {
  std::string s = "address " + std::to_string(address);
  if (address >= 0 && static_cast<std::size_t>(address) < source_of.size() &&
      !source_of[static_cast<std::size_t>(address)].empty())
    s += " (" + source_of[static_cast<std::size_t>(address)] + ")";
  return s;
}

void Vm::fault(std::string message) {
  if (fault_set_) return;
  fault_set_ = true;
  fault_message_ = std::move(message);
  halt_pc = pc;
  status = AppStatus::Stopped;
  next_check_ = 0;
}

std::string_view warning_kind_name(RuntimeWarning::Kind k) {
  switch (k) {
    case RuntimeWarning::CallStackFull: return "call-stack-full";
    case RuntimeWarning::ReturnWithoutCall: return "return-without-call";
    case RuntimeWarning::RetiOutsideHandler: return "reti-outside-handler";
    case RuntimeWarning::HandlerWithoutReti: return "handler-without-reti";
    case RuntimeWarning::ValueOutOfRange: return "value-out-of-range";
    case RuntimeWarning::RampSetting: return "ramp-setting";
    case RuntimeWarning::NoSuchMotor: return "no-such-motor";
    case RuntimeWarning::NotWritable: return "not-writable";
    case RuntimeWarning::NoSuchPort: return "no-such-port";
    case RuntimeWarning::NoSuchCoordinate: return "no-such-coordinate";
    case RuntimeWarning::NotSimulated: return "not-simulated";
    case RuntimeWarning::NoSuchType: return "no-such-type";
  }
  return "unknown";
}

// Called by the instruction at `pc` (standalone mode only); without --strict it is then ignored
// (or, for STOP in a handler, executed) as the manuals say.
bool Vm::warn(RuntimeWarning::Kind kind, std::string message) {
  if (strict) {
    fault(message + ", at " + where(pc) + " (--strict)");
    return true;
  }
  last_warning = RuntimeWarning{now - instr_time, pc, kind, std::move(message)};
  if (warnings.size() < kMaxWarnings) warnings.push_back(last_warning);
  ++warnings_total;
  return false;
}

bool Vm::note_not_simulated(int n) {
  const std::string why = not_simulated_reason(*profile, motion->name(), n);
  if (why.empty()) return false;
  const std::string once = "interrupt " + std::to_string(n) + " ";
  const InterruptVector* v = profile->vector(n);
  return note_once(once, "interrupt " + std::to_string(n) + (v ? " (" + std::string(v->name) + ")" : std::string()) +
                             " is enabled, but this run never raises it (" + vector_source_text(vector_kind(n)) +
                             " is not simulated: " + why + ")");
}

bool Vm::note_once(std::string_view once, std::string message) {
  for (const auto& nt : notes)
    if (std::string_view(nt.message).substr(0, once.size()) == once) return false;
  if (strict) return warn(RuntimeWarning::NotSimulated, std::move(message));
  RuntimeWarning note{now - instr_time, pc, RuntimeWarning::NotSimulated, std::move(message), true};
  notes.push_back(note);
  last_warning = note;
  return false;
}

bool Vm::note_not_simulated_param(int bank, int number, std::string_view mnemonic, bool read) {
  const int table = bank < 0 ? 0 : bank == 0 ? 1 : bank == 3 ? 2 : -1;
  if (table < 0 || number < 0 || number > 255 || !not_simulated_params_[static_cast<std::size_t>(table)].test(static_cast<std::size_t>(number)))
    return false;
  const ParamInfo* p = bank < 0 ? profile->axis_param(number) : profile->global_param(bank, number);
  if (!p || p->not_simulated.empty()) return false;
  const std::string what = param_text(bank < 0 ? "axis parameter" : "global parameter", number, p) +
                           (bank < 0 ? std::string() : " of bank " + std::to_string(bank));
  return note_once(what + " ",  // once per parameter, whatever the motor
                   what + " is " + (read ? "read" : "written") + " (" + std::string(mnemonic) +
                       "), but this run does not simulate it: " + std::string(p->not_simulated));
}

bool Vm::check_handler_code() {
  if (handler_left_ || sp > saved.stack_depth || pc < 0 || static_cast<std::size_t>(pc) >= handler_code.size() ||
      handler_code[static_cast<std::size_t>(pc)])
    return false;
  handler_left_ = true;
  // Reported as the instruction's own warning: it starts now, and warn() counts from its end.
  now += instr_time;
  bool faulted = warn(RuntimeWarning::HandlerWithoutReti,
                      "the handler of interrupt " + std::to_string(saved.vector) +
                          " goes on outside its code without RETI: interrupts stay blocked until a RETI or RST");
  now -= instr_time;
  return faulted;
}

bool Vm::jump_ok(std::int32_t target) {
  if (target >= 0 && target < program_size) return true;
  fault("jump to address " + std::to_string(target) + " outside the program (0.." +
        std::to_string(program_size - 1) + ") at " + where(pc));
  return false;
}

bool Vm::vector_ok(int n) const {
  if (n < 0 || n > 254) return false;
  if (profile->vectors.empty() || profile->any_parameter) return true;  // generic: every number
  return profile->vector(n) != nullptr;
}

std::int32_t Vm::tick_ms() const {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(now / kUsPerMs + tick_offset_ms));
}

void Vm::raise(int n) {
  if (n < 0 || n > 254 || vectors[static_cast<std::size_t>(n)] < 0 || !is_enabled(n)) return;
  pending[static_cast<std::size_t>(n >> 6)] |= std::uint64_t{1} << (n & 63);
  next_check_ = 0;
}

// Serves the highest-priority (lowest-numbered) pending interrupt if it may be served now.
bool Vm::try_enter_interrupt() {
  if (!global_enable || in_handler || status != AppStatus::Running) return false;
  for (std::size_t w = 0; w < 4; ++w) {
    std::uint64_t ready = pending[w] & enabled[w];
    if (!ready) continue;
    int n = static_cast<int>(w * 64) + std::countr_zero(ready);
    pending[w] &= ~(std::uint64_t{1} << (n & 63));
    saved = InterruptContext{pc, acc, x, flags, wait, sp, n};
    in_handler = true;
    handler_left_ = false;
    wait = WaitState{};
    std::int32_t from = pc;
    pc = vectors[static_cast<std::size_t>(n)];
    if (trace) trace->interrupt_enter(*this, n, from);
    return true;
  }
  return false;
}

void Vm::set_timer(int n, std::int32_t period_ms) {
  Timer& t = timers[static_cast<std::size_t>(n)];
  t.period_ms = static_cast<std::uint32_t>(period_ms);
  t.next = t.period_ms ? now + static_cast<SimTime>(t.period_ms) * kUsPerMs : kNever;
}

void Vm::fire_due_timers() {
  for (int n = 0; n < kTimers; ++n) {
    Timer& t = timers[static_cast<std::size_t>(n)];
    if (t.next > now) continue;
    SimTime period = static_cast<SimTime>(t.period_ms) * kUsPerMs;
    t.next += ((now - t.next) / period + 1) * period;  // missed periods merge into one interrupt
    raise(n);
  }
}

void Vm::handle_motion_event(const MotionEvent& ev) {
  if (trace) trace->motion_event(*this, ev);
  if (on_motion_event) on_motion_event(*this, ev);
  switch (ev.kind) {
    case MotionEventKind::TargetReached: raise(kVectorTarget0 + ev.motor); break;
    case MotionEventKind::Deviation:
      errors |= kErrDeviation;
      raise(kVectorDeviation0 + ev.motor);
      break;
    case MotionEventKind::SwitchChanged: switch_source(ev.motor, ev.input, false, ev.active); break;
    case MotionEventKind::Stall: raise(15 + ev.motor); break;
    case MotionEventKind::StepsLost:
      if (ev.value == kStepsLostStallUnseen) {  // the program relies on a stall the module cannot see (E78)
        const std::string m = "motor " + std::to_string(ev.motor);
        (void)note_once(m + " ", m + " met a hard stop or a load with stop on stall (181) on, but in StealthChop (187 > 0, below "
                                     "186) stallGuard2 measures nothing: no stall stops it, steps are lost (errata E78)");
      }
      break;
    default: break;
  }
}

void Vm::sync_motion() {
  event_buf_.clear();
  motion->advance(now, event_buf_);
  for (const auto& ev : event_buf_) handle_motion_event(ev);
}

namespace {
// Bank-3 transition setting: 1 low->high, 2 high->low, 3 both.
bool transition_fires(std::int32_t setting, bool before, bool after) {
  if (before == after) return false;
  return after ? (setting & 1) != 0 : (setting & 2) != 0;
}
}  // namespace

void Vm::apply_input(const InputEvent& ev) {
  auto idx = static_cast<std::size_t>(ev.index);
  std::string what;
  switch (ev.kind) {
    case InputEvent::Digital: {
      if (idx >= inputs.size()) return;
      const bool before = inputs[idx] != 0, after = ev.value != 0;
      inputs[idx] = after;
      what = "input " + std::to_string(ev.index) + " = " + std::to_string(after);
      if (trace) trace->input_event(*this, what);
      // Input change n: vector 39+n on the edges bank-3 parameter 39+n selects (E52).
      const int n = kVectorInput0 + ev.index;
      if (n < kVectorGlobal && transition_fires(bank3[static_cast<std::size_t>(n)], before, after)) raise(n);
      return;
    }
    case InputEvent::Analog:
      if (idx < analog.size()) analog[idx] = ev.value;
      what = "analog " + std::to_string(ev.index) + " = " + std::to_string(ev.value);
      break;
    case InputEvent::StopLeft:
    case InputEvent::StopRight:
    case InputEvent::Home: {
      if (!motor_ok(ev.index)) return;
      bool level = ev.value != 0;
      sync_motion();  // the core must be at `now` before it hears of the switch
      auto input = ev.kind == InputEvent::StopLeft    ? SwitchInput::StopLeft
                   : ev.kind == InputEvent::StopRight ? SwitchInput::StopRight
                                                      : SwitchInput::Home;
      motion->set_switch(ev.index, input, level);
      what = std::string(switch_input_name(input)) + " " + std::to_string(ev.index) + " = " + std::to_string(level);
      if (trace) trace->input_event(*this, what);
      switch_source(ev.index, input, true, level);
      return;
    }
    case InputEvent::Placed:
      if (!motor_ok(ev.index)) return;
      sync_motion();
      if (!motion->place_switch(ev.index, ev.input, ev.from, ev.to) && unplaceable_.empty())
        unplaceable_ = "the motion core '" + std::string(motion->name()) + "' cannot place switches at positions" +
                       (ev.line > 0 ? " (scenario line " + std::to_string(ev.line) + ")" : std::string());
      return;
    case InputEvent::HardStop:
    case InputEvent::LoadZone: {
      if (!motor_ok(ev.index)) return;
      sync_motion();
      const bool hard = ev.kind == InputEvent::HardStop;
      const bool ok = hard ? motion->place_hard_stop(ev.index, ev.input, ev.from)
                           : motion->place_load(ev.index, ev.from, ev.to, ev.value);
      if (!ok && unplaceable_.empty())
        unplaceable_ = "the motion core '" + std::string(motion->name()) + "' cannot model " +
                       (hard ? "hard stops" : "loads") +
                       (ev.line > 0 ? " (scenario line " + std::to_string(ev.line) + ")" : std::string());
      return;
    }
    case InputEvent::Load:
      if (!motor_ok(ev.index)) return;
      sync_motion();
      if (!motion->set_load(ev.index, ev.value)) {
        fault("the motion core '" + std::string(motion->name()) + "' cannot model loads" +
              (ev.line > 0 ? " (scenario line " + std::to_string(ev.line) + ")" : std::string()));
        return;
      }
      what = "load " + std::to_string(ev.index) + " = " + std::to_string(ev.value) + "%";
      break;
    case InputEvent::Slip:
      if (!motor_ok(ev.index)) return;
      sync_motion();
      if (!motion->models_encoder(*profile)) {  // a scenario not checked against this core: never silently
        fault("the motion core '" + std::string(motion->name()) + "' models no encoder on " + std::string(profile->name) +
              " to slip" + (ev.line > 0 ? " (scenario line " + std::to_string(ev.line) + ")" : std::string()));
        return;
      }
      motion->encoder_slip(ev.index, ev.value);
      what = "slip " + std::to_string(ev.index) + " = " + std::to_string(ev.value);
      break;
  }
  if (trace) trace->input_event(*this, what);
}

void Vm::switch_source(int motor, SwitchInput input, bool timed, bool level) {
  if (!motor_ok(motor)) return;
  MotorSwitches& s = switches[static_cast<std::size_t>(motor)];
  const auto bit = static_cast<std::uint8_t>(1u << static_cast<unsigned>(input));
  std::uint8_t& source = timed ? s.timed : s.placed;
  source = static_cast<std::uint8_t>(level ? source | bit : source & ~bit);
  bool* sw = input == SwitchInput::StopLeft ? &s.left : input == SwitchInput::StopRight ? &s.right : &s.home;
  bool before = *sw;
  *sw = ((s.timed | s.placed) & bit) != 0;
  if (input == SwitchInput::Home) return;
  int n = kVectorStopLeft0 + (input == SwitchInput::StopLeft ? 0 : 1) + 2 * motor;
  if (n < 255 && transition_fires(bank3[static_cast<std::size_t>(n)], before, *sw)) raise(n);
}

int Vm::wait_check() {
  int m = wait.motor;
  bool done = false;
  switch (wait.kind) {
    case kw::Wait::TICKS: return now >= wait.deadline ? 1 : 0;
    case kw::Wait::POS: done = motion->target_reached(m); break;
    case kw::Wait::REFSW: done = switches[static_cast<std::size_t>(m)].home; break;
    case kw::Wait::LIMSW: done = switches[static_cast<std::size_t>(m)].left || switches[static_cast<std::size_t>(m)].right; break;
    case kw::Wait::RFS: done = motion->reference_done(m); break;
    default: done = true; break;
  }
  if (done) return 1;
  if (now >= wait.deadline) {
    errors |= kErrTimeout;
    return 2;
  }
  return 0;
}

SimTime Vm::next_wakeup() const {
  SimTime t = motion->next_event();
  if (wait.active) t = std::min(t, wait.deadline);
  if (input_next < inputs_queue.size()) t = std::min(t, inputs_queue[input_next].at);
  // A timer only matters while its interrupt can be latched.
  for (int n = 0; n < kTimers; ++n)
    if (vectors[static_cast<std::size_t>(n)] >= 0 && is_enabled(n)) t = std::min(t, timers[static_cast<std::size_t>(n)].next);
  return t;
}

// The shared parts move out while the rest is copied, so a checkpoint costs the state, not the
// program.
namespace {
struct SharedParts {
  std::vector<Instruction> program;
  std::vector<std::string> source_of;
  std::vector<std::uint8_t> traps;
  std::vector<InputEvent> inputs_queue;
};
}  // namespace

Vm Vm::checkpoint() {
  SharedParts keep{std::move(program), std::move(source_of), std::move(traps), std::move(inputs_queue)};
  std::vector<Instruction> code = std::move(code_);
  Vm copy(*this);
  program = std::move(keep.program);
  source_of = std::move(keep.source_of);
  traps = std::move(keep.traps);
  inputs_queue = std::move(keep.inputs_queue);
  code_ = std::move(code);
  return copy;
}

void Vm::restore(const Vm& cp) {
  SharedParts keep{std::move(program), std::move(source_of), std::move(traps), std::move(inputs_queue)};
  std::vector<Instruction> code = std::move(code_);
  MotionCore* core = motion;
  TraceSink* sink = trace;
  auto hook = std::move(on_motion_event);
  *this = cp;
  program = std::move(keep.program);
  source_of = std::move(keep.source_of);
  traps = std::move(keep.traps);
  inputs_queue = std::move(keep.inputs_queue);
  code_ = std::move(code);
  motion = core;
  trace = sink;
  on_motion_event = std::move(hook);
  trap_hit = false;
}

}  // namespace tmcl
