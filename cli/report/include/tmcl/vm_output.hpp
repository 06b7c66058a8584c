// What tmclrun shows of a run, as stable text: the per-instruction trace, the JSON state dump
// and the exit summary. In the library so that tests and embedders can reach it.
#pragma once

#include <cstdio>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "tmcl/source_names.hpp"
#include "tmcl/vm.hpp"

namespace tmcl {

// The instruction as source text, expanded from the instruction table: "MVP ABS, 0, 51200".
// Keyword operands print by name when the value has one; unknown opcodes as "db op,type,motor,value".
std::string instruction_text(const Instruction& ins);

// Where each program address came from, e.g. "prog.tmc:12"; empty strings when unknown.
using SourceMap = std::vector<std::string>;

// --trace: one line per executed instruction and per interrupt, motion event and wait end:
//   0.000020s     3 prog.tmc:4       SAP 4, 0, 51200              A=0 X=0 F=- E=-
// The source and instruction columns are as wide as the program's longest (at least 16 and 28
// characters), so the columns stay aligned whatever the paths. With `names` an instruction shows
// the names its source gave (`JC LT, Loop`, source_names.hpp) and, where that differs from the
// plain form, the plain form with its numbers in a comment at the end: `// JC LT, 3`.
// A core in chip units (tmc429) has the units in force said once after the first instruction and
// again after each that changed them (SAP 153/154: the step rate changes at once):
//   0.000040s  units: TMC429 units: pulse divisor 1, ramp divisor 7: velocity 1 = 244.141 pps, ...
class TextTrace final : public TraceSink {
 public:
  TextTrace(std::FILE* out, const SourceMap* sources, const SourceNames* names = nullptr)
      : out_(out), sources_(sources), names_(names) {}
  void instruction(const Vm& vm, SimTime at, std::int32_t pc, const Instruction& ins) override;
  void interrupt_enter(const Vm& vm, int vector, std::int32_t from_pc) override;
  void interrupt_leave(const Vm& vm, std::int32_t to_pc) override;
  void motion_event(const Vm& vm, const MotionEvent& ev) override;
  void wait_end(const Vm& vm, std::int32_t pc, bool timeout) override;
  void input_event(const Vm& vm, const std::string& what) override;
  void warning(const Vm& vm, const RuntimeWarning& w) override;

  // Called once, after the first line that could not be written (a closed pipe, a full disk):
  // tmclrun ends the run then (RunControl::output_closed).
  std::function<void()> write_failed;

 private:
  std::string where(std::int32_t pc) const;
  void written();
  void measure(const Vm& vm);
  std::FILE* out_;
  const SourceMap* sources_;
  const SourceNames* names_;
  bool failed_ = false;
  int source_width_ = 0, text_width_ = 0;  // 0: not measured yet
  std::string units_;                      // the units note last traced
};

// "ZE EQ" style flag names; "-" when none.
std::string flags_text(std::uint8_t flags);
std::string errors_text(std::uint8_t errors);

// --json: one object (see docs/tmclrun.md for every key), ending in a newline.
std::string state_json(Vm& vm, const RunResult& result);

// The motors a summary, CSV and plot show: every motor of the module; under a profile that
// stands for any module (generic, with six), those the program names in a motor operand or that
// moved, in order (none when there are none).
std::vector<int> shown_motors(Vm& vm);

// The default exit summary: the halt on one line (a fault by kind and place only: its message is
// the error tmclrun prints), time, steps, the position of each shown motor, each user variable
// whose value differs from `vars_at_start` (its value at power-on; null: 0), run-time warnings.
std::string state_summary(Vm& vm, const RunResult& result, const std::array<std::int32_t, 256>* vars_at_start = nullptr);

// tmclrun --serve --trace: one line per answered request, e.g.
//   1.250000s module 1: MVP ABS, 0, 51200 -> 100 ok, value 51200
// (the request as source text, the reply's status as a number and in words; "(reply
// suppressed)" when global 255 kept the reply back). `reply` is the reply's nine bytes; when
// `special` they have the layout of 134 or 136 type 0 and show as what they carry:
//   0.000000s module 1: 134 ReadProgramMemory, type 0, motor 0, value 0 -> SAP 4, 0, 51200
//   0.000000s module 1: 136 GetFirmwareVersion, type 0, motor 0, value 0 -> "0015V114"
// An opcode-0 request or word is the end marker of a download: "end marker (NOP)".
std::string exchange_text(SimTime at, int module, const Instruction& request, const Frame& reply, bool special, bool sent);
// The reply status in words: 100 "ok", 4 "invalid value", ...; "status N" when unknown.
std::string status_text(int status);

// --json when there is no run to report (a bad option, assembly errors, an unreadable program,
// scenario or EEPROM file): one object (tmcl::json, one key per line), so a script always has
// JSON to parse: {"error":"input","exit":65,"message":"<the first diagnostic's message>",
//   "diagnostics":[{"file":"p.tmc","line":3,"column":5,"severity":"error","name":null,"message":"..."}],
//   "more":0}
// `kind` is usage, input or io; `more` counts diagnostics left out by --error-limit; a missing
// place is file "" and line/column 0; `name` is a warning's -W name, null for unnamed ones.
struct JsonDiagnostic {
  std::string file;
  int line = 0, column = 0;
  std::string severity = "error", name, message;
};
std::string error_json(std::string_view kind, int exit_status, const std::vector<JsonDiagnostic>& diags,
                       long long more);

}  // namespace tmcl
