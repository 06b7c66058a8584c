// The debugging engine against the library: a trap stops before its instruction and costs the
// run nothing; stepping and re-execution are deterministic (one instruction at a time gives the
// state one run gives); reverse steps return to the exact earlier state; checkpoint memory stays
// within its bound.
#include "check.hpp"
#include "os_test.hpp"

#include <map>

#include "tmcl/asm/assembler.hpp"
#include "tmcl/debug_cli.hpp"
#include "tmcl/debugger.hpp"

using namespace tmcl;
using namespace tmcl::debug;

namespace {

class MemReader final : public FileReader {
 public:
  explicit MemReader(std::string text) : text_(std::move(text)) {}
  bool read(const std::string&, std::string& out) override {
    out = text_;
    return true;
  }

 private:
  std::string text_;
};

ProgramInfo assemble_info(const std::string& source, const Profile& profile) {
  MemReader reader(source);
  AsmOptions opts;
  opts.profile = &profile;
  AsmResult res = assemble({"t.tmc"}, opts, reader);
  CHECK(res.ok());
  ProgramInfo info;
  info.program = res.program;
  info.files.push_back({"t.tmc", {}});
  for (const auto& l : res.lines) info.lines.push_back({l.file, l.line});
  for (const auto& s : res.symbols) (s.kind == SymbolKind::Label ? info.labels : info.constants).emplace_back(s.name, s.value);
  return info;
}

// A program with a loop, a fused CALC+DJNZ pair, a subroutine, a timer interrupt and motion.
const char* kProgram = R"(
        VECT 0, tick
        SGP 0, 3, 7
        EI 0
        EI 255
        SAP 4, 0, 20000
        SAP 5, 0, 50000
        MVP ABS, 0, 30000
again:  SGP 9, 2, 40
inner:  CALC ADD, 3
        DJNZ 9, inner
        CSUB sub
        GAP 1, 0
        AGP 20, 2
        GGP 30, 2
        CALC ADD, 1
        AGP 30, 2
        COMP 25
        JC LT, again
        WAIT POS, 0, 0
        STOP
sub:    CALCX ADD
        RSUB
tick:   GGP 3, 2
        CALC ADD, 1
        AGP 3, 2
        RETI
)";

struct Fixture {
  const Profile* profile = find_profile("usb-2-sd");
  std::unique_ptr<Engine> engine;
  explicit Fixture(std::uint64_t interval = 64, std::size_t budget = std::size_t{64} << 20, std::uint64_t slice = 1 << 16) {
    Setup s;
    s.slice_steps = slice;
    s.profile = profile;
    s.core_name = std::string(profile->default_motion);
    s.checkpoint_interval = interval;
    s.checkpoint_bytes = budget;
    engine = std::make_unique<Engine>(s, assemble_info(kProgram, *profile), make_motion_core(s.core_name));
  }
  Vm& vm() { return engine->vm(); }
};

// Everything a user can see of the machine, as one comparable text.
std::string state(Vm& vm) {
  std::string s = "pc=" + std::to_string(vm.pc) + " acc=" + std::to_string(vm.acc) + " x=" + std::to_string(vm.x) +
                  " flags=" + std::to_string(vm.flags) + " sp=" + std::to_string(vm.sp) + " now=" + std::to_string(vm.now) +
                  " steps=" + std::to_string(vm.steps) + " h=" + std::to_string(vm.in_handler) +
                  " pos=" + std::to_string(vm.motion->position(0));
  for (int v : {3, 9, 20, 30}) s += " v" + std::to_string(v) + "=" + std::to_string(vm.vars[static_cast<std::size_t>(v)]);
  return s;
}

}  // namespace

