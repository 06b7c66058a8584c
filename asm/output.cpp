// Writers for tmclasm's output formats. Text formats are stable: golden tests pin them.
#include "tmcl/asm/output.hpp"

#include <cstdio>

#include "tmcl/image.hpp"

namespace tmcl {
namespace {

std::string where(const AsmResult& r, const LineInfo& li) {
  if (li.file < 0) return "(appended)";
  return r.sources.files[static_cast<std::size_t>(li.file)].name + ":" + std::to_string(li.line);
}

std::string clean(std::string_view s) {
  std::size_t b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  std::size_t e = s.find_last_not_of(" \t\r");
  std::string out(s.substr(b, e - b + 1));
  for (auto& c : out) {
    auto u = static_cast<unsigned char>(c);
    if (c == '\t') c = ' ';
    else if (u < 0x20 || u >= 0x7f) c = '?';
  }
  return out;
}

}  // namespace

std::vector<std::uint8_t> format_datagrams(const std::vector<Instruction>& program, std::uint8_t address) {
  std::vector<std::uint8_t> out;
  out.reserve(program.size() * 9);
  for (const auto& ins : program) {
    auto d = datagram(address, ins);
    out.insert(out.end(), d.begin(), d.end());
  }
  return out;
}

std::string format_listing(const AsmResult& r, const Profile& profile) {
  std::string out = "; tmclasm listing: " + std::to_string(r.program.size()) + " instructions, target " +
                    std::string(profile.name) + "\n; addr  op ty mo value       ck  source\n";
  char buf[64];
  for (std::size_t i = 0; i < r.program.size(); ++i) {
    const Instruction& ins = r.program[i];
    auto b = encode7(ins);
    std::snprintf(buf, sizeof buf, "  %04zu  %02X %02X %02X %02X %02X %02X %02X  %02X  ", i, b[0], b[1], b[2], b[3], b[4],
                  b[5], b[6], record_checksum(ins));
    out += buf;
    const LineInfo& li = r.lines[i];
    out += where(r, li);
    if (li.file >= 0)
      out += "  " + clean(r.sources.files[static_cast<std::size_t>(li.file)].line(li.line));
    else
      out += "  STOP";
    out += "\n";
  }
  return out;
}

std::string format_symbols(const AsmResult& r) {
  std::string out = "# tmclasm symbols 1\n# kind\tname\tvalue\tdefined-at\tscope\n";
  for (const auto& s : r.symbols) {
    out += s.kind == SymbolKind::Label ? "label\t" : "const\t";
    out += s.name + "\t" + std::to_string(s.value) + "\t";
    if (s.defined_at.file >= 0)
      out += r.sources.files[static_cast<std::size_t>(s.defined_at.file)].name + ":" + std::to_string(s.defined_at.line);
    else
      out += "-";
    out += s.exported ? "\texport\n" : "\tlocal\n";
  }
  return out;
}

std::vector<std::uint8_t> format_output(OutputFormat f, const AsmResult& r, const Profile& profile,
                                        std::uint8_t address) {
  switch (f) {
    case OutputFormat::Bin: return write_bin(r.program);
    case OutputFormat::Datagrams: return format_datagrams(r.program, address);
    case OutputFormat::Listing: {
      std::string s = format_listing(r, profile);
      return {s.begin(), s.end()};
    }
    case OutputFormat::Symbols: {
      std::string s = format_symbols(r);
      return {s.begin(), s.end()};
    }
  }
  return {};
}

}  // namespace tmcl
