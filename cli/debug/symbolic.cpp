// Instructions as the source named their operands, for disassemble and x/i (docs/debugger.md):
// a jump, call or vector target by its label, an operand the source wrote with a constant by
// that constant ("JC LT, loop", "COMP Limit"), the numbers kept in a note ("loop = 5"). The
// source line is read back (named_operands, asm/names.hpp, as for --trace) only to learn which
// operands it named, and a name is shown only when it evaluates to the value the instruction
// holds, so a stale or odd line falls back to numbers.
#include <array>
#include <map>

#include "tmcl/asm/disasm.hpp"
#include "tmcl/asm/names.hpp"
#include "tmcl/debugger.hpp"

namespace tmcl::debug {

std::string named_instruction(const ProgramInfo& info, const Instruction& ins, std::int32_t address, Target& target,
                              std::string* numbers) {
  const OpInfo* op = op_info(ins.op);
  if (!op || op->control) return format_instruction(ins);
  std::array<std::string, 3> written{};  // per field, as the source named it (asm/names.hpp)
  if (const std::string* line = info.source_text(address); line && address >= 0 &&
                                                      static_cast<std::size_t>(address) < info.program.size() && info.program[static_cast<std::size_t>(address)] == ins)
    written = named_operands(*line, ins);
  std::map<Field, std::string> names;
  std::string notes;
  for (std::size_t i = 0; i < op->operands.size(); ++i) {
    const OperandSpec& spec = op->operands[i];
    if (spec.keywords != KwSet::None) continue;
    const std::int64_t value = spec.field == Field::Value ? ins.value : static_cast<std::int64_t>(field_of(ins, spec.field));
    std::string name;
    if (spec.role == Role::Address) {
      for (const auto& l : info.labels)
        if (l.second == value) {
          name = l.first;
          break;
        }
    }
    const std::string& text = written[static_cast<std::size_t>(spec.field)];
    if (name.empty() && !text.empty()) {
      Expr e;
      std::string err;
      std::int64_t v = 0;
      bool constant = parse_expr(text, info, e, err);
      for (const auto& n : e.nodes)
        constant = constant && (n.kind == Expr::Node::Num || n.kind == Expr::Node::Unary || n.kind == Expr::Node::Binary);
      if (constant && target.eval(e, v, err) && (v == value || (spec.field != Field::Value && (v & 255) == value)))
        name = text;
    }
    if (name.empty()) continue;
    names[spec.field] = name;
    notes += (notes.empty() ? "" : ", ") + name + " = " + std::to_string(value);
  }
  if (numbers) *numbers = notes;
  return names.empty() ? format_instruction(ins) : format_instruction(ins, names);
}

}  // namespace tmcl::debug
