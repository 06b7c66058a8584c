// Reverse execution. The machine is deterministic, so any earlier state is a checkpoint (a copy
// of the whole VM and motion core; the scenario position is part of the VM) plus re-execution
// of the instructions after it. Forward execution takes a checkpoint every
// Setup::checkpoint_interval instructions; when their memory passes Setup::checkpoint_bytes the
// older half is thinned (every second one dropped), so recent history stays dense and the cost
// of a reverse step stays one interval of re-execution. A change of state by the user (set var,
// jump) starts history again at that point: states before it cannot be re-executed.
//
// The states a reverse command lands on are those a step forward lands on: before the
// instruction that runs next (Limits::to_instruction), one per instruction executed. "Before
// instruction n+1" is the state n instructions after the start with any WAIT ended and any due
// interrupt entered, so each is named by its instruction count and found again by re-execution.
#include <algorithm>

#include "tmcl/debugger.hpp"

namespace tmcl::debug {

bool Engine::can_reverse(std::string& why) const {
  if (!reversible_) {
    why = "the motion core '" + std::string(core_->name()) + "' cannot be copied, so there is no history to go back in";
    return false;
  }
  if (checkpoints_.empty()) {
    why = "the program is not being run";
    return false;
  }
  return true;
}

std::size_t Engine::checkpoint_memory() const { return checkpoints_.size() * checkpoint_size_; }

void Engine::take_checkpoint() {
  const std::uint64_t interval = std::max<std::uint64_t>(setup_.checkpoint_interval, 1);
  next_checkpoint_ = (vm_->steps / interval + 1) * interval;
  auto at = std::lower_bound(checkpoints_.begin(), checkpoints_.end(), vm_->steps,
                             [](const Checkpoint& c, std::uint64_t s) { return c.steps < s; });
  if (at != checkpoints_.end() && at->steps == vm_->steps) return;  // already have it
  checkpoints_.insert(at, Checkpoint{vm_->steps, vm_->checkpoint(), core_->clone()});
  // Thinning: keep the first (history starts there) and the newer half; drop every second
  // one of the older half.
  while (checkpoints_.size() > 2 && checkpoint_memory() > setup_.checkpoint_bytes) {
    std::size_t half = checkpoints_.size() / 2;
    std::vector<Checkpoint> kept;
    kept.reserve(checkpoints_.size());
    for (std::size_t i = 0; i < checkpoints_.size(); ++i)
      if (i == 0 || i >= half || i % 2 == 0) kept.push_back(std::move(checkpoints_[i]));
    if (kept.size() == checkpoints_.size()) break;
    checkpoints_ = std::move(kept);
  }
}

void Engine::state_changed() {
  checkpoints_.clear();
  if (reversible_ && running_) take_checkpoint();
  refresh_watches();
}

void Engine::restore_checkpoint(const Checkpoint& cp) {
  vm_->restore(cp.vm);
  core_ = cp.core->clone();
  vm_->motion = core_.get();
}

const Engine::Checkpoint* Engine::checkpoint_before(std::uint64_t steps) const {
  const Checkpoint* best = nullptr;
  for (const auto& c : checkpoints_)
    if (c.steps <= steps) best = &c;
  return best;
}

// Restores the last checkpoint at or before `steps` and re-executes to the stop before
// instruction steps + 1, traps off (a breakpoint on the way must not stop a replay).
void Engine::replay_to(std::uint64_t steps) {
  const Checkpoint* cp = checkpoint_before(steps);
  if (!cp) return;
  restore_checkpoint(*cp);
  std::vector<std::int32_t> trapped;
  for (std::int32_t a = 0; a < vm_->program_size; ++a)
    if (vm_->trapped(a)) {
      trapped.push_back(a);
      vm_->set_trap(a, false);
    }
  for (;;) {
    RunResult r = vm_->run(Limits{steps, kNever, true});
    if (r.halt != Halt::StepLimit || vm_->steps >= steps) break;
  }
  for (auto a : trapped) vm_->set_trap(a, true);
  running_ = true;
  refresh_watches();
  // Going forward from here runs the instruction at pc: a breakpoint there does not stop it.
  checked_steps_ = vm_->steps;
  checked_pc_ = vm_->pc;
}

Stop Engine::reverse_step(std::uint64_t n) {
  std::string why;
  if (!can_reverse(why)) return Stop{StopKind::NotRunning, 0, why, 0, 0};
  std::uint64_t oldest = checkpoints_.front().steps;
  std::uint64_t target = vm_->steps >= n ? vm_->steps - n : 0;
  bool at_start = target <= oldest;
  if (vm_->steps <= oldest) return Stop{StopKind::HistoryStart, 0, "no more reverse-execution history", 0, 0};
  replay_to(std::max(target, oldest));
  return Stop{at_start && target < oldest ? StopKind::HistoryStart : StopKind::Step, 0,
              at_start && target < oldest ? "no more reverse-execution history" : "", 0, 0};
}

// reverse-next (kind 0), reverse-finish (1), reverse-continue (2): re-executes history one
// checkpoint interval at a time, newest first, one instruction at a time, and replays to the
// last stop before the present that the kind accepts: reverse-next the last at this depth or
// less (the mirror of next), reverse-finish the last at a lower depth (the CSUB, or before the
// handler was entered), reverse-continue the last at an enabled breakpoint whose condition
// holds, or the last where a watched value had just changed.
Stop Engine::reverse_scan(int kind) {
  std::string why;
  if (!can_reverse(why)) return Stop{StopKind::NotRunning, 0, why, 0, 0};
  const std::uint64_t end = vm_->steps;
  const int d = depth();
  if (kind == 1 && d == 0) return Stop{StopKind::NotRunning, 0, "\"reverse-finish\" not meaningful in the outermost frame", 0, 0};
  std::vector<std::int32_t> trapped;
  for (std::int32_t a = 0; a < vm_->program_size; ++a)
    if (vm_->trapped(a)) trapped.push_back(a);
  // Checkpoints at or before `end`, newest first: each bounds one segment of re-execution.
  std::vector<std::uint64_t> starts;
  for (const auto& c : checkpoints_)
    if (c.steps < end) starts.push_back(c.steps);
  std::reverse(starts.begin(), starts.end());
  std::uint64_t seg_end = end;
  for (std::uint64_t start : starts) {
    const Checkpoint* cp = checkpoint_before(start);
    restore_checkpoint(*cp);
    for (auto a : trapped) vm_->set_trap(a, false);
    // The first stop of the segment: before instruction start + 1.
    RunResult r = vm_->run(Limits{start, kNever, true});
    bool ended = r.halt != Halt::StepLimit;
    std::optional<std::uint64_t> hit;
    int hit_id = 0;
    std::int64_t old_v = 0, new_v = 0;
    std::vector<std::int64_t> values;
    if (kind == 2) {
      for (auto& w : watches_) {
        std::string err;
        w.valid = eval_expr(w.expr, *vm_, w.old_value, err);
      }
    }
    while (!ended && vm_->steps < seg_end) {
      const std::uint64_t at = vm_->steps;
      if (kind == 0 && depth() <= d) hit = at;
      if (kind == 1 && depth() < d) hit = at;
      if (kind == 2) {
        // Breakpoints: an enabled one at pc whose condition holds, before the instruction.
        for (auto& b : breaks_) {
          // A logpoint never stops, going forwards or backwards.
          if (!b.enabled || !b.log_message.empty() || b.address != vm_->pc) continue;
          std::int64_t v = 1;
          std::string err;
          if (b.cond.root >= 0 && !eval_expr(b.cond, *vm_, v, err)) v = 1;
          if (v) {
            hit = at;
            hit_id = b.id;
            break;
          }
        }
      }
      r = vm_->run(Limits{at + 1, kNever, true});
      ended = r.halt != Halt::StepLimit;
      if (kind == 2 && !watches_.empty()) {
        for (auto& w : watches_) {
          if (!w.enabled) continue;
          std::int64_t v = 0;
          std::string err;
          if (!eval_expr(w.expr, *vm_, v, err)) continue;
          if (w.valid && v != w.old_value && vm_->steps < end) {
            hit = vm_->steps;
            hit_id = w.id;
            old_v = w.old_value;
            new_v = v;
          }
          w.old_value = v;
          w.valid = true;
        }
      }
    }
    if (hit) {
      for (auto a : trapped) vm_->set_trap(a, true);
      replay_to(*hit);
      running_ = true;
      if (kind == 2) {
        bool is_watch = std::any_of(watches_.begin(), watches_.end(), [&](const Watchpoint& w) { return w.id == hit_id; });
        if (is_watch) return Stop{StopKind::Watchpoint, hit_id, "", old_v, new_v};
        return Stop{StopKind::Breakpoint, hit_id, "", 0, 0};
      }
      return Stop{StopKind::Step, 0, "", 0, 0};
    }
    seg_end = start;
  }
  for (auto a : trapped) vm_->set_trap(a, true);
  replay_to(checkpoints_.front().steps);
  return Stop{StopKind::HistoryStart, 0, "no more reverse-execution history", 0, 0};
}

Stop Engine::reverse_next() { return reverse_scan(0); }
Stop Engine::reverse_finish() { return reverse_scan(1); }
Stop Engine::reverse_continue() { return reverse_scan(2); }

}  // namespace tmcl::debug
