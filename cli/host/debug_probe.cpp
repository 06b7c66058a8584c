// debug_probe (debug_probe.hpp): the request sequence of `tmclctl PORT debug --probe` and its
// report. Every 135 value is shown raw as well as decoded, because the layout of its low three
// bytes is tmcl's reading (docs/virtual-module.md), not a documented fact
// (shared reference: on-module-debugging.md 1.1): a report from a real module settles it.
// 130 is never resent: a step repeated would run a second instruction.
#include "tmcl/host/debug_probe.hpp"

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <thread>

#include "tmcl/asm/disasm.hpp"
#include "tmcl/host/commands.hpp"
#include "tmcl/fileio.hpp"
#include "tmcl/image.hpp"

namespace tmcl::host {
namespace {

Instruction make(Op op, int type = 0, int motor = 0, std::int32_t value = 0) {
  return Instruction{static_cast<std::uint8_t>(op), static_cast<std::uint8_t>(type), static_cast<std::uint8_t>(motor), value};
}

// The probe program. Known A and X before the WAIT; the CSUB's subroutine changes A, so that
// stepping into it and over it differ; the JA to itself is the breakpoint patch's instruction.
constexpr std::int32_t kA = 4711, kX = 1234;
constexpr int kWaitAt = 3, kCsubAt = 4, kSubAt = 7;
std::vector<Instruction> probe_program(int wait_ticks) {
  return {make(Op::CALC, kw::CalcA::LOAD, 0, kX),         // 0
          make(Op::CALCX, kw::CalcX::SWAP),                // 1: X = 1234, A = 0
          make(Op::CALC, kw::CalcA::LOAD, 0, kA),          // 2
          make(Op::WAIT, kw::Wait::TICKS, 0, wait_ticks),  // 3
          make(Op::CSUB, 0, 0, kSubAt),                    // 4
          make(Op::JA, 0, 0, 5),                           // 5: spins
          make(Op::STOP),                                  // 6
          make(Op::CALC, kw::CalcA::ADD, 0, 1),            // 7
          make(Op::RSUB)};                                 // 8
}

std::string hex32(std::int32_t v) {
  char buf[12];
  std::snprintf(buf, sizeof buf, "%08" PRIX32, static_cast<std::uint32_t>(v));
  return buf;
}

// 135 types 0/1 as tmcl reads them: mode byte 3, wait flag byte 2, address bytes 1-0.
struct Status {
  std::int32_t raw = 0;
  std::uint32_t mode() const { return static_cast<std::uint32_t>(raw) >> 24; }
  bool waiting() const { return (static_cast<std::uint32_t>(raw) >> 16 & 0xFF) != 0; }
  int pc() const { return static_cast<int>(static_cast<std::uint32_t>(raw) & 0xFFFF); }
  std::string text() const {
    return "mode " + std::to_string(mode()) + " (" + mode_name(mode()) + "), wait flag " + (waiting() ? "1" : "0") +
           ", pc " + std::to_string(pc());
  }
};

class Prober {
 public:
  Prober(Client& c, const DebugProbeOptions& o) : c_(c), opt_(o) {}
  DebugProbeResult run();

 private:
  bool ask(const Instruction& ins, Reply& reply, bool retry = true);
  bool ask_ok(const Instruction& ins, Reply& reply, bool retry = true);
  bool status(int type, Status& s);
  bool accumulator(std::int32_t& a);
  bool step(Status& after);
  void raw(const std::string& label, const std::string& text) {
    std::string l = "  " + label;
    l.resize(l.size() < 34 ? 34 : l.size() + 1, ' ');
    raw_ += l + text + "\n";
  }
  void found(const std::string& label, const std::string& text) {
    std::string l = "  " + label + ":";
    l.resize(l.size() < 30 ? 30 : l.size() + 1, ' ');
    found_ += l + text + "\n";
  }
  void choice(const std::string& text) { choices_ += "  - " + text + "\n"; }
  bool fail(Outcome o, const std::string& message) {
    out_.outcome = o;
    out_.message = message;
    return false;
  }
  bool probe();
  void put_back();
  std::string compose() const;

