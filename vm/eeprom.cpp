// The EEPROM file (format in eeprom.hpp): text with a version line and an FNV-1a checksum,
// saved atomically through a temporary file and a rename.
#include "tmcl/eeprom.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <vector>

#include "tmcl/diag_text.hpp"
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
bool parse_eeprom_int(const std::string& s, long long lo, long long hi, long long& out) {
  std::int64_t v = 0;
  if (!s.empty() && s[0] == '+') return false;
  if (!tmcl::parse_int(s, lo, hi, v)) return false;
  out = v;
  return true;
}

// A record's shape: its word count with the keyword, and what each number after it is (the
// last one is the value, any 32-bit integer; the others are 0..`max`).
struct RecordField {
  const char* name;
  long long max;
};
struct RecordKind {
  const char* name;
  std::size_t words;
  const char* shape;
  RecordField fields[5];
};
constexpr RecordField kValue{"value", INT32_MAX};
constexpr RecordKind kRecords[] = {
    {"var", 3, "var INDEX VALUE", {{"variable number", 255}, kValue}},
    {"global", 3, "global PARAM VALUE", {{"parameter number", 255}, kValue}},
    {"global3", 3, "global3 PARAM VALUE", {{"parameter number", 255}, kValue}},
    {"axis", 4, "axis MOTOR PARAM VALUE", {{"motor number", 255}, {"parameter number", 255}, kValue}},
    {"coord", 4, "coord MOTOR N VALUE", {{"motor number", 255}, {"coordinate number", 255}, kValue}},
    {"program", 6, "program ADDRESS OP TYPE MOTOR VALUE",
     {{"address", 65535}, {"opcode", 255}, {"type", 255}, {"motor", 255}, kValue}},
};
const RecordKind* find_record(const std::string& word) {
  for (const auto& k : kRecords)
    if (word == k.name) return &k;
  return nullptr;
}

