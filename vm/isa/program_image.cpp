// The one reader of program images (program_image.hpp): .bin through image.cpp, datagram files
// here, the choice by name and contents, and the description of binary bytes given as source.
#include "tmcl/program_image.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace tmcl {
namespace {

// How many records of `size` bytes there are and how many carry a right checksum (the sum of
// the bytes before it); records == 0 when the length is not a multiple of `size`.
struct ChecksumCount {
  std::size_t records = 0, right = 0;
  bool all_right() const { return records > 0 && right == records; }
  bool all_wrong() const { return records > 0 && right == 0; }
  // More than half wrong, of two records or more (one wrong record of one is damage).
  bool mostly_wrong() const { return records >= 2 && right * 2 < records; }
};
ChecksumCount count_checksums(const std::uint8_t* p, std::size_t n, std::size_t size) {
  ChecksumCount c;
  if (n == 0 || n % size != 0) return c;
  c.records = n / size;
  for (std::size_t off = 0; off < n; off += size)
    if (sum8(p + off, size - 1) == p[off + size - 1]) ++c.right;
  return c;
}

std::string plural(std::size_t n, const char* what) { return std::to_string(n) + " " + what + (n == 1 ? "" : "s"); }

}  // namespace

ImageReadResult read_datagrams(const std::vector<std::uint8_t>& bytes) {
  ImageReadResult r;
  r.format_datagrams = true;
  if (bytes.size() % 9 != 0) {
    r.issues.push_back({bytes.size() - bytes.size() % 9, true,
                        "size " + std::to_string(bytes.size()) + " bytes is not a multiple of 9 (datagrams are 9-byte requests); " +
                            std::to_string(bytes.size() % 9) + " trailing bytes"});
    return r;
  }
  for (std::size_t off = 0; off < bytes.size(); off += 9) {
    const Request q = decode_request(&bytes[off]);
    const std::size_t n = off / 9;
    if (q.ins.op == 0) {  // the end marker: stores nothing, the next request takes its place
      r.end_markers.push_back(n);
      continue;
    }
    if (!q.checksum_ok) {
      char msg[128];
      std::snprintf(msg, sizeof msg, "datagram %zu (address %zu): checksum byte is 0x%02X, expected 0x%02X", n,
                    r.program.size(), bytes[off + 8], sum8(&bytes[off], 8));
      r.issues.push_back({off + 8, false, msg, static_cast<std::ptrdiff_t>(r.program.size())});
    }
    r.addresses.push_back(q.address);
    r.program.push_back(q.ins);
  }
  return r;
}

ImageFormat image_format_of(const std::string& name) {
  std::string lower = name;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return lower.size() >= 4 && lower.compare(lower.size() - 4, 4, ".dgm") == 0 ? ImageFormat::Datagrams : ImageFormat::Bin;
}

ImageReadResult read_image(const std::vector<std::uint8_t>& bytes, ImageFormat expected) {
  const bool dgm = expected == ImageFormat::Datagrams;
  const ChecksumCount mine = count_checksums(bytes.data(), bytes.size(), dgm ? 9 : 8);
  const bool mine_fits = bytes.size() % (dgm ? 9 : 8) == 0;
  // A few wrong checksums are damage, not another format: a warning for each, as always.
  if (mine_fits && !mine.mostly_wrong()) return dgm ? read_datagrams(bytes) : read_bin(bytes);
  // Most checksums of the expected format are wrong (a right one can be chance: one in 256), or
  // the size does not fit it: the contents decide.
  const ChecksumCount other = count_checksums(bytes.data(), bytes.size(), dgm ? 8 : 9);
  const char* mine_name = dgm ? "a datagram file" : "a TMCL-IDE .bin";
  if (other.all_right()) {
    ImageReadResult r = dgm ? read_bin(bytes) : read_datagrams(bytes);
    std::string also;  // how the expected reading fared, when not every checksum was wrong
    if (mine.right > 0)
      also = "; as " + std::string(dgm ? "datagrams" : "a .bin") + ", " + std::to_string(mine.records - mine.right) + " of " +
             std::to_string(mine.records) + " checksums are wrong";
    r.issues.insert(r.issues.begin(),
                    ImageIssue{0, false,
                               std::string("not ") + mine_name + " but " + (dgm ? "a TMCL-IDE .bin" : "datagrams") + " (" +
                                   plural(other.records, dgm ? "record" : "request") + ", every checksum right" + also +
                                   "): read as " + (dgm ? ".bin" : "datagrams")});
    return r;
  }
  if (!mine_fits || !mine.all_wrong()) return dgm ? read_datagrams(bytes) : read_bin(bytes);  // size error, or damage
  ImageReadResult r;
  r.format_datagrams = dgm;
  r.issues.push_back({0, true,
                      std::string("not ") + mine_name + ": every " + (dgm ? "request" : "record") + "'s checksum is wrong (" +
                          std::to_string(mine.records) + " of " + std::to_string(mine.records) + ")" +
                          (dgm ? "; a .bin is named .bin" : "; datagrams are named .dgm") +
                          ", and 'tmclasm -d --from bin|datagrams FILE' shows what the bytes hold"});
  return r;
}

