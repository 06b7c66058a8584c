// The prompt's line editor without a terminal: bytes in as a terminal sends them (escape
// sequences of xterm, the Linux console and VT100 keypads), the line, the cursor and the bytes
// written back checked. The same keys through a real pseudo-terminal: prompt_pty_test.cpp.
#include "check.hpp"

#include <strings.h>

#include "line_editor.hpp"

using tmcl::debug::LineEditor;

namespace {

// Feeds `keys`; returns the last event.
LineEditor::Event type(LineEditor& e, const std::string& keys) {
  LineEditor::Event ev = LineEditor::Event::None;
  for (char c : keys) ev = e.feed(c);
  return ev;
}

LineEditor fresh(LineEditor::Completer c = {}) {
  LineEditor e("(tmdb) ", std::move(c));
  e.begin();
  return e;
}

}  // namespace

TEST(typed_text_and_enter_give_the_line_and_the_prompt_is_drawn) {
  LineEditor e = fresh();
  CHECK_EQ(e.take_output(), std::string("\r(tmdb) \x1b[K\r\x1b[7C"));
  CHECK(type(e, "step 2") == LineEditor::Event::None);
  CHECK_EQ(e.buffer(), std::string("step 2"));
  CHECK_EQ(e.cursor(), std::size_t{6});
  // Each key redraws the line in place: carriage return, prompt, text, erase, cursor column.
  CHECK(e.take_output().ends_with("\r(tmdb) step 2\x1b[K\r\x1b[13C"));
  CHECK(type(e, "\r") == LineEditor::Event::Line);
  CHECK_EQ(e.take_line(), std::string("step 2"));
  CHECK(e.take_output().ends_with("\r\n"));
}

TEST(arrows_home_and_end_move_the_cursor_in_every_form_terminals_send) {
  LineEditor e = fresh();
  type(e, "prin v[1]");
  type(e, "\x1b[H");  // Home (xterm)
  CHECK_EQ(e.cursor(), std::size_t{0});
  type(e, "\x1b[F");  // End
  CHECK_EQ(e.cursor(), std::size_t{9});
  type(e, "\x1b[1~");  // Home (Linux console, VT220)
  CHECK_EQ(e.cursor(), std::size_t{0});
  type(e, "\x1b[4~");  // End
  CHECK_EQ(e.cursor(), std::size_t{9});
  type(e, "\x1bOH");  // Home (application keypad)
  type(e, "\x1bOC\x1b[C\x1b[C\x1b[C");  // four times Right, SS3 and CSI
  type(e, "t");
  CHECK_EQ(e.buffer(), std::string("print v[1]"));
  type(e, "\x1b[D\x1b[D");  // Left twice
  CHECK_EQ(e.cursor(), std::size_t{3});
  type(e, "\x1b[1;5C");  // Ctrl-Right: past the word
  CHECK_EQ(e.cursor(), std::size_t{5});
  type(e, "\x1b[1;5D");  // Ctrl-Left: back to its start
  CHECK_EQ(e.cursor(), std::size_t{0});
  type(e, "\x1b[2~\x1b[15~");  // Insert, F5: nothing
  CHECK_EQ(e.buffer(), std::string("print v[1]"));
}

TEST(control_keys_edit_as_in_readline) {
  LineEditor e = fresh();
  type(e, "break loop if v[1] == 2");
  type(e, "\x01");  // Ctrl-A
  CHECK_EQ(e.cursor(), std::size_t{0});
  type(e, "\x05");  // Ctrl-E
  CHECK_EQ(e.cursor(), e.buffer().size());
  type(e, "\x17");  // Ctrl-W: the word before the cursor
  CHECK_EQ(e.buffer(), std::string("break loop if v[1] == "));
  type(e, "\x17\x17");
  CHECK_EQ(e.buffer(), std::string("break loop if "));
  type(e, "\x02\x02\x02\x02");  // Ctrl-B four times
  type(e, "\x0b");              // Ctrl-K: to the end
  CHECK_EQ(e.buffer(), std::string("break loop"));
  type(e, "\x02\x02\x02\x02");
  type(e, "\x15");  // Ctrl-U: to the start
  CHECK_EQ(e.buffer(), std::string("loop"));
  CHECK_EQ(e.cursor(), std::size_t{0});
  type(e, "\x06\x06");  // Ctrl-F twice
  type(e, "\x7f");      // Backspace
  CHECK_EQ(e.buffer(), std::string("lop"));
  type(e, "\x04");  // Ctrl-D on a character: deletes it
  CHECK_EQ(e.buffer(), std::string("lp"));
  type(e, "\x01\x1b[3~");  // Delete
  CHECK_EQ(e.buffer(), std::string("p"));
  CHECK(type(e, "\x03") == LineEditor::Event::Cancel);  // Ctrl-C drops the line
  CHECK(e.take_output().ends_with("^C\r\n"));
  e.begin();
  CHECK(type(e, "\x04") == LineEditor::Event::Eof);  // Ctrl-D on an empty line
}