TEST(breakpoint_stops_before_its_instruction_without_counting_it) {
  Fixture f;
  std::int32_t at = 0;
  std::string err;
  CHECK(f.engine->resolve("sub", at, err));
  int id = f.engine->add_breakpoint(at, "sub", false);
  Stop s = f.engine->start(false);
  CHECK(s.kind == StopKind::Breakpoint);
  CHECK_EQ(s.id, id);
  CHECK_EQ(f.vm().pc, at);
  // The CSUB before it ran; the instruction at the trap did not.
  CHECK_EQ(f.vm().sp, 1);
  std::uint64_t steps = f.vm().steps;
  s = f.engine->step(1);
  CHECK(s.kind == StopKind::Step);
  CHECK_EQ(f.vm().steps, steps + 1);
}

TEST(a_trap_on_the_djnz_of_a_fused_pair_stops_there) {
  Fixture f;
  std::int32_t inner = 0;
  std::string err;
  CHECK(f.engine->resolve("inner", inner, err));
  f.engine->add_breakpoint(inner + 1, "*", false);  // the DJNZ fused with the CALC before it
  Stop s = f.engine->start(false);
  CHECK(s.kind == StopKind::Breakpoint);
  CHECK_EQ(f.vm().pc, inner + 1);
}

TEST(breakpoints_do_not_change_the_run) {
  Fixture plain, traced;
  Stop a = plain.engine->start(false);
  CHECK(a.kind == StopKind::Exited);
  for (const char* l : {"inner", "sub", "tick", "again"}) {
    std::int32_t at = 0;
    std::string err;
    CHECK(traced.engine->resolve(l, at, err));
    traced.engine->add_breakpoint(at, l, false);
  }
  Stop b = traced.engine->start(false);
  int hits = 0;
  while (b.kind == StopKind::Breakpoint) {
    ++hits;
    b = traced.engine->cont();
  }
  CHECK(b.kind == StopKind::Exited);
  CHECK(hits > 100);
  CHECK_EQ(state(traced.vm()), state(plain.vm()));
}

TEST(one_instruction_at_a_time_gives_the_state_one_run_gives) {
  Fixture stepped, run;
  stepped.engine->start(true);
  run.engine->start(true);
  std::map<std::uint64_t, std::string> seen;
  for (int i = 0; i < 3000; ++i) {
    Stop s = stepped.engine->step(1);
    if (s.kind != StopKind::Step) break;
    seen[stepped.vm().steps] = state(stepped.vm());
  }
  for (std::uint64_t at : {std::uint64_t{1}, std::uint64_t{77}, std::uint64_t{500}, std::uint64_t{1234}, std::uint64_t{2999}}) {
    Fixture fresh;
    fresh.engine->start(true);
    fresh.engine->step(at);
    CHECK_EQ(state(fresh.vm()), seen[at]);
  }
}

TEST(reverse_steps_return_to_the_exact_earlier_state) {
  Fixture f(50);
  f.engine->start(true);
  std::map<std::uint64_t, std::string> seen;
  seen[0] = state(f.vm());
  for (int i = 0; i < 1500; ++i) {
    f.engine->step(1);
    seen[f.vm().steps] = state(f.vm());
  }
  for (std::uint64_t back : {1, 2, 7, 49, 50, 51, 333}) {
    std::uint64_t target = f.vm().steps - back;
    Stop s = f.engine->reverse_step(back);
    CHECK(s.kind == StopKind::Step);
    CHECK_EQ(state(f.vm()), seen[target]);
  }
  // Forward again from a replayed state: the same states as the first time.
  f.engine->step(10);
  CHECK_EQ(state(f.vm()), seen[f.vm().steps]);
}

TEST(reverse_finish_and_next_land_on_the_call) {
  Fixture f;
  std::int32_t sub = 0;
  std::string err;
  CHECK(f.engine->resolve("sub", sub, err));
  f.engine->add_breakpoint(sub + 1, "*", false);  // the RSUB
  CHECK(f.engine->start(false).kind == StopKind::Breakpoint);
  CHECK_EQ(f.engine->depth(), 1);
  Stop s = f.engine->reverse_finish();
  CHECK(s.kind == StopKind::Step);
  CHECK_EQ(f.engine->depth(), 0);
  CHECK_EQ(f.vm().program[static_cast<std::size_t>(f.vm().pc)].op, static_cast<std::uint8_t>(Op::CSUB));
}

