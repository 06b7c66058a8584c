// Limits::stop (issue 28 item 1): a request from outside (tmclrun's SIGINT, SIGTERM, a closed
// trace output) ends run() with Halt::Interrupted between two instructions, also in an endless
// loop the fast path runs and in a WAIT; a run() called again goes on exactly as if it had not
// returned, so tmclrun's wall-clock note changes nothing the program does.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include "check.hpp"
#include "os_test.hpp"
#include "machine.hpp"
#include "tmcl/vm_output.hpp"

using namespace vmtest;
using tmcl::Halt;
using tmcl::Op;

namespace {

std::atomic<bool> g_flag{false};

// A timer interrupt every 10 ms counting in v1, moves back and forth with WAIT POS, and a busy
// loop counting in v0 meanwhile: every path of the run loop (fast, slow, WAIT, interrupts).
std::vector<Instruction> busy_program() {
  return {I(Op::VECT, 0, 0, 12),     I(Op::SGP, 0, 3, 10),     I(Op::EI, 0),       I(Op::EI, 255),
          I(Op::MVP, 0, 0, 20000),   I(Op::CALCV, 0, 0, 1),    I(Op::GAP, 8, 0),   I(Op::JC, 0, 0, 5),
          I(Op::MVP, 0, 0, 0),       I(Op::WAIT, 1, 0, 0),     I(Op::JA, 0, 0, 4), I(Op::STOP),
          I(Op::CALCV, 0, 1, 1),     I(Op::RETI)};
}

struct Run {
  std::unique_ptr<tmcl::MotionCore> core = tmcl::make_motion_core("tmc4361");
  tmcl::Vm vm{tmcl::generic_profile(), *core};
  Run() {
    vm.load(busy_program());
    vm.power_on(nullptr);
    vm.start(0);
  }
  std::string state() {
    return std::to_string(vm.now) + " " + std::to_string(vm.steps) + " " + std::to_string(vm.pc) + " " +
           std::to_string(vm.vars[0]) + " " + std::to_string(vm.vars[1]) + " " + std::to_string(vm.axis_param(0, 1));
  }
};

// Sets the flag after every n-th line it is shown, like a signal arriving there.
class Interrupter final : public tmcl::TraceSink {
 public:
  explicit Interrupter(tmcl::TraceSink& inner, int n) : inner_(inner), n_(n) {}
  void instruction(const tmcl::Vm& vm, tmcl::SimTime at, std::int32_t pc, const Instruction& ins) override {
    inner_.instruction(vm, at, pc, ins);
    tick();
  }
  void interrupt_enter(const tmcl::Vm& vm, int v, std::int32_t from) override {
    inner_.interrupt_enter(vm, v, from);
    tick();
  }
  void interrupt_leave(const tmcl::Vm& vm, std::int32_t to) override { inner_.interrupt_leave(vm, to); }
  void motion_event(const tmcl::Vm& vm, const tmcl::MotionEvent& ev) override {
    inner_.motion_event(vm, ev);
    tick();
  }
  void wait_end(const tmcl::Vm& vm, std::int32_t pc, bool timeout) override {
    inner_.wait_end(vm, pc, timeout);
    tick();
  }
  void input_event(const tmcl::Vm& vm, const std::string& what) override { inner_.input_event(vm, what); }

 private:
  void tick() {
    if (++count_ % n_ == 0) g_flag = true;
  }
  tmcl::TraceSink& inner_;
  int n_, count_ = 0;
};

std::string slurp(std::FILE* f) {
  std::string s;
  std::rewind(f);
  for (int c; (c = std::fgetc(f)) != EOF;) s += static_cast<char>(c);
  return s;
}

}  // namespace

