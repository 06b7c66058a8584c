// Fault injection for the virtual module (tmclrun --serve --faults SPEC): the line between the
// module and the host misbehaves on purpose, so that host software — tmclctl, PyTrinamic
// scripts, a PLC — can be tested against what real RS-485 and USB lines do. Docs:
// docs/virtual-module.md, "Faults".
//
//   SPEC := RULE { ',' RULE }
//   RULE := KIND ['=' DURATION] ['@' WHEN]  |  'seed=' N
//   KIND := drop | corrupt | delay | split | silence | stale
//   WHEN := N            the Nth reply on the line (1-based)
//         | every=N      every Nth reply
//         | cmd=C        every reply to command C (a number or a mnemonic: cmd=134, cmd=GAP)
//         | cmd=C#K      only the Kth reply to command C
//         | p=X          each reply with probability X (0 < X <= 1), drawn from the seed
//   no '@': every reply.
//
// drop: the reply is not sent. corrupt: its checksum byte is wrong. delay=D: it is sent D later.
// split[=D]: its first 4 bytes go out at once, the other 5 after D (default 5ms). silence=D: the
// reply is not sent and every request arriving in the next D is ignored unexecuted (a module
// rebooting or a bus held by another master). stale: the previous reply on the line is sent
// again just before this one. Several rules can hit one reply: silence or drop win; otherwise a
// delay, the stale copy, the corruption and the split all apply. Durations are wall-clock time
// (the injector converts them with --time-scale). For a given seed and request sequence the
// same replies are hit every time.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tmcl/sim_time.hpp"

namespace tmcl {

struct FaultRule {
  enum Kind : std::uint8_t { Drop, Corrupt, Delay, Split, Silence, Stale } kind = Drop;
  enum When : std::uint8_t { Always, Nth, Every, Command, Probability } when = Always;
  SimTime duration = 0;     // delay, split pause, silence (microseconds of wall-clock time)
  std::uint64_t n = 0;      // Nth, Every; Command: the Kth (0: every)
  int command = -1;         // Command
  double probability = 0;   // Probability
};

struct FaultPlan {
  std::vector<FaultRule> rules;
  std::uint64_t seed = 1;
  bool empty() const { return rules.empty(); }
};

// Parses SPEC; false with `error` naming the bad rule.
bool parse_faults(std::string_view spec, FaultPlan& plan, std::string& error);
std::string_view fault_kind_name(FaultRule::Kind kind);

// Applies a plan to the replies of a line. Time is the line's clock (simulated microseconds,
// monotonic); `scale` converts the plan's wall-clock durations to it.
class FaultInjector {
 public:
  FaultInjector(FaultPlan plan, double scale);

  // One reply frame produced at `now`, answering command `command` (-1: unknown).
  void reply(const std::uint8_t* frame, std::size_t n, int command, SimTime now);
  // False while a silence lasts: incoming bytes are to be ignored.
  bool listening(SimTime now) const { return now >= silent_until_; }
  // Appends the bytes due by `now` to `out`, in order.
  void release(SimTime now, std::vector<std::uint8_t>& out);
  // When the next held byte falls due (kNever: nothing held).
  SimTime next_release() const;

  struct Counters {
    std::uint64_t replies = 0, dropped = 0, corrupted = 0, delayed = 0, split = 0, silenced = 0, stale = 0;
  };
  const Counters& counters() const { return counters_; }

 private:
  bool hits(FaultRule& rule, std::size_t index, int command);
  std::uint64_t next_random();

  FaultPlan plan_;
  double scale_;
  std::uint64_t state_;
  std::vector<std::uint64_t> command_counts_;  // per rule: replies to its command seen
  std::vector<std::uint8_t> previous_;         // the last reply sent (for stale)
  struct Held {
    SimTime due;
    std::vector<std::uint8_t> bytes;
  };
  std::vector<Held> held_;  // in due order
  SimTime silent_until_ = 0;
  Counters counters_;
};

}  // namespace tmcl
