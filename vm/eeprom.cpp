// The EEPROM file (format in eeprom.hpp): text with a version line and an FNV-1a checksum,
// saved atomically through a temporary file and a rename.
#include "tmcl/eeprom.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <vector>

#include "tmcl/fileio.hpp"
#include "tmcl/numbers.hpp"

#include <fcntl.h>
#include <unistd.h>

namespace tmcl {
namespace {

// Said with every checksum complaint: a hand-edited file is mended by re-sealing it.
constexpr const char* kSealHint = "; if you edited it on purpose, run 'tmclrun --eeprom-seal FILE'";

std::uint32_t fnv1a(std::string_view s) {
  std::uint32_t h = 2166136261u;
  for (unsigned char c : s) {
    h ^= c;
    h *= 16777619u;
  }
  return h;
}

// EEPROM numbers are decimal integers in range, read by the one decimal reader, written as
// eeprom_to_text writes them: a minus sign, never a plus.
bool parse_int(const std::string& s, long long lo, long long hi, long long& out) {
  std::int64_t v = 0;
  if (!s.empty() && s[0] == '+') return false;
  if (!tmcl::parse_int(s, lo, hi, v)) return false;
  out = v;
  return true;
}

}  // namespace

std::string eeprom_to_text(const EepromImage& image) {
  std::ostringstream os;
  os << "tmcl-eeprom 1\n";
  os << "profile " << (image.profile.empty() ? "generic" : image.profile) << "\n";
  for (const auto& [n, v] : image.vars) os << "var " << n << " " << v << "\n";
  for (const auto& [n, v] : image.globals) os << "global " << n << " " << v << "\n";
  for (const auto& [k, v] : image.axis) os << "axis " << k.first << " " << k.second << " " << v << "\n";
  for (const auto& [k, v] : image.coords) os << "coord " << k.first << " " << k.second << " " << v << "\n";
  std::string body = os.str();
  char check[32];
  std::snprintf(check, sizeof check, "check %08x\n", fnv1a(body));
  return body + check;
}

bool eeprom_from_text(const std::string& text, const std::string& file, EepromImage& image, std::string& error,
                      bool check_checksum) {
  image = EepromImage{};
  auto fail = [&](int line, const std::string& msg) {
    error = file + ":" + std::to_string(line) + ": error: " + msg;
    return false;
  };
  std::size_t pos = 0;
  int line_no = 0;
  bool checked = false;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) {
      if (check_checksum) return fail(line_no + 1, "EEPROM file is truncated (no final newline)" + std::string(kSealHint));
      end = text.size();  // sealing: a hand-edited last line may lack its newline
    }
    std::string line = text.substr(pos, end - pos);
    ++line_no;
    if (checked && check_checksum) return fail(line_no, "text after the checksum line");
    std::istringstream is(line);
    std::vector<std::string> w;
    for (std::string t; is >> t;) w.push_back(t);
    long long a = 0, b = 0, c = 0;
    if (line_no == 1) {
      if (w.size() != 2 || w[0] != "tmcl-eeprom") return fail(1, "not a tmclrun EEPROM file (expected 'tmcl-eeprom 1')");
      if (w[1] != "1") return fail(1, "unsupported EEPROM file version " + w[1] + " (this tmclrun reads version 1)");
    } else if (!w.empty() && w[0] == "check") {
      unsigned long expect = 0;
      if (check_checksum) {
        if (w.size() != 2 || w[1].size() != 8 || std::sscanf(w[1].c_str(), "%8lx", &expect) != 1)
          return fail(line_no, "malformed checksum line" + std::string(kSealHint));
        if (fnv1a(std::string_view(text).substr(0, pos)) != expect)
          return fail(line_no, "EEPROM file is corrupt (checksum mismatch)" + std::string(kSealHint));
      }
      checked = true;
    } else if (w.size() == 2 && w[0] == "profile") {
      image.profile = w[1];
    } else if (w.size() == 3 && w[0] == "var" && parse_int(w[1], 0, 255, a) && parse_int(w[2], INT32_MIN, INT32_MAX, b)) {
      if (!image.vars.emplace(static_cast<int>(a), static_cast<std::int32_t>(b)).second) return fail(line_no, "duplicate record");
    } else if (w.size() == 3 && w[0] == "global" && parse_int(w[1], 0, 255, a) && parse_int(w[2], INT32_MIN, INT32_MAX, b)) {
      if (!image.globals.emplace(static_cast<int>(a), static_cast<std::int32_t>(b)).second) return fail(line_no, "duplicate record");
    } else if (w.size() == 4 && (w[0] == "axis" || w[0] == "coord") && parse_int(w[1], 0, 255, a) &&
               parse_int(w[2], 0, 255, b) && parse_int(w[3], INT32_MIN, INT32_MAX, c)) {
      auto& map = w[0] == "axis" ? image.axis : image.coords;
      if (!map.emplace(std::make_pair(static_cast<int>(a), static_cast<int>(b)), static_cast<std::int32_t>(c)).second)
        return fail(line_no, "duplicate record");
    } else {
      return fail(line_no, "malformed EEPROM record '" + line + "'");
    }
    pos = end + 1;
  }
  if (line_no == 0) return fail(1, "EEPROM file is empty");
  if (!checked && check_checksum) return fail(line_no, "EEPROM file is truncated (no checksum line)" + std::string(kSealHint));
  return true;
}

bool load_eeprom_file(const std::string& path, EepromImage& image, bool& existed, std::string& error) {
  image = EepromImage{};
  existed = false;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 && errno == ENOENT) return true;  // a new EEPROM: empty
  existed = true;
  std::vector<std::uint8_t> bytes;
  std::string why;
  if (!read_file(path, bytes, why, kMaxEepromBytes)) {
    error = path + ": error: cannot read EEPROM file: " + why;
    return false;
  }
  return eeprom_from_text(std::string(bytes.begin(), bytes.end()), path, image, error);
}

// Through a temporary file, fsync and rename: a killed process or a power cut never leaves a
// half-written EEPROM file.
bool save_eeprom_file(const std::string& path, const EepromImage& image, std::string& error) {
  const std::string text = eeprom_to_text(image);
  std::string why;
  if (!write_file_atomic(path, std::vector<std::uint8_t>(text.begin(), text.end()), why, true)) {
    error = path + ": error: cannot write EEPROM file: " + why;
    return false;
  }
  return true;
}

bool seal_eeprom_file(const std::string& path, std::string& error) {
  std::vector<std::uint8_t> bytes;
  std::string why;
  if (!read_file(path, bytes, why, kMaxEepromBytes)) {
    error = path + ": error: cannot read EEPROM file: " + why;
    return false;
  }
  EepromImage image;
  if (!eeprom_from_text(std::string(bytes.begin(), bytes.end()), path, image, error, false)) return false;
  return save_eeprom_file(path, image, error);
}

}  // namespace tmcl
