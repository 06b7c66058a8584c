// The disassembler. The one rule: the source it writes reassembles with plain `tmclasm` (no
// options, no warnings) to the identical records. So a record is written in mnemonic form only
// when that form encodes to exactly these bytes without a warning — every field the mnemonic does
// not take is 0, every keyword field holds a keyword, every jump target lies inside the program,
// no value lies outside the range of the generic profile's tables — and as
// `.raw OP, TYPE, MOTOR, VALUE` with a comment saying why otherwise. A program that does
// not end in STOP gets `#no_append_stop`, so that reassembly does not add one.
#include "tmcl/asm/disasm.hpp"

#include <algorithm>

#include "internal.hpp"
#include <cstdio>
#include <map>
#include <optional>
#include <set>

#include "tmcl/image.hpp"
#include "tmcl/program_image.hpp"

namespace tmcl {
namespace {

using detail::upper;


// A negative value for a parameter that takes none (a timer period) is written as the unsigned
// number its 32 bits are, which the assembler takes without the warning a negative one gets.
bool unsigned_parameter(const Instruction& ins) {
  const ParamInfo* p = nullptr;
  if (ins.op == static_cast<std::uint8_t>(Op::SAP) || ins.op == static_cast<std::uint8_t>(Op::SAPX))
    p = generic_profile().axis_param(ins.type);
  else if (ins.op == static_cast<std::uint8_t>(Op::SGP))
    p = generic_profile().global_param(ins.motor, ins.type);
  return p && p->min >= 0;
}

std::string number(const Instruction& ins, Field f) {
  if (f == Field::Value && ins.value < 0 && unsigned_parameter(ins)) return std::to_string(static_cast<std::uint32_t>(ins.value));
  return f == Field::Value ? std::to_string(ins.value) : std::to_string(field_of(ins, f));
}

std::string with_addend(const std::string& name, std::int64_t k) {
  if (k == 0) return name;
  return name + (k < 0 ? " - " + std::to_string(0 - static_cast<std::uint64_t>(k)) : " + " + std::to_string(k));
}

// Names for addresses: given ones first, then generated ones (L0012) that clash with nothing.
class Labels {
 public:
  explicit Labels(std::size_t n) : n_(n) {}
  // A given name; false when it is invalid or taken.
  bool add(const std::string& name, std::int64_t address) {
    if (!is_valid_name(name) || address < 0 || address > static_cast<std::int64_t>(n_)) return false;
    if (!used_.insert(upper(name)).second) return false;
    at_[address].push_back(name);
    return true;
  }
  void reserve(const std::string& name) { used_.insert(upper(name)); }
  // A name reserved before (an object's own label).
  void add_reserved(const std::string& name, std::int64_t address) {
    if (address >= 0 && address <= static_cast<std::int64_t>(n_)) at_[address].push_back(name);
  }
  // The name of `address`, generating one if there is none yet.
  const std::string& need(std::int64_t address) {
    auto& names = at_[address];
    if (names.empty()) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "L%04lld", static_cast<long long>(address));
      std::string name = buf;
      while (!used_.insert(upper(name)).second) name += "_";
      names.push_back(name);
    }
    return names.front();
  }
  const std::vector<std::string>* at(std::int64_t address) const {
    auto it = at_.find(address);
    return it == at_.end() ? nullptr : &it->second;
  }

 private:
  std::size_t n_;
  std::map<std::int64_t, std::vector<std::string>> at_;
  std::set<std::string> used_;
};

// Symbolic text for a relocated field (objects); empty when the field is not relocated.
using FieldText = std::map<std::pair<std::size_t, int>, std::string>;

struct Form {
  std::string text;
  std::string why;  // non-empty: written as .raw for this reason
};

