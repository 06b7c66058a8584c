// Fuzzes the object and library readers: any bytes are read or rejected without a crash or a
// read past the end; an object that reads is written back byte for byte, dumped and
// disassembled. The first input byte chooses whether the CRC is repaired first, so that the
// fuzzer also reaches everything behind the integrity check.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "tmcl/asm/disasm.hpp"
#include "tmcl/asm/object.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  bool repair = data[0] & 1;
  std::vector<std::uint8_t> bytes(data + 1, data + size);
  if (repair && bytes.size() >= 4) {
    std::uint32_t crc = tmcl::crc32(bytes.data(), bytes.size() - 4);
    for (int i = 0; i < 4; ++i) bytes[bytes.size() - 4 + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(crc >> (8 * i));
  }
  std::string error;
  tmcl::ObjectFile obj;
  if (tmcl::read_object(bytes.data(), bytes.size(), obj, error)) {
    if (tmcl::write_object(obj) != bytes) __builtin_trap();
    (void)tmcl::dump_object(obj);
    (void)tmcl::disassemble_object(obj, {});
  } else if (error.empty()) {
    __builtin_trap();  // a rejection must say why
  }
  tmcl::Library lib;
  if (tmcl::read_library(bytes.data(), bytes.size(), lib, error)) (void)tmcl::dump_library(lib);
  return 0;
}
