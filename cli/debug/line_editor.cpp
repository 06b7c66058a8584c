// The prompt's line editor (line_editor.hpp): one line, redrawn in place with VT100 sequences
// ("\r", the prompt, the visible part of the line, erase to the end, the cursor moved right),
// scrolled sideways when it is wider than the terminal, as linenoise and readline do.
#include "line_editor.hpp"

#include <algorithm>
#include <cctype>

namespace tmcl::debug {
namespace {

constexpr char kEsc = 27;
constexpr std::size_t kMaxLine = 64 << 10;  // as the piped command line's bound (serve.cpp)

bool word_char(char c) {
  return !std::isspace(static_cast<unsigned char>(c)) && std::string("(),[]=<>!+-*%&|^~").find(c) == std::string::npos;
}

bool same_prefix(const std::string& s, const std::string& prefix) {
  if (s.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[i])) != std::tolower(static_cast<unsigned char>(prefix[i]))) return false;
  return true;
}

}  // namespace

LineEditor::LineEditor(std::string prompt, Completer completer) : prompt_(std::move(prompt)), completer_(std::move(completer)) {}

void LineEditor::begin(bool keep) {
  if (!keep) {
    buf_.clear();
    pos_ = 0;
  }
  hist_pos_ = history_.size();
  saved_.clear();
  esc_ = Esc::None;
  search_ = false;
  last_tab_ = false;
  refresh();
}

std::string LineEditor::take_line() { return std::move(line_); }

std::string LineEditor::take_output() {
  std::string out;
  out.swap(out_);
  return out;
}

void LineEditor::hide() { out_ += "\r\x1b[K"; }
void LineEditor::show() { refresh(); }

void LineEditor::add_history(const std::string& line) {
  if (line.find_first_not_of(" \t") == std::string::npos) return;
  if (!history_.empty() && history_.back() == line) return;
  history_.push_back(line);
}

LineEditor::Event LineEditor::feed(char c) {
  switch (esc_) {
    case Esc::None: break;
    case Esc::Start:
      if (c == '[') {
        esc_ = Esc::Csi;
        esc_params_.clear();
      } else if (c == 'O') {
        esc_ = Esc::Ss3;
      } else {
        esc_ = Esc::None;
        // Alt-b, Alt-f: a word left or right (Meta sends ESC before the key).
        if (c == 'b') return escape_end('D', "1;5");
        if (c == 'f') return escape_end('C', "1;5");
      }
      return Event::None;
    case Esc::Csi:
      if (c >= 0x30 && c <= 0x3f) {
        if (esc_params_.size() < 16) esc_params_ += c;
        return Event::None;
      }
      esc_ = Esc::None;
      return escape_end(c, esc_params_);
    case Esc::Ss3: esc_ = Esc::None; return escape_end(c, "");
  }
  if (search_) {
    bool consumed = false;
    Event ev = Event::None;
    search_key(c, consumed, ev);
    if (consumed) return ev;
  }
  return key(c);
}

LineEditor::Event LineEditor::key(char c) {
  if (c != '\t') last_tab_ = false;
  switch (c) {
    case '\r':
    case '\n':
      pos_ = buf_.size();
      refresh();
      out_ += "\r\n";
      line_ = buf_;
      return Event::Line;
    case 1: pos_ = 0; break;                                   // Ctrl-A
    case 2: if (pos_ > 0) --pos_; break;                       // Ctrl-B
    case 3:                                                    // Ctrl-C
      out_ += "^C\r\n";
      buf_.clear();
      pos_ = 0;
      return Event::Cancel;
    case 4:                                                    // Ctrl-D
      if (buf_.empty()) {
        out_ += "\r\n";
        return Event::Eof;
      }
      if (pos_ < buf_.size()) buf_.erase(pos_, 1);
      break;
    case 5: pos_ = buf_.size(); break;                         // Ctrl-E
    case 6: if (pos_ < buf_.size()) ++pos_; break;             // Ctrl-F
    case 8:
    case 127:                                                  // Backspace
      if (pos_ > 0) buf_.erase(--pos_, 1);
      break;
    case '\t': complete(); return Event::None;
    case 11: buf_.erase(pos_); break;                          // Ctrl-K
    case 12: out_ += "\x1b[H\x1b[2J"; break;                   // Ctrl-L
    case 14: history_move(1); return Event::None;              // Ctrl-N
    case 16: history_move(-1); return Event::None;             // Ctrl-P
    case 18:                                                   // Ctrl-R
      search_ = true;
      query_.clear();
      before_search_ = buf_;
      before_pos_ = pos_;
      found_ = false;
      match_ = history_.size();
      break;
    case 21: buf_.erase(0, pos_); pos_ = 0; break;             // Ctrl-U
    case 23: {                                                 // Ctrl-W: the word before the cursor
      std::size_t p = pos_;
      while (p > 0 && std::isspace(static_cast<unsigned char>(buf_[p - 1]))) --p;
      while (p > 0 && !std::isspace(static_cast<unsigned char>(buf_[p - 1]))) --p;
      buf_.erase(p, pos_ - p);
      pos_ = p;
      break;
    }
    case kEsc: esc_ = Esc::Start; return Event::None;
    default:
      if (static_cast<unsigned char>(c) < 0x20) return Event::None;  // other control keys
      insert(std::string(1, c));
      return Event::None;
  }
  refresh();
  return Event::None;
}