TEST(checkpoint_memory_stays_within_its_bound) {
  Fixture f(16, 64 * 1024);
  f.engine->start(false);
  CHECK(f.engine->checkpoint_count() > 2);
  CHECK(f.engine->checkpoint_memory() <= std::size_t{64} * 1024);
  // Still able to go back one instruction from the end.
  std::uint64_t steps = f.vm().steps;
  CHECK(f.engine->reverse_step(1).kind == StopKind::Step);
  CHECK_EQ(f.vm().steps, steps - 1);
}

TEST(watchpoint_on_a_variable_stops_after_the_instruction_that_changed_it) {
  Fixture f;
  std::string err;
  int id = f.engine->add_watchpoint("v[30]", err);
  CHECK(id > 0);
  Stop s = f.engine->start(false);
  CHECK(s.kind == StopKind::Watchpoint);
  CHECK_EQ(s.old_value, 0);
  CHECK_EQ(s.new_value, 1);
  CHECK_EQ(f.vm().program[static_cast<std::size_t>(f.vm().pc - 1)].op, static_cast<std::uint8_t>(Op::AGP));
}

TEST(watchpoint_on_time_stops_at_the_exact_instant) {
  Fixture f;
  std::string err;
  CHECK(f.engine->add_watchpoint("time >= 123457us", err) > 0);
  Stop s = f.engine->start(false);
  CHECK(s.kind == StopKind::Watchpoint);
  CHECK_EQ(f.vm().now, SimTime{123457});
}

TEST(variable_watchpoint_sees_a_change_that_is_undone_at_once_and_indexed_writes) {
  const Profile* profile = find_profile("usb-2-sd");
  Setup s;
  s.profile = profile;
  s.core_name = "ideal";
  Engine e(s, assemble_info("SGP 7, 2, 5\nSGP 7, 2, 0\nCALC LOAD, 7\nCALCX LOAD\nSIV 9\nSIV 9\nCALCVA ADD, 7\nSTOP\n", *profile),
           make_motion_core("ideal"));
  std::string err;
  CHECK(e.add_watchpoint("v[7] * 2", err) > 0);
  std::vector<std::int64_t> seen;
  Stop st = e.start(false);
  while (st.kind == StopKind::Watchpoint) {
    seen.push_back(st.new_value);
    st = e.cont();
  }
  CHECK(st.kind == StopKind::Exited);
  CHECK_EQ(seen.size(), std::size_t{4});  // 10, 0, 18 (SIV), 32 (CALCVA); the second SIV changes nothing
  if (seen.size() == 4) {
    CHECK_EQ(seen[0], 10);
    CHECK_EQ(seen[1], 0);
    CHECK_EQ(seen[2], 18);
    CHECK_EQ(seen[3], 32);
  }
}

// Engine::on_slice (DAP pause, debugging while serving): a run cut into slices, each bounded in
// time by what on_slice returns, ends in the state one run gives; pause_for() from on_slice stops
// with its text; a breakpoint set meanwhile does not cancel finish's temporary stop.
TEST(a_run_in_slices_gives_the_state_one_run_gives) {
  Fixture plain, sliced(64, std::size_t{64} << 20, 16);
  Stop a = plain.engine->start(false);
  int calls = 0;
  sliced.engine->on_slice = [&] {
    ++calls;
    return sliced.vm().now + 137;  // as a server pacing by the wall clock would
  };
  Stop b = sliced.engine->start(false);
  CHECK(a.kind == StopKind::Exited && b.kind == StopKind::Exited);
  CHECK_EQ(state(sliced.vm()), state(plain.vm()));
  CHECK(calls > 10);
}

TEST(pause_for_from_on_slice_stops_with_its_text) {
  Fixture f(64, std::size_t{64} << 20, 16);
  int calls = 0;
  f.engine->on_slice = [&] {
    if (++calls == 3) f.engine->pause_for("Program stopped: the host stopped the program (command 128).");
    return kNever;
  };
  Stop st = f.engine->start(true);
  CHECK(st.kind == StopKind::Entry);
  st = f.engine->step(f.engine->setup().slice_steps * 10);  // long enough for three slices
  CHECK(st.kind == StopKind::Pause);
  CHECK_EQ(calls, 3);
  CHECK_EQ(st.message, std::string("Program stopped: the host stopped the program (command 128)."));
}

