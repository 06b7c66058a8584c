// A module as the debugger's target (tmclctl PORT debug PROGRAM): the program runs on the module,
// driven with the control commands the manuals document (128 stop, 129 run, 130 step, 131 reset,
// 132/133 download, 134 read program memory, 135 application status) and read with GAP, GGP, GIO.
// Command 141 ("breakpoint", in firmware headers only) is not used.
//
// Breakpoints at full speed: before the program runs freely, the instruction at every enabled
// breakpoint is replaced by a jump to itself (a patch: 132 at that address, JA, 133), so the
// program spins there; the debugger sees the pc in 135, stops the program (128), puts every
// instruction back (verified with 134) and decides with the shared rules (Target) whether the
// hit stops. So while the debugger holds the program, program memory is as loaded: patches
// exist only while the program runs. Continuing from a breakpoint steps over its instruction
// (130) before the patches go back in. --no-patch debugs by stepping alone.
//
// Nothing may be left behind on the module: every way a session ends removes the patches and
// verifies them (restore()); a session killed meanwhile is recognised by the next attach (a jump
// to itself where the program has another instruction) and repaired there. docs/debugger.md,
// "Debugging on a module".
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tmcl/debug_target.hpp"
#include "tmcl/host/client.hpp"

namespace tmcl::debug {

struct ModuleSetup {
  std::string program_name;  // PROGRAM as given, for messages ("prog.tmc")
  bool patch = true;         // false: --no-patch, breakpoints by stepping alone
  int poll_ms = 2;           // between two status reads (135) while the program runs freely
  int reconnect_ms = 5000;   // a lost connection: how long the port may take to come back
  // Opens the port again after it was lost (closing the old one; null with `error` when it cannot
  // be opened now); the target then talks through the client returned.
  std::function<host::Client*(std::string& error)> reconnect;
};

class ModuleTarget final : public Target {
 public:
  ModuleTarget(host::Client& client, const Profile& profile, ProgramInfo info, ModuleSetup setup);
  ~ModuleTarget() override;

  // Reads the module's program memory (134) and the program's state (135). Patches left by a
  // killed session are put back (and said, with `notes`); any other difference from PROGRAM is
  // named and makes the commands that run the program refuse until `load`. False with `error`
  // when the module does not answer.
  bool attach(std::string& notes, std::string& error);
  // Downloads PROGRAM as tmclctl download does (end marker, read-back verify); stops it first.
  bool load(std::string& error) override;
  // Removes every patch and verifies it (134). False with `message` naming the addresses still
  // patched when the module could not be reached (also after waiting for a lost port).
  bool restore(std::string& message);
  // DAP `attach`: the program as it is on the module, nothing reset. With `stop`, a running
  // program is stopped (128) where it is; the stop (Entry) says where and in what state. Without,
  // a running program is left running (nullopt); a stopped one is reported where it stopped.
  std::optional<Stop> attached(bool stop);
  // A program running on the module while no command runs it (attached running): stopped (128)
  // where it is. False when it is not running that way.
  bool running_by_itself() const { return mode_ == 1; }
  Stop halt();
  bool loaded() const { return differs_.empty(); }
  bool lost() const { return lost_; }  // the module stopped answering
  const std::string& difference() const { return differs_; }
  // Requests sent so far (for the cost of a command: docs/performance.md).
  std::uint64_t requests() const;

  std::string name() const override { return "a module"; }
  bool eval(const Expr& e, std::int64_t& value, std::string& error) override;
  bool assign(const Expr& lhs, std::int64_t value, std::string& error) override;
  std::int32_t pc() override { return pc_; }
  std::int32_t program_size() const override { return static_cast<std::int32_t>(memory_.size()); }
  Instruction instruction(std::int32_t address) override;
  int depth() const override;
  std::vector<Frame> frames() override;
  bool frames_unknown_above() const override { return !stack_known_; }
  std::string status() override;

  Stop start(bool stop_at_entry) override;
  Stop cont() override;
  Stop step(std::uint64_t n = 1) override;
  Stop next() override;
  Stop finish() override;
  Stop until(std::int32_t address) override;
  void kill() override;
  void set_pc(std::int32_t) override {}  // the CLI refuses `jump` on a module in words
  bool can_reverse(std::string& why) const override {
    why = "the module keeps no history";
    return false;
  }
  Stop reverse_step(std::uint64_t) override { return cannot("reverse-step", "the module keeps no history"); }
  Stop reverse_next() override { return cannot("reverse-next", "the module keeps no history"); }
  Stop reverse_finish() override { return cannot("reverse-finish", "the module keeps no history"); }
  Stop reverse_continue() override { return cannot("reverse-continue", "the module keeps no history"); }
  int add_watchpoint(const std::string& text, std::string& error) override;