// The source of record `i`. `symbolic` maps relocated fields to their text; in a program (not an
// object) an address operand names the label of its target, which must lie inside the program.
Form render(const std::vector<Instruction>& code, std::size_t i, const FieldText& symbolic, bool object,
            bool force_raw, Labels& labels) {
  const Instruction& ins = code[i];
  auto sym = [&](Field f) -> const std::string* {
    auto it = symbolic.find({i, static_cast<int>(f)});
    return it == symbolic.end() ? nullptr : &it->second;
  };
  auto in_program = [&](std::int64_t a) { return a >= 0 && a < static_cast<std::int64_t>(code.size()); };
  const OpInfo* info = op_info(ins.op);
  Form form;
  if (force_raw) form.why = "written with .raw";
  else if (!info) form.why = "opcode " + std::to_string(ins.op) + " is not a TMCL instruction";
  else if (info->control) form.why = std::string(info->id) + " is a direct-mode command, not a program instruction";
  if (form.why.empty()) {
    std::string ops;
    bool used[3] = {false, false, false};
    for (const auto& spec : info->operands) {
      used[static_cast<int>(spec.field)] = true;
      std::string text;
      std::uint32_t v = field_of(ins, spec.field);
      if (const std::string* s = sym(spec.field)) {
        text = *s;
        // A lone name in a keyword position would be read as that keyword.
        if (spec.keywords != KwSet::None && keyword_value(spec.keywords, text)) text = "(" + text + ")";
      } else if (spec.keywords != KwSet::None) {
        auto k = keyword_name(spec.keywords, static_cast<std::uint8_t>(v));
        if (!k) {
          form.why = "no keyword for " + std::string(kwset_name(spec.keywords)) + " " + std::to_string(v);
          break;
        }
        text = std::string(*k);
      } else if (spec.role == Role::Address && !object) {
        if (!in_program(ins.value)) {
          form.why = std::string(info->mnemonic) + " to " + std::to_string(ins.value) + ", outside the program";
          break;
        }
        text = labels.need(ins.value);
      } else {
        text = number(ins, spec.field);
      }
      ops += (ops.empty() ? " " : ", ") + text;
    }
    for (int f = 0; f < 3 && form.why.empty(); ++f)
      if (!used[f] && (field_of(ins, static_cast<Field>(f)) != 0 || sym(static_cast<Field>(f))))
        form.why = std::string(info->mnemonic) + " with " + field_name(static_cast<Field>(f)) + " " +
                   number(ins, static_cast<Field>(f)) + " (" + std::string(info->mnemonic) + " has no " +
                   field_name(static_cast<Field>(f)) + " operand)";
    // A value plain tmclasm warns of (one outside the range of generic's tables) stays .raw too.
    if (form.why.empty() && !sym(Field::Type) && !sym(Field::Motor) && !sym(Field::Value)) {
      detail::Stmt probe;
      probe.op = info;
      Diagnostics warned;
      detail::check_against_profile(generic_profile(), probe, ins, warned);
      if (!warned.all().empty()) form.why = warned.all().front().message;
    }
    if (form.why.empty()) {
      form.text = std::string(info->mnemonic) + ops;
      return form;
    }
  }
  // .raw: fields as numbers, relocated fields symbolic, an address inside the program as a label.
  auto field = [&](Field f) {
    if (const std::string* s = sym(f)) return *s;
    if (!object && f == Field::Value && info && !info->control && in_program(ins.value))
      for (const auto& spec : info->operands)
        if (spec.role == Role::Address) return labels.need(ins.value);
    return number(ins, f);
  };
  form.text = ".raw " + std::to_string(ins.op) + ", " + field(Field::Type) + ", " + field(Field::Motor) + ", " +
              field(Field::Value);
  return form;
}

struct Line {
  std::string text, comment;
};

std::string pad_comment(const std::string& text, const std::string& comment) {
  std::string s = "  " + text;
  if (s.size() < 40) s.resize(40, ' ');
  else s += "  ";
  return s + "; " + comment + "\n";
}

std::string address_text(std::size_t a) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%04zu", a);
  return buf;
}

// Lays out header, prelude (directives, constants), labels and instructions.
std::string layout(const std::vector<std::string>& header, const std::vector<std::string>& prelude,
                   const std::vector<Form>& forms, const std::vector<std::string>& notes, const Labels& labels,
                   bool no_append_stop, const std::vector<std::string>& places = {}) {
  std::string out;
  for (const auto& h : header) out += "; " + h + "\n";
  if (no_append_stop) out += "#no_append_stop  // the image does not end in STOP; reassembly must not add one\n";
  for (const auto& p : prelude) out += p + "\n";
  out += "\n";
  for (std::size_t i = 0; i <= forms.size(); ++i) {
    if (const auto* names = labels.at(static_cast<std::int64_t>(i)))
      for (const auto& n : *names) out += n + ":\n";
    if (i == forms.size()) break;
    std::string comment = address_text(i);
    if (i < places.size() && !places[i].empty()) comment += "  " + places[i];
    if (!forms[i].why.empty()) comment += "  " + forms[i].why;
    if (i < notes.size() && !notes[i].empty()) comment += "  " + notes[i];
    out += pad_comment(forms[i].text, comment);
  }
  return out;
}

