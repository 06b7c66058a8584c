// Durations, scenarios, instruction text, trace and JSON shape, the generic profile.
#include <cstdio>

#include "check.hpp"
#include "os_test.hpp"
#include "machine.hpp"
#include "tmcl/duration.hpp"
#include "tmcl/scenario.hpp"
#include "tmcl/vm_output.hpp"

using namespace vmtest;
using tmcl::Op;

TEST(durations) {
  CHECK_EQ(tmcl::parse_duration("50us").value_or(-1), 50);
  CHECK_EQ(tmcl::parse_duration("10ms").value_or(-1), 10'000);
  CHECK_EQ(tmcl::parse_duration("2s").value_or(-1), 2'000'000);
  CHECK_EQ(tmcl::parse_duration("1min").value_or(-1), 60'000'000);
  CHECK_EQ(tmcl::parse_duration("0").value_or(-1), 0);
  CHECK(!tmcl::parse_duration("10"));
  CHECK(!tmcl::parse_duration("ms"));
  CHECK(!tmcl::parse_duration("-1s"));
  CHECK(!tmcl::parse_duration("1.5us"));
  CHECK(!tmcl::parse_duration("1y"));
  CHECK(!tmcl::parse_duration("99999999999999999999min"));
  CHECK_EQ(tmcl::format_time(12'000'020), std::string("12.000020s"));
}

TEST(scenario_parsing) {
  std::vector<tmcl::InputEvent> ev;
  std::string err;
  CHECK(tmcl::parse_scenario("# c\n\nat 10ms input 0 = 1\nat 1s analog 2 = -512 # x\nat 2s left 0 = 1\n", "s.txt", ev, err));
  CHECK_EQ(ev.size(), 3u);
  CHECK_EQ(ev[1].at, 1'000'000);
  CHECK_EQ(ev[1].value, -512);
  CHECK_EQ(ev[2].line, 5);
  const char* bad[] = {"at 1s bogus 0 = 1", "at 1x input 0 = 1", "at 1s input 9 = 1", "at 1s input 0 1",
                       "when 1s input 0 = 1", "at 1s input 0 = 99999999999"};
  for (const char* b : bad) {
    ev.clear();
    CHECK(!tmcl::parse_scenario(std::string("\n") + b + "\n", "s.txt", ev, err));
    CHECK(err.rfind("s.txt:2:", 0) == 0);
  }
}

TEST(instruction_text) {
  CHECK_EQ(tmcl::instruction_text(I(Op::MVP, 0, 0, 51200)), std::string("MVP ABS, 0, 51200"));
  CHECK_EQ(tmcl::instruction_text(I(Op::WAIT, 1, 0, 0)), std::string("WAIT POS, 0, 0"));
  CHECK_EQ(tmcl::instruction_text(I(Op::CALCX, 10)), std::string("CALCX SWAP"));
  CHECK_EQ(tmcl::instruction_text(I(Op::RSUB)), std::string("RSUB"));
  CHECK_EQ(tmcl::instruction_text(I(Op::JC, 5, 0, 10)), std::string("JC GE, 10"));
  CHECK_EQ(tmcl::instruction_text(Instruction{99, 1, 2, 3}), std::string("?? 99, 1, 2, 3"));
}

TEST(json_has_every_documented_key) {
  Machine m({I(Op::SGP, 0, 2, 5), I(Op::STOP)});
  auto r = m.run();
  std::string j = tmcl::state_json(m.vm, r);
  for (const char* k : {"\"halt\":\"stop\"", "\"message\":", "\"profile\":", "\"motion\":\"ideal\"", "\"time_us\":", "\"time_ms\":",
                        "\"steps\":2", "\"pc\":1", "\"acc\":", "\"x\":", "\"flags\":", "\"errors\":", "\"stack\":",
                        "\"vars\":[5,", "\"axis\":[{", "\"coords\":[[", "\"inputs\":", "\"analog\":", "\"outputs\":",
                        "\"globals\":", "\"interrupts\":"})
    CHECK(j.find(k) != std::string::npos);
}

TEST(trace_lines) {
  tmcl_test::CapturedFile f;
  tmcl::SourceMap src = {"p.tmc:1", "p.tmc:2"};
  tmcl::TextTrace t(f.get(), &src);
  Machine m({I(Op::MVP, 0, 0, 10), I(Op::STOP)}, test_profile(), 20);
  m.vm.trace = &t;
  m.run();
  const std::string out = f.text();
  CHECK(out.find("0.000000s     0 p.tmc:1          MVP ABS, 0, 10") != std::string::npos);
  CHECK(out.find("motion: motor 0 target reached at position 10") != std::string::npos);
  CHECK(out.find("0.000020s     1 p.tmc:2          STOP") != std::string::npos);
}

TEST(generic_profile_runs) {
  Machine m({I(Op::SAP, 200, 0, 5), I(Op::GAP, 200, 0), I(Op::STOP)}, tmcl::generic_profile());
  m.run();
  CHECK_EQ(m.vm.acc, 5);
}

// SAC (SPI bus access, TMCM-351): no SPI device is attached to the virtual module, so the bus
// reads back 0 into the accumulator; a chip select or byte count the manual does not list is
// refused (status 3, 4 in direct mode). A module without SAC refuses it (status 6).
TEST(sac_reads_zero_from_the_bus) {
  Machine m({I(Op::CALC, 0, 0, 0), I(Op::CALC, 1, 0, 5), I(Op::SAC, 0, 2, 0x1234), I(Op::STOP)},
            *tmcl::find_profile("tmcm-351"));
  m.run();
  CHECK_EQ(m.vm.acc, 0);
  auto r = m.vm.execute_direct(I(Op::SAC, 128 + 3, 4, 0));
  CHECK_EQ(r.status, 100);
  CHECK_EQ(r.value, 0);
  CHECK_EQ(m.vm.execute_direct(I(Op::SAC, 1, 1, 0)).status, 3);  // no chip select 1 (0, 2, 3)
  CHECK_EQ(m.vm.execute_direct(I(Op::SAC, 0, 5, 0)).status, 4);  // 1 to 4 bytes
  Machine other({I(Op::STOP)}, *tmcl::find_profile("tmcm-1110"));
  CHECK_EQ(other.vm.execute_direct(I(Op::SAC, 0, 1, 0)).status, 6);
}
