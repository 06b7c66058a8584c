// Program images for the VM: .bin through image.hpp, datagram files here.
#include "tmcl/program_image.hpp"

#include <algorithm>
#include <cctype>

namespace tmcl {

ImageReadResult read_datagrams(const std::vector<std::uint8_t>& bytes) {
  ImageReadResult r;
  if (bytes.size() % 9 != 0) {
    r.issues.push_back({bytes.size() - bytes.size() % 9, true,
                        "datagram file size " + std::to_string(bytes.size()) + " is not a multiple of 9"});
    return r;
  }
  for (std::size_t off = 0; off < bytes.size(); off += 9) {
    const std::uint8_t* d = &bytes[off];
    if (d[1] == 0) break;  // end marker
    const Instruction ins = decode7(d + 1);
    std::uint8_t sum = sum8(d, 8);
    if (sum != d[8])
      r.issues.push_back({off, false, "datagram " + std::to_string(off / 9) + ": checksum " + std::to_string(d[8]) +
                                          " does not match " + std::to_string(sum)});
    r.program.push_back(ins);
  }
  return r;
}

bool read_program_image(const std::string& name, const std::vector<std::uint8_t>& bytes, std::vector<Instruction>& program,
                        std::string& messages) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  bool dgm = lower.size() >= 4 && lower.compare(lower.size() - 4, 4, ".dgm") == 0;
  ImageReadResult r = dgm ? read_datagrams(bytes) : read_bin(bytes);
  bool ok = true;
  for (const auto& issue : r.issues) {
    messages += name + ": " + (issue.error ? "error: " : "warning: ") + issue.message + " (byte offset " +
                std::to_string(issue.offset) + ")\n";
    ok = ok && !issue.error;
  }
  program = std::move(r.program);
  return ok;
}

}  // namespace tmcl