TEST(a_breakpoint_set_during_finish_keeps_its_temporary_stop) {
  Fixture f(64, std::size_t{64} << 20, 1);  // on_slice after every instruction
  std::int32_t sub = 0, stop_at = 0;
  std::string err;
  CHECK(f.engine->resolve("sub", sub, err));
  CHECK(f.engine->resolve("sub", stop_at, err));
  f.engine->add_breakpoint(sub, "sub", false);
  Stop s = f.engine->start(false);
  CHECK(s.kind == StopKind::Breakpoint);
  const std::int32_t back = f.vm().stack[0];  // the instruction after the CSUB
  bool added = false;
  f.engine->on_slice = [&] {
    if (!added) f.engine->add_breakpoint(stop_at - 1, "*", false);  // the STOP: never reached from here
    added = true;
    return kNever;
  };
  s = f.engine->finish();
  CHECK(added);
  CHECK(s.kind == StopKind::Step);
  CHECK_EQ(f.vm().pc, back);
}

// The first stepping rule against the trace itself: the stops of one `step` after another are
// the instructions a traced run lists, each at its address and start instant (a WAIT counts once;
// a handler entered in a WAIT or between two instructions is stopped at its first instruction),
// and reverse-step from the end visits the same stops backwards.
namespace {
struct Listing final : TraceSink {
  std::vector<std::pair<std::int32_t, SimTime>> at;  // each instruction's address and start
  void instruction(const Vm&, SimTime t, std::int32_t pc, const Instruction&) override { at.emplace_back(pc, t); }
  void interrupt_enter(const Vm&, int, std::int32_t) override {}
  void interrupt_leave(const Vm&, std::int32_t) override {}
  void motion_event(const Vm&, const MotionEvent&) override {}
  void wait_end(const Vm&, std::int32_t, bool) override {}
  void input_event(const Vm&, const std::string&) override {}
};
}  // namespace

TEST(each_step_stops_before_the_next_instruction_the_trace_lists) {
  Fixture traced, stepped(50);
  Listing listing;
  traced.vm().trace = &listing;
  CHECK(traced.engine->start(false).kind == StopKind::Exited);
  CHECK(listing.at.size() > 500);
  stepped.engine->start(true);
  std::vector<std::pair<std::int32_t, SimTime>> stops{{stepped.vm().pc, stepped.vm().now}};
  for (std::size_t i = 1; i < listing.at.size(); ++i) {
    Stop s = stepped.engine->step(1);
    CHECK(s.kind == StopKind::Step);
    if (s.kind != StopKind::Step) break;
    stops.emplace_back(stepped.vm().pc, stepped.vm().now);
  }
  CHECK(stops == listing.at);
  std::size_t differ = 0;
  while (differ < stops.size() && differ < listing.at.size() && stops[differ] == listing.at[differ]) ++differ;
  CHECK_EQ(differ, listing.at.size());
  // Backwards: the same stops in reverse order, down to the first instruction.
  for (std::size_t i = stops.size() - 1; i-- > 0;) {
    CHECK(stepped.engine->reverse_step(1).kind == StopKind::Step);
    if (stepped.vm().pc != stops[i].first || stepped.vm().now != stops[i].second) {
      CHECK_EQ(i, std::size_t{0});  // reports the first mismatch only
      break;
    }
  }
  CHECK_EQ(stepped.vm().steps, std::uint64_t{0});
}

