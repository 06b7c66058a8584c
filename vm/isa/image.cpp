// Reading and writing TMCL-IDE .bin images (the bytes through codec.hpp).
#include "tmcl/image.hpp"

#include "tmcl/fileio.hpp"

#include <cstdio>

namespace tmcl {

bool ImageReadResult::ok() const {
  for (const auto& i : issues)
    if (i.error) return false;
  return true;
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
    const Instruction ins = decode7(p);
    std::uint8_t want = sum8(p, 7);
    if (want != p[7]) {
      char msg[128];
      std::snprintf(msg, sizeof msg, "record %zu (address %zu): checksum byte is 0x%02X, expected 0x%02X", off / 8,
                    off / 8, p[7], want);
      r.issues.push_back({off + 7, false, msg, static_cast<std::ptrdiff_t>(off / 8)});
    }
    r.program.push_back(ins);
  }
  return r;
}

}  // namespace tmcl