 private:
  class Reader;
  struct Status {
    std::uint32_t mode = 0;  // 0 stopped, 1 running, 2 step, 3 reset, 4 download
    bool wait = false;
    std::int32_t pc = 0;
  };
  bool ask(const Instruction& ins, std::int32_t& value, std::string& error, bool retry = true);
  bool read_status(Status& s, std::string& error);
  bool read_registers(std::string& error);  // A and X (135 types 2, 3), before any direct read
  // 134 at `address`; with `past_end`, status 4 (an address past the end of memory) is that.
  bool read_word(std::int32_t address, Instruction& out, std::string& error, bool* past_end = nullptr);
  // Writes `words` at their addresses in one download session (132 per address, 133 at the end);
  // a store whose reply was lost is stored again only after 132 has set the pointer again.
  bool write(const std::vector<std::pair<std::int32_t, Instruction>>& words, std::string& error);
  bool verify(const std::vector<std::pair<std::int32_t, Instruction>>& words, std::string& error);
  bool patch(const std::vector<std::int32_t>& addresses, std::string& error);
  bool unpatch(std::string& error);
  bool reconnected(std::string& error);  // the port lost: wait for it to come back
  Stop refused(const std::string& command) const;
  Stop failed(const std::string& error);  // the module did not answer: the session cannot go on
  Stop stopped_here(StopKind kind, std::string message = "");
  // A program running when a command comes (attached to a running module): stopped (128) first.
  // `ok` false with the stop to report when that failed.
  Stop hold(bool& ok);
  // One instruction (130), a WAIT with its wait: 135 is read until the wait flag is clear, with
  // 130 again for a firmware whose 130 returns at once during a WAIT.
  Stop step_one();
  // After one instruction at `at` took the program to `to`: the frames entered and left (a call,
  // a return, an interrupt handler entered when `to` is not where the instruction goes), and
  // last_delta_.
  void track(std::int32_t at, const Instruction& ins, std::int32_t to);
  // Where the instruction at `at` goes (empty: it cannot be told, a return whose caller is unknown).
  std::vector<std::int32_t> destinations(std::int32_t at, const Instruction& ins) const;
  // Runs freely until a breakpoint stops it, an address in `temps` is reached at most `goal`
  // frames deeper than now (0: this frame or an outer one; -1: an outer one), the program stops
  // or a pause; with watchpoints (or without patches) instruction by instruction. With temps,
  // the depth is counted from here: every CSUB, CALL, RSUB, RETI and RST is patched too and
  // stepped over (130), as the frames are kept while stepping.
  Stop run(const std::vector<std::int32_t>& temps, int goal);
  // `tracking`: every instruction that changes the depth is among the marks and stepped over, so
  // the frames stay known; else they are forgotten (only the frame at the stop is known).
  Stop free_run(const std::vector<std::int32_t>& marks, bool tracking, bool& paused, bool& ended);
  Stop run_to_mark(std::int32_t mark);
  bool hit_at_pc(Stop& stop);
  void waiting();  // on_wait, once the command has run a while (a quick stop reads no input meanwhile)  // the breakpoints at pc, not yet counted for this stop

  host::Client* client_;
  ModuleSetup setup_;
  std::vector<Instruction> memory_;  // program memory as loaded (read at attach, written by load)
  std::string differs_;              // why the module's program is not PROGRAM ("" when it is)
  std::vector<std::pair<std::int32_t, Instruction>> patched_;  // address, the instruction it covers
  std::int32_t pc_ = 0;
  bool waiting_ = false;        // the wait flag at the last stop
  std::uint32_t mode_ = 0;
  bool regs_valid_ = false;     // A and X read at this stop
  std::int32_t acc_ = 0, x_ = 0;
  // The frames seen entered while stepping, outermost first: a call's address, or an interrupt
  // handler's entry (the address the interrupted code resumes at, with the vector).
  std::vector<Frame> stack_;
  bool stack_known_ = true;     // false after a free run: frames above may exist
  int last_delta_ = 0;          // how the last step changed the depth (+1 entered, -1 left)
  std::int32_t counted_pc_ = -1;  // the breakpoints at this pc have had this stop's hit
  std::chrono::steady_clock::time_point command_start_{};
  bool worn_said_ = false;      // the EEPROM-wear note was given
  bool lost_ = false;           // the module stopped answering: nothing more is asked
  bool port_failed_ = false;    // the last request failed on the port itself (not a silence)
};

// tmclctl PORT debug PROGRAM: the command line (or, with dap, the Debug Adapter Protocol) on a
// module. Returns tmclctl's exit status.
struct ModuleFrontEnd {
  std::string program;          // .tmc, or .bin/.dgm with symbols
  std::string symbols;          // --symbols FILE
  std::vector<std::string> source_dirs;
  std::vector<std::string> include_dirs;  // -I
  std::string commands_file;    // --debug-commands FILE
  bool dap = false;
  ModuleSetup setup;
};
int debug_module(host::Client& client, const Profile& profile, ModuleFrontEnd fe, std::FILE* in, std::FILE* out);

// The addresses of `words` that hold a jump to themselves (JA N at address N), the mark of a
// breakpoint patch a debugger left: tmclctl download and upload warn about them.
std::vector<std::int32_t> self_jumps(const std::vector<Instruction>& words);

}  // namespace tmcl::debug
