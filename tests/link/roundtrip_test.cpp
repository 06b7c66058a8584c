// The disassembler's promise on real programs: every .tmc under examples/ and tests/golden/ that
// assembles without error is assembled, disassembled and reassembled, and must give the
// identical bytes with no diagnostic — as a .bin, as datagrams, without the appended STOP, and as
// an object (-c -> -d -> -c, linked alone when it imports nothing).
#include <algorithm>
#include <filesystem>

#include "check.hpp"
#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/disasm.hpp"
#include "tmcl/asm/output.hpp"
#include "tmcl/image.hpp"

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> programs() {
  std::vector<fs::path> out;
  for (const char* dir : {"examples", "tests/golden"})
    for (const auto& e : fs::recursive_directory_iterator(fs::path(TMCL_SOURCE_DIR) / dir))
      if (e.path().extension() == ".tmc") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

std::string str(const std::vector<std::uint8_t>& v) { return std::string(v.begin(), v.end()); }

// Reassembles `source`; the bytes, or empty with the diagnostics printed.
tmcl::AsmResult reassemble(const std::string& source, bool relocatable = false) {
  tmcl::MemoryReader reader;
  reader.files["re.tmc"] = source;
  tmcl::AsmOptions o;
  o.relocatable = relocatable;
  auto r = tmcl::assemble({"re.tmc"}, o, reader);
  if (!r.ok() || r.diags.warning_count() > 0)
    std::fprintf(stderr, "%s---\n%s", source.substr(0, 3000).c_str(), r.diags.render(r.sources).c_str());
  return r;
}

}  // namespace

TEST(every_program_round_trips) {
  int tried = 0, passed = 0;
  for (const auto& path : programs()) {
    for (bool append : {true, false}) {
      tmcl::DiskReader disk;
      tmcl::AsmOptions o;
      o.append_stop = append;
      auto a = tmcl::assemble({path.string()}, o, disk);
      if (!a.ok()) continue;
      ++tried;
      auto image = tmcl::write_bin(a.program);
      auto d = tmcl::disassemble("p.bin", str(image), {});
      CHECK(d.ok());
      auto r = reassemble(d.source);
      // An empty image reassembles with the empty-program warning, and only with it.
      int expected_warnings = a.program.empty() ? 1 : 0;
      bool ok = r.ok() && r.diags.warning_count() == expected_warnings && tmcl::write_bin(r.program) == image;
      // Datagrams to module 7: the same instructions, and the address comes back.
      auto dgm = tmcl::format_datagrams(a.program, 7);
      auto dd = tmcl::disassemble("p.dgm", str(dgm), {});
      auto rd = reassemble(dd.source);
      ok = ok && dd.ok() && (a.program.empty() || dd.source.find("--address 7") != std::string::npos) &&
           tmcl::format_datagrams(rd.program, 7) == dgm;
      if (!ok) std::fprintf(stderr, "round trip failed: %s (append STOP %d)\n", path.string().c_str(), append);
      CHECK(ok);
      passed += ok;
    }
  }
  std::printf("%d of %d assembled programs round-trip\n", passed, tried);
  CHECK(tried >= 60);
}

TEST(every_object_round_trips) {
  int tried = 0;
  for (const auto& path : programs()) {
    tmcl::DiskReader disk;
    tmcl::AsmOptions o;
    o.relocatable = true;
    auto a = tmcl::assemble({path.string()}, o, disk);
    if (!a.ok() || !a.object) continue;
    ++tried;
    auto bytes = tmcl::write_object(*a.object);
    auto d = tmcl::disassemble("p.o", str(bytes), {});
    CHECK(d.ok());
    auto r = reassemble(d.source, true);
    CHECK(r.ok() && r.object);
    if (!r.ok() || !r.object) {
      std::fprintf(stderr, "object round trip failed: %s\n", path.string().c_str());
      continue;
    }
    // The same code, relocations, exports and imports (labels may gain generated names).
    CHECK(r.object->code == a.object->code);
    CHECK_EQ(r.object->relocs.size(), a.object->relocs.size());
    CHECK_EQ(r.object->flags, a.object->flags);
    bool imports = false;
    for (const auto& s : a.object->symbols) imports = imports || s.binding == tmcl::ObjBinding::Import;
    if (imports) continue;
    tmcl::MemoryReader mem;
    mem.files["a.o"] = str(bytes);
    mem.files["b.o"] = str(tmcl::write_object(*r.object));
    auto la = tmcl::assemble({"a.o"}, {}, mem), lb = tmcl::assemble({"b.o"}, {}, mem);
    CHECK(la.ok() == lb.ok());
    CHECK(tmcl::write_bin(la.program) == tmcl::write_bin(lb.program));
  }
  std::printf("%d objects round-trip\n", tried);
  CHECK(tried >= 60);
}

// examples/library/: the library is built from sources, both programs link against it for the
// USB-2-SD without a diagnostic, get only the members they use, and equal the source link.
TEST(library_example_links) {
  fs::path dir = fs::path(TMCL_SOURCE_DIR) / "examples/library";
  tmcl::DiskReader disk;
  tmcl::AsmOptions o;
  auto lib = tmcl::make_library({(dir / "homing.tmc").string(), (dir / "jog.tmc").string(),
                                 (dir / "faults.tmc").string()},
                                o, disk);
  CHECK(lib.ok());
  CHECK_EQ(lib.warnings, 0);
  CHECK_EQ(lib.library.members.size(), std::size_t{3});
  tmcl::MemoryReader mem;
  mem.files["libmotion.a"] = str(tmcl::write_library(lib.library));
  for (const char* prog : {"pickplace.tmc", "scanner.tmc"}) {
    std::string text;
    CHECK(disk.read((dir / prog).string(), text));
    mem.files[prog] = text;
    tmcl::AsmOptions usb;
    usb.profile = tmcl::find_profile("usb-2-sd");
    // Includes of the program come from the bundled files; the reader serves the rest.
    auto linked = tmcl::assemble({prog, "libmotion.a"}, usb, mem);
    CHECK(linked.ok());
    CHECK_EQ(linked.diags.warning_count(), 0);
    if (!linked.ok()) std::fprintf(stderr, "%s", linked.diags.render(linked.sources).c_str());
    auto direct = tmcl::assemble({(dir / prog).string(), (dir / "homing.tmc").string(), (dir / "jog.tmc").string(),
                                  (dir / "faults.tmc").string()},
                                 usb, disk);
    CHECK(direct.ok());
    CHECK(tmcl::write_bin(linked.program) == tmcl::write_bin(direct.program));
  }
}
