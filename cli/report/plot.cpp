// The SVG writer of plot.hpp, by hand: stacked panels with "nice" ticks (1/2/5 x 10^k), series
// decimated to at most a few points per pixel column (keeping each column's minimum and maximum,
// so peaks survive), event markers as faint vertical lines with a glyph on top and a hover title.
// Its output is pinned byte for byte by tmclrun's plot goldens (tests/golden/run/plot-*).
#include "tmcl/plot.hpp"
#include "tmcl/xml.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>

#include "plot_text.hpp"

namespace tmcl {

std::string_view mark_name(Mark m) {
  switch (m) {
    case Mark::MoveIssued: return "move issued";
    case Mark::TargetReached: return "target reached";
    case Mark::Interrupt: return "interrupt";
    case Mark::StopSwitch: return "stop switch";
    case Mark::HomeSwitch: return "home switch";
    case Mark::Rebased: return "position re-based";
    case Mark::Stall: return "stall";
    case Mark::Contact: return "contact";
    case Mark::Other: return "event";
  }
  return "event";
}

std::string_view plot_colour(std::size_t index) {
  static constexpr std::string_view kColours[] = {"#1f5fbf", "#1e9a4a", "#d0342c", "#7b3fb5",
                                                  "#e07b00", "#0a8a8a", "#8c564b", "#c2185b"};
  return kColours[index % std::size(kColours)];
}

namespace report {

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  std::string s = buf;
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);  // no "-0.000"
  return s;
}

std::string seconds(SimTime t) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%s%lld.%06lld", t < 0 ? "-" : "", static_cast<long long>(std::llabs(t) / 1000000),
                static_cast<long long>(std::llabs(t) % 1000000));
  return buf;
}

}  // namespace report

namespace {

using report::fixed;
using report::seconds;


struct Ticks {
  double lo, hi, step;
};

// Axis range covering [lo, hi] with about `n` ticks at 1, 2 or 5 x 10^k.
Ticks nice_ticks(double lo, double hi, int n) {
  if (!(hi > lo)) {
    double pad = std::max(1.0, std::fabs(lo) * 0.1);
    lo -= pad;
    hi += pad;
  }
  double raw = (hi - lo) / n;
  double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double f : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (f * mag >= raw) {
      step = f * mag;
      break;
    }
  return {std::floor(lo / step + 1e-9) * step, std::ceil(hi / step - 1e-9) * step, step};
}

// A tick label: plain up to 10^4, then k / M / G with at most 3 significant decimals.
std::string tick_label(double v, double step) {
  if (std::fabs(v) < step * 1e-6) return "0";
  double a = std::fabs(v);
  const char* suffix = "";
  double div = 1;
  if (a >= 1e9) suffix = "G", div = 1e9;
  else if (a >= 1e6) suffix = "M", div = 1e6;
  else if (a >= 1e4) suffix = "k", div = 1e3;
  // As many decimals as the step needs to be exact (2.5 s steps read 2.5, 5, 7.5, not 2, 5, 8).
  double s = step / div;
  int decimals = 0;
  while (decimals < 6 && std::fabs(s * std::pow(10.0, decimals) - std::round(s * std::pow(10.0, decimals))) > 1e-6)
    ++decimals;
  std::string t = fixed(v / div, decimals);
  return t + suffix;
}

struct Series {
  std::vector<double> t, y;
};

// Keeps first, min, max and last of every pixel column (in time order).
Series decimate(const std::vector<double>& t, const std::vector<double>& y, double t0, double t1, int columns) {
  Series out;
  const std::size_t n = std::min(t.size(), y.size());  // a short line ends early
  if (n == 0) return out;
  double span = t1 > t0 ? t1 - t0 : 1;
  std::size_t i = 0;
  while (i < n) {
    auto col = static_cast<long>((t[i] - t0) / span * columns);
    std::size_t j = i, imin = i, imax = i;
    while (j < n && static_cast<long>((t[j] - t0) / span * columns) == col) {
      if (y[j] < y[imin]) imin = j;
      if (y[j] > y[imax]) imax = j;
      ++j;
    }
    std::array<std::size_t, 4> pick{i, std::min(imin, imax), std::max(imin, imax), j - 1};
    std::size_t last = static_cast<std::size_t>(-1);
    for (std::size_t p : pick)
      if (p != last) {
        out.t.push_back(t[p]);
        out.y.push_back(y[p]);
        last = p;
      }
    i = j;
  }
  return out;
}

struct MarkStyle {
  const char* colour;
  const char* glyph;  // SVG path around (0,0), about 10 px
};

MarkStyle mark_style(Mark m) {
  switch (m) {
    case Mark::MoveIssued: return {"#555555", "M-5,-6 L5,-6 L0,3 Z"};          // triangle down
    case Mark::TargetReached: return {"#7b3fb5", "M0,-6 L5,-1 L0,4 L-5,-1 Z"};  // diamond
    case Mark::Interrupt: return {"#e07b00", "M-4,-5 L4,-5 L4,3 L-4,3 Z"};      // square
    case Mark::StopSwitch: return {"#b00020", "M-5,3 L5,3 L0,-6 Z"};             // triangle up
    case Mark::HomeSwitch: return {"#2e7d32", "M0,-6 L5,-1 L5,4 L-5,4 L-5,-1 Z"};  // a house, green
    case Mark::Rebased: return {"#1565c0", "M-5,-6 L5,-6 L-5,4 L5,4 Z"};            // an hourglass: the count jumps
    case Mark::Stall: return {"#c2185b", "M-2,-6 L2,-6 L5,-3 L5,1 L2,4 L-2,4 L-5,1 L-5,-3 Z"};  // an octagon: a stop sign
    case Mark::Contact: return {"#8c564b", "M-6,-5 L0,-1 L-6,3 Z M2,-6 L5,-6 L5,4 L2,4 Z"};  // a wedge against a wall, the hard stop's brown
    case Mark::Other: return {"#0a8a8a", "M-4.5,-1 a4.5,4.5 0 1,0 9,0 a4.5,4.5 0 1,0 -9,0"};  // circle
  }
  return {"#000000", ""};
}

}  // namespace


