// Did-you-mean and caret lines for every diagnostic (suggest.hpp).
#include "tmcl/diag_text.hpp"

#include <algorithm>
#include <cctype>

namespace tmcl {

namespace {

bool upper_eq(char x, char y) {
  return std::toupper(static_cast<unsigned char>(x)) == std::toupper(static_cast<unsigned char>(y));
}

// Optimal string alignment distance, case-insensitive.
int edit_distance(std::string_view a, std::string_view b) {
  std::vector<int> before(b.size() + 1), prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = static_cast<int>(j);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = static_cast<int>(i);
    for (std::size_t j = 1; j <= b.size(); ++j) {
      bool same = upper_eq(a[i - 1], b[j - 1]);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (same ? 0 : 1)});
      // Two swapped letters (SPA for SAP) count as one edit, not two.
      if (i > 1 && j > 1 && upper_eq(a[i - 1], b[j - 2]) && upper_eq(a[i - 2], b[j - 1]))
        cur[j] = std::min(cur[j], before[j - 2] + 1);
    }
    before = prev;
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

// Whether the character at `s[i]`, `n` bytes of valid UTF-8, is shown as it is in a quoted line:
// not a C1 control (U+0080..U+009F), nor an invisible one that would move the caret or turn the
// text around (zero-width and direction marks and overrides, U+200B..U+200F, U+202A..U+202E,
// U+2060..U+206F, the byte-order mark U+FEFF).
bool printable(std::string_view s, std::size_t i, std::size_t n) {
  auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[i + k]); };
  if (n == 2) return !(b(0) == 0xC2 && b(1) < 0xA0);
  if (n != 3) return true;
  if (b(0) == 0xE2 && b(1) == 0x80) return !((b(2) >= 0x8B && b(2) <= 0x8F) || (b(2) >= 0xAA && b(2) <= 0xAE));
  if (b(0) == 0xE2 && b(1) == 0x81) return !(b(2) >= 0xA0 && b(2) <= 0xAF);
  return !(b(0) == 0xEF && b(1) == 0xBB && b(2) == 0xBF);
}

}  // namespace

std::size_t utf8_length(std::string_view s, std::size_t i) {
  auto b = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  unsigned char c = b(i);
  std::size_t n = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC2 ? 2 : 0;
  if (n == 0 || c > 0xF4 || i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((b(i + k) & 0xC0) != 0x80) return 0;
  if (c == 0xE0 && b(i + 1) < 0xA0) return 0;   // overlong
  if (c == 0xED && b(i + 1) >= 0xA0) return 0;  // surrogate
  if (c == 0xF0 && b(i + 1) < 0x90) return 0;   // overlong
  if (c == 0xF4 && b(i + 1) >= 0x90) return 0;  // above U+10FFFF
  return n;
}

std::string closest_match(std::string_view word, const std::vector<std::string_view>& candidates) {
  if (word.size() > 64) return {};
  std::string_view best;
  int best_d = 1 << 30;
  for (auto c : candidates) {
    if (c.size() > 64) continue;
    int d = edit_distance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  // Close enough: at most a third of the word wrong, and never the whole word.
  int limit = static_cast<int>(word.size()) / 3;  // names of one or two letters get no guess
  if (best_d == 0 || best_d > limit) return {};
  return std::string(best);
}

std::string caret_lines(std::string_view line, int col, int len) {
  // The line character by character: a tab as it is (the caret line repeats it, so that both
  // move alike), a printable character of valid UTF-8 as it is (the "±" of a test file, a
  // comment's "°C"), any other byte as '?'. The caret line has a blank for each character before
  // the column and a tilde for each character after the first underlined one.
  const std::size_t from = static_cast<std::size_t>(std::max(1, col) - 1);
  const std::size_t to = std::min(line.size(), from + static_cast<std::size_t>(std::max(1, len)));
  std::string out = " ", under = " ";
  bool caret = false;
  for (std::size_t i = 0; i < line.size();) {
    const auto u = static_cast<unsigned char>(line[i]);
    const std::size_t valid = u >= 0x80 ? utf8_length(line, i) : 1;
    const std::size_t n = std::max<std::size_t>(valid, 1);  // a byte of invalid UTF-8 is a '?' of its own
    if (valid == 0 || (valid == 1 && u != '\t' && (u < 0x20 || u == 0x7f)) || (valid > 1 && !printable(line, i, valid)))
      out += '?';
    else
      out.append(line.substr(i, n));
    if (i < from) {
      under += u == '\t' ? '\t' : ' ';
    } else if (i < to) {
      under += caret ? '~' : '^';
      caret = true;
    }
    i += n;
  }
  if (!caret) under += std::string(from - std::min(from, line.size()), ' ') + '^';
  return out + "\n" + under + "\n";
}

std::string more_errors_note(const std::string& where, long long errors, long long warnings) {
  std::string what = std::to_string(errors) + " more error" + (errors == 1 ? "" : "s");
  if (warnings > 0) what += " and " + std::to_string(warnings) + " warning" + (warnings == 1 ? "" : "s");
  return (where.empty() ? std::string() : where + ": ") + "note: " + what + " not shown (--error-limit N changes the limit, 0 shows all)\n";
}

std::vector<LineWord> split_words(std::string_view line) {
  std::vector<LineWord> w;
  for (std::size_t i = 0; i < line.size();) {
    if (line[i] == ' ' || line[i] == '\t') {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
    w.push_back({std::string(line.substr(i, j - i)), static_cast<int>(i) + 1});
    i = j;
  }
  return w;
}

std::string render_file_diags(const std::vector<FileDiag>& diags, int limit) {
  std::string out;
  std::size_t shown = 0;
  for (const auto& d : diags) {
    if (limit > 0 && shown == static_cast<std::size_t>(limit)) break;
    out += d.file + ":" + std::to_string(d.line) + (d.col > 0 ? ":" + std::to_string(d.col) : std::string()) +
           ": error: " + d.message + "\n";
    if (d.col > 0) out += caret_lines(d.source, d.col, d.len);
    ++shown;
  }
  if (shown < diags.size()) out += more_errors_note(diags.front().file, static_cast<long long>(diags.size() - shown));
  return out;
}

}  // namespace tmcl
