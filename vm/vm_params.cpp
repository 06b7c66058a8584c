// Parameter, coordinate and I/O access with the module profile's rules. Each function returns a
// direct-mode status; standalone mode ignores a command whose status is not 100 (E3). Motion
// parameters the core owns are forwarded to it, everything else lives in the VM. The motion
// commands are in vm_motion.cpp.
#include "tmcl/params.hpp"
#include "tmcl/vm.hpp"

namespace tmcl {
namespace {

std::uint8_t from_core(ParamWrite w) {
  switch (w) {
    case ParamWrite::Ok: return kStatusOk;
    case ParamWrite::ReadOnly: return kStatusWrongType;
    case ParamWrite::OutOfRange: return kStatusInvalidValue;
  }
  return kStatusInvalidValue;
}

// The profile's access rules for a parameter: nullptr when the profile accepts every number
// without access checks (generic), so only a listed parameter of a real module is access-checked.
// Ranges apply under every profile where its tables list the parameter (accepts(), profile.hpp).
const ParamInfo* rules(const Profile& profile, const ParamInfo* p) { return profile.any_parameter ? nullptr : p; }

// Global parameters the VM computes itself, whatever the profile's table says about storage.
bool computed_global(int param) {
  return param == kGpApplicationStatus || param == kGpDownloadMode || param == kGpProgramCounter || param == kGpTickTimer ||
         param == kGpRandomNumber;
}

// Whether global parameter `param` of bank 0 or 3 has an EEPROM copy that STGP and RSGP may
// store or restore: a known parameter marked EEPROM or auto-stored (any, on a generic profile),
// never a computed one. Bank 3 is a bank like 0 here (errata M2: the interrupt settings' E is
// STGP/RSGP); a module without bank 3 has no such bank (invalid value, E3).
std::uint8_t eeprom_global_status(const Profile& profile, int bank, int param) {
  if (bank == 3 && profile.bank3.empty() && !profile.any_parameter) return kStatusInvalidValue;
  const ParamInfo* p = rules(profile, profile.global_param(bank, param));
  if (!p && !profile.any_parameter) return kStatusWrongType;
  if (p && !(p->access & (kEeprom | kAutoStore))) return kStatusWrongType;
  if (bank == 0 && computed_global(param)) return kStatusWrongType;
  return kStatusOk;
}

}  // namespace

const ParamInfo* Vm::range_refusing(bool is_axis, int bank, int param, std::int64_t value) const {
  const ParamInfo* p = is_axis ? profile->axis_param(param) : profile->global_param(bank, param);
  if (p && !accepts(*p, value)) return p;
  if (is_axis && motion->owns(param)) p = motion->range(param);
  return p && !accepts(*p, value) ? p : nullptr;
}

std::uint8_t Vm::set_axis(int motor, int param, std::int32_t value) {
  if (!motor_ok(motor)) return kStatusInvalidValue;
  const ParamInfo* p = rules(*profile, profile->axis_param(param));
  if (!p && !profile->any_parameter) return kStatusWrongType;
  if (p && !(p->access & kWrite)) return kStatusWrongType;
  if (const ParamInfo* r = profile->axis_param(param); r && !accepts(*r, value)) return kStatusInvalidValue;
  if (motion->owns(param)) {
    sync_motion();
    std::uint8_t st = from_core(motion->set_param(motor, param, value));
    next_check_ = 0;
    return st;
  }
  axis[static_cast<std::size_t>(motor)][static_cast<std::size_t>(param)] = value;
  axis_written[static_cast<std::size_t>(motor)][static_cast<std::size_t>(param)] = true;
  return kStatusOk;
}

std::uint8_t Vm::get_axis(int motor, int param, std::int32_t& value) {
  if (!motor_ok(motor)) return kStatusInvalidValue;
  const ParamInfo* p = rules(*profile, profile->axis_param(param));
  if (!p && !profile->any_parameter) return kStatusWrongType;
  if (p && !(p->access & kRead)) return kStatusWrongType;
  value = axis_param(motor, param);
  return kStatusOk;
}

std::int32_t Vm::axis_param(int motor, int param) {
  if (motion->owns(param)) {
    sync_motion();
    return motion->get_param(motor, param);
  }
  return axis[static_cast<std::size_t>(motor)][static_cast<std::size_t>(param)];
}

std::uint8_t Vm::store_axis(int motor, int param) {
  if (!motor_ok(motor)) return kStatusInvalidValue;
  const ParamInfo* p = rules(*profile, profile->axis_param(param));
  if (!p && !profile->any_parameter) return kStatusWrongType;
  if (p && !(p->access & kEeprom) && !profile->any_parameter) return kStatusWrongType;
  eeprom.axis[{motor, param}] = axis_param(motor, param);
  eeprom_dirty = true;
  return kStatusOk;
}

std::uint8_t Vm::restore_axis(int motor, int param) {
  if (!motor_ok(motor)) return kStatusInvalidValue;
  const ParamInfo* p = rules(*profile, profile->axis_param(param));
  if (!p && !profile->any_parameter) return kStatusWrongType;
  if (p && !(p->access & kEeprom) && !profile->any_parameter) return kStatusWrongType;
  auto it = eeprom.axis.find({motor, param});
  const ParamInfo* info = profile->axis_param(param);
  std::int32_t v = it != eeprom.axis.end() ? it->second : (info ? info->default_value : 0);  // E16: factory default
  if (motion->owns(param)) {
    sync_motion();
    (void)motion->set_param(motor, param, v);
    next_check_ = 0;
  } else {
    axis[static_cast<std::size_t>(motor)][static_cast<std::size_t>(param)] = v;
  }
  return kStatusOk;
}

std::int32_t Vm::global_param(int bank, int param) {
  std::int32_t v = 0;
  (void)get_global(bank, param, v);
  return v;
}

std::uint8_t Vm::set_global(int bank, int param, std::int32_t value) {
  if (param < 0 || param > 255) return kStatusWrongType;
  auto idx = static_cast<std::size_t>(param);
  if (bank == 2) {
    vars[idx] = value;
    return kStatusOk;
  }
  if (bank != 0 && bank != 3) return kStatusInvalidValue;
  const ParamInfo* p = rules(*profile, profile->global_param(bank, param));
  if (!p && !profile->any_parameter) return kStatusWrongType;
  if (p && !(p->access & kWrite)) return kStatusWrongType;
  if (const ParamInfo* r = profile->global_param(bank, param); r && !accepts(*r, value)) return kStatusInvalidValue;
  if (bank == 3) {
    set_bank3(param, value);
    if (const ParamInfo* info = profile->global_param(3, param); info && (info->access & kAutoStore)) {
      eeprom.bank3[param] = value;
      eeprom_dirty = true;
    }
    return kStatusOk;
  }
  if (param == kGpApplicationStatus || param == kGpDownloadMode || param == kGpProgramCounter)
    return kStatusWrongType;  // read-only status
  if (param == kGpTickTimer) {
    tick_offset_ms = static_cast<std::int64_t>(static_cast<std::uint32_t>(value)) - now / kUsPerMs;
    return kStatusOk;
  }
  if (param == kGpRandomNumber) {
    random_state = static_cast<std::uint32_t>(value);
    return kStatusOk;
  }
  bank0[idx] = value;
  if (const ParamInfo* info = profile->global_param(0, param); info && (info->access & kAutoStore)) {
    eeprom.globals[param] = value;
    eeprom_dirty = true;
  }
  return kStatusOk;
}

std::uint8_t Vm::get_global(int bank, int param, std::int32_t& value) {
  if (param < 0 || param > 255) return kStatusWrongType;
  auto idx = static_cast<std::size_t>(param);
  if (bank == 2) {
    value = vars[idx];
    return kStatusOk;
  }
  if (bank != 0 && bank != 3) return kStatusInvalidValue;
  const ParamInfo* p = rules(*profile, profile->global_param(bank, param));
  if (!p && !profile->any_parameter && !(bank == 0 && computed_global(param))) return kStatusWrongType;
  if (p && !(p->access & kRead)) return kStatusWrongType;
  if (bank == 3) {
    value = bank3[idx];
    return kStatusOk;
  }
  switch (param) {
    case kGpApplicationStatus: value = static_cast<std::int32_t>(status); break;
    case kGpDownloadMode: value = 0; break;  // download mode: never, for a running program
    case kGpProgramCounter: value = pc; break;
    case kGpTickTimer: value = tick_ms(); break;
    case kGpRandomNumber:
      // E17: xorshift32, 31-bit results; the seed is what SGP 133 wrote (0 becomes 1).
      if (random_state == 0) random_state = 1;
      random_state ^= random_state << 13;
      random_state ^= random_state >> 17;
      random_state ^= random_state << 5;
      value = static_cast<std::int32_t>(random_state & 0x7FFFFFFFu);
      break;
    default: value = bank0[idx]; break;
  }
  return kStatusOk;
}

std::uint8_t Vm::store_global(int bank, int param) {
  if (param < 0 || param > 255) return kStatusWrongType;
  if (bank == 2) {
    if (param >= profile->eeprom_user_vars) return kStatusWrongType;  // not backed on this module
    eeprom.vars[param] = vars[static_cast<std::size_t>(param)];
    eeprom_dirty = true;
    return kStatusOk;
  }
  if (bank != 0 && bank != 3) return kStatusInvalidValue;
  if (std::uint8_t st = eeprom_global_status(*profile, bank, param); st != kStatusOk) return st;
  auto idx = static_cast<std::size_t>(param);
  (bank == 0 ? eeprom.globals : eeprom.bank3)[param] = bank == 0 ? bank0[idx] : bank3[idx];
  eeprom_dirty = true;
  return kStatusOk;
}

std::uint8_t Vm::restore_global(int bank, int param) {
  if (param < 0 || param > 255) return kStatusWrongType;
  if (bank == 2) {
    if (param >= profile->eeprom_user_vars) return kStatusWrongType;
    auto it = eeprom.vars.find(param);
    vars[static_cast<std::size_t>(param)] = it != eeprom.vars.end() ? it->second : 0;
    return kStatusOk;
  }
  if (bank != 0 && bank != 3) return kStatusInvalidValue;
  if (std::uint8_t st = eeprom_global_status(*profile, bank, param); st != kStatusOk) return st;
  const auto& stored = bank == 0 ? eeprom.globals : eeprom.bank3;
  auto it = stored.find(param);
  const ParamInfo* info = profile->global_param(bank, param);
  const std::int32_t v = it != stored.end() ? it->second : (info ? info->default_value : 0);  // E16: factory default
  if (bank == 0)
    bank0[static_cast<std::size_t>(param)] = v;
  else
    set_bank3(param, v);
  return kStatusOk;
}

// Bank 3 as SGP, RSGP and power-up set it: a timer period (0 … 2) restarts its timer.
void Vm::set_bank3(int param, std::int32_t value) {
  bank3[static_cast<std::size_t>(param)] = value;
  if (param < kTimers) set_timer(param, value);
  next_check_ = 0;
}

// ---------------------------------------------------------------- coordinates

std::uint8_t Vm::set_coord(int motor, int n, std::int32_t value) {
  if (n < 0 || n >= profile->coords) return kStatusWrongType;
  if (motor == 255) {  // SCO n, 255: copy RAM -> EEPROM (n = 0: all but coordinate 0)
    for (int m = 0; m < profile->motors; ++m)
      for (int c = (n == 0 ? 1 : n); c <= (n == 0 ? profile->coords - 1 : n); ++c)
        eeprom.coords[{m, c}] = coords[static_cast<std::size_t>(m)][static_cast<std::size_t>(c)];
    eeprom_dirty = true;
    return kStatusOk;
  }
  if (!motor_ok(motor)) return kStatusInvalidValue;
  coords[static_cast<std::size_t>(motor)][static_cast<std::size_t>(n)] = value;
  if (bank0[kGpCoordinatesInEeprom] != 0 && n != 0) {  // coordinates are kept in the EEPROM too
    eeprom.coords[{motor, n}] = value;
    eeprom_dirty = true;
  }
  return kStatusOk;
}

std::uint8_t Vm::get_coord(int motor, int n, std::int32_t& value) {
  if (n < 0 || n >= profile->coords) return kStatusWrongType;
  if (motor == 255) {  // GCO n, 255: copy EEPROM -> RAM
    for (int m = 0; m < profile->motors; ++m)
      for (int c = (n == 0 ? 1 : n); c <= (n == 0 ? profile->coords - 1 : n); ++c) {
        auto it = eeprom.coords.find({m, c});
        coords[static_cast<std::size_t>(m)][static_cast<std::size_t>(c)] = it != eeprom.coords.end() ? it->second : 0;
      }
    value = 0;
    return kStatusOk;
  }
  if (!motor_ok(motor)) return kStatusInvalidValue;
  value = coords[static_cast<std::size_t>(motor)][static_cast<std::size_t>(n)];
  return kStatusOk;
}

std::uint8_t Vm::capture_coord(int motor, int n, std::int32_t& value) {
  if (n < 0 || n >= profile->coords) return kStatusWrongType;
  if (!motor_ok(motor)) return kStatusInvalidValue;
  sync_motion();
  value = motion->position(motor);
  return set_coord(motor, n, value);
}

// ---------------------------------------------------------------- inputs and outputs
// Bank 0: digital inputs, bank 1: analog inputs, bank 2: digital outputs (E18), as the profile's
// ports list them (E53): a port the module lacks is a wrong type (3), a bank other than 0 … 2 an
// invalid value (4). `ports any` (generic) takes every port of banks 0 … 2 (SIO: bank 2 only).

namespace {
// Bit n: digital port n of `bank` (the inputs of bank 0, the outputs of bank 2) that the profile lists.
std::int32_t bit_vector(const Profile& profile, int bank, const std::array<std::int32_t, Vm::kPorts>& states) {
  std::uint32_t v = 0;
  for (const auto& p : profile.ports)
    if (p.bank == bank && p.kind == PortKind::Digital && p.output == (bank == 2) && p.number < 32 && states[p.number] != 0)
      v |= 1u << p.number;
  return static_cast<std::int32_t>(v);
}
}  // namespace

std::uint8_t Vm::set_io(int port, int bank, std::int32_t value) {
  if (bank < 0 || bank > 2) return kStatusInvalidValue;
  auto n = static_cast<std::size_t>(port);
  if (profile->any_port) {
    if (port < 0 || port >= kPorts) return kStatusWrongType;
    if (bank != 2) return kStatusInvalidValue;
    outputs[n] = value != 0;
    return kStatusOk;
  }
  const IoPort* p = profile->write_port(bank, port);
  if (!p) return kStatusWrongType;
  if (p->kind == PortKind::Bits) {  // SIO 255, 2, mask: every output at once
    if (value < p->min || value > p->max) return kStatusInvalidValue;
    for (const auto& o : profile->ports)
      if (o.bank == bank && o.output && o.kind == PortKind::Digital && o.number < 32) outputs[o.number] = (value >> o.number) & 1;
    return kStatusOk;
  }
  if (p->kind == PortKind::Analog && (value < p->min || value > p->max)) return kStatusInvalidValue;
  auto& states = bank == 2 ? outputs : settings;
  states[n] = p->kind == PortKind::Digital && bank == 2 ? value != 0 : value;
  return kStatusOk;
}

std::uint8_t Vm::get_io(int port, int bank, std::int32_t& value) {
  if (bank < 0 || bank > 2) return kStatusInvalidValue;
  auto n = static_cast<std::size_t>(port);
  auto& states = bank == 0 ? inputs : bank == 1 ? analog : outputs;
  if (profile->any_port) {
    if (port < 0 || port >= kPorts) return kStatusWrongType;
    value = states[n];
    return kStatusOk;
  }
  const IoPort* p = profile->read_port(bank, port);
  if (!p) return kStatusWrongType;
  value = p->kind == PortKind::Bits ? bit_vector(*profile, bank, states) : states[n];  // listed: n < kPorts
  return kStatusOk;
}

std::string Vm::ports_text(int bank, bool write) const { return profile->port_numbers(bank, write); }

}  // namespace tmcl
