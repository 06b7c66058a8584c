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

}  // namespace

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
  std::string out = " ";
  for (char c : line) {
    auto u = static_cast<unsigned char>(c);
    out += (c != '\t' && (u < 0x20 || u >= 0x7f)) ? '?' : c;
  }
  out += "\n ";
  col = std::max(1, col);
  for (int i = 1; i < col; ++i) {
    bool tab = static_cast<std::size_t>(i - 1) < line.size() && line[static_cast<std::size_t>(i - 1)] == '\t';
    out += tab ? '\t' : ' ';
  }
  out += '^';
  int room = static_cast<int>(line.size()) - col;
  for (int i = 1; i < std::min(len, room + 1); ++i) out += '~';
  return out + "\n";
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