TEST(stop_request_ends_an_endless_loop_on_the_fast_path) {
  Machine m({I(Op::CALCV, 0, 0, 1), I(Op::JA, 0, 0, 0)}, test_profile(), 20);
  g_flag = false;
  std::thread signaller([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
    g_flag = true;
  });
  tmcl::Limits lim;
  lim.stop = &g_flag;
  auto r = m.vm.run(lim);  // no limit: only the request ends it
  signaller.join();
  CHECK(r.halt == Halt::Interrupted);
  CHECK_EQ(std::string(tmcl::halt_name(r.halt)), std::string("interrupted"));
  CHECK(m.vm.steps > 0);
  CHECK_EQ(m.vm.vars[0], static_cast<std::int32_t>((m.vm.steps + 1) / 2));  // between two instructions
}

TEST(stop_request_in_a_wait_and_after_stop) {
  tmcl::Limits lim;
  lim.stop = &g_flag;
  g_flag = false;
  Machine w({I(Op::WAIT, 0, 0, 100000), I(Op::STOP)}, test_profile(), 20);
  lim.max_steps = 1;
  CHECK(w.vm.run(lim).halt == Halt::StepLimit);  // the WAIT of 1000 s has begun
  lim.max_steps = UINT64_MAX;
  g_flag = true;
  CHECK(w.vm.run(lim).halt == Halt::Interrupted);
  CHECK(w.vm.wait.active);
  g_flag = false;
  CHECK(w.vm.run(lim).halt == Halt::Stop);
  CHECK_EQ(w.vm.now, 100000 * 10000 + 20);  // as without the request
  // After STOP, while the motors settle, a request ends the settling too.
  auto core = tmcl::make_motion_core("tmc4361");
  tmcl::Vm s(tmcl::generic_profile(), *core);
  s.load({I(Op::MVP, 0, 0, 1000000), I(Op::STOP)});
  s.power_on(nullptr);
  s.start(0);
  tmcl::Limits until;
  until.until = 1000;
  CHECK(s.run(until).halt == Halt::TimeLimit);  // stopped, the motor still moving
  g_flag = true;
  CHECK(s.run(lim).halt == Halt::Interrupted);
  g_flag = false;
  CHECK(s.run(lim).halt == Halt::Stop);
  CHECK_EQ(s.motion->position(0), 1000000);
}

TEST(an_interrupted_traced_run_goes_on_as_if_uninterrupted) {
  std::FILE* plain = tmcl_test::scratch_file();
  std::FILE* cut = tmcl_test::scratch_file();
  CHECK(plain && cut);
  if (!plain || !cut) return;
  tmcl::Limits lim;
  lim.until = 300'000;
  Run a;
  tmcl::TextTrace ta(plain, nullptr);
  a.vm.trace = &ta;
  auto ra = a.vm.run(lim);
  Run b;
  tmcl::TextTrace tb(cut, nullptr);
  Interrupter every7(tb, 7);
  b.vm.trace = &every7;
  lim.stop = &g_flag;
  g_flag = false;
  int interruptions = 0;
  tmcl::RunResult rb;
  while ((rb = b.vm.run(lim)).halt == Halt::Interrupted) {
    ++interruptions;
    g_flag = false;
  }
  CHECK(interruptions > 100);
  CHECK(ra.halt == rb.halt);
  CHECK_EQ(a.state(), b.state());
  CHECK(slurp(plain) == slurp(cut));
  std::fclose(plain);
  std::fclose(cut);
}

TEST(an_interrupted_fast_run_goes_on_as_if_uninterrupted) {
  tmcl::Limits lim;
  lim.until = 60'000'000;
  Run a;
  auto ra = a.vm.run(lim);
  Run b;
  lim.stop = &g_flag;
  g_flag = true;  // at least once: before the first instruction
  std::atomic<bool> done{false};
  std::thread signaller([&] {
    while (!done) {
      g_flag = true;
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
  });
  int interruptions = 0;
  tmcl::RunResult rb;
  while ((rb = b.vm.run(lim)).halt == Halt::Interrupted) {
    ++interruptions;
    g_flag = false;
  }
  done = true;
  signaller.join();
  CHECK(interruptions >= 1);
  CHECK(ra.halt == rb.halt);
  CHECK_EQ(a.state(), b.state());
}
