// Fuzzes the disassembler's round trip: any sequence of 8-byte records (checksums repaired)
// disassembles to source that assembles back to the identical bytes.
#include <cstdint>
#include <string>
#include <vector>

#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/disasm.hpp"
#include "tmcl/asm/output.hpp"
#include "tmcl/image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<tmcl::Instruction> program;
  for (std::size_t off = 0; off + 7 <= size && program.size() < 4096; off += 7)
    program.push_back({data[off], data[off + 1], data[off + 2],
                       static_cast<std::int32_t>((std::uint32_t{data[off + 3]} << 24) | (std::uint32_t{data[off + 4]} << 16) |
                                                 (std::uint32_t{data[off + 5]} << 8) | data[off + 6])});
  std::vector<std::uint8_t> bin = tmcl::write_bin(program);
  tmcl::DisasmOptions opts;
  opts.kind = tmcl::ImageKind::Bin;
  tmcl::DisasmResult d = tmcl::disassemble("in.bin", std::string(bin.begin(), bin.end()), opts);
  if (!d.ok()) __builtin_trap();
  tmcl::MemoryReader reader;
  reader.files["out.tmc"] = d.source;
  tmcl::AsmResult r = tmcl::assemble({"out.tmc"}, tmcl::AsmOptions{}, reader);
  if (!r.ok() || tmcl::write_bin(r.program) != bin) __builtin_trap();
  return 0;
}