// The end of an escape sequence: CSI or SS3 `final` with its parameters ("1;5" is Ctrl).
LineEditor::Event LineEditor::escape_end(char final, const std::string& params) {
  if (search_) end_search(true);  // a cursor key ends the search, keeping the match
  last_tab_ = false;
  const bool word = params.size() >= 3 && params.compare(params.size() - 2, 2, ";5") == 0;
  switch (final) {
    case 'A': history_move(-1); return Event::None;
    case 'B': history_move(1); return Event::None;
    case 'C':
      if (word) {
        while (pos_ < buf_.size() && !std::isalnum(static_cast<unsigned char>(buf_[pos_]))) ++pos_;
        while (pos_ < buf_.size() && std::isalnum(static_cast<unsigned char>(buf_[pos_]))) ++pos_;
      } else if (pos_ < buf_.size()) {
        ++pos_;
      }
      break;
    case 'D':
      if (word) {
        while (pos_ > 0 && !std::isalnum(static_cast<unsigned char>(buf_[pos_ - 1]))) --pos_;
        while (pos_ > 0 && std::isalnum(static_cast<unsigned char>(buf_[pos_ - 1]))) --pos_;
      } else if (pos_ > 0) {
        --pos_;
      }
      break;
    case 'H': pos_ = 0; break;
    case 'F': pos_ = buf_.size(); break;
    case '~':
      if (params == "1" || params == "7") pos_ = 0;
      else if (params == "4" || params == "8") pos_ = buf_.size();
      else if (params == "3" && pos_ < buf_.size()) buf_.erase(pos_, 1);  // Delete
      break;
    default: return Event::None;  // F-keys, PageUp, ...: nothing
  }
  refresh();
  return Event::None;
}

void LineEditor::insert(const std::string& text) {
  if (buf_.size() + text.size() > kMaxLine) {  // a paste without an end: not a command line
    out_ += '\a';
    return;
  }
  buf_.insert(pos_, text);
  pos_ += text.size();
  refresh();
}

void LineEditor::set_line(const std::string& text) {
  buf_ = text;
  pos_ = buf_.size();
  refresh();
}

void LineEditor::history_move(int delta) {
  if (history_.empty()) return;
  const long to = static_cast<long>(hist_pos_) + delta;
  if (to < 0 || to > static_cast<long>(history_.size())) return;
  if (hist_pos_ == history_.size()) saved_ = buf_;
  hist_pos_ = static_cast<std::size_t>(to);
  set_line(hist_pos_ == history_.size() ? saved_ : history_[hist_pos_]);
}