  Client& c_;
  const DebugProbeOptions& opt_;
  DebugProbeResult out_;
  std::vector<Instruction> saved_;
  bool saved_ok_ = false, changed_ = false;
  std::uint32_t mode_before_ = 0;
  std::string raw_, found_, choices_, restored_;
};

bool Prober::ask(const Instruction& ins, Reply& reply, bool retry) {
  Result r = c_.request(ins, retry);
  if (r.ok()) {
    reply = r.reply;
    return true;
  }
  const Outcome o = r.fail == Fail::Cancelled ? Outcome::Cancelled : r.fail == Fail::Port ? Outcome::Port : Outcome::NoReply;
  return fail(o, r.error);
}

bool Prober::ask_ok(const Instruction& ins, Reply& reply, bool retry) {
  if (!ask(ins, reply, retry)) return false;
  if (reply.status == kStatusOk) return true;
  return fail(Outcome::BadStatus, "the module answered " + std::to_string(reply.status) + " (" + status_text(reply.status) +
                                      ") to " + c_.describe(ins));
}

bool Prober::status(int type, Status& s) {
  Reply r;
  if (!ask_ok(make(Op::GetApplicationStatus, type), r)) return false;
  s.raw = r.value;
  return true;
}

bool Prober::accumulator(std::int32_t& a) {
  Status s;
  if (!status(2, s)) return false;
  a = s.raw;
  return true;
}

// One 130 (never resent), then 135 type 1. A firmware that answers a step in a WAIT only when the
// wait is over (S24) needs the wait's length on top of the reply timeout.
bool Prober::step(Status& after) {
  Reply r;
  const int timeout = c_.options().timeout_ms;
  c_.set_timeout(timeout + opt_.wait_ticks * 10 + 1000);
  const bool ok = ask_ok(make(Op::StepApplication), r, false);
  c_.set_timeout(timeout);
  return ok && status(1, after);
}

bool Prober::probe() {
  Reply r;
  Status s;
  // Does the firmware have the control commands at all? (The published stepRocker mini-TMCL
  // answers 135 with status 2.)
  if (!ask(make(Op::GetApplicationStatus, 1), r)) return false;
  if (r.status != kStatusOk) {
    found("135 (application status)", "status " + std::to_string(r.status) + " (" + status_text(r.status) + ")");
    choice("none: without 135 the debugger cannot see where a program is (this firmware has no stand-alone TMCL "
           "programs, or does not let a host control them)");
    return fail(Outcome::BadStatus, "the module answered " + std::to_string(r.status) + " (" + status_text(r.status) +
                                        ") to 135: it cannot be debugged");
  }
  mode_before_ = static_cast<std::uint32_t>(r.value) >> 24;
  raw("before the probe", "135/1 " + hex32(r.value));

  // The module's program, kept to put back.
  TransferResult t = upload(c_, opt_.memory, saved_, nullptr);
  if (t.outcome != Outcome::Ok) return fail(t.outcome, t.message);
  saved_ok_ = true;
  if (!ask_ok(make(Op::StopApplication), r)) return false;
  changed_ = true;
  const std::vector<Instruction> program = probe_program(opt_.wait_ticks);
  t = download(c_, program, 0, opt_.memory, nullptr);
  if (t.outcome == Outcome::Ok) t = verify(c_, program, 0, opt_.memory, nullptr);
  if (t.outcome != Outcome::Ok) return fail(t.outcome, "loading the probe program: " + t.message);

  // After reset.
  Status s0, s1;
  std::int32_t a = 0, x = 0;
  if (!ask_ok(make(Op::ResetApplication), r) || !status(0, s0) || !status(1, s1) || !accumulator(a) || !status(3, s))
    return false;
  x = s.raw;
  raw("after 131", "135/0 " + hex32(s0.raw) + "  135/1 " + hex32(s1.raw) + "  A " + std::to_string(a) + "  X " +
                       std::to_string(x));
  found("after reset (131)", s1.text() + ", A " + std::to_string(a) + ", X " + std::to_string(x) +
                                 (s1.mode() == 0 ? " (as tmclrun --variant reset-reports-stopped)" : ""));
  const std::uint32_t reset_mode = s1.mode();

  // Running, inside the WAIT: the three instructions before it take microseconds, yet a fast
  // line asks sooner; polled until the wait flag shows (half a second at most).
  if (!ask_ok(make(Op::RunApplication), r) || !status(1, s1)) return false;
  for (const auto until = Clock::now() + std::chrono::milliseconds(500);
       s1.mode() == 1 && s1.pc() <= kWaitAt && !s1.waiting() && Clock::now() < until;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    if (!status(1, s1)) return false;
  }
  if (!accumulator(a) || !status(3, s)) return false;
  x = s.raw;
  raw("after 129, in the WAIT", "135/1 " + hex32(s1.raw) + "  A " + std::to_string(a) + "  X " + std::to_string(x));
  found("running, in the WAIT", s1.text() + ", A " + std::to_string(a) + ", X " + std::to_string(x));
  const bool layout = s1.mode() == 1 && s1.pc() == kWaitAt && s1.waiting() && a == kA && x == kX;
  if (!layout)
    found("note", "not mode 1, wait flag 1, pc 3, A 4711, X 1234 as tmcl reads 135: see the raw values");

  // Stopped inside the WAIT.
  if (!ask_ok(make(Op::StopApplication), r) || !status(1, s1)) return false;
  raw("after 128", "135/1 " + hex32(s1.raw));
  found("after stop (128)", s1.text());
  const bool in_wait = s1.pc() == kWaitAt && s1.waiting();

  // 130 in the WAIT: at once with the wait flag set, or when the wait is over.
  Status s2;
  const auto t0 = Clock::now();
  if (!step(s2)) return false;
  const auto took = Clock::now() - t0;
  raw("after 130 in the WAIT", "135/1 " + hex32(s2.raw));
  enum class StepWait { AtOnce, WhenOver, Unknown } step_wait = StepWait::Unknown;
  if (!in_wait) {
    found("130 during a WAIT", "not checked: the WAIT was over before 130 was sent (a slow line?)");
  } else if (s2.pc() == kWaitAt && s2.waiting()) {
    step_wait = StepWait::AtOnce;
    found("130 during a WAIT", "answers at once, the wait flag still set");
  } else if (s2.pc() == kCsubAt && !s2.waiting() &&
             took >= std::chrono::milliseconds(opt_.wait_ticks)) {  // a tenth of the wait (ticks of 10 ms)
    step_wait = StepWait::WhenOver;
    found("130 during a WAIT", "answers when the wait is over (as tmclrun --variant step-waits)");
  } else {
    found("130 during a WAIT", "unexpected: " + s2.text());
  }
  // Step until the WAIT is behind (at once: a few polls, as the debugger does).
  const auto deadline = Clock::now() + std::chrono::milliseconds(opt_.wait_ticks * 10 + 3000);
  while (s2.pc() == kWaitAt && Clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (!step(s2)) return false;
  }
  raw("after the WAIT", "135/1 " + hex32(s2.raw));

  // 130 on the CSUB: into the subroutine, or over it.
  enum class StepCall { Into, Over, Unknown } step_call = StepCall::Unknown;
  if (s2.pc() != kCsubAt) {
    found("130 on a CSUB", "not checked: the program did not reach the CSUB by stepping (" + s2.text() + ")");
  } else {
    if (!step(s2) || !accumulator(a)) return false;
    raw("after 130 on the CSUB", "135/1 " + hex32(s2.raw) + "  A " + std::to_string(a));
    if (s2.pc() == kSubAt) {
      step_call = StepCall::Into;
      found("130 on a CSUB", "enters the subroutine (pc 7)");
    } else if (s2.pc() == kCsubAt + 1) {
      step_call = StepCall::Over;
      found("130 on a CSUB", "runs the subroutine as one step (pc 5)");
    } else {
      found("130 on a CSUB", "unexpected: " + s2.text());
    }
  }

  // A direct GAP while stopped, then the accumulator.
  std::int32_t before = 0, after = 0;
  if (!ask_ok(make(Op::StopApplication), r) || !accumulator(before)) return false;
  const Instruction gap = make(Op::GAP, 4, 0);
  if (!ask(gap, r)) return false;
  if (!accumulator(after)) return false;
  raw("GAP 4, 0 while stopped", "A " + std::to_string(before) + " before, reply " + std::to_string(r.status) + " value " +
                                    std::to_string(r.value) + ", A " + std::to_string(after) + " after");
  enum class Reads { LeaveA, LoadA, Unknown } reads = Reads::Unknown;
  if (r.status != kStatusOk) {
    found("direct GAP while stopped", "not checked: GAP 4, 0 answered " + std::to_string(r.status));
  } else if (r.value == before) {
    found("direct GAP while stopped", "not checked: GAP 4, 0 read " + std::to_string(r.value) + ", the value A held");
  } else if (after == before) {
    reads = Reads::LeaveA;
    found("direct GAP while stopped", "leaves the accumulator alone");
  } else if (after == r.value) {
    reads = Reads::LoadA;
    found("direct GAP while stopped", "loads the accumulator (as tmclrun --variant direct-read-sets-a)");
  } else {
    found("direct GAP while stopped", "unexpected: A became " + std::to_string(after));
  }

  // 134 at the last address of program memory and one past it.
  enum class PastEnd { Refused, Zero, Other, Unknown } past_end = PastEnd::Unknown;
  if (opt_.memory <= 0) {
    found("134 past the end", "not checked: the size of program memory is not known (give -t)");
  } else {
    for (int at : {opt_.memory - 1, opt_.memory}) {
      if (!ask(make(Op::ReadProgramMemory, 0, 0, at), r)) return false;
      const bool stored = r.status == kStatusOk && r.op == static_cast<std::uint8_t>(Op::ReadProgramMemory);
      const std::string word = r.stored.op == 0 ? std::string("opcode 0 (the end marker)") : format_instruction(r.stored);
      const std::string what =
          stored ? "reads " + word : "status " + std::to_string(r.status) + " (" + status_text(r.status) + ")";
      raw("134 at " + std::to_string(at) + (at == opt_.memory ? " (past the end)" : ""),
          what + "  [" + hex(r.bytes.data(), 9) + "]");
      if (at != opt_.memory) continue;
      if (r.status == 4) {
        past_end = PastEnd::Refused;
        found("134 past the end", "status 4 (invalid value)");
      } else if (r.status == kStatusOk && r.stored.op == 0) {
        past_end = PastEnd::Zero;
        found("134 past the end", "reads opcode 0 (as tmclrun --variant read-past-memory-zero)");
      } else {
        past_end = PastEnd::Other;
        found("134 past the end", what);
      }
    }
  }

  // What the debugger does on this module.
  if (step_wait == StepWait::AtOnce)
    choice("stepping over a WAIT: 130, then 135 until the wait flag is clear, stepping again after each poll (Ctrl-C pauses)");
  else if (step_wait == StepWait::WhenOver)
    choice("stepping over a WAIT: one 130, whose reply comes when the wait is over: the reply timeout is raised by the "
           "wait's length, and Ctrl-C is answered after it");
  else
    choice("stepping over a WAIT: 130 and 135 polls until the wait flag is clear, either way (not settled here)");
  if (step_call == StepCall::Over)
    choice("step: 130 runs a whole subroutine here, so `step` cannot enter one and says so; frames are never shown "
           "for calls not seen");
  else
    choice("step: 130 enters a CSUB; `next` steps over it with a breakpoint at the return address");
  if (reads == Reads::LeaveA)
    choice("print A, print X: 135 types 2 and 3, read at every stop before any direct GAP, GGP or GIO (here they "
           "would be safe later too)");
  else
    choice("print A, print X: 135 types 2 and 3, read at every stop before any direct GAP, GGP or GIO, which may "
           "change A on this firmware");
  choice(std::string("start (131): mode ") + std::to_string(reset_mode) + " after 131 is taken as stopped before address 0");
  if (past_end == PastEnd::Refused)
    choice("reading program memory (x, disassemble, the check at attach): 134 up to the end marker or status 4");
  else if (opt_.memory > 0)
    choice("reading program memory (x, disassemble, the check at attach): 134 up to the end marker, never at address " +
           std::to_string(opt_.memory) + " or beyond (memory past the end is not refused here)");
  return true;
}

// The module's program back, verified; the program stopped at address 0.
void Prober::put_back() {
  if (!changed_) return;
  if (opt_.before_restore) opt_.before_restore();
  c_.set_timeout(std::max(c_.options().timeout_ms, 1000));
  c_.set_retries(std::max(c_.options().retries, 3));
  Result stop = c_.request(make(Op::StopApplication));
  TransferResult t{stop.ok() ? Outcome::Ok : Outcome::NoReply, stop.error, 0};
  if (t.outcome == Outcome::Ok) t = download(c_, saved_, 0, opt_.memory, nullptr);
  if (t.outcome == Outcome::Ok) t = verify(c_, saved_, 0, opt_.memory, nullptr);
  if (t.outcome == Outcome::Ok) {
    Result reset = c_.request(make(Op::ResetApplication));
    restored_ = "the module's program (" + std::to_string(saved_.size()) + " instruction" + (saved_.size() == 1 ? "" : "s") +
                ") is back, verified with 134" + (reset.ok() ? "; stopped at address 0" : "");
    if (mode_before_ == 1) restored_ += " (it was running before the probe: `tmclctl PORT run` starts it)";
    return;
  }
  std::string why = t.message, error;
  const std::vector<std::uint8_t> bin = write_bin(saved_);
  const bool kept = write_file_atomic(opt_.rescue_path, bin, error);
  restored_ = "the module's program could NOT be put back (" + why + "); it is " +
              (kept ? "saved in " + opt_.rescue_path + ": `tmclctl PORT download " + opt_.rescue_path + "` puts it back"
                    : "lost: " + error);
  if (out_.outcome == Outcome::Ok) out_ = DebugProbeResult{t.outcome == Outcome::Ok ? Outcome::NoReply : t.outcome, restored_, {}};
}

std::string Prober::compose() const {
  std::string s = "tmcl debug probe (paste this into an issue)\n";
  s += "module:           " + opt_.module + "\n";
  s += "program memory:   " + (opt_.memory > 0 ? std::to_string(opt_.memory) + " instructions" : std::string("not known")) + "\n";
  if (saved_ok_)
    s += "module's program: " + std::to_string(saved_.size()) + " instruction" + (saved_.size() == 1 ? "" : "s") +
         " (read with 134 first, put back at the end)\n";
  if (raw_.empty() && found_.empty()) return s + (restored_.empty() ? "" : "\n" + restored_ + "\n");
  s += "\nprobe program:\n";
  const std::vector<Instruction> program = probe_program(opt_.wait_ticks);
  for (std::size_t i = 0; i < program.size(); ++i) {
    std::string n = std::to_string(i);
    s += std::string(5 - n.size(), ' ') + n + "  " + format_instruction(program[i]) + "\n";
  }
  s += "\nreplies (135/0, 135/1: the value in hex; tmcl reads byte 3 as the mode, byte 2 as the wait\n"
       "flag, bytes 1-0 as the download pointer (type 0) or the program counter (type 1)):\n";
  s += raw_;
  if (!found_.empty()) s += "\nfindings:\n" + found_;
  if (!choices_.empty()) s += "\nthe debugger's choices on this module:\n" + choices_;
  if (!restored_.empty()) s += "\n" + restored_ + "\n";
  return s;
}

DebugProbeResult Prober::run() {
  const bool ok = probe();
  put_back();  // on success a program that cannot be put back is the failure
  if (!ok) out_.message += changed_ ? "; " + restored_ : std::string("; nothing was changed on the module");
  out_.report = compose();
  return out_;
}

}  // namespace

DebugProbeResult debug_probe(Client& client, const DebugProbeOptions& options) { return Prober(client, options).run(); }

}  // namespace tmcl::host
