// Writers for tmclasm's output formats. Text formats are stable: golden tests pin them.
#include "tmcl/asm/output.hpp"

#include <algorithm>
#include <cstdio>

#include "tmcl/asm/disasm.hpp"
#include "tmcl/asm/symbols.hpp"
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
    // A linked object carries no source text: its instructions are shown disassembled.
    if (li.file >= 0 && r.sources.files[static_cast<std::size_t>(li.file)].path.rfind("<object ", 0) == 0)
      out += "  " + format_instruction(ins);
    else if (li.file >= 0)
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
  return out + format_line_table(r);
}

std::string format_map(const AsmResult& r) {
  const Profile& p = r.profile ? *r.profile : generic_profile();
  std::string out = "# tmclasm map 1\n# target " + std::string(p.name) + ", " + std::to_string(r.program.size()) +
                    (r.program.size() == 1 ? " instruction" : " instructions");
  if (p.program_memory > 0) out += " of " + std::to_string(p.program_memory);
  out += "\n\n# inputs\n# first last  size  input\n";
  char buf[64];
  auto range = [&](int first, int count, const std::string& name, const std::string& reason) {
    if (count > 0)
      std::snprintf(buf, sizeof buf, "  %04d  %04d %5d  ", first, first + count - 1, count);
    else
      std::snprintf(buf, sizeof buf, "  %04d  -    %5d  ", first, count);
    out += buf + name + (reason.empty() ? "" : "  (for " + reason + ")") + "\n";
  };
  for (const auto& in : r.inputs) range(in.first, in.count, in.name, in.reason);
  if (r.appended_stop) range(static_cast<int>(r.program.size()) - 1, 1, "(appended STOP)", "");
  if (!r.unused_members.empty()) {
    out += "\n# library members not linked\n";
    for (const auto& m : r.unused_members) out += "  " + m + "\n";
  }
  // Every label, and the constants other units can see; local constants (the dozens an include
  // file defines) are in the symbols format (-f symbols).
  auto shown = [](const Symbol& s) { return s.kind == SymbolKind::Label || s.exported; };
  out += "\n# symbols\n# kind  value        scope   name";
  std::size_t width = 4;
  for (const auto& s : r.symbols)
    if (shown(s)) width = std::max(width, s.name.size());
  out += std::string(width - 4, ' ') + "  defined-at\n";
  for (const auto& s : r.symbols) {
    if (!shown(s)) continue;
    if (s.kind == SymbolKind::Label)
      std::snprintf(buf, sizeof buf, "  label %04lld         ", static_cast<long long>(s.value));
    else
      std::snprintf(buf, sizeof buf, "  const %-12lld ", static_cast<long long>(s.value));
    out += buf;
    out += s.exported ? "export  " : "local   ";
    out += s.name + std::string(width - s.name.size(), ' ') + "  ";
    if (s.defined_at.file >= 0)
      out += r.sources.files[static_cast<std::size_t>(s.defined_at.file)].name + ":" + std::to_string(s.defined_at.line);
    else
      out += "-";
    out += "\n";
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
