// Unit tests of objects, linking and the disassembler: symbolic values in objects, relocation,
// library member selection, the object reader under every truncation and every flipped byte,
// and 100,000 random instruction records that must survive disassemble -> reassemble exactly.
#include <random>

#include "check.hpp"
#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/disasm.hpp"
#include "tmcl/asm/object.hpp"
#include "tmcl/image.hpp"

namespace {

struct Env {
  tmcl::MemoryReader reader;
  tmcl::AsmOptions opts;
  // Assembles `name` into an object; empty bytes on error (diagnostics printed).
  std::string object(const std::string& name, const std::string& text) {
    reader.files[name] = text;
    tmcl::AsmOptions o = opts;
    o.relocatable = true;
    auto r = tmcl::assemble({name}, o, reader);
    if (!r.ok() || !r.object) {
      std::fprintf(stderr, "%s", r.diags.render(r.sources).c_str());
      return {};
    }
    auto bytes = tmcl::write_object(*r.object);
    return std::string(bytes.begin(), bytes.end());
  }
  tmcl::AsmResult link(const std::vector<std::string>& files) { return tmcl::assemble(files, opts, reader); }
};

const char* kLib = R"(#export Home, Speed, Entry
Speed = 2000
Entry = Home + 1
Home: SAP 4, 0, Speed
  JA Home
  RSUB
)";
const char* kMain = R"(#import Home, Speed, Entry
Start: CSUB Home
  SAP 4, 0, Speed + 1
  JA Start + 2
  JA Entry
  STOP
)";

std::vector<std::uint8_t> bin(const tmcl::AsmResult& r) { return tmcl::write_bin(r.program); }

}  // namespace

TEST(objects_link_like_sources) {
  Env e;
  e.reader.files["lib.tmc"] = kLib;
  e.reader.files["main.tmc"] = kMain;
  auto from_sources = e.link({"main.tmc", "lib.tmc"});
  CHECK(from_sources.ok());
  e.reader.files["main.o"] = e.object("main.tmc", kMain);
  e.reader.files["lib.o"] = e.object("lib.tmc", kLib);
  auto from_objects = e.link({"main.o", "lib.o"});
  CHECK(from_objects.ok());
  CHECK(bin(from_objects) == bin(from_sources));
  auto mixed = e.link({"main.o", "lib.tmc"});
  CHECK(mixed.ok());
  CHECK(bin(mixed) == bin(from_sources));
  CHECK_EQ(from_objects.program[0].value, 5);  // CSUB Home: main has 5 instructions
  CHECK_EQ(from_objects.program[1].value, 2001);
  CHECK_EQ(from_objects.program[2].value, 2);
  CHECK_EQ(from_objects.program[3].value, 6);  // Entry = Home + 1, exported constant relative to base
}

TEST(symbolic_values_in_objects) {
  Env e;
  auto bytes = e.object("a.tmc", "#import X\nA: JA B - A + X\nB: SAP 4, 0, X + 3 - 1\n");
  tmcl::ObjectFile obj;
  std::string error;
  CHECK(tmcl::read_object(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), obj, error));
  CHECK_EQ(obj.relocs.size(), std::size_t{2});
  CHECK_EQ(obj.relocs[0].addend, 1);  // B - A cancels the base
  CHECK(obj.relocs[0].term == tmcl::ObjTerm::Symbol);
  CHECK_EQ(obj.relocs[1].addend, 2);
  // Not relocatable: reported, naming the operand.
  e.reader.files["bad.tmc"] = "#import X\nL: JA L * 2\nSAP 4, 0, -X\nC = X | 1\nCOMP C\n";
  tmcl::AsmOptions o;
  o.relocatable = true;
  auto r = tmcl::assemble({"bad.tmc"}, o, e.reader);
  CHECK_EQ(r.diags.error_count(), 3);
  std::string text = r.diags.render(r.sources);
  CHECK(text.find("operand 'L * 2' is not relocatable") != std::string::npos);
  CHECK(text.find("constant 'C' is not relocatable") != std::string::npos);
}

