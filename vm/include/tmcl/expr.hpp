// The debugger's expressions and what they know of the program, in the VM's layer so that every
// front end that inspects a machine shares one vocabulary: the debugger (print, display, set var,
// conditions, watchpoints) and the test runner's expectations (cli/testrun). ProgramInfo is a
// program with its source places, texts, labels and constants; an Expr is parsed once against it
// and evaluated on a live VM.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tmcl/vm.hpp"

namespace tmcl {

// What the debugger knows of the program: its instructions, the source place of each, the
// sources' text (for `list`), labels and constants.
struct ProgramInfo {
  std::vector<Instruction> program;
  struct Line {
    int file = -1;  // index into files; -1: unknown (a .bin without line table, appended STOP)
    int line = 0;
  };
  std::vector<Line> lines;  // per address (may be shorter than program)
  struct File {
    std::string name;
    std::vector<std::string> text;  // lines; empty when the text is not at hand
    std::string path = {};          // a .bin's source: the absolute path where it was found
  };
  std::vector<File> files;
  std::vector<std::pair<std::string, std::int64_t>> labels;     // name, address
  std::vector<std::pair<std::string, std::int64_t>> constants;  // name, value

  std::string place(std::int32_t address) const;         // "prog.tmc:12", or "" when unknown
  std::string function_of(std::int32_t address) const;   // "loop", "loop+2", or ""
  std::optional<std::int64_t> symbol(const std::string& name) const;  // label or constant (case-insensitive)
  const std::string* source_text(std::int32_t address) const;  // that address's source line, if known
};

// ---- expressions: registers, v[n], ap(param, motor), gp(bank, n), in(n), ain(n), out(n), time,
// steps, pc, position M and velocity M (ap(1, M), ap(3, M)), labels and constants, with C's
// operators; durations like 2s are microseconds ----
struct Expr {
  struct Node {
    enum Kind : std::uint8_t { Num, Reg, Var, Ap, Gp, In, Ain, Out, Unary, Binary } kind = Num;
    std::int64_t value = 0;  // Num; Reg: which register; Unary/Binary: the operator
    int a = -1, b = -1;      // operand nodes
    // Where the node is in `text` (bytes), for a caret under it.
    std::uint32_t at = 0, len = 0;
  };
  std::vector<Node> nodes;
  int root = -1;
  std::string text;
  bool uses_time() const;    // reads time or motion state: may change between instructions
  bool assignable() const;   // the root is a register, variable or parameter
};
// On failure `error` says what and, when `error_at` is given, it receives the byte offset in
// `text` where the mistake is (for a caret under it).
bool parse_expr(const std::string& text, const ProgramInfo& info, Expr& out, std::string& error,
                std::size_t* error_at = nullptr);
// What an expression reads: a VM (eval_expr on a Vm below), or a module through its host
// protocol (tmclctl PORT test). A read that cannot be made is false with `error` saying why.
class ExprReader {
 public:
  enum Reg : std::uint8_t { Acc, X, Flags, Errors, Pc, Sp, Time, Steps };
  virtual ~ExprReader() = default;
  virtual int motors() const = 0;
  virtual bool reg(Reg r, std::int64_t& out, std::string& error) = 0;
  virtual bool var(int n, std::int64_t& out, std::string& error) = 0;                   // 0..255
  virtual bool axis(int param, int motor, std::int64_t& out, std::string& error) = 0;   // motor < motors()
  virtual bool global(int bank, int param, std::int64_t& out, std::string& error) = 0;
  // in(n), ain(n), out(n): `kind` is Expr::Node::In, Ain or Out; n < Vm::kPorts.
  virtual bool port(int kind, int n, std::int64_t& out, std::string& error) = 0;
};
bool eval_expr(const Expr& e, ExprReader& reader, std::int64_t& value, std::string& error);
// Evaluates on the VM; false with `error` (e.g. "no axis parameter 300 on usb-2-sd").
bool eval_expr(const Expr& e, Vm& vm, std::int64_t& value, std::string& error);
// Assigns to the expression's root (set var): through the VM's parameter rules.
bool assign_expr(const Expr& e, Vm& vm, std::int64_t value, std::string& error);

}  // namespace tmcl
