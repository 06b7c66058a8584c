// The bytes of the TMCL host protocol as the server tests write and read them: a request frame,
// the reply a module should send, hex text both ways, a reply's value. No I/O: the protocol
// engine's test (test_protocol.cpp, built for Windows too) and the transports' client share it.
#pragma once

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "tmcl/image.hpp"
#include "tmcl/vm.hpp"

namespace srvtest {

using Bytes = std::vector<std::uint8_t>;
// The operation bytes the tests send most.
inline constexpr std::uint8_t kGgp = static_cast<std::uint8_t>(tmcl::Op::GGP);
inline constexpr std::uint8_t kSgp = static_cast<std::uint8_t>(tmcl::Op::SGP);
inline constexpr std::uint8_t kStgp = static_cast<std::uint8_t>(tmcl::Op::STGP);

inline Bytes frame(std::uint8_t addr, std::uint8_t op, std::uint8_t type, std::uint8_t motor, std::int32_t value) {
  auto d = tmcl::datagram(addr, tmcl::Instruction{op, type, motor, value});
  return Bytes(d.begin(), d.end());
}

inline Bytes reply_bytes(std::uint8_t host, std::uint8_t mod, std::uint8_t status, std::uint8_t op, std::int32_t value) {
  const auto v = static_cast<std::uint32_t>(value);
  Bytes r{host, mod, status, op, static_cast<std::uint8_t>(v >> 24), static_cast<std::uint8_t>(v >> 16),
          static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v), 0};
  r[8] = tmcl::sum8(r.data(), 8);
  return r;
}

inline std::string hex(const Bytes& b) {
  static const char* d = "0123456789ABCDEF";
  std::string s;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (i) s += ' ';
    s += d[b[i] >> 4];
    s += d[b[i] & 15];
  }
  return s;
}

inline Bytes parse_hex(const std::string& text) {
  Bytes b;
  std::istringstream in(text);
  std::string tok;
  while (in >> tok) b.push_back(static_cast<std::uint8_t>(std::stoul(tok, nullptr, 16)));
  return b;
}

inline std::int32_t value_of(const Bytes& r) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(r[4]) << 24 | static_cast<std::uint32_t>(r[5]) << 16 |
                                   static_cast<std::uint32_t>(r[6]) << 8 | r[7]);
}

}  // namespace srvtest
