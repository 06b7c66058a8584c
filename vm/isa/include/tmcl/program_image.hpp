// Reading a program image for the VM: a TMCL-IDE .bin (8 bytes per instruction) or a datagram
// file as tmclasm -f datagrams writes it (one 9-byte request per instruction).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tmcl/image.hpp"

namespace tmcl {

// Reads 9-byte requests (address, op, type, motor, value MSB first, checksum). A size that is not
// a multiple of 9 is an error; a bad checksum a warning; an opcode-0 end marker ends the program.
ImageReadResult read_datagrams(const std::vector<std::uint8_t>& bytes);

// Picks the reader by file name (.bin / .dgm, any case) and renders its issues as
// "FILE: error: ..." / "FILE: warning: ..." lines into `messages`. False on any error.
bool read_program_image(const std::string& name, const std::vector<std::uint8_t>& bytes, std::vector<Instruction>& program,
                        std::string& messages);

}  // namespace tmcl
