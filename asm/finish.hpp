// Finishing a program, once for the full pipeline (assembler.cpp) and the fast path
// (fast_path.cpp): the STOP appended unless the program ends with one, jump targets inside the
// program, and the module's program memory. The full pipeline reports what these find; the fast
// path gives up on it, so the full pipeline reports it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "internal.hpp"

namespace tmcl::detail {

// Appends STOP (with no source line) unless the program already ends with one; true when it did.
inline bool append_stop(std::vector<Instruction>& program, std::vector<LineInfo>& lines) {
  if (!program.empty() && program.back().op == static_cast<std::uint8_t>(Op::STOP)) return false;
  program.push_back(Instruction{static_cast<std::uint8_t>(Op::STOP), 0, 0, 0});
  lines.push_back(LineInfo{-1, 0});
  return true;
}

// A jump to `target` leaves a program of `size` instructions (a warning, -Waddress).
inline bool outside_program(std::int64_t target, std::size_t size) {
  return target < 0 || target >= static_cast<std::int64_t>(size);
}
inline std::string outside_program_message(std::int64_t target, std::size_t size) {
  return "address " + std::to_string(target) + " is outside the program (addresses 0 to " +
         std::to_string(size - 1) + ")";
}

// `size` instructions do not fit the module's program memory (an error).
inline bool exceeds_memory(const Profile& profile, std::size_t size) {
  return profile.program_memory > 0 && size > static_cast<std::size_t>(profile.program_memory);
}
inline std::string exceeds_memory_message(const Profile& profile, std::size_t size, bool appended, bool object) {
  return std::string(object ? "the object needs " : "the program needs ") + std::to_string(size) + " instructions" +
         (appended ? " (with the appended STOP)" : "") + " but " + std::string(profile.title) + " has room for " +
         std::to_string(profile.program_memory);
}

}  // namespace tmcl::detail
