// Fuzzes the assembler on source text. The input is split into files at lines "#FILE name":
// the first part is main.tmc, each later part an include file served from memory, so that
// include chains, cycles and errors inside includes are reached. Checks: no crash, no hang;
// a successful run has one line record per instruction and renders every output format; and
// the fast path and the full assembler give the same result (or the same diagnostics).
#include <cstdint>
#include <string>

#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/output.hpp"
#include "same_result.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  tmcl::MemoryReader reader;
  std::string name = "main.tmc";
  std::size_t pos = 0;
  while (true) {
    std::size_t next = text.find("\n#FILE ", pos);
    reader.files[name] = text.substr(pos, next == std::string::npos ? std::string::npos : next - pos);
    if (next == std::string::npos) break;
    std::size_t eol = text.find('\n', next + 7);
    name = text.substr(next + 7, eol == std::string::npos ? std::string::npos : eol - next - 7);
    if (eol == std::string::npos) break;
    pos = eol + 1;
  }
  tmcl::AsmOptions opts;
  opts.profile = size % 2 ? tmcl::find_profile("usb-2-sd") : nullptr;
  tmcl::AsmResult r = tmcl::assemble({"main.tmc"}, opts, reader);
  tmcl::AsmOptions full_only = opts;
  full_only.fast_path = false;
  if (!tmcl_test::result_difference(r, tmcl::assemble({"main.tmc"}, full_only, reader)).empty()) __builtin_trap();
  std::string diags = r.diags.render(r.sources);
  if (r.ok()) {
    if (r.lines.size() != r.program.size()) __builtin_trap();
    const tmcl::Profile& p = opts.profile ? *opts.profile : tmcl::generic_profile();
    for (auto f : {tmcl::OutputFormat::Bin, tmcl::OutputFormat::Datagrams, tmcl::OutputFormat::Listing,
                   tmcl::OutputFormat::Symbols})
      (void)tmcl::format_output(f, r, p, 1);
  } else if (diags.empty()) {
    __builtin_trap();  // a failed run must say why
  }
  return 0;
}
