// The debugger's prompt on a terminal (docs/debugger.md, "The prompt"): the line editor
// (line_editor.hpp) on a terminal in raw mode (os_console.hpp) while a line is typed, and in the
// terminal's own mode while a command runs, so Ctrl-C still pauses a running program. The
// history is kept in a file, $TMCLRUN_HISTORY or ~/.tmclrun_history. Used only when standard
// input and output are both terminals; piped commands are read as they always were.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "line_editor.hpp"
#include "tmcl/os_console.hpp"

namespace tmcl::debug {

// Where the history is kept: $TMCLRUN_HISTORY (empty: nowhere), else $HOME/.tmclrun_history.
std::string history_path();

class TerminalPrompt {
 public:
  // Both descriptors terminals, and TERM not "dumb".
  static bool usable(int in_fd, int out_fd);

  TerminalPrompt(int in_fd, int out_fd, std::string prompt, LineEditor::Completer completer);
  ~TerminalPrompt();  // the terminal's own mode again
  TerminalPrompt(const TerminalPrompt&) = delete;
  TerminalPrompt& operator=(const TerminalPrompt&) = delete;

  // Raw mode and a fresh prompt (keep: with the line that was being typed when it stopped).
  void start(bool keep = false);
  // The terminal's own mode (a command runs).
  void stop();
  bool editing() const { return editing_; }

  // Typed bytes (and those left over from before): a whole line entered (in `line`, and the
  // history), the end of input (Ctrl-D on an empty line), or nothing yet. Bytes after a line
  // wait for the next start().
  enum class Got { Nothing, Line, End };
  Got feed(const char* data, std::size_t n, std::string& line);
  // Blocking: start(), bytes until a line (nothing at the end of input), stop().
  std::optional<std::string> read_line();

  // Something printed above the prompt (a note of the server): the line being typed is erased
  // first and drawn again after `print`, so the note never lands inside it.
  void above(const std::function<void()>& print);

 private:
  void flush();

  int in_, out_;
  LineEditor editor_;
  std::string pending_;  // typed ahead of the line being handled
  std::string history_file_;
  os::SavedTerminal saved_;
  bool have_saved_ = false;
  bool editing_ = false;
};

}  // namespace tmcl::debug
