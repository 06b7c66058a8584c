// The conformance tables' rows against the virtual machine itself, on every bundled module with
// its own profile and motion core: a `stored` row reads back what was written (or, read-only,
// its power-on default); a `refused` command (not a control command: those are the protocol's)
// is refused in direct mode (status 6) and faults a program; a module without a reference
// search ends a WAIT RFS at once; every timer and motor raises its own vectors. The row format
// is docs/conformance/README.md's; the tables are read as conformance_tables_test.cpp reads them.
#include <filesystem>
#include <memory>
#include <utility>
#include <vector>
#include <string>

#include "check.hpp"
#include "conformance_table.hpp"
#include "tmcl/isa.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/params.hpp"
#include "tmcl/vm.hpp"

namespace fs = std::filesystem;
using conformance::Row;
using conformance::Section;

namespace {

// A module as the tools run it: its profile, its motion core, powered on.
struct Module {
  std::unique_ptr<tmcl::MotionCore> core;
  tmcl::Vm vm;
  explicit Module(const tmcl::Profile& p) : core(tmcl::make_profile_motion_core(p)), vm(p, *core) { vm.power_on(nullptr); }
};

tmcl::Instruction ins(int op, int type, int motor, std::int32_t value) {
  return tmcl::Instruction{static_cast<std::uint8_t>(op), static_cast<std::uint8_t>(type), static_cast<std::uint8_t>(motor), value};
}

// A value a write may take that is not the default: the far end of the range from it, within
// 32 bits (a bank-3 period of up to 2^32 - 1 takes 1).
std::int32_t other_value(const tmcl::ParamInfo& p) {
  const std::int64_t hi = std::min<std::int64_t>(p.max, INT32_MAX), lo = std::max<std::int64_t>(p.min, INT32_MIN);
  return static_cast<std::int32_t>(p.default_value == hi ? lo : hi);
}

std::string where(const tmcl::Profile& p, const Row& r) {
  return (r.from.empty() ? std::string(p.name) + ".md" : r.from) + ":" + std::to_string(r.line);
}

void check_stored(const tmcl::Profile& p, const Row& r, const tmcl::ParamInfo* info, int set_op, int get_op, int bank) {
  if (!info) return;  // conformance_tables says so
  Module m(p);
  const int n = info->number;
  std::int32_t want = info->default_value;
  if (info->access & tmcl::kWrite) {
    want = other_value(*info);
    const tmcl::DirectReply w = m.vm.execute_direct(ins(set_op, n, bank, want));
    if (w.status != tmcl::kStatusOk)
      tmcl_test::fail(__FILE__, __LINE__, where(p, r) + ": writing " + std::to_string(want) + " answered status " + std::to_string(w.status));
  }
  const tmcl::DirectReply g = m.vm.execute_direct(ins(get_op, n, bank, 0));
  if (g.status != tmcl::kStatusOk || g.value != want)
    tmcl_test::fail(__FILE__, __LINE__, where(p, r) + ": a stored parameter reads " + std::to_string(g.value) + " (status " +
                                            std::to_string(g.status) + "), not " + std::to_string(want));
}

// What a program can observe of the motors: every axis parameter but `skip` of every motor, read
// (GAP) while motor 0 turns under a load of 60 % (where the core models loads) and after it
// stopped, and the motion events on the way.
std::vector<std::int64_t> observed(const tmcl::Profile& p, int skip, std::int32_t value) {
  Module m(p);
  if (skip >= 0) (void)m.vm.execute_direct(ins(5, skip, 0, value));
  (void)m.core->set_load(0, 60);
  const tmcl::ParamInfo* vmax = p.axis_param(4);
  m.core->rotate(0, vmax && vmax->default_value > 0 ? vmax->default_value / 2 : 1000);
  std::vector<std::int64_t> seen;
  std::vector<tmcl::MotionEvent> events;
  auto read_all = [&] {
    for (int motor = 0; motor < p.motors; ++motor)
      for (const tmcl::ParamInfo& q : p.axis_params)
        if (q.number != skip && (q.access & tmcl::kRead)) seen.push_back(m.vm.execute_direct(ins(6, q.number, motor, 0)).value);
  };
  m.core->advance(1'000'000, events);
  read_all();
  m.core->stop(0);
  m.core->advance(3'000'000, events);
  read_all();
  for (const auto& e : events) seen.insert(seen.end(), {e.at, static_cast<std::int64_t>(e.kind), e.position, e.value});
  return seen;
}

// A `stored` row claims that no program observes the parameter (README, *Row format*): writing
// it changes nothing the motors show a program. Issue 41: rows 6 and 140 said so while the run
// current and the microstep resolution moved the load value and the actual current.
void check_unobserved(const tmcl::Profile& p, const Row& r, const tmcl::ParamInfo* info) {
  if (!info || !(info->access & tmcl::kWrite)) return;
  const std::int32_t v = other_value(*info);
  if (observed(p, info->number, v) != observed(p, info->number, info->default_value))
    tmcl_test::fail(__FILE__, __LINE__, where(p, r) + ": a stored parameter, yet writing " + std::to_string(v) +
                                            " changes what the motors show a program: the row must say how");
}

}  // namespace