bool read_program_image(const std::string& name, const std::vector<std::uint8_t>& bytes, std::vector<Instruction>& program,
                        std::string& messages) {
  ImageReadResult r = read_image(bytes, image_format_of(name));
  // A marker with requests after it is not where a host puts one: say what it means here.
  if (!r.end_markers.empty() && r.end_markers.front() + r.end_markers.size() < bytes.size() / 9) {
    const std::size_t first = r.end_markers.front();
    r.issues.push_back({first * 9, false,
                        "datagram " + std::to_string(first) +
                            " is an opcode-0 end marker with requests after it; as in download mode it stores nothing, "
                            "and the requests after it continue the program"});
  }
  bool ok = true;
  for (const auto& issue : r.issues) {
    messages += name + ": " + (issue.error ? "error: " : "warning: ") + issue.message + " (byte offset " +
                std::to_string(issue.offset) + ")\n";
    ok = ok && !issue.error;
  }
  program = std::move(r.program);
  return ok;
}

bool has_binary_control_byte(const std::string& text) {
  const auto* p = reinterpret_cast<const unsigned char*>(text.data());
  unsigned char any = 0;
  for (std::size_t i = 0, n = text.size(); i < n; ++i) any |= static_cast<unsigned char>(binary_control_byte(p[i]));
  return any != 0;
}

std::string describe_binary(const std::string& text) {
  const auto* p = reinterpret_cast<const std::uint8_t*>(text.data());
  const std::size_t n = text.size();
  std::size_t nul = n;
  for (std::size_t i = 0; i < n; ++i)
    if (p[i] == 0) {
      nul = i;
      break;
    }
  if (nul < n) {
    const ChecksumCount bin = count_checksums(p, n, 8), dgm = count_checksums(p, n, 9);
    if (bin.all_right()) return "a TMCL-IDE .bin image (" + plural(bin.records, "record") + " of 8 bytes, every checksum right)";
    if (dgm.all_right()) return "a datagram file (" + plural(dgm.records, "request") + " of 9 bytes, every checksum right)";
    return "binary data (a NUL byte at offset " + std::to_string(nul) + ")";
  }
  // A control byte other than white space, or invalid UTF-8 outside comments in many places:
  // source is text. A few stray bytes (a Latin-1 letter) are left to the lexer's own errors,
  // which point at each of them.
  constexpr std::size_t kInvalidUtf8 = 8;
  std::size_t line = 1, invalid = 0, first_line = 0;
  bool comment = false;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t c = p[i];
    if (c == '\n') {
      ++line;
      comment = false;
      continue;
    }
    if (binary_control_byte(c)) {
      char msg[96];
      std::snprintf(msg, sizeof msg, "binary data (a control byte 0x%02X at offset %zu)", c, i);
      return msg;
    }
    if (comment) continue;
    if (c == ';' || (c == '/' && i + 1 < n && p[i + 1] == '/')) {
      comment = true;
      continue;
    }
    if (c < 0x80) continue;
    const std::size_t len = (c & 0xE0) == 0xC0 ? 2 : (c & 0xF0) == 0xE0 ? 3 : (c & 0xF8) == 0xF0 ? 4 : 0;
    bool valid = len != 0 && c >= 0xC2 && c <= 0xF4 && i + len <= n;
    for (std::size_t k = 1; valid && k < len; ++k) valid = (p[i + k] & 0xC0) == 0x80;
    if (valid) {
      i += len - 1;
      continue;
    }
    if (invalid++ == 0) first_line = line;
  }
  if (invalid >= kInvalidUtf8)
    return "binary data (" + std::to_string(invalid) + " bytes of invalid UTF-8 outside comments, the first on line " +
           std::to_string(first_line) + ")";
  return {};
}

}  // namespace tmcl
