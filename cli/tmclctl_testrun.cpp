// tmclctl PORT test (cli/tmclctl_testrun.hpp): a module as the test runner reads it. Each value an
// expectation names is a request (GGP for v[n], GAP for ap(p, m), GIO for in/ain/out, 135 for
// acc, x and pc); the program is downloaded and verified (cli/host's transfers), reset and run.
// The first time the module stays silent or the port fails, the run ends: the test under way ends
// as an error at once, later tests are skipped rather than each waiting out its timeouts, and
// tmclctl exits as for that failure anywhere else (69, 74).
#include "tmclctl_testrun.hpp"

#include <cstdio>

#include "tmcl/host/transfer.hpp"
#include "tmcl/testrun.hpp"

namespace {

using tmcl::Instruction;
using tmcl::Op;
namespace host = tmcl::host;

class HostModule final : public tmcl::testrun::Module {
 public:
  HostModule(host::Client& client, const tmcl::Profile& profile, volatile std::sig_atomic_t* stop)
      : client_(client), profile_(profile), stop_(stop) {}

  int motors() const override { return profile_.motors; }
  bool reg(Reg r, std::int64_t& out, std::string& error) override {
    static const char* const kNames[] = {"acc", "x", "flags", "errors", "pc", "sp", "time", "steps"};
    if (r != Acc && r != X && r != Pc) {
      error = std::string("'") + kNames[r] + "' cannot be read from a module (acc, x and pc can)";
      return false;
    }
    const std::uint8_t type = r == Acc ? 2 : r == X ? 3 : 1;
    if (!ask({static_cast<std::uint8_t>(Op::GetApplicationStatus), type, 0, 0}, out, error)) return false;
    if (r == Pc) out &= 0xFFFF;
    return true;
  }
  bool var(int n, std::int64_t& out, std::string& error) override { return ask(ins(Op::GGP, n, 2), out, error); }
  bool axis(int p, int motor, std::int64_t& out, std::string& error) override { return ask(ins(Op::GAP, p, motor), out, error); }
  bool global(int bank, int p, std::int64_t& out, std::string& error) override { return ask(ins(Op::GGP, p, bank), out, error); }
  bool port(int kind, int n, std::int64_t& out, std::string& error) override {
    return ask(ins(Op::GIO, n, kind == tmcl::Expr::Node::In ? 0 : kind == tmcl::Expr::Node::Ain ? 1 : 2), out, error);
  }

  bool load_and_start(const std::vector<Instruction>& program, std::string& error) override {
    std::int64_t ignored = 0;
    if (!ask(ins(Op::StopApplication, 0, 0), ignored, error)) return false;
    for (auto* transfer : {&host::download, &host::verify}) {
      const host::TransferResult t = transfer(client_, program, 0, profile_.program_memory, nullptr);
      if (t.outcome != host::Outcome::Ok) {
        error = t.message;
        if (t.outcome == host::Outcome::NoReply || t.outcome == host::Outcome::Port)
          failed(t.outcome == host::Outcome::NoReply ? host::Fail::NoReply : host::Fail::Port, t.message);
        return false;
      }
    }
    return ask(ins(Op::ResetApplication, 0, 0), ignored, error) && ask(ins(Op::RunApplication, 0, 0), ignored, error);
  }
  bool running(bool& out, std::string& error) override {
    std::int64_t status = 0;
    if (!ask(ins(Op::GetApplicationStatus, 0, 0), status, error)) return false;
    out = (static_cast<std::uint32_t>(status) >> 24) == 1;
    return true;
  }
  void stop() override {
    std::int64_t ignored = 0;
    std::string error;
    ask(ins(Op::StopApplication, 0, 0), ignored, error);
  }
  // Ctrl-C, or the module failed: the test under way stops waiting.
  bool cancelled() const override { return *stop_ != 0 || fail_ != host::Fail::None; }

  host::Fail fail() const { return fail_; }

 private:
  static Instruction ins(Op op, int type, int motor) {
    return {static_cast<std::uint8_t>(op), static_cast<std::uint8_t>(type), static_cast<std::uint8_t>(motor), 0};
  }
  void failed(host::Fail f, const std::string& message) {
    if (fail_ != host::Fail::None) return;
    fail_ = f;
    fail_message_ = message;
  }
  bool ask(const Instruction& i, std::int64_t& out, std::string& error) {
    if (fail_ != host::Fail::None) {  // nothing more is asked of a module that failed
      error = fail_message_;
      return false;
    }
    const host::Result r = client_.request(i);
    if (!r.ok()) {
      error = r.error;
      failed(r.fail, r.error);
      return false;
    }
    if (r.reply.status != host::kStatusOk) {
      error = "the module answered " + std::to_string(r.reply.status) + " (" + host::status_text(r.reply.status) + ") to " +
              client_.describe(i);
      return false;
    }
    out = r.reply.value;
    return true;
  }

  host::Client& client_;
  const tmcl::Profile& profile_;
  volatile std::sig_atomic_t* stop_;
  host::Fail fail_ = host::Fail::None;
  std::string fail_message_;
};

}  // namespace

int tmclctl_test(host::Client& client, const tmcl::Profile& profile, const std::string& target,
                 const std::vector<std::string>& paths, const std::vector<std::string>& include_dirs, const std::string& junit,
                 volatile std::sig_atomic_t* stop, host::Fail& failed) {
  HostModule module(client, profile, stop);
  tmcl::testrun::SuiteOptions o;
  o.run.tool = "tmclctl";
  o.run.target = target;  // not profile.name: a profile file's name need not be a target
  o.run.target_given = true;  // the module is the one connected, whatever a program's first line names
  o.run.asm_options.include_dirs = include_dirs;
  o.jobs = 1;  // one module
  o.junit = junit;
  o.run_one = [&](const std::string& path, tmcl::testrun::ProgramCache& cache) {
    if (module.fail() == host::Fail::None) return tmcl::testrun::run_test_live(path, o.run, cache, module);
    tmcl::testrun::TestResult skipped;
    skipped.path = path;
    skipped.status = tmcl::testrun::TestResult::Skip;
    skipped.skip_reason = "not run: the module failed in an earlier test";
    return skipped;
  };
  const int status = tmcl::testrun::run_command(paths, o, stdout, stderr);
  failed = module.fail();
  return *stop ? 130 : status;
}