// Tab: the word before the cursor completed as far as the candidates agree (with a blank after
// a whole word); a second Tab lists them when they still differ.
void LineEditor::complete() {
  if (!completer_) return;
  std::size_t start = pos_;
  while (start > 0 && word_char(buf_[start - 1])) --start;
  const std::string prefix = buf_.substr(start, pos_ - start);
  std::vector<std::string> cands = completer_(buf_.substr(0, pos_), start);
  std::sort(cands.begin(), cands.end());
  cands.erase(std::unique(cands.begin(), cands.end()), cands.end());
  if (cands.empty()) {
    out_ += '\a';
    last_tab_ = false;
    return;
  }
  std::string common = cands.front();
  for (const auto& c : cands) {
    std::size_t n = 0;
    while (n < common.size() && n < c.size() && std::tolower(static_cast<unsigned char>(common[n])) == std::tolower(static_cast<unsigned char>(c[n])))
      ++n;
    common.resize(n);
  }
  if (cands.size() == 1) {  // the word as the candidate spells it, and a blank after a whole word
    const char last = common.empty() ? ' ' : common.back();
    if (last != '(' && last != '[' && last != ':' && last != '$') common += ' ';
  } else {  // the part the user typed stays as typed (candidates may differ in case)
    common = prefix + common.substr(std::min(prefix.size(), common.size()));
  }
  if (common.size() > prefix.size() || (common.size() == prefix.size() && common != prefix && same_prefix(common, prefix))) {
    buf_.replace(start, prefix.size(), common);
    pos_ = start + common.size();
    last_tab_ = false;
    refresh();
    return;
  }
  if (!last_tab_) {
    out_ += '\a';
    last_tab_ = true;
    return;
  }
  // The list, in columns under the line, then the line again.
  std::size_t widest = 0;
  for (const auto& c : cands) widest = std::max(widest, c.size());
  const std::size_t col = widest + 2, per_row = std::max<std::size_t>(1, static_cast<std::size_t>(width_) / col);
  const std::size_t rows = (cands.size() + per_row - 1) / per_row;
  out_ += "\r\n";
  for (std::size_t r = 0; r < rows; ++r) {
    std::string row;
    for (std::size_t k = r; k < cands.size(); k += rows) {
      row += cands[k];
      if (k + rows < cands.size()) row += std::string(col - cands[k].size(), ' ');
    }
    out_ += row + "\r\n";
  }
  refresh();
}

// Ctrl-R: typed characters extend the query and the newest entry holding it shows; Ctrl-R again
// goes to an older one, Backspace shortens the query, Ctrl-G or Ctrl-C gives the line back as it
// was; Enter runs the match, any other key takes it into the line and then does its own work.
void LineEditor::search_key(char c, bool& consumed, Event& ev) {
  consumed = true;
  ev = Event::None;
  if (c == 18) {
    if (found_ && match_ > 0) search_from(match_ - 1);
  } else if (c == 7 || c == 3) {
    end_search(false);
    return;
  } else if (c == 8 || c == 127) {
    if (!query_.empty()) query_.pop_back();
    found_ = false;
    if (!query_.empty() && !history_.empty()) search_from(history_.size() - 1);
  } else if (static_cast<unsigned char>(c) >= 0x20 && c != 127) {
    query_ += c;
    if (!history_.empty()) search_from(found_ ? match_ : history_.size() - 1);
  } else {
    consumed = false;  // any other key takes the match into the line, then does its own work
    end_search(true);
    return;
  }
  refresh();
}

bool LineEditor::search_from(std::size_t start) {
  if (query_.empty() || history_.empty()) return false;
  for (std::size_t i = std::min(start, history_.size() - 1) + 1; i-- > 0;)
    if (history_[i].find(query_) != std::string::npos) {
      match_ = i;
      found_ = true;
      return true;
    }
  found_ = false;
  return false;
}

void LineEditor::end_search(bool accept) {
  search_ = false;
  if (accept && found_ && match_ < history_.size()) {
    buf_ = history_[match_];
    pos_ = buf_.size();
    hist_pos_ = match_;
  } else if (!accept) {
    buf_ = before_search_;
    pos_ = before_pos_;
  }
  refresh();
}

void LineEditor::refresh() {
  // The text drawn is `head` + `tail` (prompt and line, or the search's), the cursor `at` columns in.
  std::string head;
  const std::string* tail = &buf_;
  std::size_t at = 0;
  if (search_) {
    const bool failed = !found_ && !query_.empty();
    head = std::string(failed ? "(failed reverse-i-search)`" : "(reverse-i-search)`") + query_ + "': ";
    static const std::string kNone;
    tail = match_ < history_.size() ? &history_[match_] : &kNone;
    at = head.size() + tail->size();
  } else {
    head = prompt_;
    at = head.size() + pos_;
  }
  // Keep the cursor on the screen: scroll the line left when it would pass the last column.
  const std::size_t avail = static_cast<std::size_t>(std::max(width_ - 1, 10));
  const std::size_t offset = at > avail ? at - avail : 0;
  std::string shown;
  if (offset >= head.size()) shown = tail->substr(offset - head.size(), avail);
  else if (head.size() - offset >= avail) shown = head.substr(offset, avail);
  else shown = head.substr(offset) + tail->substr(0, avail - (head.size() - offset));
  out_ += "\r" + shown + "\x1b[K\r";
  if (std::size_t col = at - offset; col > 0) out_ += "\x1b[" + std::to_string(col) + "C";
}

}  // namespace tmcl::debug
