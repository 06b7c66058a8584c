// Debugging while serving (tmclrun --serve tcp:... --debug PROGRAM): one thread owns the VM. The
// virtual module's loop (ServeLoop) runs with the debugger's standard input as an extra
// descriptor; while the debugger holds the program (at its prompt) the module moves simulated
// time and the motors with the wall clock and answers its host, and a command that runs the
// program runs it in the engine, paced by the wall clock through Engine::on_slice, which serves
// the host between slices. Host control commands show in the debugger (docs/debugger.md,
// "Debugging while serving").
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <iostream>
#include <streambuf>
#include <utility>

#include "terminal.hpp"
#include "tmcl/debug_cli.hpp"
#include "tmcl/os_net.hpp"

namespace tmcl::debug {
namespace {

// Direct-mode commands that only read: they change nothing the debugger keeps.
bool reads_only(std::uint8_t op) {
  switch (static_cast<Op>(op)) {
    case Op::GAP:
    case Op::GGP:
    case Op::GIO:
    case Op::GCO:
    case Op::ReadProgramMemory:
    case Op::GetApplicationStatus:
    case Op::GetFirmwareVersion:
    case Op::PositionReachedEvent: return true;
    default: return false;
  }
}

// The server's notes ("client connected from ...") a line at a time, so that each can be printed
// above the prompt instead of inside the line being typed.
class LineSink final : public std::streambuf {
 public:
  explicit LineSink(std::function<void(const std::string&)> emit) : emit_(std::move(emit)) {}

 protected:
  int_type overflow(int_type c) override {
    if (c == traits_type::eof()) return traits_type::not_eof(c);
    if (c == '\n') {
      emit_(std::exchange(line_, std::string()));
    } else {
      line_ += static_cast<char>(c);
    }
    return c;
  }

 private:
  std::function<void(const std::string&)> emit_;
  std::string line_;
};

class Served {
 public:
  Served(Engine& engine, const ServeOptions& options, std::FILE* in, std::FILE* out)
      : e_(engine),
        opt_(options),
        in_fd_(::fileno(in)),
        poll_fd_(os::pollable_input(in_fd_)),
        tty_(::isatty(in_fd_) != 0),
        out_(out),
        cli_(engine, out, !tty_, true) {
    if (tty_ && TerminalPrompt::usable(in_fd_, ::fileno(out))) {
      editor_ = std::make_unique<TerminalPrompt>(in_fd_, ::fileno(out), "(tmdb) ", [this](const std::string& l, std::size_t at) {
        return cli_.completions(l, at);
      });
      std::ostream* log = opt_.log ? opt_.log : &std::cerr;
      notes_ = std::make_unique<LineSink>([this, log](const std::string& line) {
        std::fflush(out_);
        editor_->above([&] { *log << line << std::endl; });
      });
      notes_stream_ = std::make_unique<std::ostream>(notes_.get());
      opt_.log = notes_stream_.get();
    }
    opt_.run_program = [this](SimTime until) { run_program(until); };
    opt_.on_interrupt = [this] {
      if (executing_) stop_program("");  // Ctrl-C stops the program, not the server
    };
    auto trace = opt_.on_exchange;
    opt_.on_exchange = [this, trace](const TmclModule::Exchange& x) {
      if (trace) trace(x);
      from_host(x);
    };
    e_.on_slice = [this] { return slice(); };
  }
  ~Served() { os::release_pollable_input(poll_fd_, in_fd_); }
  Served(const Served&) = delete;
  Served& operator=(const Served&) = delete;

  int run() {
    loop_ = std::make_unique<ServeLoop>(e_.vm(), opt_);
    if (int rc = loop_->open(); rc != 0) return rc;
    if (e_.vm().status == AppStatus::Running) {  // --autostart, or global 77
      e_.external_change();
      resume_ = "[the module started the program (autostart): continuing]";
    }
    prompt();
    while (!quit_) {
      if (!resume_.empty()) {
        if (editor_ && editor_->editing()) {
          editor_->above([] {});  // the prompt goes; the note and the run's stop come after it
          editor_->stop();
        }
        cli_.note(std::exchange(resume_, std::string()));
        execute([this] { cli_.report(e_.cont()); });
        prompt(true);  // with the line the user was typing
        continue;
      }
      if (!loop_->poll_once(-1, poll_fd_)) break;
      if (loop_->extra_ready()) read_commands();
    }
    int rc = loop_->close();
    return rc != 0 ? rc : cli_.status();
  }

 private:
  void prompt(bool keep_line = false) {
    if (quit_) return;
    std::fflush(out_);
    if (editor_) {
      editor_->start(keep_line);
      edit_pending();  // lines typed ahead while the last command ran
    } else if (tty_) {
      std::fputs("(tmdb) ", out_);
      std::fflush(out_);
    }
  }

  // The line editor's lines, each a command: typed now (`buf`) or before.
  void edit(const char* buf, std::size_t n) {
    std::string line;
    for (TerminalPrompt::Got got = editor_->feed(buf, n, line); !quit_; got = editor_->feed(nullptr, 0, line)) {
      if (got == TerminalPrompt::Got::Nothing) return;
      editor_->stop();
      if (got == TerminalPrompt::Got::End) {
        std::fputs("quit\n", out_);
        quit_ = true;
        return;
      }
      command(line);
      if (quit_) return;
      std::fflush(out_);
      editor_->start();
    }
  }
  void edit_pending() { edit(nullptr, 0); }