TEST(every_stored_row_changes_nothing_a_program_observes) {
  for (const tmcl::Profile* p : conformance::modules()) {
    const conformance::Table t = conformance::read_table(conformance::table_file(*p));
    for (const auto& [sec, rows] : t.rows)
      for (const Row& r : rows)
        if (sec == Section::Axis && r.status == "stored") check_unobserved(*p, r, p->axis_param(std::stoi(r.key)));
  }
}

TEST(every_stored_row_reads_back_what_was_written) {
  for (const tmcl::Profile* p : conformance::modules()) {
    const conformance::Table t = conformance::table_of(*p);
    for (const auto& [sec, rows] : t.rows)
      for (const Row& r : rows) {
        if (r.status != "stored") continue;
        const int n = std::stoi(r.key);
        switch (sec) {
          case Section::Axis: check_stored(*p, r, p->axis_param(n), 5, 6, 0); break;
          case Section::Bank0: check_stored(*p, r, p->global_param(0, n), 9, 10, 0); break;
          case Section::Bank3: check_stored(*p, r, p->global_param(3, n), 9, 10, 3); break;
          default: break;
        }
      }
  }
}

TEST(every_refused_command_is_refused_in_direct_mode_and_faults_a_program) {
  int checked = 0;
  for (const tmcl::Profile* p : conformance::modules()) {
    const conformance::Table t = conformance::table_of(*p);
    auto it = t.rows.find(Section::Commands);
    if (it == t.rows.end()) continue;
    for (const Row& r : it->second) {
      if (r.status != "refused") continue;
      const int op = std::stoi(r.key);
      const tmcl::OpInfo* info = tmcl::op_info(static_cast<std::uint8_t>(op));
      if (!info || info->control) continue;  // the protocol's (control_commands_missing_from_profile_are_status_6)
      Module m(*p);
      const tmcl::DirectReply d = m.vm.execute_direct(ins(op, 0, 0, 0));
      if (d.status != tmcl::kStatusNotAvailable)
        tmcl_test::fail(__FILE__, __LINE__, where(*p, r) + ": direct mode answered status " + std::to_string(d.status));
      if (!p->standalone) continue;
      Module run(*p);
      run.vm.load({ins(op, 0, 0, 0), ins(static_cast<int>(tmcl::Op::STOP), 0, 0, 0)});
      run.vm.start(0);
      if (run.vm.run(tmcl::Limits{1000}).halt != tmcl::Halt::Fault)
        tmcl_test::fail(__FILE__, __LINE__, where(*p, r) + ": a program went on past it");
      ++checked;
    }
  }
  CHECK(checked > 50);
}

// The USB-2-SD and the TMC2300-MOTOR-EVAL list WAIT RFS but have no RFS: no search ever runs,
// so the wait ends at once (errata M28).
TEST(wait_rfs_ends_at_once_without_a_search) {
  for (const char* name : {"usb-2-sd", "tmc2300-eval"}) {
    const tmcl::Profile* p = tmcl::find_profile(name);
    CHECK(p != nullptr && !p->has_command(static_cast<std::uint8_t>(tmcl::Op::RFS)));
    if (!p) continue;
    Module m(*p);
    m.vm.load({ins(static_cast<int>(tmcl::Op::WAIT), 4, 0, 0), ins(static_cast<int>(tmcl::Op::STOP), 0, 0, 0)});
    m.vm.start(0);
    const tmcl::RunResult r = m.vm.run(tmcl::Limits{1000, 10'000'000});
    CHECK(r.halt == tmcl::Halt::Stop);
    CHECK(m.vm.now < 1000);  // two instructions' time, no wait
  }
}