bool ends_in_stop(const std::vector<Instruction>& code) {
  return !code.empty() && code.back().op == static_cast<std::uint8_t>(Op::STOP);
}

}  // namespace

std::string format_instruction(const Instruction& ins) {
  // Alone, an address has no label: written as a number (addresses are not range-checked here).
  std::vector<Instruction> one{ins};
  Labels labels(1);
  Form f = render(one, 0, {}, true, false, labels);
  return f.text;
}

std::string format_instruction(const Instruction& ins, const std::map<Field, std::string>& names) {
  std::vector<Instruction> one{ins};
  Labels labels(1);
  FieldText symbolic;
  for (const auto& [field, text] : names) symbolic[{0, static_cast<int>(field)}] = text;
  return render(one, 0, symbolic, true, false, labels).text;
}

std::string disassemble_program(const std::vector<Instruction>& program, const LabelNames* names,
                                const std::vector<std::string>& header, const std::vector<std::string>& notes) {
  Labels labels(program.size());
  if (names)
    for (const auto& [name, address] : names->labels) labels.add(name, address);
  std::vector<Form> forms;
  for (std::size_t i = 0; i < program.size(); ++i) forms.push_back(render(program, i, {}, false, false, labels));
  // A line table in the symbols file: each instruction's source position after its address.
  std::vector<std::string> places;
  if (names && !names->lines.empty()) {
    places.resize(program.size());
    for (std::size_t i = 0; i < program.size(); ++i) {
      auto [file, line] = names->lines.at(static_cast<std::int64_t>(i));
      if (file >= 0) places[i] = names->lines.files[static_cast<std::size_t>(file)] + ":" + std::to_string(line);
    }
  }
  return layout(header, {}, forms, notes, labels, !ends_in_stop(program), places);
}

std::string disassemble_object(const ObjectFile& obj, const std::vector<std::string>& header) {
  const std::size_t n = obj.code.size();
  Labels labels(n);
  for (const auto& s : obj.symbols) labels.reserve(s.name);
  for (const auto& s : obj.symbols)
    if (s.kind == ObjSymKind::Label && s.binding != ObjBinding::Import) labels.add_reserved(s.name, s.value);
  // A base-relative value names the label at that address, or the label at 0 plus an offset.
  auto base_text = [&](std::int64_t k) {
    if (k >= 0 && k <= static_cast<std::int64_t>(n)) return labels.need(k);
    return with_addend(labels.need(0), k);
  };
  FieldText symbolic;
  for (const auto& r : obj.relocs)
    symbolic[{r.index, static_cast<int>(r.field)}] =
        r.term == ObjTerm::Base ? base_text(r.addend) : with_addend(obj.symbols[r.symbol].name, r.addend);
  std::vector<std::string> prelude;
  std::string imports, exports;
  for (const auto& s : obj.symbols) {
    if (s.binding == ObjBinding::Import) imports += (imports.empty() ? "#import " : ", ") + s.name;
    if (s.binding == ObjBinding::Export) exports += (exports.empty() ? "#export " : ", ") + s.name;
  }
  if (!imports.empty()) prelude.push_back(imports);
  if (!exports.empty()) prelude.push_back(exports);
  for (const auto& s : obj.symbols) {
    // Local constants live on only as values in operands; the exported ones others may use.
    if (s.kind != ObjSymKind::Constant || s.binding != ObjBinding::Export) continue;
    std::string value = s.term == ObjTerm::Absolute ? std::to_string(s.value)
                        : s.term == ObjTerm::Base   ? base_text(s.value)
                                                    : with_addend(obj.symbols[s.term_symbol].name, s.value);
    prelude.push_back(s.name + " = " + value);
  }
  std::vector<Form> forms;
  for (std::size_t i = 0; i < n; ++i)
    forms.push_back(render(obj.code, i, symbolic, true, i < obj.code_flags.size() && (obj.code_flags[i] & kInsRaw),
                           labels));
  return layout(header, prelude, forms, {}, labels, (obj.flags & kObjNoAppendStop) != 0);
}

