// Reading and writing TMCL-IDE .bin images and building 9-byte datagrams.
#include "tmcl/image.hpp"

#include "tmcl/fileio.hpp"

#include <cstdio>

namespace tmcl {

bool ImageReadResult::ok() const {
  for (const auto& i : issues)
    if (i.error) return false;
  return true;
}

std::uint8_t sum8(const std::uint8_t* bytes, std::size_t n) {
  std::uint8_t s = 0;
  for (std::size_t i = 0; i < n; ++i) s = static_cast<std::uint8_t>(s + bytes[i]);
  return s;
}

std::vector<std::uint8_t> write_bin(const std::vector<Instruction>& program) {
  std::vector<std::uint8_t> out;
  out.reserve(program.size() * 8);
  prefer_huge_pages(out.data(), out.capacity());
  for (const auto& ins : program) {
    auto b = encode7(ins);
    out.insert(out.end(), b.begin(), b.end());
    out.push_back(sum8(b.data(), b.size()));
  }
  return out;
}

ImageReadResult read_bin(const std::vector<std::uint8_t>& bytes) {
  ImageReadResult r;
  if (bytes.size() % 8 != 0) {
    r.issues.push_back({bytes.size() - bytes.size() % 8, true,
                        "size " + std::to_string(bytes.size()) +
                            " bytes is not a multiple of 8 (a .bin holds 8-byte records); " +
                            std::to_string(bytes.size() % 8) + " trailing bytes"});
    return r;
  }
  r.program.reserve(bytes.size() / 8);
  for (std::size_t off = 0; off < bytes.size(); off += 8) {
    const std::uint8_t* p = bytes.data() + off;
    Instruction ins;
    ins.op = p[0];
    ins.type = p[1];
    ins.motor = p[2];
    ins.value = static_cast<std::int32_t>((std::uint32_t{p[3]} << 24) | (std::uint32_t{p[4]} << 16) |
                                          (std::uint32_t{p[5]} << 8) | std::uint32_t{p[6]});
    std::uint8_t want = sum8(p, 7);
    if (want != p[7]) {
      char msg[128];
      std::snprintf(msg, sizeof msg, "record %zu (address %zu): checksum byte is 0x%02X, expected 0x%02X", off / 8,
                    off / 8, p[7], want);
      r.issues.push_back({off + 7, false, msg});
    }
    r.program.push_back(ins);
  }
  return r;
}

std::array<std::uint8_t, 9> datagram(std::uint8_t address, const Instruction& ins) {
  std::array<std::uint8_t, 9> d{};
  d[0] = address;
  auto b = encode7(ins);
  for (int i = 0; i < 7; ++i) d[1 + i] = b[i];
  d[8] = sum8(d.data(), 8);
  return d;
}

}  // namespace tmcl