// set var hardstop|load (issue 34): Tab offers the machine's inputs and the words of their lines;
// a hard stop placed before `start` belongs to the machine and holds the motor in every run (here
// stop on stall stops it there: 206 reads 0, 208 bit 0 is set), and a core without mechanics
// refuses at the prompt without faulting the program.
TEST(set_var_hardstop_and_load_at_the_prompt) {
  const Profile* profile = find_profile("tmcm-1110");
  Setup s;
  s.profile = profile;
  s.core_name = std::string(profile->default_motion);
  Engine e(s, assemble_info("SAP 140, 0, 4\nSAP 181, 0, 200\nROL 0, 400\nloop: WAIT TICKS, 0, 10\nJA loop\n", *profile),
           make_motion_core(s.core_name));
  std::FILE* out = tmcl_test::scratch_file();
  CHECK(out != nullptr);
  if (!out) return;
  CommandLine cli(e, out, false, false);
  auto offers = [&](const std::string& line) {
    std::string all;
    for (const auto& c : cli.completions(line, line.find_last_of(' ') + 1)) all += c + " ";
    return all;
  };
  CHECK_EQ(offers("set var ").substr(0, 21), std::string("switch hardstop load "));  // then the lvalues
  CHECK_EQ(offers("set var h"), std::string("hardstop "));
  CHECK_EQ(offers("set var hardstop "), std::string("left right "));
  CHECK_EQ(offers("set var hardstop left 0 "), std::string("at "));
  CHECK_EQ(offers("set var load 0 "), std::string("from "));
  CHECK_EQ(offers("set var load 0 from -10 "), std::string("to "));
  cli.line("set var hardstop left 0 at -3000");
  for (int run = 0; run < 2; ++run) {
    cli.line("start");
    cli.line("advance 1s");
    // Held at the hard stop; the counter runs on to the next fullstep's measurement, which reads 0.
    CHECK(e.vm().motion->position(0) <= -3000 && e.vm().motion->position(0) > -3016);
    std::int32_t v = 0;
    CHECK_EQ(e.vm().get_axis(0, 206, v), kStatusOk);
    CHECK_EQ(v, 0);
    CHECK_EQ(e.vm().get_axis(0, 208, v), kStatusOk);
    CHECK_EQ(v & 1, 1);
    cli.line("kill");
  }
  std::fclose(out);

  Fixture f;  // the USB-2-SD's core models no loads
  std::string error;
  InputEvent load;
  load.kind = InputEvent::Load;
  load.value = 50;
  CHECK(f.engine->start(true).kind == StopKind::Entry);
  CHECK(!f.engine->set_machine(load, error));
  CHECK_EQ(error, "the motion core '" + std::string(f.vm().motion->name()) + "' cannot model loads on usb-2-sd");
  CHECK(!f.vm().faulted());
}

// A change by hand in the middle of a run (set var hardstop) keeps the scenario's timed lines
// that came before it: `run` again replays them (here a load at 200 ms, under which 206 reads
// less than running free), as it did before the change.
TEST(a_change_by_hand_keeps_the_scenarios_earlier_lines_for_the_next_run) {
  const Profile* profile = find_profile("tmcm-1110");
  Setup s;
  s.profile = profile;
  s.core_name = std::string(profile->default_motion);
  InputEvent load;
  load.kind = InputEvent::Load;
  load.at = 200 * kUsPerMs;
  load.value = 40;
  s.inputs = {load};
  Engine e(s, assemble_info("SAP 140, 0, 4\nROL 0, 400\nloop: WAIT TICKS, 0, 10\nJA loop\n", *profile),
           make_motion_core(s.core_name));
  std::FILE* out = tmcl_test::scratch_file();
  CHECK(out != nullptr);
  if (!out) return;
  CommandLine cli(e, out, false, false);
  auto load_value = [&] {
    std::int32_t v = 0;
    CHECK_EQ(e.vm().get_axis(0, 206, v), kStatusOk);
    return v;
  };
  cli.line("start");
  cli.line("advance 100ms");
  const std::int32_t free = load_value();
  cli.line("advance 200ms");
  const std::int32_t loaded = load_value();
  CHECK(loaded < free);
  cli.line("set var hardstop right 0 at 100000");
  cli.line("kill");
  cli.line("start");
  cli.line("advance 300ms");
  CHECK_EQ(load_value(), loaded);
  std::fclose(out);
}
