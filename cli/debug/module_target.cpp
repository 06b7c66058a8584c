// The module target (debug_module.hpp): reading the module, attaching and loading, breakpoint
// patches and their removal. How the program is run and stopped is module_run.cpp.
#include <algorithm>
#include <thread>

#include "tmcl/asm/disasm.hpp"
#include "module_commands.hpp"
#include "tmcl/debug_module.hpp"
#include "tmcl/host/commands.hpp"
#include "tmcl/host/transfer.hpp"

namespace tmcl::debug {
namespace {

using module_cmd::code;
using module_cmd::ctl;
Instruction self_jump(std::int32_t address) { return {code(Op::JA), 0, 0, address}; }

std::string addresses_text(const std::vector<std::pair<std::int32_t, Instruction>>& words) {
  std::string s;
  for (const auto& w : words) s += (s.empty() ? "" : ", ") + std::to_string(w.first);
  return s;
}

}  // namespace

std::vector<std::int32_t> self_jumps(const std::vector<Instruction>& words) {
  std::vector<std::int32_t> out;
  for (std::size_t a = 0; a < words.size(); ++a)
    if (words[a] == self_jump(static_cast<std::int32_t>(a))) out.push_back(static_cast<std::int32_t>(a));
  return out;
}

// Expressions read over the host protocol: A and X as 135 read them at this stop (before any
// direct read, which older firmware let change A), the rest with GGP, GAP and GIO.
class ModuleTarget::Reader final : public ExprReader {
 public:
  explicit Reader(ModuleTarget& t) : t_(t) {}
  int motors() const override { return t_.profile().motors; }
  bool reg(Reg r, std::int64_t& out, std::string& error) override {
    static const char* const kNames[] = {"A", "X", "flags", "errors", "pc", "sp", "time", "steps"};
    if (r == Pc) return out = t_.pc_, true;
    if (r != Acc && r != X) {
      error = std::string("'") + kNames[r] + "' cannot be read from a module (A, X and pc can: 135 reads them)";
      return false;
    }
    if (!t_.regs_valid_ && !t_.read_registers(error)) return false;
    out = r == Acc ? t_.acc_ : t_.x_;
    return true;
  }
  bool var(int n, std::int64_t& out, std::string& error) override { return get(Op::GGP, n, 2, out, error); }
  bool axis(int p, int motor, std::int64_t& out, std::string& error) override { return get(Op::GAP, p, motor, out, error); }
  bool global(int bank, int p, std::int64_t& out, std::string& error) override { return get(Op::GGP, p, bank, out, error); }
  bool port(int kind, int n, std::int64_t& out, std::string& error) override {
    return get(Op::GIO, n, kind == Expr::Node::In ? 0 : kind == Expr::Node::Ain ? 1 : 2, out, error);
  }