namespace {

// The plot within [from, to]: samples and marks outside it left out.
Plot windowed(const Plot& plot, SimTime from, SimTime to) {
  Plot w;
  w.line_names = plot.line_names;
  std::size_t first = 0;
  while (first < plot.times.size() && plot.times[first] < from) ++first;
  std::size_t last = first;
  while (last < plot.times.size() && plot.times[last] <= to) ++last;
  w.times.assign(plot.times.begin() + static_cast<std::ptrdiff_t>(first), plot.times.begin() + static_cast<std::ptrdiff_t>(last));
  for (const auto& p : plot.panels) {
    PlotPanel q = p;
    for (auto& line : q.lines) {
      const std::size_t b = std::min(first, line.size()), e = std::min(last, line.size());
      line = std::vector<double>(line.begin() + static_cast<std::ptrdiff_t>(b), line.begin() + static_cast<std::ptrdiff_t>(e));
    }
    w.panels.push_back(std::move(q));
  }
  for (const auto& m : plot.marks)
    if (m.at >= from && m.at <= to) w.marks.push_back(m);
  return w;
}

// The interrupts of one kind (one label): a row of ticks, not a line over the panels each.
struct TickRow {
  std::string label;
  std::vector<SimTime> at;
};

std::vector<TickRow> tick_rows(const std::vector<RecordedMark>& marks) {
  std::vector<TickRow> rows;
  for (const auto& m : marks) {
    if (m.kind != Mark::Interrupt) continue;
    auto it = std::find_if(rows.begin(), rows.end(), [&](const TickRow& r) { return r.label == m.label; });
    if (it == rows.end()) it = rows.insert(rows.end(), TickRow{m.label, {}});
    it->at.push_back(m.at);
  }
  return rows;
}

// One legend entry: its width in pixels and its SVG drawn at (x, baseline y).
struct LegendItem {
  double width;
  std::function<void(std::ostream&, double, double)> draw;
};

}  // namespace

