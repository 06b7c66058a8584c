// The requests the module target builds (module_target.cpp, module_run.cpp): an opcode's number
// and a control command (128-135) to the module's motor 0. One copy: a unity build puts both
// files in one unit.
#pragma once

#include <cstdint>

#include "tmcl/codec.hpp"
#include "tmcl/isa.hpp"

namespace tmcl::debug::module_cmd {

constexpr std::uint8_t code(Op o) { return static_cast<std::uint8_t>(o); }
inline Instruction ctl(Op o, int type = 0, std::int32_t value = 0) { return {code(o), static_cast<std::uint8_t>(type), 0, value}; }

}  // namespace tmcl::debug::module_cmd