namespace {

// Runs `body` (instructions from address 0) with a handler at address 20 that counts its calls in
// user variable 0, on module `p` with its own core; returns the count. `inputs` are scenario events.
std::int32_t handler_calls(const tmcl::Profile& p, std::vector<tmcl::Instruction> body, std::vector<tmcl::InputEvent> inputs = {}) {
  using tmcl::Op;
  auto op = [](Op o) { return static_cast<int>(o); };
  body.resize(20, ins(op(Op::STOP), 0, 0, 0));
  body.push_back(ins(op(Op::GGP), 0, 2, 0));
  body.push_back(ins(op(Op::CALC), 0, 0, 1));  // ADD 1
  body.push_back(ins(op(Op::AGP), 0, 2, 0));
  body.push_back(ins(op(Op::RETI), 0, 0, 0));
  Module m(p);
  m.vm.load(body);
  m.vm.add_inputs(std::move(inputs));
  m.vm.start(0);
  const tmcl::RunResult r = m.vm.run(tmcl::Limits{100000, 60'000'000});
  if (r.halt != tmcl::Halt::Stop) tmcl_test::fail(__FILE__, __LINE__, std::string(p.name) + ": " + std::string(tmcl::halt_name(r.halt)) + " " + r.message);
  return m.vm.vars[0];
}

}  // namespace

// The rows of the timer, target-reached and stop-switch vectors and of their bank-3 settings,
// for every timer and every motor of every module, each raised by what raises it.
TEST(every_timer_and_motor_raises_its_own_vectors) {
  using tmcl::Op;
  auto op = [](Op o) { return static_cast<int>(o); };
  int checked = 0;
  for (const tmcl::Profile* p : conformance::modules()) {
    const std::string name(p->name);
    for (int n = 0; n < 3; ++n) {
      if (!p->vector(n)) continue;
      const std::int32_t calls = handler_calls(*p, {ins(op(Op::VECT), n, 0, 20), ins(op(Op::SGP), n, 3, 100), ins(op(Op::EI), n, 0, 0),
                                                    ins(op(Op::EI), 255, 0, 0), ins(op(Op::WAIT), 0, 0, 55), ins(op(Op::STOP), 0, 0, 0)});
      if (calls != 5) tmcl_test::fail(__FILE__, __LINE__, name + ": timer " + std::to_string(n) + " every 100 ms for 550 ms: " + std::to_string(calls) + " calls");
      ++checked;
    }
    for (int motor = 0; motor < p->motors; ++motor) {
      const int target = 3 + motor;
      if (p->vector(target)) {
        const std::int32_t calls = handler_calls(*p, {ins(op(Op::VECT), target, 0, 20), ins(op(Op::EI), target, 0, 0), ins(op(Op::EI), 255, 0, 0),
                                                      ins(op(Op::MVP), 0, motor, 100), ins(op(Op::WAIT), 1, motor, 0),
                                                      ins(op(Op::WAIT), 0, 0, 1), ins(op(Op::STOP), 0, 0, 0)});
        if (calls != 1) tmcl_test::fail(__FILE__, __LINE__, name + ": motor " + std::to_string(motor) + " reached its target: " + std::to_string(calls) + " calls of vector " + std::to_string(target));
        ++checked;
      }
      for (int side = 0; side < 2; ++side) {
        const int v = 27 + 2 * motor + side;
        if (!p->vector(v) || !p->global_param(3, v)) continue;
        const auto kind = side == 0 ? tmcl::InputEvent::StopLeft : tmcl::InputEvent::StopRight;
        std::vector<tmcl::InputEvent> inputs(2);
        inputs[0].at = 100'000, inputs[0].kind = kind, inputs[0].index = motor, inputs[0].value = 1;
        inputs[1].at = 200'000, inputs[1].kind = kind, inputs[1].index = motor, inputs[1].value = 0;
        // 1: low to high only; the opening at 200 ms raises nothing.
        const std::int32_t calls = handler_calls(*p, {ins(op(Op::VECT), v, 0, 20), ins(op(Op::SGP), v, 3, 1), ins(op(Op::EI), v, 0, 0),
                                                      ins(op(Op::EI), 255, 0, 0), ins(op(Op::WAIT), 0, 0, 30), ins(op(Op::STOP), 0, 0, 0)},
                                                 inputs);
        if (calls != 1) tmcl_test::fail(__FILE__, __LINE__, name + ": switch of vector " + std::to_string(v) + " closed and opened: " + std::to_string(calls) + " calls");
        ++checked;
      }
    }
  }
  CHECK(checked > 40);
}