void write_svg(std::ostream& out, const Plot& whole, const PlotOptions& opt) {
  const bool window = opt.from > 0 || opt.to != kNever;
  const Plot cut = window ? windowed(whole, opt.from, opt.to) : Plot{};
  const Plot& plot = window ? cut : whole;
  const int W = opt.width, H = opt.height;
  const int left = 96, right = 28, bottom = 62, gap = 26;
  const int plot_w = W - left - right;
  const int panels = std::max(1, static_cast<int>(plot.panels.size()));
  const auto& times = plot.times;
  auto label = [](const PlotPanel& p) { return p.unit.empty() ? p.title : p.title + " [" + p.unit + "]"; };
  const char* dashes[] = {"", "7,4", "2,3", "10,3,2,3", "14,5", "6,3,1,3,1,3"};
  std::size_t lines = 0;
  for (const auto& p : plot.panels) lines = std::max(lines, p.lines.size());
  const std::vector<TickRow> rows = tick_rows(plot.marks);

  // The legend: quantities, lines (when more than one), marker kinds present; wrapped in rows
  // of 20 px within the picture's width.
  std::vector<LegendItem> legend;
  for (const auto& p : plot.panels) {
    const std::string text = label(p);
    legend.push_back({28 + 6.8 * static_cast<double>(text.size()) + 14, [text, colour = p.colour](std::ostream& o, double x, double y) {
                        o << "<line x1=\"" << x << "\" y1=\"" << y - 4 << "\" x2=\"" << x + 22 << "\" y2=\"" << y - 4
                          << "\" stroke=\"" << colour << "\" stroke-width=\"2.5\"/>";
                        o << "<text x=\"" << x + 28 << "\" y=\"" << y << "\" font-size=\"13\" fill=\"#333\">" << xml_text(text) << "</text>\n";
                      }});
  }
  if (lines > 1)
    for (std::size_t m = 0; m < lines; ++m) {
      const std::string name = m < plot.line_names.size() ? plot.line_names[m] : "line " + std::to_string(m);
      legend.push_back({std::max(90.0, 28 + 6.8 * static_cast<double>(name.size()) + 14), [name, dash = dashes[m % std::size(dashes)]](std::ostream& o, double x, double y) {
                          o << "<line x1=\"" << x << "\" y1=\"" << y - 4 << "\" x2=\"" << x + 22 << "\" y2=\"" << y - 4
                            << "\" stroke=\"#444\" stroke-width=\"2\" stroke-dasharray=\"" << dash << "\"/>";
                          o << "<text x=\"" << x + 28 << "\" y=\"" << y << "\" font-size=\"13\" fill=\"#333\">" << xml_text(name) << "</text>\n";
                        }});
    }
  constexpr int kMarkKinds = static_cast<int>(Mark::Other) + 1;  // Other is the enum's last
  bool present[kMarkKinds] = {};
  for (const auto& m : plot.marks) present[static_cast<int>(m.kind)] = true;
  for (int k = 0; k < kMarkKinds; ++k) {
    if (!present[k]) continue;
    const auto kind = static_cast<Mark>(k);
    legend.push_back({16 + 6.8 * static_cast<double>(mark_name(kind).size()) + 14, [kind](std::ostream& o, double x, double y) {
                        MarkStyle st = mark_style(kind);
                        if (kind == Mark::Interrupt)  // a tick, as in the interrupt rows
                          o << "<line x1=\"" << x + 6 << "\" y1=\"" << y - 9 << "\" x2=\"" << x + 6 << "\" y2=\"" << y + 1
                            << "\" stroke=\"" << st.colour << "\" stroke-width=\"2\"/>";
                        else
                          o << "<path transform=\"translate(" << x + 6 << ',' << y - 4 << ")\" d=\"" << st.glyph << "\" fill=\""
                            << st.colour << "\"/>";
                        o << "<text x=\"" << x + 16 << "\" y=\"" << y << "\" font-size=\"13\" fill=\"#333\">" << mark_name(kind)
                          << "</text>\n";
                      }});
  }
  std::vector<std::pair<double, double>> placed_legend;  // x, baseline of each item
  {
    double lx = left, ly = 58;
    for (const auto& item : legend) {
      if (lx > left && lx + item.width - 14 > W - right) {
        lx = left;
        ly += 20;
      }
      placed_legend.emplace_back(lx, ly);
      lx += item.width;
    }
  }
  const int legend_rows = placed_legend.empty() ? 1 : static_cast<int>((placed_legend.back().second - 58) / 20) + 1;
  // Below the legend: three levels of event glyphs, then one 14-px row per kind of interrupt.
  const int row_h = 14;
  const int top = 104 + 20 * (legend_rows - 1) + row_h * static_cast<int>(rows.size());
  const int marks_base = top - row_h * static_cast<int>(rows.size());  // the glyphs sit above it
  const int panel_h = (H - top - bottom - (panels - 1) * gap) / panels;

  double t_lo = static_cast<double>(opt.from) * 1e-6;
  double t_end = times.empty() ? t_lo : static_cast<double>(times.back()) * 1e-6;
  for (const auto& m : plot.marks) t_end = std::max(t_end, static_cast<double>(m.at) * 1e-6);
  Ticks tx = nice_ticks(t_lo, t_end > t_lo ? t_end : t_lo + 1, 10);
  const double first_tick = std::ceil(t_lo / tx.step - 1e-9) * tx.step;  // on the nice grid
  tx.lo = t_lo;
  if (t_end > t_lo) tx.hi = t_end;  // the axis ends with the data
  auto X = [&](double t) { return left + (t - tx.lo) / (tx.hi - tx.lo) * plot_w; };

  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" viewBox=\"0 0 " << W
      << ' ' << H << "\" font-family=\"Helvetica, Arial, sans-serif\">\n";
  out << "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  // A long title (a core in chip units names them there) is set smaller, to fit the width: a bold
  // character is about 0.6 em wide.
  double title_chars = 0;
  for (unsigned char c : opt.title) title_chars += (c & 0xC0) != 0x80;
  const int title_font = std::clamp(static_cast<int>((W - left - 16) / (0.6 * std::max(1.0, title_chars))), 10, 19);
  out << "<text x=\"" << left << "\" y=\"30\" font-size=\"" << title_font << "\" font-weight=\"bold\" fill=\"#222\">"
      << xml_text(opt.title) << "</text>\n";

  for (std::size_t i = 0; i < legend.size(); ++i) legend[i].draw(out, placed_legend[i].first, placed_legend[i].second);

  // interrupt rows: the label in the margin, one path of ticks, one hover title
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const int y = marks_base + row_h * static_cast<int>(r) + 1;
    const TickRow& row = rows[r];
    const char* colour = mark_style(Mark::Interrupt).colour;
    out << "<text x=\"" << left - 6 << "\" y=\"" << y + 9 << "\" font-size=\"11\" fill=\"" << colour
        << "\" text-anchor=\"end\">" << xml_text(row.label) << "</text>";
    out << "<path stroke=\"" << colour << "\" stroke-width=\"1.5\" d=\"";
    std::string last;
    for (SimTime t : row.at) {
      char buf[48];
      std::snprintf(buf, sizeof buf, "M%.1f,%dv10", X(static_cast<double>(t) * 1e-6), y);
      if (buf != last) out << buf;  // ticks on one pixel are one
      last = buf;
    }
    out << "\"><title>" << xml_text(row.label) << ": " << row.at.size() << (row.at.size() == 1 ? " interrupt at " : " interrupts, ")
        << seconds(row.at.front()) << " s" << (row.at.size() == 1 ? "" : " to " + seconds(row.at.back()) + " s")
        << "</title></path>\n";
  }

  std::vector<double> tsec(times.size());
  for (std::size_t i = 0; i < times.size(); ++i) tsec[i] = static_cast<double>(times[i]) * 1e-6;

  for (std::size_t p = 0; p < plot.panels.size(); ++p) {
    const PlotPanel& panel = plot.panels[p];
    const int y0 = top + static_cast<int>(p) * (panel_h + gap);
    // data range over all lines; in a window of time over the lines that change in it (a motor
    // standing far away would squash the one that moves: issue 41), the others clipped to the panel
    auto changes = [&](const std::vector<double>& ys) {
      for (std::size_t i = 1; i < ys.size() && i < times.size(); ++i)
        if (ys[i] != ys[0]) return true;
      return false;
    };
    bool some_change = false, some_still = false;
    for (const auto& ys : panel.lines) (changes(ys) ? some_change : some_still) = true;
    const bool clip = window && some_change && some_still;
    double lo = 0, hi = 0;
    bool any = false;
    for (const auto& ys : panel.lines) {
      if (clip && !changes(ys)) continue;
      for (std::size_t i = 0; i < ys.size() && i < times.size(); ++i) {
        lo = any ? std::min(lo, ys[i]) : ys[i];
        hi = any ? std::max(hi, ys[i]) : ys[i];
        any = true;
      }
    }
    // levels (a hard stop) inside the axis, so that the wall shows where the shaft meets it;
    // not in a zoomed panel that scales to what moves (one far away would squash it)
    if (!clip)
      for (const auto& lv : panel.levels) {
        lo = any ? std::min(lo, lv.value) : lv.value;
        hi = any ? std::max(hi, lv.value) : lv.value;
        any = true;
        for (const auto& [at, v] : lv.moves) {
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
      }
    if (panel.keep_zero) {
      lo = std::min(lo, 0.0);
      hi = std::max(hi, 0.0);
    }
    Ticks ty = nice_ticks(lo, hi, 5);
    auto Y = [&](double v) { return y0 + panel_h - (v - ty.lo) / (ty.hi - ty.lo) * panel_h; };

    out << "<g>\n<rect x=\"" << left << "\" y=\"" << y0 << "\" width=\"" << plot_w << "\" height=\"" << panel_h
        << "\" fill=\"#fafbfc\" stroke=\"#c8ccd0\"/>\n";
    if (clip)
      out << "<clipPath id=\"panel" << p << "\"><rect x=\"" << left << "\" y=\"" << y0 << "\" width=\"" << plot_w
          << "\" height=\"" << panel_h << "\"/></clipPath>\n";
    for (double v = ty.lo; v <= ty.hi + ty.step * 1e-6; v += ty.step) {
      double y = Y(v);
      bool zero = std::fabs(v) < ty.step * 1e-6;
      out << "<line x1=\"" << left << "\" y1=\"" << y << "\" x2=\"" << left + plot_w << "\" y2=\"" << y << "\" stroke=\""
          << (zero ? "#9aa0a6" : "#e3e6e9") << "\" stroke-width=\"1\"/>";
      out << "<text x=\"" << left - 8 << "\" y=\"" << y + 4 << "\" font-size=\"12\" fill=\"#444\" text-anchor=\"end\">"
          << tick_label(v, ty.step) << "</text>\n";
    }
    for (double t = first_tick; t <= tx.hi + tx.step * 1e-6; t += tx.step) {
      double x = X(t);
      out << "<line x1=\"" << x << "\" y1=\"" << y0 << "\" x2=\"" << x << "\" y2=\"" << y0 + panel_h
          << "\" stroke=\"#e3e6e9\" stroke-width=\"1\"/>\n";
    }
    // axis title, rotated, in the quantity's colour
    out << "<text transform=\"translate(" << 22 << ',' << y0 + panel_h / 2 << ") rotate(-90)\" font-size=\"14\" "
        << "font-weight=\"bold\" text-anchor=\"middle\" fill=\"" << panel.colour << "\">"
        << xml_text(panel.axis_title.empty() ? label(panel) : panel.axis_title) << "</text>\n";
    // event lines (interrupts have their rows above)
    for (const auto& m : plot.marks) {
      if (m.kind == Mark::Interrupt) continue;
      double x = X(static_cast<double>(m.at) * 1e-6);
      out << "<line x1=\"" << x << "\" y1=\"" << y0 << "\" x2=\"" << x << "\" y2=\"" << y0 + panel_h << "\" stroke=\""
          << mark_style(m.kind).colour << "\" stroke-opacity=\"0.45\" stroke-dasharray=\"3,3\"/>\n";
    }
    // levels: a broad pale brown band across the panel (a wall; the shaft's line, which stands at
    // it, stays visible on top), labelled above its right end (below it at the panel's top)
    for (const auto& lv : panel.levels) {
      // One segment per stretch of time the level holds a value (one across the panel unless the
      // count was re-based), the label above the last.
      double value = lv.value, from = tx.lo;
      std::optional<double> label_y;
      auto segment = [&](double to) {
        const double x1 = X(std::max(from, tx.lo)), x2 = X(std::min(to, tx.hi));
        const double y = Y(value);
        if (x2 <= x1 || y < y0 - 0.5 || y > y0 + panel_h + 0.5) return;  // outside the window or a zoomed panel
        out << "<line x1=\"" << x1 << "\" y1=\"" << y << "\" x2=\"" << x2 << "\" y2=\"" << y
            << "\" stroke=\"#8c564b\" stroke-opacity=\"0.35\" stroke-width=\"5\"/>";
        label_y = y;
      };
      for (const auto& [at, v] : lv.moves) {
        const double t = static_cast<double>(at) * 1e-6;
        segment(t);
        value = v;
        from = t;
      }
      segment(tx.hi);
      if (!label_y) continue;
      const double y = *label_y;
      out << "<text x=\"" << left + plot_w - 4 << "\" y=\"" << (y - 4 < y0 + 12 ? y + 13 : y - 4)
          << "\" font-size=\"12\" fill=\"#8c564b\" text-anchor=\"end\">" << xml_text(lv.label) << "</text>\n";
    }
    // series
    for (std::size_t m = 0; m < panel.lines.size(); ++m) {
      Series s = decimate(tsec, panel.lines[m], tx.lo, tx.hi, plot_w);
      if (s.t.empty()) continue;
      out << "<polyline fill=\"none\" stroke=\"" << panel.colour << "\" stroke-width=\"2\" stroke-linejoin=\"round\"";
      if (clip) out << " clip-path=\"url(#panel" << p << ")\"";
      if (m > 0) out << " stroke-dasharray=\"" << dashes[m % std::size(dashes)] << "\"";
      out << " points=\"";
      char buf[64];
      for (std::size_t i = 0; i < s.t.size(); ++i) {
        std::snprintf(buf, sizeof buf, "%.1f,%.1f ", X(s.t[i]), Y(s.y[i]));
        out << buf;
      }
      out << "\"/>\n";
    }
    out << "</g>\n";
  }

  // markers on top of the first panel, with hover titles; markers closer than 9 px stack upward
  std::vector<std::pair<double, int>> placed;  // x and level of markers drawn so far
  for (const auto& m : plot.marks) {
    if (m.kind == Mark::Interrupt) continue;
    MarkStyle st = mark_style(m.kind);
    double x = X(static_cast<double>(m.at) * 1e-6);
    int level = 0;
    for (bool clash = true; clash && level < 2;) {
      clash = false;
      for (const auto& [px, pl] : placed)
        if (pl == level && std::fabs(px - x) < 9) clash = true;
      if (clash) ++level;
    }
    placed.emplace_back(x, level);
    out << "<path transform=\"translate(" << x << ',' << marks_base - 8 - 13 * level << ")\" d=\"" << st.glyph << "\" fill=\"" << st.colour
        << "\"><title>" << seconds(m.at) << " s: "
        // a label that begins with the kind's name ("position re-based: ...") is not prefixed twice
        << (m.label.rfind(std::string(mark_name(m.kind)) + ":", 0) == 0 ? xml_text(m.label)
            : xml_text(mark_name(m.kind)) + (m.label.empty() ? "" : ": " + xml_text(m.label)))
        << (m.motor >= 0 ? " (motor " + std::to_string(m.motor) + ")" : "")
        << "</title></path>\n";
  }

  // time axis
  const int yb = top + panels * panel_h + (panels - 1) * gap;
  for (double t = first_tick; t <= tx.hi + tx.step * 1e-6; t += tx.step) {
    double x = X(t);
    out << "<line x1=\"" << x << "\" y1=\"" << yb << "\" x2=\"" << x << "\" y2=\"" << yb + 5 << "\" stroke=\"#666\"/>";
    out << "<text x=\"" << x << "\" y=\"" << yb + 20 << "\" font-size=\"12\" fill=\"#444\" text-anchor=\"middle\">"
        << tick_label(t, tx.step) << "</text>\n";
  }
  out << "<text x=\"" << left + plot_w / 2 << "\" y=\"" << H - 14
      << "\" font-size=\"14\" font-weight=\"bold\" text-anchor=\"middle\" fill=\"#333\">time [s]</text>\n";
  out << "</svg>\n";
}

}  // namespace tmcl