DisasmResult disassemble(const std::string& name, const std::string& bytes, const DisasmOptions& options) {
  DisasmResult r;
  auto warn = [&](const std::string& text) { r.messages.push_back({options.warnings_are_errors, text}); };
  ImageKind kind = options.kind;
  if (kind == ImageKind::Auto) {
    FileKind fk = sniff_file(bytes);
    if (fk == FileKind::Object) kind = ImageKind::Object;
    else if (fk == FileKind::Library) kind = ImageKind::Library;
    else if (name.size() > 4 && upper(name.substr(name.size() - 4)) == ".DGM") kind = ImageKind::Datagrams;
    else kind = ImageKind::Bin;
  }
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
  std::string shown = name == "-" ? "<stdin>" : name;
  switch (kind) {
    case ImageKind::Library:
      r.messages.push_back({true, "is a library; disassemble one of its objects (tmclasm --dump-object lists them)"});
      return r;
    case ImageKind::Object: {
      ObjectFile obj;
      std::string error;
      if (!read_object(data, bytes.size(), obj, error)) {
        r.messages.push_back({true, "invalid object: " + error});
        return r;
      }
      std::vector<std::string> header = {
          "tmclasm disassembly of the object " + shown + " (" + std::to_string(obj.code.size()) +
              " instructions, target " + obj.target + ")",
          "Reassemble with: tmclasm -c" + (obj.target == "generic" ? std::string() : " -t " + obj.target) +
              " FILE.tmc  (links to the identical bytes)"};
      r.source = disassemble_object(obj, header);
      return r;
    }
    case ImageKind::Datagrams:
    case ImageKind::Bin:
    case ImageKind::Auto: break;
  }
  // The one image reader of every tool (program_image.hpp). Without --from the name says which
  // format to expect and the contents decide when every checksum of that format is wrong.
  const std::vector<std::uint8_t> raw(bytes.begin(), bytes.end());
  const ImageFormat named = kind == ImageKind::Datagrams ? ImageFormat::Datagrams : ImageFormat::Bin;
  const ImageReadResult image = options.kind == ImageKind::Auto         ? read_image(raw, named)
                                : named == ImageFormat::Datagrams ? read_datagrams(raw)
                                                                  : read_bin(raw);
  const bool dgm = image.format_datagrams;
  std::vector<std::string> notes(image.program.size());
  for (const auto& issue : image.issues) {
    if (issue.error) {
      r.messages.push_back({true, issue.message});
      continue;
    }
    if (issue.instruction < 0) {
      warn(issue.message);
      continue;
    }
    const std::size_t len = dgm ? 8 : 7;  // the bytes the checksum sums; the checksum follows
    const std::uint8_t* p = data + (issue.offset - len);
    char msg[96];
    std::snprintf(msg, sizeof msg, "checksum was 0x%02X in the input, reassembly writes 0x%02X", p[len], sum8(p, len));
    notes[static_cast<std::size_t>(issue.instruction)] = msg;
    warn(issue.message + "; reassembly writes the correct checksum");
  }
  // Opcode 0 in a datagram file is the end marker, not an instruction (docs/errata.md E40).
  for (std::size_t n : image.end_markers)
    warn("datagram " + std::to_string(n) +
         " is an opcode-0 end marker, not an instruction: the source leaves it out and reassembly does not write it");
  if (!r.ok()) return r;
  if (dgm) {
    std::set<int> addresses(image.addresses.begin(), image.addresses.end());
    int module = addresses.empty() ? 1 : *addresses.begin();
    if (addresses.size() > 1)
      warn("the datagrams are addressed to " + std::to_string(addresses.size()) +
           " different modules; reassembly addresses all of them to module " + std::to_string(module));
    std::vector<std::string> header = {
        "tmclasm disassembly of " + shown + " (datagrams for module " + std::to_string(module) + ", " +
            std::to_string(image.program.size()) + " instructions)",
        "Reassemble with: tmclasm -f datagrams --address " + std::to_string(module) +
            " FILE.tmc  (gives the identical bytes)"};
    r.source = disassemble_program(image.program, options.names, header, notes);
    return r;
  }
  if (!r.ok()) return r;
  std::vector<std::string> header = {
      "tmclasm disassembly of " + shown + " (TMCL-IDE .bin, " + std::to_string(image.program.size()) + " instructions)",
      "Reassemble with: tmclasm FILE.tmc  (gives the identical bytes)"};
  r.source = disassemble_program(image.program, options.names, header, notes);
  return r;
}

}  // namespace tmcl
