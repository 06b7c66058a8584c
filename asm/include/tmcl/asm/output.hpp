// The output formats of tmclasm (docs/tmclasm.md): TMCL-IDE .bin, datagrams, listing, symbols.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tmcl/asm/assembler.hpp"

namespace tmcl {

enum class OutputFormat { Bin, Datagrams, Listing, Symbols };

// One 9-byte request per instruction, to module `address`, ready to send after command 132.
std::vector<std::uint8_t> format_datagrams(const std::vector<Instruction>& program, std::uint8_t address);
// Address, instruction bytes with checksum, source file:line and the source line.
std::string format_listing(const AsmResult& result, const Profile& profile);
// "kind<TAB>name<TAB>value<TAB>file:line<TAB>scope" per label and constant, then the line table
// (symbols.hpp; docs/tmclasm.md).
std::string format_symbols(const AsmResult& result);
// The link map (--map): each input's address range, library members linked and why, and every
// symbol's final value (docs/tmclasm.md).
std::string format_map(const AsmResult& result);
// The output in the chosen format, as bytes.
std::vector<std::uint8_t> format_output(OutputFormat f, const AsmResult& result, const Profile& profile,
                                        std::uint8_t address);

}  // namespace tmcl
