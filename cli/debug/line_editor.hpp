// The debugger prompt's line editor on a terminal (docs/debugger.md, "The prompt"): the keys
// readline users know (arrows, Home/End, Ctrl-A/E/B/F/K/U/W/D/L, Up/Down and Ctrl-P/N through
// the history, Ctrl-R reverse search, Tab completion). Pure logic: bytes in (as the terminal
// sends them, escape sequences included), the line and the bytes to write out (VT100 escape
// sequences that redraw one line), so it is tested without a terminal. terminal.cpp puts a real
// terminal in raw mode and feeds it; the history file is read and written there too.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace tmcl::debug {

class LineEditor {
 public:
  // Candidates for the word being completed: `line` up to the cursor, the word from `word_start`.
  using Completer = std::function<std::vector<std::string>(const std::string& line, std::size_t word_start)>;

  explicit LineEditor(std::string prompt, Completer completer = {});

  enum class Event {
    None,    // still editing
    Line,    // Enter: take_line() has the line
    Eof,     // Ctrl-D on an empty line
    Cancel,  // Ctrl-C: the line was dropped (begin() starts another)
  };
  void begin(bool keep = false);  // a new line (keep: the one being typed goes on): the prompt is drawn
  Event feed(char byte);     // one byte from the terminal
  std::string take_line();   // after Event::Line
  std::string take_output(); // what to write to the terminal since the last call

  // A note printed above the prompt: hide() erases the line being edited, show() draws it again.
  void hide();
  void show();

  void set_width(int columns) { width_ = columns > 10 ? columns : 80; }
  // History: oldest first. Empty lines and a repeat of the last entry are not added.
  void add_history(const std::string& line);
  const std::vector<std::string>& history() const { return history_; }

  const std::string& buffer() const { return buf_; }
  std::size_t cursor() const { return pos_; }
  bool searching() const { return search_; }

 private:
  enum class Esc { None, Start, Csi, Ss3 };
  Event key(char c);
  Event escape_end(char final, const std::string& params);
  void refresh();
  void insert(const std::string& text);
  void set_line(const std::string& text);
  void history_move(int delta);
  void complete();
  void search_key(char c, bool& consumed, Event& ev);
  bool search_from(std::size_t start);  // sets match_ to the newest entry at or before start
  void end_search(bool accept);

  std::string prompt_;
  Completer completer_;
  std::string buf_, out_, line_;
  std::size_t pos_ = 0;
  int width_ = 80;
  Esc esc_ = Esc::None;
  std::string esc_params_;
  std::vector<std::string> history_;
  std::size_t hist_pos_ = 0;  // history_.size(): the line being typed
  std::string saved_;         // the line being typed, while browsing the history
  bool last_tab_ = false;     // a second Tab lists the candidates
  bool search_ = false;       // Ctrl-R
  std::string query_, before_search_;
  std::size_t before_pos_ = 0;
  std::size_t match_ = 0;     // index into history_ of the current match
  bool found_ = false;
};

}  // namespace tmcl::debug