TEST(library_members_are_chosen_transitively) {
  Env e;
  tmcl::Library lib;
  auto add = [&](const std::string& name, const std::string& text) {
    std::string b = e.object(name + ".tmc", text);
    tmcl::ObjectFile obj;
    std::string error;
    CHECK(tmcl::read_object(reinterpret_cast<const std::uint8_t*>(b.data()), b.size(), obj, error));
    lib.members.push_back({name + ".o", obj});
  };
  add("a", "#export A\n#import B\nA: CSUB B\nRSUB\n");
  add("unused", "#export U\nU: RSUB\n");
  add("b", "#export B\nB: RSUB\n");
  add("dup", "#export B\nB: STOP\n");  // B is already defined by b.o: never linked
  auto lb = tmcl::write_library(lib);
  e.reader.files["lib.a"] = std::string(lb.begin(), lb.end());
  e.reader.files["main.tmc"] = "#import A\nCSUB A\nSTOP\n";
  auto r = e.link({"main.tmc", "lib.a"});
  CHECK(r.ok());
  CHECK_EQ(r.inputs.size(), std::size_t{3});
  CHECK_EQ(r.inputs[1].name, std::string("lib.a(a.o)"));
  CHECK_EQ(r.inputs[2].name, std::string("lib.a(b.o)"));
  CHECK_EQ(r.unused_members.size(), std::size_t{2});
  CHECK_EQ(r.program.size(), std::size_t{6});  // with the appended STOP
}

