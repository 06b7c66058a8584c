// named_instruction_text (source_names.hpp): the instruction table expanded with a program's names.
#include "tmcl/source_names.hpp"

#include "tmcl/isa.hpp"

namespace tmcl {

std::string named_instruction_text(const Instruction& ins, std::int64_t address, const SourceNames* names) {
  const OpInfo* info = op_info(ins.op);
  if (!info || info->control)
    return "?? " + std::to_string(ins.op) + ", " + std::to_string(ins.type) + ", " + std::to_string(ins.motor) + ", " +
           std::to_string(ins.value);
  const std::array<std::string, 3>* named = nullptr;
  if (names && address >= 0 && static_cast<std::size_t>(address) < names->operands.size())
    named = &names->operands[static_cast<std::size_t>(address)];
  std::string s(info->mnemonic);
  bool first = true;
  for (const auto& o : info->operands) {
    s += first ? " " : ", ";
    first = false;
    const auto field = static_cast<std::size_t>(o.field);
    if (named && !(*named)[field].empty()) {
      s += (*named)[field];
      continue;
    }
    const std::int64_t v = o.field == Field::Type ? ins.type : o.field == Field::Motor ? ins.motor : ins.value;
    if (o.role == Role::Address && names) {
      if (auto it = names->labels.find(v); it != names->labels.end()) {
        s += it->second;
        continue;
      }
    }
    if (o.keywords != KwSet::None && v >= 0 && v <= 255) {
      if (auto name = keyword_name(o.keywords, static_cast<std::uint8_t>(v))) {
        s += *name;
        continue;
      }
    }
    s += std::to_string(v);
  }
  return s;
}

}  // namespace tmcl
