// The virtual module's line (bus.hpp): one or several modules on one byte stream, their clocks,
// and fault injection on the replies.
#include "tmcl/bus.hpp"

#include <algorithm>

#include "tmcl/image.hpp"

namespace tmcl {

Line::Line(Vm& primary, const ServeOptions& options) {
  modules_.push_back(Member{std::make_unique<TmclModule>(primary, options.protocol), &primary, 0});
  for (const BusModule& b : options.bus) {
    modules_.push_back(Member{std::make_unique<TmclModule>(*b.vm, b.protocol), b.vm, 0});
    // A bus member starts its program like the primary does: global 77 (or --autostart, which
    // serve() applies to the primary only).
    if (b.vm->profile->global_param(0, 77) && b.vm->bank0[77] != 0 && b.vm->program_size > 0) b.vm->start(0);
  }
  for (auto& m : modules_) m.module->on_exchange = options.on_exchange;  // --serve --trace
  modules_.front().module->run_program = options.run_program;            // --serve --debug
  if (!options.faults.empty()) faults_.emplace(options.faults, options.time_scale);
  out_.reserve(4096);
}

void Line::set_on_message(const std::function<void(const std::string&)>& f) {
  for (std::size_t i = 0; i < modules_.size(); ++i) {
    if (modules_.size() == 1 || !f) {
      modules_[i].module->on_message = f;
    } else {
      const std::string who = "module " + std::to_string(modules_[i].module->module_address()) + ": ";
      modules_[i].module->on_message = [f, who](const std::string& s) { f(who + s); };
    }
  }
}

// Which command the next reply answers: the last intact 9-byte frame seen (one host, one request
// at a time). Only needed for cmd= fault rules.
void Line::track_requests(const std::uint8_t* data, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    if (window_fill_ == 9) {
      std::copy(window_ + 1, window_ + 9, window_);
      window_fill_ = 8;
    }
    window_[window_fill_++] = data[i];
    if (window_fill_ == 9 && sum8(window_, 8) == window_[8]) {
      last_command_ = window_[1];
      window_fill_ = 0;
    }
  }
}

void Line::collect() {
  for (Member& m : modules_) {
    if (m.module->take_power_cycle()) m.offset = now_ - m.vm->now;  // it restarted at 0 just now
    std::vector<std::uint8_t>& o = m.module->output();
    if (o.empty()) continue;
    if (!faults_) {
      out_.insert(out_.end(), o.begin(), o.end());
    } else {
      for (std::size_t at = 0; at + 9 <= o.size(); at += 9) faults_->reply(o.data() + at, 9, last_command_, now_);
    }
    o.clear();
  }
  if (faults_) faults_->release(now_, out_);
}

void Line::receive(const std::uint8_t* data, std::size_t n) {
  if (faults_) {
    if (!faults_->listening(now_)) return;  // silence: the bytes are lost unheard
    track_requests(data, n);
  }
  for (Member& m : modules_) m.module->receive(data, n);
  collect();
}

bool Line::window_pending() const {
  for (const Member& m : modules_)
    if (m.module->window_pending()) return true;
  return false;
}

void Line::gap_elapsed() {
  for (Member& m : modules_) m.module->gap_elapsed();
  collect();
}

void Line::drop_partial() {
  for (Member& m : modules_) m.module->drop_partial();
  window_fill_ = 0;
}

void Line::advance(SimTime until) {
  if (until > now_) now_ = until;
  for (Member& m : modules_) {
    m.module->advance(now_ - m.offset);
    collect();
  }
  if (faults_) faults_->release(now_, out_);
}

SimTime Line::next_wakeup() const {
  SimTime next = faults_ ? faults_->next_release() : kNever;
  for (const Member& m : modules_) {
    const SimTime w = m.module->next_wakeup();
    if (w != kNever) next = std::min(next, w + m.offset);
  }
  return next;
}

}  // namespace tmcl
