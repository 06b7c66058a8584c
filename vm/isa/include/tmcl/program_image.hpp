// The one reader of program images for every tool (tmclasm -d, tmclrun, tmclctl, the debugger):
// a TMCL-IDE .bin (8-byte records) or a datagram file as tmclasm -f datagrams writes it (one
// 9-byte request per instruction). The name says which format is expected; the contents decide
// when most checksums of that format are wrong (docs/tmclrun.md, "Program images").
//
// The rule for opcode 0 (docs/errata.md E40): a datagram file is a
// download stream, read as a module in download mode stores it into empty memory: an opcode-0
// request is the end marker TMCL-IDE and go-tmcl send, it stores nothing (errata S7), and every
// other request is the next instruction. A .bin is program memory word for word: an opcode-0
// record is an instruction word like any other (it faults when executed).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tmcl/image.hpp"

namespace tmcl {

enum class ImageFormat : std::uint8_t { Bin, Datagrams };

// Reads 9-byte requests. A size that is not a multiple of 9 is an error; a bad checksum a
// warning; opcode-0 end markers are left out of the program (ImageReadResult::end_markers).
ImageReadResult read_datagrams(const std::vector<std::uint8_t>& bytes);

// Reads an image expected in `expected` format (from its name or an option). When most record
// checksums of that format are wrong (more than half, of two records or more), the contents
// decide: an image whose every checksum of the other format is right is read as that format,
// with one warning saying so. Otherwise an image whose every checksum is wrong is refused with
// an error saying what it is not and what to try, and one with some right is read as expected,
// a warning for each wrong record.
ImageReadResult read_image(const std::vector<std::uint8_t>& bytes, ImageFormat expected);

// The format a file name asks for: .dgm (any case) datagrams, anything else .bin.
ImageFormat image_format_of(const std::string& name);

// Reads through read_image with the format of the name and renders its issues as
// "FILE: error: ..." / "FILE: warning: ..." lines into `messages`. False on any error.
bool read_program_image(const std::string& name, const std::vector<std::uint8_t>& bytes, std::vector<Instruction>& program,
                        std::string& messages);

// What binary bytes given as source look like, for one error instead of hundreds: "a TMCL-IDE
// .bin image (12 records, every checksum right)", "a datagram file (...)", "binary data (a NUL
// byte at offset 3)", a control byte, or 8 and more bytes of invalid UTF-8 outside comments.
// Empty when `text` may be source (a few stray non-ASCII bytes get the lexer's own errors).
std::string describe_binary(const std::string& text);
// The control bytes that make describe_binary() call a text binary data: below TAB, between CR
// and space (the subtraction wraps the others above 17), DEL. Arithmetic, so that a loop over a
// text vectorizes.
constexpr bool binary_control_byte(unsigned char c) {
  return (c < 9) | (static_cast<unsigned char>(c - 14) < 18) | (c == 127);
}
// Whether `text` holds such a byte anywhere, comments included: one vectorized pass (the
// assembler's fast path, which skips comments unread, asks it before it takes a file).
bool has_binary_control_byte(const std::string& text);

}  // namespace tmcl
