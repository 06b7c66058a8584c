// Program images on disk: the TMCL-IDE .bin format (8 bytes per instruction: opcode, type,
// motor/bank, value MSB first, checksum = 8-bit sum of the first 7) and 9-byte datagrams.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "tmcl/codec.hpp"
#include "tmcl/isa.hpp"

namespace tmcl {

// One problem found while reading an image, at a byte offset.
struct ImageIssue {
  std::size_t offset;
  bool error;  // false: warning (a bad record checksum)
  std::string message;
  std::ptrdiff_t instruction = -1;  // the program address a bad checksum belongs to (-1: none)
};

struct ImageReadResult {
  std::vector<Instruction> program;
  std::vector<ImageIssue> issues;
  bool format_datagrams = false;         // read as datagrams (program_image.hpp), else as .bin
  std::vector<std::uint8_t> addresses;   // datagrams: the module address of each instruction
  std::vector<std::size_t> end_markers;  // datagrams: numbers of the opcode-0 end markers left out
  bool ok() const;
};

std::vector<std::uint8_t> write_bin(const std::vector<Instruction>& program);
// Reads a .bin: a size that is not a multiple of 8 is an error; a record whose checksum byte
// does not match is a warning naming the record and both checksums.
ImageReadResult read_bin(const std::vector<std::uint8_t>& bytes);

// A 9-byte TMCL request, as `tmclasm -f datagrams` writes one per instruction (codec.hpp).
inline Frame datagram(std::uint8_t address, const Instruction& ins) { return encode_request(address, ins); }

}  // namespace tmcl
