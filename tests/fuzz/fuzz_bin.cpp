// Fuzzes the TMCL-IDE .bin reader: any bytes must be read or rejected without a crash; a file
// that reads without issues must be written back byte for byte.
#include <cstdint>
#include <vector>

#include "tmcl/image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> bytes(data, data + size);
  tmcl::ImageReadResult r = tmcl::read_bin(bytes);
  if (r.ok() && r.issues.empty() && tmcl::write_bin(r.program) != bytes) __builtin_trap();
  if (!r.ok() && size % 8 == 0) __builtin_trap();  // only a bad size is an error
  return 0;
}
