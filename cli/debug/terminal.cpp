// The prompt on a terminal (terminal.hpp): raw mode (os_console.hpp) for the line editor, the window's
// width, and the history file (one line per command, appended as each is entered, the newest
// kHistoryKept read back at the start).
#include "terminal.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <fstream>

namespace tmcl::debug {
namespace {

constexpr std::size_t kHistoryKept = 1000;

}  // namespace

std::string history_path() {
  if (const char* p = std::getenv("TMCLRUN_HISTORY")) return p;
  const char* home = std::getenv("HOME");
  return home && *home ? std::string(home) + "/.tmclrun_history" : "";
}

bool TerminalPrompt::usable(int in_fd, int out_fd) {
  const char* term = std::getenv("TERM");
  return ::isatty(in_fd) && ::isatty(out_fd) && term && *term && std::string(term) != "dumb";
}

TerminalPrompt::TerminalPrompt(int in_fd, int out_fd, std::string prompt, LineEditor::Completer completer)
    : in_(in_fd), out_(out_fd), editor_(std::move(prompt), std::move(completer)), history_file_(history_path()) {
  if (history_file_.empty()) return;
  std::ifstream f(history_file_);
  std::vector<std::string> lines;
  for (std::string l; std::getline(f, l);)
    if (!l.empty()) lines.push_back(l);
  for (std::size_t i = lines.size() > kHistoryKept ? lines.size() - kHistoryKept : 0; i < lines.size(); ++i) editor_.add_history(lines[i]);
}

TerminalPrompt::~TerminalPrompt() { stop(); }

void TerminalPrompt::start(bool keep) {
  os::terminal_raw(in_, saved_, have_saved_);
  editor_.set_width(os::terminal_width(out_));
  editor_.begin(keep);
  editing_ = true;
  flush();
}

void TerminalPrompt::stop() {
  if (have_saved_) os::terminal_restore(in_, saved_);
  editing_ = false;
}

TerminalPrompt::Got TerminalPrompt::feed(const char* data, std::size_t n, std::string& line) {
  if (n > 0) pending_.append(data, n);
  std::size_t used = 0;
  Got got = Got::Nothing;
  while (editing_ && got == Got::Nothing && used < pending_.size()) {
    switch (editor_.feed(pending_[used++])) {
      case LineEditor::Event::None: break;
      case LineEditor::Event::Line:
        line = editor_.take_line();
        editor_.add_history(line);
        if (!history_file_.empty() && line.find_first_not_of(" \t") != std::string::npos)
          std::ofstream(history_file_, std::ios::app) << line << '\n';
        editing_ = false;  // the next line waits for start()
        got = Got::Line;
        break;
      case LineEditor::Event::Eof:
        editing_ = false;
        got = Got::End;
        break;
      case LineEditor::Event::Cancel: editor_.begin(); break;
    }
  }
  pending_.erase(0, used);
  flush();
  return got;
}

std::optional<std::string> TerminalPrompt::read_line() {
  start();
  std::string line;
  Got got = feed(nullptr, 0, line);
  while (got == Got::Nothing) {
    char buf[256];
    ssize_t n = ::read(in_, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      got = Got::End;
      break;
    }
    got = feed(buf, static_cast<std::size_t>(n), line);
  }
  stop();
  if (got == Got::End) return std::nullopt;
  return line;
}

void TerminalPrompt::above(const std::function<void()>& print) {
  if (!editing_) return print();
  editor_.hide();
  flush();
  print();
  editor_.show();
  flush();
}

void TerminalPrompt::flush() {
  std::string out = editor_.take_output();
  for (std::size_t at = 0; at < out.size();) {
    ssize_t n = ::write(out_, out.data() + at, static_cast<unsigned>(std::min<std::size_t>(out.size() - at, 1u << 30)));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    at += static_cast<std::size_t>(n);
  }
}

}  // namespace tmcl::debug