 private:
  bool get(Op op, int type, int motor, std::int64_t& out, std::string& error) {
    // A and X first: a direct read may change A on older firmware (on-module-debugging.md 3).
    if (!t_.regs_valid_ && !t_.read_registers(error)) return false;
    std::int32_t v = 0;
    if (!t_.ask({code(op), static_cast<std::uint8_t>(type), static_cast<std::uint8_t>(motor), 0}, v, error)) return false;
    out = v;
    return true;
  }
  ModuleTarget& t_;
};

ModuleTarget::ModuleTarget(host::Client& client, const Profile& profile, ProgramInfo info, ModuleSetup setup)
    : Target(profile, std::move(info)), client_(&client), setup_(std::move(setup)) {}

ModuleTarget::~ModuleTarget() = default;

std::uint64_t ModuleTarget::requests() const { return client_->stats().requests; }

bool ModuleTarget::ask(const Instruction& ins, std::int32_t& value, std::string& error, bool retry) {
  if (lost_) return error = "the module does not answer any more", false;
  const host::Result r = client_->request(ins, retry);
  if (!r.ok()) {
    error = r.error;
    port_failed_ = r.fail == host::Fail::Port;
    return false;
  }
  if (r.reply.status != host::kStatusOk && r.reply.status != host::kStatusLoaded) {
    error = "the module answered " + std::to_string(r.reply.status) + " (" + host::status_text(r.reply.status) + ") to " +
            client_->describe(ins);
    return false;
  }
  value = r.reply.value;
  return true;
}

// 135 type 1: the mode in the top byte, the wait flag in the next, the pc in the low 16 bits (the
// virtual module's layout; errata D1).
bool ModuleTarget::read_status(Status& s, std::string& error) {
  std::int32_t v = 0;
  if (!ask(ctl(Op::GetApplicationStatus, 1), v, error)) return false;
  const auto u = static_cast<std::uint32_t>(v);
  s.mode = u >> 24;
  s.wait = ((u >> 16) & 0xFF) != 0;
  s.pc = static_cast<std::int32_t>(u & 0xFFFF);
  return true;
}

bool ModuleTarget::read_registers(std::string& error) {
  if (!ask(ctl(Op::GetApplicationStatus, 2), acc_, error) || !ask(ctl(Op::GetApplicationStatus, 3), x_, error)) return false;
  regs_valid_ = true;
  return true;
}

// 134 does not name the address it answers, so a stale copy of an earlier reply cannot be told
// from the right one (errata H1): a word that is not the one expected is read once more.
bool ModuleTarget::read_word(std::int32_t address, Instruction& out, std::string& error, bool* past_end) {
  const Instruction read = ctl(Op::ReadProgramMemory, 0, address);
  host::Result r;
  for (int n = 0; n < 2; ++n) {
    r = client_->request(read);
    if (!r.ok()) return error = r.error, false;
    if (past_end && r.reply.status == 4 && r.reply.op == read.op) {  // an address past the end of memory
      *past_end = true;
      out = Instruction{};
      return true;
    }
    if (r.reply.status != host::kStatusOk) {
      error = "the module answered " + std::to_string(r.reply.status) + " (" + host::status_text(r.reply.status) +
              ") to " + client_->describe(read);
      return false;
    }
    const bool expected = static_cast<std::size_t>(address) < info_.program.size()
                              ? r.reply.stored == info_.program[static_cast<std::size_t>(address)]
                              : r.reply.stored.op == 0;
    if (expected) break;
  }
  out = r.reply.stored;
  return true;
}

Instruction ModuleTarget::instruction(std::int32_t address) {
  if (address < 0 || static_cast<std::size_t>(address) >= memory_.size()) return Instruction{};
  return memory_[static_cast<std::size_t>(address)];
}

bool ModuleTarget::attach(std::string& notes, std::string& error) {
  Status s;
  if (!read_status(s, error)) return false;
  const int memory = profile().program_memory;
  const auto& prog = info_.program;
  memory_.clear();
  std::vector<std::pair<std::int32_t, Instruction>> left;  // a killed session's patches
  std::string first;
  int others = 0;
  for (std::int32_t a = 0; memory <= 0 || a < memory; ++a) {
    Instruction w;
    bool past_end = false;  // memory ends here (a module whose size the profile does not give)
    if (!read_word(a, w, error, &past_end)) return false;
    const bool in_program = static_cast<std::size_t>(a) < prog.size();
    if (past_end && !in_program) break;
    if (!in_program && w.op == 0) break;  // the module's end marker, where PROGRAM ends too
    const Instruction want = in_program ? prog[static_cast<std::size_t>(a)] : Instruction{};
    if (in_program && w == want) {
      memory_.push_back(w);
      continue;
    }
    if (in_program && w == self_jump(a)) {  // a patch (or another program's loop): decided below
      left.emplace_back(a, want);
      memory_.push_back(w);
      continue;
    }
    if (first.empty()) {
      first = "address " + std::to_string(a) + ": the module has " + (w.op == 0 ? "the end of its program" : format_instruction(w)) +
              ", " + setup_.program_name + " has " + (in_program ? format_instruction(want) : "its end");
    } else {
      ++others;
    }
    if (in_program && w.op == 0) {  // the module's program ends here; the rest is PROGRAM's to show
      for (std::size_t b = static_cast<std::size_t>(a); b < prog.size(); ++b) memory_.push_back(Instruction{});
      break;
    }
    memory_.push_back(w);
  }
  if (!first.empty()) {
    // Another program: its jumps to themselves are its own, not ours to repair.
    others += static_cast<int>(left.size());
    left.clear();
    differs_ = first + (others ? " (and " + std::to_string(others) + " more difference" + (others == 1 ? "" : "s") + ")" : "");
    notes += "The module's program differs from " + setup_.program_name + " at " + differs_ + ".\n`load` downloads " +
             setup_.program_name + "; until then the program is not run.\n";
  } else if (!left.empty()) {
    // A jump to itself where PROGRAM has another instruction, and everything else as PROGRAM:
    // the patch of a session that could not remove it (killed). Put back and verified.
    if (s.mode == 1 && !ask(ctl(Op::StopApplication), s.pc, error)) return false;
    patched_ = left;
    if (!unpatch(error)) return false;
    for (const auto& w : left) {
      memory_[static_cast<std::size_t>(w.first)] = w.second;
      notes += "Restored address " + std::to_string(w.first) + " to " + format_instruction(w.second) + ": a breakpoint's " +
               format_instruction(self_jump(w.first)) + " that an earlier session left on the module.\n";
    }
    if (s.mode == 1) notes += "The program was running; it was stopped (128) to put them back.\n";
    if (!read_status(s, error)) return false;
  }
  pc_ = s.pc;
  mode_ = s.mode;
  waiting_ = s.wait;
  running_ = s.mode == 1 || s.mode == 2;
  stack_known_ = !running_;
  if (s.mode == 1)
    notes += "The program is running on the module (at address " + std::to_string(pc_) +
             "): a command that runs it stops it first (128); `continue` waits for it to stop.\n";
  return true;
}

bool ModuleTarget::load(std::string& error) {
  std::int32_t ignored = 0;
  if (!ask(ctl(Op::StopApplication), ignored, error)) return false;
  const int memory = profile().program_memory;
  for (auto* transfer : {&host::download, &host::verify}) {
    const host::TransferResult t = transfer(*client_, info_.program, 0, memory, nullptr);
    if (t.outcome != host::Outcome::Ok) return error = t.message, false;
  }
  memory_ = info_.program;
  differs_.clear();
  patched_.clear();
  running_ = false;
  stack_.clear();
  stack_known_ = true;
  Status s;
  if (!read_status(s, error)) return false;
  pc_ = s.pc;
  mode_ = s.mode;
  waiting_ = s.wait;
  regs_valid_ = false;
  return true;
}

// ---- patches ----

bool ModuleTarget::write(const std::vector<std::pair<std::int32_t, Instruction>>& words, std::string& error) {
  if (words.empty()) return true;
  std::int32_t ignored = 0;
  bool ok = true;
  for (const auto& [address, ins] : words) {
    if (!ask(ctl(Op::EnterDownloadMode, 0, address), ignored, error)) {
      ok = false;
      break;
    }
    const host::Result r = host::store(*client_, address, ins);
    if (!r.ok() || r.reply.status != host::kStatusLoaded) {
      error = !r.ok() ? r.error
                      : "the module answered " + std::to_string(r.reply.status) + " (" + host::status_text(r.reply.status) +
                            ") to " + client_->describe(ins);
      ok = false;
      break;
    }
  }
  std::string quit_error;
  if (!ask(ctl(Op::ExitDownloadMode), ignored, quit_error) && ok) error = quit_error, ok = false;
  return ok;
}

bool ModuleTarget::verify(const std::vector<std::pair<std::int32_t, Instruction>>& words, std::string& error) {
  for (const auto& [address, ins] : words) {
    Instruction got;
    for (int n = 0; n < 2; ++n) {
      const host::Result r = client_->request(ctl(Op::ReadProgramMemory, 0, address));
      if (!r.ok()) return error = r.error, false;
      got = r.reply.stored;
      if (got == ins) break;
    }
    if (!(got == ins))
      return error = "address " + std::to_string(address) + " reads " + format_instruction(got) + " after writing " +
                     format_instruction(ins),
             false;
  }
  return true;
}

bool ModuleTarget::patch(const std::vector<std::int32_t>& addresses, std::string& error) {
  std::vector<std::pair<std::int32_t, Instruction>> words;
  for (std::int32_t a : addresses) {
    if (a < 0 || a >= program_size()) continue;
    if (std::any_of(patched_.begin(), patched_.end(), [&](const auto& p) { return p.first == a; })) continue;
    if (std::any_of(words.begin(), words.end(), [&](const auto& w) { return w.first == a; })) continue;
    words.emplace_back(a, self_jump(a));
  }
  if (words.empty()) return true;
  if (!worn_said_) {
    worn_said_ = true;
    note("Note: on a module a breakpoint is a jump to itself written into program memory, and each hit writes it twice "
         "(out and back in): EEPROM or flash wears with every write. --no-patch debugs by stepping alone.");
  }
  // Remembered before the write: a write that fails half-way may have stored some.
  for (const auto& w : words) patched_.emplace_back(w.first, memory_[static_cast<std::size_t>(w.first)]);
  return write(words, error) && verify(words, error);
}

bool ModuleTarget::unpatch(std::string& error) {
  if (patched_.empty()) return true;
  if (!write(patched_, error) || !verify(patched_, error)) return false;
  patched_.clear();
  return true;
}

// The module stopped answering, or the port went away: asked again every 200 ms until the
// timeout (a port that failed is opened again first). True once it answers.
bool ModuleTarget::reconnected(std::string& error) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(setup_.reconnect_ms);
  const bool was_lost = lost_;
  lost_ = false;
  while (std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    std::string err;
    if (port_failed_) {
      host::Client* c = setup_.reconnect ? setup_.reconnect(err) : nullptr;
      if (!c) {
        error = err;
        continue;
      }
      client_ = c;
      port_failed_ = false;
    }
    Status s;
    if (read_status(s, err)) return true;
    error = err;
  }
  lost_ = was_lost;
  return false;
}