  // Reads what standard input has; every whole line is a command. End of input quits.
  void read_commands() {
    char buf[4096];
    long n = os::read_some(poll_fd_, buf, sizeof buf);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) return;
    if (editor_ && n > 0) return edit(buf, static_cast<std::size_t>(n));
    if (n <= 0) {
      if (!pending_.empty()) command(std::exchange(pending_, std::string()));
      quit_ = true;
      return;
    }
    pending_.append(buf, static_cast<std::size_t>(n));
    for (std::size_t nl; !quit_ && (nl = pending_.find('\n')) != std::string::npos;) {
      std::string line = pending_.substr(0, nl);
      pending_.erase(0, nl + 1);
      command(line);
      prompt();
    }
    if (pending_.size() > kMaxLine) {  // no newline in sight: not a command line
      pending_.clear();
      cli_.note("error: a command line longer than " + std::to_string(kMaxLine) + " bytes was dropped");
      prompt();
    }
  }
  static constexpr std::size_t kMaxLine = 64 << 10;

  void command(const std::string& line) {
    // The module's time first catches up with the wall clock (the loop slept until this line).
    if (!loop_->poll_once(0, -1)) quit_ = true;
    // Time passed while the program was held: re-execution from before could not reproduce it.
    if (e_.vm().now != held_at_) e_.external_change();
    execute([&] {
      if (!cli_.line(line)) quit_ = true;
    });
  }

  // Runs a debugger command; a run inside it is paced by slice().
  template <typename F>
  void execute(F f) {
    executing_ = true;
    stopping_ = false;
    f();
    executing_ = false;
    held_at_ = e_.vm().now;
  }

  // TmclModule::run_program: the instant the wall clock has reached. While the debugger holds
  // the program, time and the motors move on without it (a real module's motors keep moving
  // while its program is stopped); while a command runs it, the engine gets there (slice()).
  void run_program(SimTime until) {
    reached_ = until;
    if (executing_) return;
    Vm& vm = e_.vm();
    if (until > vm.now) {
      vm.now = until;
      vm.sync_motion();
    }
  }

  // Engine::on_slice: serve the host until the wall clock lets simulated time go on.
  SimTime slice() {
    Vm& vm = e_.vm();
    for (;;) {
      int wait_ms = 0;
      if (reached_ <= vm.now) {
        wait_ms = 1;
        // In a WAIT, nothing happens before the VM's next event: sleep until then (at most 1 s).
        if (vm.wait.active) {
          SimTime next = vm.next_wakeup();
          double ms = next == kNever ? 1000.0 : static_cast<double>(next - vm.now) / (opt_.time_scale > 0 ? opt_.time_scale : 1.0) / 1000.0;
          wait_ms = static_cast<int>(std::clamp(ms, 1.0, 1000.0));
        }
      }
      if (!loop_->poll_once(wait_ms, -1)) {
        quit_ = true;
        stop_program("The server stopped.");
      }
      if (stopping_) return vm.now;
      if (reached_ > vm.now) return reached_;
    }
  }

  void stop_program(const std::string& why) {
    stopping_ = true;
    e_.pause_for(why);
  }

  // A request the module answered: what it did to the program shows in the debugger.
  void from_host(const TmclModule::Exchange& x) {
    if (x.status != kStatusOk || reads_only(x.request.op)) return;
    const auto op = static_cast<Op>(x.request.op);
    e_.external_change();  // history restarts: re-execution could not replay the host's request
    std::string what;
    switch (op) {
      case Op::StopApplication: what = "stopped the program (command 128)"; break;
      case Op::RunApplication:
        if (!executing_) resume_ = "[the host started the program (command 129): continuing]";
        return;
      case Op::StepApplication: what = "stepped the program (command 130)"; break;
      case Op::ResetApplication: what = "reset the program (command 131)"; break;
      case Op::EnterDownloadMode: what = "is downloading a program (command 132): source lines and labels may no longer apply"; break;
      case Op::SoftwareReset: what = "restarted the module (command 255)"; break;
      default: return;  // a parameter, a variable, a move: the program goes on (or stays held)
    }
    if (executing_) {
      stop_program("Program stopped: the host " + what + ".");
    } else if (editor_ && editor_->editing()) {
      std::fflush(out_);
      editor_->above([&] {
        cli_.report(Stop{StopKind::Pause, 0, "[the host " + what + "]", 0, 0});
        std::fflush(out_);
      });
    } else {
      cli_.report(Stop{StopKind::Pause, 0, "[the host " + what + "]", 0, 0});
      prompt();
    }
  }

  Engine& e_;
  ServeOptions opt_;
  int in_fd_;
  int poll_fd_;  // what the server's loop waits on for in_fd_'s input (os_net.hpp, pollable_input)
  bool tty_;
  std::FILE* out_;
  CommandLine cli_;
  std::unique_ptr<ServeLoop> loop_;
  std::unique_ptr<TerminalPrompt> editor_;     // on a terminal: the line editor
  std::unique_ptr<LineSink> notes_;            // the server's notes, printed above the prompt
  std::unique_ptr<std::ostream> notes_stream_;
  std::string pending_;      // a command line not yet complete
  bool executing_ = false;   // a debugger command is running (the engine runs the program)
  bool stopping_ = false;    // the running program is to stop (host, Ctrl-C, shutdown)
  bool quit_ = false;
  SimTime reached_ = 0;      // the instant the wall clock has reached, in the module's time
  SimTime held_at_ = 0;      // the instant the program was last held at
  std::string resume_;       // non-empty: continue the program (the host started it), saying this
};

}  // namespace

int serve_debug(Engine& engine, const ServeOptions& options, std::FILE* in, std::FILE* out) {
  Served served(engine, options, in, out);
  return served.run();
}

}  // namespace tmcl::debug
