// The debugger's source lookup for images (cli/debug/source.cpp): a symbols file's line table
// gives a .bin's ProgramInfo every address's file and line and the text of the sources found
// beside the symbols file or in a --source-dir folder (with their absolute path, which DAP clients
// send back in setBreakpoints); a missing source is a warning, not a failure.
#include "check.hpp"
#include "os_test.hpp"


#include <filesystem>
#include <fstream>

#include "source.hpp"  // cli/debug, private to the library
#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/output.hpp"

using namespace tmcl;
using namespace tmcl::debug;

namespace {

const char* kSource = "// t.tmc\nstart:  SAP 4, 0, 100\n        CSUB sub\n        STOP\nsub:    GAP 1, 0\n        RSUB\n";

struct TempDir {
  std::filesystem::path path;
  TempDir() {
    path = tmcl_test::make_temp_dir("tmcl-source-test");
  }
  ~TempDir() {
    std::error_code ec;
    if (!path.empty()) std::filesystem::remove_all(path, ec);
  }
  void write(const std::string& name, const std::string& text) const { std::ofstream(path / name) << text; }
};

// Assembles kSource as "t.tmc" and writes its symbols as dir/prog.sym; the program.
std::vector<Instruction> build(const TempDir& dir) {
  MemoryReader reader;
  reader.files["t.tmc"] = kSource;
  AsmOptions opts;
  opts.symbols = true;
  AsmResult r = assemble({"t.tmc"}, opts, reader);
  CHECK(r.ok());
  dir.write("prog.sym", format_symbols(r));
  return r.program;
}

}  // namespace

TEST(sources_beside_the_symbols_file_give_positions_text_and_an_absolute_path) {
  TempDir dir;
  CHECK(!dir.path.empty());
  ProgramInfo info;
  info.program = build(dir);
  dir.write("t.tmc", kSource);
  std::string messages;
  CHECK(apply_symbols((dir.path / "prog.sym").string(), {}, info, messages));
  CHECK_EQ(messages, std::string());
  CHECK_EQ(info.files.size(), std::size_t{1});
  if (info.files.empty()) return;
  CHECK_EQ(info.files[0].name, std::string("t.tmc"));
  CHECK_EQ(info.files[0].path, (dir.path / "t.tmc").lexically_normal().string());
  CHECK_EQ(info.files[0].text.size(), std::size_t{6});
  CHECK_EQ(info.place(1), std::string("t.tmc:3"));
  CHECK_EQ(info.place(3), std::string("t.tmc:5"));
  CHECK_EQ(info.place(5), std::string());  // the appended STOP
  CHECK(info.source_text(4) && *info.source_text(4) == "        RSUB");
  CHECK_EQ(info.labels.size(), std::size_t{2});

  // A DAP client names the file by the absolute path it was given.
  const Profile* profile = find_profile("usb-2-sd");
  Setup s;
  s.profile = profile;
  s.core_name = std::string(profile->default_motion);
  Engine engine(s, info, make_motion_core(s.core_name));
  std::int32_t by_name = -1, by_path = -1;
  std::string err;
  CHECK(engine.resolve("t.tmc:5", by_name, err));
  CHECK(engine.resolve(info.files[0].path + ":5", by_path, err));
  CHECK_EQ(by_name, 3);
  CHECK_EQ(by_path, 3);
}

TEST(a_missing_source_is_a_warning_and_a_source_dir_finds_it) {
  TempDir dir, elsewhere;
  ProgramInfo info;
  info.program = build(dir);
  std::string messages;
  CHECK(apply_symbols((dir.path / "prog.sym").string(), {}, info, messages));
  CHECK(messages.find("warning: source file 't.tmc' not found") != std::string::npos);
  CHECK_EQ(info.place(1), std::string("t.tmc:3"));  // positions without text
  CHECK(info.source_text(1) == nullptr);

  elsewhere.write("t.tmc", kSource);
  ProgramInfo again;
  again.program = info.program;
  messages.clear();
  CHECK(apply_symbols((dir.path / "prog.sym").string(), {elsewhere.path.string()}, again, messages));
  CHECK_EQ(messages, std::string());
  CHECK(again.source_text(1) && *again.source_text(1) == "        CSUB sub");
}

TEST(a_malformed_symbols_file_fails_naming_its_line) {
  TempDir dir;
  dir.write("bad.sym", "# tmclasm symbols 1\n# tmclasm lines 1\n#lines\t0\t1\t0\t1\n");
  ProgramInfo info;
  info.program.resize(2);
  std::string messages;
  CHECK(!apply_symbols((dir.path / "bad.sym").string(), {}, info, messages));
  CHECK(messages.find("bad.sym:3: error: file number 0 has no '#file' record") != std::string::npos);
}
