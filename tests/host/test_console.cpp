// The names of a console session (host/console.hpp), without a module: TMCLParam.tmc and the
// module's include file predefined, NAME = VALUE and #include kept, a typed constant given a new
// value, included names kept, and what is not one instruction refused with the assembler's words.
#include "check.hpp"
#include "tmclctl_test.hpp"
#include "tmcl/host/console.hpp"

namespace {

using tmcl::host::ConsoleSession;
using Kind = ConsoleSession::Entry::Kind;

const tmcl::Profile& profile(const char* name) { return *tmcl::find_profile(name); }

TEST(console_predefines_tmclparam_and_the_module_include) {
  CHECK_EQ(ConsoleSession(profile("usb-2-sd"), {}).predefined(),
           (std::vector<std::string>{"TMCLParam.tmc", "Interrupts.inc", "USB-2-SD.inc"}));
  CHECK_EQ(ConsoleSession(profile("tmc2300-eval"), {}).predefined(),
           (std::vector<std::string>{"TMCLParam.tmc", "TMC2300-MOTOR-EVAL.inc"}));
  // A bundled module without an include-file line gets the file generated from its profile, so
  // its own parameter names work (issue 33, 3: AP_SoftStopEnable is 26 on the 1260, not 149).
  CHECK_EQ(ConsoleSession(profile("tmcm-1260"), {}).predefined(),
           (std::vector<std::string>{"TMCLParam.tmc", "Interrupts.inc", "TMCM-1260.inc"}));
  CHECK_EQ(ConsoleSession(profile("tmcm-3110"), {}).predefined(),
           (std::vector<std::string>{"TMCLParam.tmc", "Interrupts.inc", "TMCM-3110.inc"}));
  {
    ConsoleSession pd(profile("pd60-1260"), {});
    auto e = pd.enter("GAP AP_SoftStopEnable, 0");
    CHECK(e.kind == Kind::Send);
    CHECK(e.ins == (tmcl::Instruction{6, 26, 0, 0}));
    e = pd.enter("SGP GP3_Timer0Period, 3, 100");
    CHECK(e.kind == Kind::Send);
    CHECK(e.ins == (tmcl::Instruction{9, 0, 3, 100}));
  }
  // generic has the USB-2-SD's parameter tables, so the USB-2-SD's names.
  CHECK_EQ(tmcl::host::module_include_file(profile("generic")), std::string("USB-2-SD.inc"));
  ConsoleSession s(profile("usb-2-sd"), {});
  auto e = s.enter("SAP APMaxPositioningSpeed, Motor0, 1000");  // TMCLParam.tmc's names
  CHECK(e.kind == Kind::Send);
  CHECK(e.ins == (tmcl::Instruction{5, 4, 0, 1000}));
  CHECK_EQ(e.messages, std::string());
  e = s.enter("GAP AP_ActualPosition, 0");  // USB-2-SD.inc's
  CHECK(e.kind == Kind::Send);
  CHECK(e.ins == (tmcl::Instruction{6, 1, 0, 0}));
}

TEST(console_keeps_constants_and_includes) {
  ConsoleSession s(profile("usb-2-sd"), {hosttest::temp_dir()});
  hosttest::write_temp("moves.inc", "// distances\nFar = 5000\nNear = Far / 2\n");
  auto e = s.enter("Speed = 1000");
  CHECK(e.kind == Kind::Defined);
  CHECK_EQ(e.defined, (std::vector<std::string>{"Speed = 1000"}));
  CHECK_EQ(e.messages, std::string());  // not "the program has no instructions"
  e = s.enter("SAP 4, 0, Speed * 2");
  CHECK(e.kind == Kind::Send);
  CHECK_EQ(e.ins.value, 2000);
  e = s.enter("#include moves.inc");  // found through -I
  CHECK(e.kind == Kind::Defined);
  CHECK_EQ(e.defined, (std::vector<std::string>{"Far = 5000", "Near = 2500"}));
  CHECK_EQ(s.enter("MVP ABS, 0, near").ins.value, 2500);  // names are case-insensitive
  CHECK(s.enter("// only a comment").kind == Kind::Nothing);
  CHECK(s.enter("#include TMCLParam.tmc").kind == Kind::Nothing);  // included once, as in a program
}

// An -I folder that cannot be searched is a warning, as in tmclasm (issue 28, item 9): once, with
// the first line typed, not with every line.
TEST(console_warns_once_of_an_include_folder_that_does_not_exist) {
  ConsoleSession s(profile("usb-2-sd"), {"/nonexistent-tmcl-folder"});
  auto e = s.enter("SAP 4, 0, 1000");
  CHECK(e.kind == Kind::Send);
  CHECK_EQ(e.messages, std::string("tmclasm: warning: include folder '/nonexistent-tmcl-folder' (-I) does not exist\n"));
  e = s.enter("GAP 4, 0");
  CHECK(e.kind == Kind::Send);
  CHECK_EQ(e.messages, std::string());
}

TEST(console_typed_constants_take_new_values_included_ones_do_not) {
  ConsoleSession s(profile("usb-2-sd"), {});
  s.enter("Speed = 1000");
  auto e = s.enter("speed = 2000");
  CHECK(e.kind == Kind::Defined);
  CHECK_EQ(e.defined, (std::vector<std::string>{"speed = 2000 (was 1000)"}));
  CHECK_EQ(s.enter("SAP 4, 0, Speed").ins.value, 2000);
  e = s.enter("APMaxCurrent = 9");
  CHECK(e.kind == Kind::Error);
  CHECK(hosttest::has(e.messages, "<command line>:1:1: error: constant 'APMaxCurrent' redefined with a different value (9; it was 6)"));
  CHECK(hosttest::has(e.messages, "'APMaxCurrent' is 6 for the session, from TMCLParam.tmc (predefined)"));
  CHECK(!hosttest::has(e.messages, "-D"));  // the session's definitions are not shown as -D options
  CHECK_EQ(s.enter("SAP APMaxCurrent, 0, 1").ins.type, 6);
}

TEST(console_refuses_what_is_not_one_instruction) {
  ConsoleSession s(profile("usb-2-sd"), {hosttest::temp_dir()});
  auto e = s.enter("SAP APMaxPositioningSped, 0, 1");
  CHECK(e.kind == Kind::Error);
  CHECK(hosttest::has(e.messages, "<command line>:1:5: error: use of undefined symbol 'APMaxPositioningSped'"));
  CHECK(hosttest::has(e.messages, "did you mean 'APMaxPositioningSpeed'?"));
  e = s.enter("Loop:");
  CHECK(e.kind == Kind::Error);
  CHECK(hosttest::has(e.messages, "label 'Loop' means nothing in direct mode"));
  hosttest::write_temp("sub.inc", "Slow = 10\nROL 0, Slow\nMST 0\n");
  e = s.enter("#include sub.inc");
  CHECK(e.kind == Kind::Error);
  CHECK(hosttest::has(e.messages, "is 2 instructions; one at a time is sent, and nothing was kept"));
  CHECK(s.enter("SAP 4, 0, Slow").kind == Kind::Error);  // nothing was kept
  e = s.enter("#include nothere.inc");
  CHECK(e.kind == Kind::Error);
  CHECK(hosttest::has(e.messages, "cannot find include file 'nothere.inc'"));
}

}  // namespace
