// The one codec of TMCL's binary forms, beside the instruction table (opcodes.def): 32-bit
// values MSB first, instruction fields by name, the 7 instruction bytes, the 8-bit checksum, and
// the 9-byte frames a host and a module exchange. The assembler, disassembler, object files,
// images, the VM, the virtual module and host tools all encode and decode through these, so a
// byte order or a checksum rule exists once.
//
//   Frame f = encode_request(1, ins);            // host -> module: address, 7 bytes, checksum
//   Request q = decode_request(f.data());         // what a module reads (q.checksum_ok)
//   Frame r = encode_reply({2, 1, 100, op, v});   // module -> host
//   Reply p = decode_reply(r.data());             // what a host reads (p.checksum_ok)
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace tmcl {

// One program instruction (the checksum of the .bin record is not part of it).
struct Instruction {
  std::uint8_t op = 0;
  std::uint8_t type = 0;
  std::uint8_t motor = 0;
  std::int32_t value = 0;
  friend bool operator==(const Instruction&, const Instruction&) = default;
};

// Which instruction field an operand fills (opcodes.def) or a relocation patches (objects).
enum class Field : std::uint8_t { Type, Motor, Value };

// ---- 32-bit values, most significant byte first (.bin records, datagrams, replies) ----
inline std::int32_t decode_be32(const std::uint8_t* p) {
  return static_cast<std::int32_t>(std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 |
                                   std::uint32_t{p[3]});
}
inline void encode_be32(std::int32_t value, std::uint8_t* p) {
  const auto v = static_cast<std::uint32_t>(value);
  p[0] = static_cast<std::uint8_t>(v >> 24);
  p[1] = static_cast<std::uint8_t>(v >> 16);
  p[2] = static_cast<std::uint8_t>(v >> 8);
  p[3] = static_cast<std::uint8_t>(v);
}

// ---- instruction fields by name (operands of opcodes.def, relocations of object files) ----
// The field as an unsigned number: type and motor 0..255, the value's 32 bits.
inline std::uint32_t field_of(const Instruction& ins, Field f) {
  switch (f) {
    case Field::Type: return ins.type;
    case Field::Motor: return ins.motor;
    case Field::Value: return static_cast<std::uint32_t>(ins.value);
  }
  return 0;
}
// The field's name in messages: "type", "motor/bank", "value".
inline const char* field_name(Field f) {
  switch (f) {
    case Field::Type: return "type";
    case Field::Motor: return "motor/bank";
    case Field::Value: return "value";
  }
  return "?";
}
// Stores the low bits of `v` that the field holds (8 for type and motor, 32 for the value).
inline void set_field(Instruction& ins, Field f, std::int64_t v) {
  switch (f) {
    case Field::Type: ins.type = static_cast<std::uint8_t>(v); break;
    case Field::Motor: ins.motor = static_cast<std::uint8_t>(v); break;
    case Field::Value: ins.value = static_cast<std::int32_t>(static_cast<std::uint32_t>(v)); break;
  }
}

// ---- the 7 instruction bytes: op, type, motor/bank, value MSB first ----
inline std::array<std::uint8_t, 7> encode7(const Instruction& ins) {
  std::array<std::uint8_t, 7> b{ins.op, ins.type, ins.motor, 0, 0, 0, 0};
  encode_be32(ins.value, b.data() + 3);
  return b;
}
inline Instruction decode7(const std::uint8_t* p) { return Instruction{p[0], p[1], p[2], decode_be32(p + 3)}; }

// ---- checksums ----
// 8-bit sum of n bytes: a .bin record sums its 7 instruction bytes, a frame its first 8.
inline std::uint8_t sum8(const std::uint8_t* bytes, std::size_t n) {
  std::uint8_t s = 0;
  for (std::size_t i = 0; i < n; ++i) s = static_cast<std::uint8_t>(s + bytes[i]);
  return s;
}
// The .bin record checksum of an instruction.
inline std::uint8_t record_checksum(const Instruction& ins) {
  const auto b = encode7(ins);
  return sum8(b.data(), b.size());
}

// ---- 9-byte frames of the TMCL host protocol ----
using Frame = std::array<std::uint8_t, 9>;
inline constexpr std::size_t kFrameSize = 9;

// Whether byte 8 of a frame is the sum of bytes 0..7.
inline bool frame_checksum_ok(const std::uint8_t* frame) { return sum8(frame, 8) == frame[8]; }

// Host -> module: module address, op, type, motor, value (MSB first), checksum.
struct Request {
  std::uint8_t address = 1;
  Instruction ins;
  bool checksum_ok = true;  // decode only
};
inline Frame encode_request(std::uint8_t address, const Instruction& ins) {
  Frame f{address};
  const auto b = encode7(ins);
  for (std::size_t i = 0; i < b.size(); ++i) f[1 + i] = b[i];
  f[8] = sum8(f.data(), 8);
  return f;
}
inline Request decode_request(const std::uint8_t* frame) {
  return Request{frame[0], decode7(frame + 1), frame_checksum_ok(frame)};
}

// Module -> host: host address, module address, status, op, value (MSB first), checksum.
// Commands 134 and 136 type 0 answer with special frames (docs/virtual-module.md); decode those
// from the bytes.
struct Reply {
  std::uint8_t host = 2;
  std::uint8_t module = 1;
  std::uint8_t status = 100;
  std::uint8_t op = 0;
  std::int32_t value = 0;
  bool checksum_ok = true;  // decode only
};
inline Frame encode_reply(const Reply& r) {
  Frame f{r.host, r.module, r.status, r.op};
  encode_be32(r.value, f.data() + 4);
  f[8] = sum8(f.data(), 8);
  return f;
}
inline Reply decode_reply(const std::uint8_t* frame) {
  return Reply{frame[0], frame[1], frame[2], frame[3], decode_be32(frame + 4), frame_checksum_ok(frame)};
}

// ---- the virtual module's refusal of a second TCP client (docs/virtual-module.md, errata S2) ----
// While a client is connected, tmclrun --serve tcp accepts a second connection, sends this one
// line of ASCII at once, closes its side and discards what the client sends; tmclctl recognises
// it as the first bytes of a connection and says the module is busy. A TMCL host that does not
// know it reads nine bytes of text as a reply with a wrong checksum (no nine bytes of it have a
// right one, checked below), then the end of the connection: a failure, never a reply.
inline constexpr std::string_view kBusyRefusal = "busy: this module is serving another client (one at a time)\n";
inline constexpr std::string_view kBusyPrefix = "busy:";  // how a client tells the refusal from a reply

namespace detail {
constexpr bool refusal_has_no_frame() {
  for (std::size_t i = 0; i + kFrameSize <= kBusyRefusal.size(); ++i) {
    unsigned sum = 0;
    for (std::size_t k = 0; k < 8; ++k) sum += static_cast<unsigned char>(kBusyRefusal[i + k]);
    if ((sum & 0xFF) == static_cast<unsigned char>(kBusyRefusal[i + 8])) return false;
  }
  return true;
}
}  // namespace detail
static_assert(detail::refusal_has_no_frame(), "a TMCL host must never read a frame in the busy refusal");

}  // namespace tmcl