// Every truncation and every single flipped byte of an object and a library is rejected (the CRC
// or the size catches it); with the CRC recomputed, the structural checks must reject the file
// or read something that writes back to the same bytes, and linking it must not crash.
TEST(corrupted_objects_are_rejected_never_misread) {
  Env e;
  std::string b = e.object("lib.tmc", std::string(kLib) + "#import Q\nVal = Q + 1\n.raw 9, 0, Q, Home\n");
  CHECK(!b.empty());
  const auto* p = reinterpret_cast<const std::uint8_t*>(b.data());
  tmcl::ObjectFile good, obj;
  std::string error;
  CHECK(tmcl::read_object(p, b.size(), good, error));
  for (std::size_t n = 0; n < b.size(); ++n) CHECK(!tmcl::read_object(p, n, obj, error));
  std::vector<std::uint8_t> copy(b.begin(), b.end());
  int structural_ok = 0;
  for (std::size_t i = 0; i < copy.size(); ++i) {
    for (std::uint8_t mask : {std::uint8_t{0x01}, std::uint8_t{0x80}, std::uint8_t{0xFF}}) {
      copy[i] ^= mask;
      CHECK(!tmcl::read_object(copy.data(), copy.size(), obj, error));
      // The same damage behind a valid CRC.
      std::vector<std::uint8_t> fixed = copy;
      std::uint32_t crc = tmcl::crc32(fixed.data(), fixed.size() - 4);
      for (int k = 0; k < 4; ++k) fixed[fixed.size() - 4 + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(crc >> (8 * k));
      if (tmcl::read_object(fixed.data(), fixed.size(), obj, error)) {
        ++structural_ok;
        CHECK(tmcl::write_object(obj) == fixed);
        e.reader.files["x.o"] = std::string(fixed.begin(), fixed.end());
        auto r = e.link({"x.o"});  // may fail (undefined Q), must not crash
        (void)r;
        tmcl::disassemble("x.o", e.reader.files["x.o"], {});
      }
      copy[i] ^= mask;
    }
  }
  CHECK(structural_ok > 0);  // values and names may change legally; the sweep reached the end
  tmcl::Library lib;
  lib.members.push_back({"lib.o", good});
  auto lb = tmcl::write_library(lib);
  tmcl::Library back;
  CHECK(tmcl::read_library(lb.data(), lb.size(), back, error));
  for (std::size_t n = 0; n < lb.size(); ++n) CHECK(!tmcl::read_library(lb.data(), n, back, error));
  for (std::size_t i = 0; i < lb.size(); ++i) {
    lb[i] ^= 0x10;
    CHECK(!tmcl::read_library(lb.data(), lb.size(), back, error));
    lb[i] ^= 0x10;
  }
}

TEST(object_errors_name_what_is_wrong) {
  Env e;
  std::string b = e.object("a.tmc", "A: JA A\n");
  std::vector<std::uint8_t> v(b.begin(), b.end());
  tmcl::ObjectFile obj;
  std::string error;
  CHECK(!tmcl::read_object(v.data(), v.size() - 1, obj, error));
  CHECK(error.find("truncated") != std::string::npos);
  v[8] = 2;
  CHECK(!tmcl::read_object(v.data(), v.size(), obj, error));
  CHECK(error.find("version 2") != std::string::npos);
  v[8] = 1;
  v[20] ^= 1;
  CHECK(!tmcl::read_object(v.data(), v.size(), obj, error));
  CHECK(error.find("CRC-32") != std::string::npos);
  const std::uint8_t text[] = "SAP 4, 0, 1";
  CHECK(!tmcl::read_object(text, sizeof text, obj, error));
  CHECK(error.find("magic") != std::string::npos);
  CHECK_EQ(tmcl::crc32(reinterpret_cast<const std::uint8_t*>("123456789"), 9), 0xCBF43926u);
}

// Random records: half of them well-formed instructions of the table (so that the mnemonic form,
// keywords and labels are exercised), the rest any 8 bytes. Programs of 1000 records, 100 of them.
TEST(random_records_round_trip) {
  std::mt19937 rng(20240601);
  std::vector<std::uint8_t> known;
  for (const auto& op : tmcl::all_ops()) known.push_back(op.code);
  auto byte = [&] { return static_cast<std::uint8_t>(rng() & 0xFF); };
  int programs = 0;
  for (int p = 0; p < 100; ++p) {
    std::vector<tmcl::Instruction> prog;
    const int n = 1000;
    for (int i = 0; i < n; ++i) {
      tmcl::Instruction ins;
      unsigned kind = rng() % 8;
      if (kind < 4) {
        ins.op = known[rng() % known.size()];
        const tmcl::OpInfo* info = tmcl::op_info(ins.op);
        for (const auto& spec : info->operands) {
          std::uint32_t v = spec.role == tmcl::Role::Address ? static_cast<std::uint32_t>(rng() % (n + 2))
                            : spec.keywords != tmcl::KwSet::None ? static_cast<std::uint32_t>(rng() % 13)
                                                                : static_cast<std::uint32_t>(rng());
          if (spec.field == tmcl::Field::Type) ins.type = static_cast<std::uint8_t>(v);
          if (spec.field == tmcl::Field::Motor) ins.motor = static_cast<std::uint8_t>(v);
          if (spec.field == tmcl::Field::Value) ins.value = static_cast<std::int32_t>(v);
        }
        if (kind == 0) ins.type = byte();  // sometimes a field the mnemonic has no operand for
      } else {
        ins = {byte(), byte(), byte(), static_cast<std::int32_t>(rng())};
      }
      prog.push_back(ins);
    }
    if (p % 2 == 0) prog.back() = tmcl::Instruction{28, 0, 0, 0};  // half end in STOP
    auto image = tmcl::write_bin(prog);
    std::string bytes(image.begin(), image.end());
    tmcl::DisasmResult d = tmcl::disassemble("r.bin", bytes, {});
    CHECK(d.ok());
    tmcl::MemoryReader reader;
    reader.files["r.tmc"] = d.source;
    auto r = tmcl::assemble({"r.tmc"}, tmcl::AsmOptions{}, reader);
    CHECK(r.ok());
    CHECK_EQ(r.diags.warning_count(), 0);
    bool same = tmcl::write_bin(r.program) == image;
    CHECK(same);
    if (!same || !r.ok()) {
      std::fprintf(stderr, "%s", r.diags.render(r.sources).substr(0, 2000).c_str());
      break;
    }
    ++programs;
  }
  CHECK_EQ(programs, 100);
}

TEST(disassembly_of_edge_images) {
  // Empty, no final STOP, bad checksum, bad size, datagrams.
  for (std::string bytes : {std::string(), std::string("\x16\x00\x00\x00\x00\x00\x00\x16", 8)}) {
    auto d = tmcl::disassemble("e.bin", bytes, {});
    CHECK(d.ok());
    CHECK(d.source.find("#no_append_stop") != std::string::npos);
    tmcl::MemoryReader reader;
    reader.files["e.tmc"] = d.source;
    auto r = tmcl::assemble({"e.tmc"}, tmcl::AsmOptions{}, reader);
    CHECK(r.ok());
    CHECK(tmcl::write_bin(r.program) == std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
  }
  std::string bad("\x1C\x00\x00\x00\x00\x00\x00\x00", 8);
  auto d = tmcl::disassemble("b.bin", bad, {});
  CHECK(d.ok());
  CHECK_EQ(d.messages.size(), std::size_t{1});
  tmcl::DisasmOptions werror;
  werror.warnings_are_errors = true;
  CHECK(!tmcl::disassemble("b.bin", bad, werror).ok());
  CHECK(!tmcl::disassemble("b.bin", bad + "x", {}).ok());
  auto dg = tmcl::disassemble("p.dgm", std::string("\x01\x16\x00\x00\x00\x00\x00\x00\x17", 9), {});
  CHECK(dg.ok());
  CHECK(dg.source.find("JA L0000") != std::string::npos);
  CHECK_EQ(tmcl::format_instruction({22, 1, 0, 5}), std::string(".raw 22, 1, 0, 5"));
  CHECK_EQ(tmcl::format_instruction({19, 2, 0, -5}), std::string("CALC MUL, -5"));
}