bool ModuleTarget::restore(std::string& message) {
  if (patched_.empty()) return true;
  std::string error;
  if (unpatch(error)) return true;
  if (reconnected(error) && unpatch(error)) return true;
  message = "program memory is still patched at address" + std::string(patched_.size() == 1 ? " " : "es ") +
            addresses_text(patched_) + " (a jump to itself each; " + error +
            "): the next `tmclctl PORT debug PROGRAM` puts them back";
  return false;
}

// ---- state ----

bool ModuleTarget::eval(const Expr& e, std::int64_t& value, std::string& error) {
  Reader reader(*this);
  return eval_expr(e, reader, value, error);
}

bool ModuleTarget::assign(const Expr& lhs, std::int64_t value, std::string& error) {
  if (lhs.root < 0) return error = "nothing to assign to", false;
  const Expr::Node& n = lhs.nodes[static_cast<std::size_t>(lhs.root)];
  auto index = [&](int node, std::int64_t& out) {
    Expr sub = lhs;
    sub.root = node;
    return eval(sub, out, error);
  };
  if (value < INT32_MIN || value > INT32_MAX) return error = std::to_string(value) + " does not fit 32 bits", false;
  const auto v32 = static_cast<std::int32_t>(value);
  std::int64_t a = 0, b = 0;
  Instruction ins;
  switch (n.kind) {
    case Expr::Node::Reg:
      error = "set var " + lhs.text + ": not on a module: no command writes its registers (A and X are read with 135)";
      return false;
    case Expr::Node::Var:
      if (!index(n.a, a)) return false;
      ins = {code(Op::SGP), static_cast<std::uint8_t>(a), 2, v32};
      break;
    case Expr::Node::Ap:
      if (!index(n.a, a) || !index(n.b, b)) return false;
      ins = {code(Op::SAP), static_cast<std::uint8_t>(a), static_cast<std::uint8_t>(b), v32};
      break;
    case Expr::Node::Gp:
      if (!index(n.a, a) || !index(n.b, b)) return false;
      ins = {code(Op::SGP), static_cast<std::uint8_t>(b), static_cast<std::uint8_t>(a), v32};
      break;
    case Expr::Node::Out:
      if (!index(n.a, a)) return false;
      ins = {code(Op::SIO), static_cast<std::uint8_t>(a), 2, v32};
      break;
    case Expr::Node::In:
    case Expr::Node::Ain:
      error = "set var " + lhs.text + ": not on a module: its inputs are real ones";
      return false;
    default: error = "'" + lhs.text + "' cannot be assigned"; return false;
  }
  if (!regs_valid_ && !read_registers(error)) return false;
  std::int32_t ignored = 0;
  if (!ask(ins, ignored, error)) return false;
  refresh_watches();
  return true;
}

int ModuleTarget::depth() const { return static_cast<int>(stack_.size()) + (stack_known_ ? 0 : 1); }

std::vector<Target::Frame> ModuleTarget::frames() {
  std::vector<Frame> out{{pc_, false}};
  for (auto i = stack_.rbegin(); i != stack_.rend(); ++i) out.push_back(*i);
  return out;
}

std::string ModuleTarget::status() { return host::mode_name(mode_) + (waiting_ ? ", in WAIT" : ""); }

int ModuleTarget::add_watchpoint(const std::string& text, std::string& error) {
  const int id = Target::add_watchpoint(text, error);
  if (id)
    note("Note: on a module a watchpoint is checked after every instruction: the program runs by stepping (130), "
         "each instruction several requests, instead of at full speed.");
  return id;
}

}  // namespace tmcl::debug