TEST(up_and_down_walk_the_history_and_give_back_the_line_being_typed) {
  LineEditor e = fresh();
  e.add_history("break loop");
  e.add_history("run");
  e.add_history("run");  // a repeat is kept once
  e.add_history("   ");  // blank lines are not kept
  CHECK_EQ(e.history().size(), std::size_t{2});
  e.begin();
  type(e, "p v");
  type(e, "\x1b[A");
  CHECK_EQ(e.buffer(), std::string("run"));
  type(e, "\x1b[A");
  CHECK_EQ(e.buffer(), std::string("break loop"));
  type(e, "\x1b[A");  // the oldest: stays
  CHECK_EQ(e.buffer(), std::string("break loop"));
  type(e, "\x1bOB");  // Down (SS3)
  CHECK_EQ(e.buffer(), std::string("run"));
  type(e, "\x0e");  // Ctrl-N
  CHECK_EQ(e.buffer(), std::string("p v"));
  type(e, "\x10");  // Ctrl-P
  CHECK_EQ(e.buffer(), std::string("run"));
  CHECK(type(e, "\r") == LineEditor::Event::Line);
  CHECK_EQ(e.take_line(), std::string("run"));
}

TEST(ctrl_r_searches_the_history_backwards) {
  LineEditor e = fresh();
  for (const char* l : {"break loop", "print v[1]", "break bump", "step"}) e.add_history(l);
  e.begin();
  type(e, "x");
  type(e, "\x12");
  CHECK(e.searching());
  type(e, "br");
  CHECK(e.take_output().ends_with("\r(reverse-i-search)`br': break bump\x1b[K\r\x1b[34C"));
  type(e, "\x12");  // an older match
  CHECK(e.take_output().find("`br': break loop") != std::string::npos);
  type(e, "z");  // no entry holds "brz"
  CHECK(e.take_output().find("(failed reverse-i-search)`brz'") != std::string::npos);
  type(e, "\x7f");  // Backspace: "br" again, from the newest
  CHECK(e.take_output().find("`br': break bump") != std::string::npos);
  type(e, "\x07");  // Ctrl-G: the line as it was
  CHECK(!e.searching());
  CHECK_EQ(e.buffer(), std::string("x"));
  type(e, "\x12pri\x1b[D");  // a cursor key takes the match into the line and moves
  CHECK(!e.searching());
  CHECK_EQ(e.buffer(), std::string("print v[1]"));
  CHECK_EQ(e.cursor(), std::size_t{9});
  type(e, "\x15\x12ste");
  CHECK(type(e, "\r") == LineEditor::Event::Line);  // Enter runs the match
  CHECK_EQ(e.take_line(), std::string("step"));
}

TEST(tab_completes_as_far_as_the_candidates_agree_and_a_second_tab_lists_them) {
  std::vector<std::string> seen;
  LineEditor e = fresh([&](const std::string& line, std::size_t start) {
    seen.push_back(line.substr(start));
    std::vector<std::string> all = {"bump", "BumpTwice", "loop"}, out;
    for (const auto& w : all)
      if (w.size() >= line.size() - start && strncasecmp(w.c_str(), line.c_str() + start, line.size() - start) == 0) out.push_back(w);
    return out;
  });
  type(e, "break lo\t");
  CHECK_EQ(e.buffer(), std::string("break loop "));  // one candidate: completed, a blank after
  type(e, "\x15p v[1] + b\t");
  CHECK_EQ(e.buffer(), std::string("p v[1] + bump"));  // the common part ("bump", "BumpTwice")
  CHECK_EQ(seen.back(), std::string("b"));
  e.take_output();
  type(e, "\t");  // nothing more in common: a bell
  CHECK_EQ(e.take_output(), std::string("\a"));
  type(e, "\t");  // again: the list, then the line
  std::string out = e.take_output();
  CHECK(out.find("\r\nBumpTwice  bump\r\n") != std::string::npos || out.find("\r\nBumpTwice  bump  \r\n") != std::string::npos);
  CHECK(out.ends_with("\r(tmdb) p v[1] + bump\x1b[K\r\x1b[20C"));
  type(e, "\x15zz\t");
  CHECK_EQ(e.buffer(), std::string("zz"));
}

TEST(a_line_wider_than_the_terminal_scrolls_to_keep_the_cursor_in_view) {
  LineEditor e = fresh();
  e.set_width(20);
  e.begin();
  e.take_output();
  type(e, "print 1234567890123456789");
  std::string out = e.take_output();
  CHECK(out.ends_with("\x1b[K\r\x1b[19C"));  // the cursor in the last column but one
  CHECK(out.find("4567890123456789\x1b[K") != std::string::npos);
  type(e, "\x01");
  CHECK(e.take_output().ends_with("\r(tmdb) print 123456\x1b[K\r\x1b[7C"));
}

TEST(a_note_above_the_prompt_erases_the_line_and_draws_it_again) {
  LineEditor e = fresh();
  type(e, "print 1");
  e.take_output();
  e.hide();
  CHECK_EQ(e.take_output(), std::string("\r\x1b[K"));
  e.show();
  CHECK_EQ(e.take_output(), std::string("\r(tmdb) print 1\x1b[K\r\x1b[14C"));
  e.begin(true);  // a new prompt that keeps the line (the program ran meanwhile)
  CHECK_EQ(e.buffer(), std::string("print 1"));
}

TEST(a_line_stops_growing_at_64_kib) {
  LineEditor e = fresh();
  type(e, std::string(70000, 'x'));
  CHECK_EQ(e.buffer().size(), std::size_t{64 << 10});
  CHECK(e.take_output().ends_with("\a"));
}