// The string forms of the readers: every error (up to the default cap) as one text, without the
// final newline.
std::string rendered(const std::vector<FileDiag>& diags) {
  std::string text = render_file_diags(diags, kDefaultErrorLimit);
  if (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

}  // namespace

std::string eeprom_to_text(const EepromImage& image) {
  std::ostringstream os;
  os << "tmcl-eeprom 1\n";
  os << "profile " << (image.profile.empty() ? "generic" : image.profile) << "\n";
  for (const auto& [n, v] : image.vars) os << "var " << n << " " << v << "\n";
  for (const auto& [n, v] : image.globals) os << "global " << n << " " << v << "\n";
  for (const auto& [n, v] : image.bank3) os << "global3 " << n << " " << v << "\n";
  for (const auto& [k, v] : image.axis) os << "axis " << k.first << " " << k.second << " " << v << "\n";
  for (const auto& [k, v] : image.coords) os << "coord " << k.first << " " << k.second << " " << v << "\n";
  for (std::size_t a = 0; a < image.program.size(); ++a) {
    const Instruction& i = image.program[a];
    os << "program " << a << " " << int{i.op} << " " << int{i.type} << " " << int{i.motor} << " " << i.value << "\n";
  }
  std::string body = os.str();
  char check[32];
  std::snprintf(check, sizeof check, "check %08x\n", fnv1a(body));
  return body + check;
}

bool eeprom_from_text(const std::string& text, const std::string& file, EepromImage& image, std::vector<FileDiag>& diags,
                      bool check_checksum) {
  image = EepromImage{};
  const std::size_t errors_before = diags.size();
  std::map<std::string, int> seen;  // "var 3" -> the line that set it, for duplicates
  // Program words by address, with their lines: the program must run from 0 without a gap.
  struct ProgramLine {
    int line;
    std::string source;
  };
  std::map<int, std::pair<Instruction, ProgramLine>> program;
  std::size_t pos = 0;
  int line_no = 0;
  bool checked = false;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    const bool unterminated = end == std::string::npos;
    if (unterminated) end = text.size();
    std::string line = text.substr(pos, end - pos);
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string& source = line;
    std::vector<LineWord> w = split_words(line);
    auto error = [&](int col, int len, const std::string& msg) { diags.push_back({file, line_no, col, len, msg, source}); };
    auto at_word = [&](std::size_t i, const std::string& msg) { error(w[i].col, static_cast<int>(w[i].text.size()), msg); };
    auto at_line = [&](const std::string& msg) { error(1, static_cast<int>(source.size()), msg); };
    // Sealing takes a hand-edited last line without its newline; a run refuses a cut-off file.
    if (unterminated && check_checksum) {
      error(static_cast<int>(source.size()) + 1, 1, "EEPROM file is truncated (no final newline)" + std::string(kSealHint));
      break;
    }
    if (checked && check_checksum) {
      at_line("text after the checksum line");
      break;
    }
    if (line_no == 1) {
      // Not our header: the rest is not worth an error a line.
      if (w.size() != 2 || w[0].text != "tmcl-eeprom") {
        at_line("not a tmclrun EEPROM file (expected 'tmcl-eeprom 1')");
        return false;
      }
      if (w[1].text != "1") {
        at_word(1, "unsupported EEPROM file version " + w[1].text + " (this tmclrun reads version 1)");
        return false;
      }
    } else if (w.empty()) {
      at_line("empty line (every line is a record)");
    } else if (w[0].text == "check") {
      unsigned long expect = 0;
      if (check_checksum) {
        if (w.size() != 2 || w[1].text.size() != 8 || std::sscanf(w[1].text.c_str(), "%8lx", &expect) != 1)
          at_line("malformed checksum line" + std::string(kSealHint));
        else if (fnv1a(std::string_view(text).substr(0, pos)) != expect)
          at_word(1, "EEPROM file is corrupt (checksum mismatch)" + std::string(kSealHint));
      }
      checked = true;
    } else if (w[0].text == "profile") {
      if (w.size() != 2) at_line("malformed EEPROM record '" + source + "' (expected 'profile NAME')");
      else image.profile = w[1].text;
    } else if (const RecordKind* kind = find_record(w[0].text)) {
      // Every word is checked, so one line can carry several errors.
      if (w.size() != kind->words) {
        at_line("malformed EEPROM record '" + source + "' (expected '" + kind->shape + "')");
      } else {
        long long n[5] = {0, 0, 0, 0, 0};
        bool ok = true;
        for (std::size_t i = 1; i < w.size(); ++i) {
          const RecordField& f = kind->fields[i - 1];
          const bool value = i + 1 == w.size();
          if (!parse_eeprom_int(w[i].text, value ? INT32_MIN : 0, f.max, n[i - 1])) {
            at_word(i, "malformed EEPROM record '" + source + "': bad " + f.name + " '" + w[i].text + "' (" +
                           (value ? std::string("a 32-bit integer") : "0.." + std::to_string(f.max)) + ")");
            ok = false;
          }
        }
        if (ok) {
          std::string key = w[0].text + " " + w[1].text + (kind->words == 4 ? " " + w[2].text : std::string());
          if (auto [it, fresh] = seen.emplace(key, line_no); !fresh) {
            at_line("duplicate record: " + key + " is already set on line " + std::to_string(it->second));
          } else if (kind->words == 6) {
            program.emplace(static_cast<int>(n[0]),
                            std::pair{Instruction{static_cast<std::uint8_t>(n[1]), static_cast<std::uint8_t>(n[2]),
                                                  static_cast<std::uint8_t>(n[3]), static_cast<std::int32_t>(n[4])},
                                      ProgramLine{line_no, source}});
          } else if (kind->words == 3) {
            auto& map = w[0].text == "var" ? image.vars : w[0].text == "global" ? image.globals : image.bank3;
            map.emplace(static_cast<int>(n[0]), static_cast<std::int32_t>(n[1]));
          } else {
            auto& map = w[0].text == "axis" ? image.axis : image.coords;
            map.emplace(std::make_pair(static_cast<int>(n[0]), static_cast<int>(n[1])), static_cast<std::int32_t>(n[2]));
          }
        }
      }
    } else {
      // Every record this reader knows, from its one table.
      std::vector<std::string_view> names;
      std::string listed;
      for (const auto& k : kRecords) names.push_back(k.name);
      names.insert(names.end(), {"profile", "check"});
      for (std::string_view n : names) listed += (listed.empty() ? "" : ", ") + std::string(n);
      std::string hint = closest_match(w[0].text, names);
      at_word(0, "malformed EEPROM record '" + source + "': unknown record '" + w[0].text + "' (" + listed + ")" +
                     (hint.empty() ? "" : "; did you mean '" + hint + "'?"));
    }
    pos = end + 1;
  }
  // Program memory is read from address 0 to the first gap on a module: a gap is a broken file.
  int expect_address = 0;
  for (const auto& [address, word] : program) {
    if (address != expect_address) {
      diags.push_back({file, word.second.line, 1, static_cast<int>(word.second.source.size()),
                       "program record for address " + std::to_string(address) + ", but address " +
                           std::to_string(expect_address) + " has none (program memory runs from address 0 without a gap)",
                       word.second.source});
      break;
    }
    image.program.push_back(word.first);
    ++expect_address;
  }
  std::stable_sort(diags.begin() + static_cast<std::ptrdiff_t>(errors_before), diags.end(),
                   [](const FileDiag& a, const FileDiag& b) { return a.line < b.line; });
  if (line_no == 0) {
    diags.push_back({file, 1, 0, 1, "EEPROM file is empty", ""});
  } else if (!checked && check_checksum) {
    diags.push_back({file, line_no, 0, 1, "EEPROM file is truncated (no checksum line)" + std::string(kSealHint), ""});
  }
  return diags.size() == errors_before;
}

bool eeprom_from_text(const std::string& text, const std::string& file, EepromImage& image, std::string& error,
                      bool check_checksum) {
  std::vector<FileDiag> diags;
  if (eeprom_from_text(text, file, image, diags, check_checksum)) return true;
  error = rendered(diags);
  return false;
}

bool load_eeprom_file(const std::string& path, EepromImage& image, bool& existed, std::vector<FileDiag>& diags,
                      std::string& error) {
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
  return eeprom_from_text(std::string(bytes.begin(), bytes.end()), path, image, diags);
}

bool load_eeprom_file(const std::string& path, EepromImage& image, bool& existed, std::string& error) {
  std::vector<FileDiag> diags;
  if (load_eeprom_file(path, image, existed, diags, error)) return true;
  if (!diags.empty()) error = rendered(diags);
  return false;
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

bool seal_eeprom_file(const std::string& path, std::vector<FileDiag>& diags, std::string& error) {
  std::vector<std::uint8_t> bytes;
  std::string why;
  if (!read_file(path, bytes, why, kMaxEepromBytes)) {
    error = path + ": error: cannot read EEPROM file: " + why;
    return false;
  }
  EepromImage image;
  if (!eeprom_from_text(std::string(bytes.begin(), bytes.end()), path, image, diags, false)) return false;
  return save_eeprom_file(path, image, error);
}

bool seal_eeprom_file(const std::string& path, std::string& error) {
  std::vector<FileDiag> diags;
  if (seal_eeprom_file(path, diags, error)) return true;
  if (!diags.empty()) error = rendered(diags);
  return false;
}

}  // namespace tmcl
