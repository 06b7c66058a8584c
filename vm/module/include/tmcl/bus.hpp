// The line the virtual module's I/O loop (serve) talks over: one module, or several on one bus
// as on RS-485 (tmclrun --serve pty --module 1:a.tmc --module 2:b.tmc), optionally with fault
// injection (faults.hpp) between the modules and the host.
//
// Every module hears every byte and keeps its own framing, VM, profile, EEPROM image and
// address; only the addressed one answers (a request for another address is "foreign" to it).
// The line has one clock, simulated time since serving began: each module runs on it with its
// own offset, which a software reset (255, 137) moves so that the module restarts at 0 without
// the others noticing.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tmcl/faults.hpp"
#include "tmcl/server.hpp"

namespace tmcl {

class Line {
 public:
  // `primary` with options.protocol, then each of options.bus; options.faults when not empty.
  Line(Vm& primary, const ServeOptions& options);

  void receive(const std::uint8_t* data, std::size_t n);
  bool window_pending() const;
  void gap_elapsed();
  void drop_partial();
  void advance(SimTime until);
  SimTime next_wakeup() const;
  // Always false: power cycles are absorbed by the per-module offsets.
  bool take_power_cycle() { return false; }
  std::vector<std::uint8_t>& output() { return out_; }
  void set_on_message(const std::function<void(const std::string&)>& f);

  TmclModule& primary() { return *modules_.front().module; }
  std::size_t size() const { return modules_.size(); }
  const FaultInjector* faults() const { return faults_ ? &*faults_ : nullptr; }

 private:
  void collect();
  void track_requests(const std::uint8_t* data, std::size_t n);

  struct Member {
    std::unique_ptr<TmclModule> module;
    Vm* vm;
    SimTime offset = 0;  // line time at which this module's simulated time was 0
  };
  std::vector<Member> modules_;
  std::optional<FaultInjector> faults_;
  std::vector<std::uint8_t> out_;
  SimTime now_ = 0;          // the line's clock: the last instant advanced to
  std::uint8_t window_[9]{};  // the last 9 bytes received, to know which command a reply answers
  std::size_t window_fill_ = 0;
  int last_command_ = -1;
};

}  // namespace tmcl
