// Instructions as the source named their operands, for disassemble and x/i (docs/debugger.md):
// a jump, call or vector target by its label, an operand the source wrote with a constant by
// that constant ("JC LT, loop", "COMP Limit"), the numbers kept in a note ("loop = 5"). The
// source line is read back only to learn which operands it named, and a name is shown only when
// it evaluates to the value the instruction holds, so a stale or odd line falls back to numbers.
#include <cctype>

#include "tmcl/asm/disasm.hpp"
#include "tmcl/debugger.hpp"

namespace tmcl::debug {
namespace {

std::string strip(const std::string& s) {
  std::size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

bool ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// The operand texts of a source line: after an optional "label:" and the mnemonic, split at the
// commas outside parentheses; comments (//, ;, /*) cut off.
std::vector<std::string> operand_texts(std::string line) {
  for (const char* mark : {"//", ";", "/*"})
    if (auto at = line.find(mark); at != std::string::npos) line.resize(at);
  std::size_t i = line.find_first_not_of(" \t");
  if (i == std::string::npos) return {};
  std::size_t word = i;
  while (word < line.size() && ident_char(line[word])) ++word;
  if (word < line.size() && line[word] == ':') {  // a label first
    i = line.find_first_not_of(" \t", word + 1);
    if (i == std::string::npos) return {};
  }
  while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;  // the mnemonic
  std::vector<std::string> out;
  std::string cur;
  int nesting = 0;
  for (; i < line.size(); ++i) {
    char c = line[i];
    if (c == '(') ++nesting;
    if (c == ')') --nesting;
    if (c == ',' && nesting == 0) {
      out.push_back(strip(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!strip(cur).empty() || !out.empty()) out.push_back(strip(cur));
  return out;
}

bool names_something(const std::string& text, const ProgramInfo& info) {
  for (std::size_t i = 0; i < text.size();) {
    if (std::isalpha(static_cast<unsigned char>(text[i])) || text[i] == '_') {
      std::size_t j = i;
      while (j < text.size() && ident_char(text[j])) ++j;
      if (info.symbol(text.substr(i, j - i))) return true;
      i = j;
    } else {
      ++i;
    }
  }
  return false;
}

}  // namespace

std::string named_instruction(const ProgramInfo& info, const Instruction& ins, std::int32_t address, Vm& vm,
                              std::string* numbers) {
  const OpInfo* op = op_info(ins.op);
  if (!op || op->control) return format_instruction(ins);
  std::vector<std::string> written;
  if (const std::string* line = info.source_text(address); line && address >= 0 &&
                                                      static_cast<std::size_t>(address) < info.program.size() && info.program[static_cast<std::size_t>(address)] == ins)
    written = operand_texts(*line);
  if (written.size() != op->operands.size()) written.clear();
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
    if (name.empty() && i < written.size() && names_something(written[i], info)) {
      Expr e;
      std::string err;
      std::int64_t v = 0;
      bool constant = parse_expr(written[i], info, e, err);
      for (const auto& n : e.nodes)
        constant = constant && (n.kind == Expr::Node::Num || n.kind == Expr::Node::Unary || n.kind == Expr::Node::Binary);
      if (constant && eval_expr(e, vm, v, err) && (v == value || (spec.field != Field::Value && (v & 255) == value)))
        name = written[i];
    }
    if (name.empty()) continue;
    names[spec.field] = name;
    notes += (notes.empty() ? "" : ", ") + name + " = " + std::to_string(value);
  }
  if (numbers) *numbers = notes;
  return names.empty() ? format_instruction(ins) : format_instruction(ins, names);
}

}  // namespace tmcl::debug
