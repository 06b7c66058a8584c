// Motion recording, CSV and SVG output (motion_plot.hpp). The SVG is written by hand: three
// panels with "nice" ticks (1/2/5 x 10^k), series decimated to at most a few points per pixel
// column (keeping each column's minimum and maximum, so peaks survive), event markers as faint
// vertical lines with a glyph on top and a hover title.
#include "tmcl/motion_plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

namespace tmcl {

std::string_view mark_name(Mark m) {
  switch (m) {
    case Mark::MoveIssued: return "move issued";
    case Mark::TargetReached: return "target reached";
    case Mark::Interrupt: return "interrupt";
    case Mark::StopSwitch: return "stop switch";
    case Mark::Other: return "event";
  }
  return "event";
}

MotionRecorder::MotionRecorder(int motors, SimTime period) : motors_(motors), period_(period > 0 ? period : 1000) {}

void MotionRecorder::sample_until(const MotionCore& core, SimTime to) {
  for (; next_ <= to; next_ += period_) {
    times_.push_back(next_);
    for (int m = 0; m < motors_; ++m) samples_.push_back(core.sample_at(m, next_));
  }
}

void MotionRecorder::mark(SimTime at, int motor, Mark kind, std::string label, std::optional<std::int64_t> position) {
  marks_.push_back({at, motor, kind, std::move(label), position});
}

void MotionRecorder::motion_event(const MotionEvent& ev) {
  Mark k = ev.kind == MotionEventKind::TargetReached ? Mark::TargetReached : Mark::Other;
  mark(ev.at, ev.motor, k, std::string(motion_event_name(ev.kind)), ev.position);
}

namespace {

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

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string xml(std::string_view s) {
  std::string r;
  for (char c : s) {
    switch (c) {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      default: r += c;
    }
  }
  return r;
}

// "move issued: MVP ABS, 0, 5000"; a core's event is just its name ("velocity reached").
std::string event_text(const RecordedMark& m) {
  std::string kind(mark_name(m.kind));
  if (m.label.empty() || m.label == kind) return kind;
  if (m.kind == Mark::Other) return m.label;
  return kind + ": " + m.label;
}

}  // namespace

void write_csv(std::ostream& out, const MotionRecorder& rec) {
  out << "# time in s, position in microsteps, velocity in pps, acceleration in pps^2; sample period "
      << seconds(rec.period()) << " s\n";
  out << "time_s,motor,position,velocity_pps,acceleration_pps2,event\n";
  const auto& times = rec.times();
  const auto& marks = rec.marks();
  std::vector<std::size_t> order(marks.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return marks[a].at < marks[b].at; });
  std::size_t k = 0;
  const auto motors = static_cast<std::size_t>(rec.motors());
  for (std::size_t i = 0; i <= times.size(); ++i) {
    // events at an instant come after that instant's samples
    SimTime limit = i < times.size() ? times[i] : std::numeric_limits<SimTime>::max();
    for (; k < order.size() && marks[order[k]].at < limit; ++k) {
      const RecordedMark& m = marks[order[k]];
      out << seconds(m.at) << ',' << (m.motor >= 0 ? std::to_string(m.motor) : std::string()) << ','
          << (m.position ? std::to_string(*m.position) : std::string()) << ",,,"
          << csv_field(event_text(m)) << '\n';
    }
    if (i == times.size()) break;
    for (std::size_t m = 0; m < motors; ++m) {
      const MotionSample& s = rec.samples()[i * motors + m];
      out << seconds(times[i]) << ',' << m << ',' << s.position << ',' << fixed(s.velocity, 3) << ','
          << fixed(s.acceleration, 3) << ",\n";
    }
    // marks exactly at this sample instant
    for (; k < order.size() && marks[order[k]].at == times[i]; ++k) {
      const RecordedMark& m = marks[order[k]];
      out << seconds(m.at) << ',' << (m.motor >= 0 ? std::to_string(m.motor) : std::string()) << ','
          << (m.position ? std::to_string(*m.position) : std::string()) << ",,,"
          << csv_field(event_text(m)) << '\n';
    }
  }
}

// ------------------------------------------------------------------------------------- SVG
namespace {

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
  if (t.empty()) return out;
  double span = t1 > t0 ? t1 - t0 : 1;
  std::size_t i = 0;
  while (i < t.size()) {
    auto col = static_cast<long>((t[i] - t0) / span * columns);
    std::size_t j = i, imin = i, imax = i;
    while (j < t.size() && static_cast<long>((t[j] - t0) / span * columns) == col) {
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
    case Mark::Other: return {"#0a8a8a", "M-4.5,-1 a4.5,4.5 0 1,0 9,0 a4.5,4.5 0 1,0 -9,0"};  // circle
  }
  return {"#000000", ""};
}

}  // namespace

void write_svg(std::ostream& out, const MotionRecorder& rec, const PlotOptions& opt) {
  const int W = opt.width, H = opt.height;
  const int left = 96, right = 28, top = 104, bottom = 62, gap = 26;
  const int plot_w = W - left - right;
  const int panel_h = (H - top - bottom - 2 * gap) / 3;
  const auto motors = static_cast<std::size_t>(rec.motors());
  const auto& times = rec.times();

  double t_end = times.empty() ? 0 : static_cast<double>(times.back()) * 1e-6;
  for (const auto& m : rec.marks()) t_end = std::max(t_end, static_cast<double>(m.at) * 1e-6);
  Ticks tx = nice_ticks(0, t_end > 0 ? t_end : 1, 10);
  tx.lo = 0;
  if (t_end > 0) tx.hi = t_end;  // the axis ends with the data; ticks stay on the nice grid
  auto X = [&](double t) { return left + (t - tx.lo) / (tx.hi - tx.lo) * plot_w; };

  struct Quantity {
    const char* title;
    const char* unit;
    const char* colour;
  };
  const Quantity q[3] = {{"position", "µsteps", "#1f5fbf"}, {"velocity", "pps", "#1e9a4a"}, {"acceleration", "pps²", "#d0342c"}};
  const char* dashes[] = {"", "7,4", "2,3", "10,3,2,3"};

  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" viewBox=\"0 0 " << W
      << ' ' << H << "\" font-family=\"Helvetica, Arial, sans-serif\">\n";
  out << "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  out << "<text x=\"" << left << "\" y=\"30\" font-size=\"19\" font-weight=\"bold\" fill=\"#222\">" << xml(opt.title)
      << "</text>\n";

  // legend: quantities, motors (when more than one), marker kinds present
  {
    double lx = left;
    const double ly = 58;
    for (const auto& qq : q) {
      out << "<line x1=\"" << lx << "\" y1=\"" << ly - 4 << "\" x2=\"" << lx + 22 << "\" y2=\"" << ly - 4
          << "\" stroke=\"" << qq.colour << "\" stroke-width=\"2.5\"/>";
      out << "<text x=\"" << lx + 28 << "\" y=\"" << ly << "\" font-size=\"13\" fill=\"#333\">" << qq.title << " ["
          << qq.unit << "]</text>\n";
      lx += 28 + 6.8 * static_cast<double>(std::string_view(qq.title).size() + std::string_view(qq.unit).size() + 3) + 14;
    }
    if (motors > 1)
      for (std::size_t m = 0; m < motors && m < 4; ++m) {
        out << "<line x1=\"" << lx << "\" y1=\"" << ly - 4 << "\" x2=\"" << lx + 22 << "\" y2=\"" << ly - 4
            << "\" stroke=\"#444\" stroke-width=\"2\" stroke-dasharray=\"" << dashes[m] << "\"/>";
        out << "<text x=\"" << lx + 28 << "\" y=\"" << ly << "\" font-size=\"13\" fill=\"#333\">motor " << m << "</text>\n";
        lx += 90;
      }
    bool present[5] = {};
    for (const auto& m : rec.marks()) present[static_cast<int>(m.kind)] = true;
    for (int k = 0; k < 5; ++k) {
      if (!present[k]) continue;
      MarkStyle st = mark_style(static_cast<Mark>(k));
      out << "<path transform=\"translate(" << lx + 6 << ',' << ly - 4 << ")\" d=\"" << st.glyph << "\" fill=\""
          << st.colour << "\"/>";
      out << "<text x=\"" << lx + 16 << "\" y=\"" << ly << "\" font-size=\"13\" fill=\"#333\">"
          << mark_name(static_cast<Mark>(k)) << "</text>\n";
      lx += 16 + 6.8 * static_cast<double>(mark_name(static_cast<Mark>(k)).size()) + 14;
    }
  }

  std::vector<double> tsec(times.size());
  for (std::size_t i = 0; i < times.size(); ++i) tsec[i] = static_cast<double>(times[i]) * 1e-6;

  for (int p = 0; p < 3; ++p) {
    const int y0 = top + p * (panel_h + gap);
    // data range over all motors
    double lo = 0, hi = 0;
    bool any = false;
    std::vector<std::vector<double>> ys(motors, std::vector<double>(times.size()));
    for (std::size_t i = 0; i < times.size(); ++i)
      for (std::size_t m = 0; m < motors; ++m) {
        const MotionSample& s = rec.samples()[i * motors + m];
        double v = p == 0 ? static_cast<double>(s.position) : p == 1 ? s.velocity : s.acceleration;
        ys[m][i] = v;
        lo = any ? std::min(lo, v) : v;
        hi = any ? std::max(hi, v) : v;
        any = true;
      }
    if (p > 0) {  // velocity and acceleration: keep 0 in view
      lo = std::min(lo, 0.0);
      hi = std::max(hi, 0.0);
    }
    Ticks ty = nice_ticks(lo, hi, 5);
    auto Y = [&](double v) { return y0 + panel_h - (v - ty.lo) / (ty.hi - ty.lo) * panel_h; };

    out << "<g>\n<rect x=\"" << left << "\" y=\"" << y0 << "\" width=\"" << plot_w << "\" height=\"" << panel_h
        << "\" fill=\"#fafbfc\" stroke=\"#c8ccd0\"/>\n";
    for (double v = ty.lo; v <= ty.hi + ty.step * 1e-6; v += ty.step) {
      double y = Y(v);
      bool zero = std::fabs(v) < ty.step * 1e-6;
      out << "<line x1=\"" << left << "\" y1=\"" << y << "\" x2=\"" << left + plot_w << "\" y2=\"" << y << "\" stroke=\""
          << (zero ? "#9aa0a6" : "#e3e6e9") << "\" stroke-width=\"1\"/>";
      out << "<text x=\"" << left - 8 << "\" y=\"" << y + 4 << "\" font-size=\"12\" fill=\"#444\" text-anchor=\"end\">"
          << tick_label(v, ty.step) << "</text>\n";
    }
    for (double t = tx.lo; t <= tx.hi + tx.step * 1e-6; t += tx.step) {
      double x = X(t);
      out << "<line x1=\"" << x << "\" y1=\"" << y0 << "\" x2=\"" << x << "\" y2=\"" << y0 + panel_h
          << "\" stroke=\"#e3e6e9\" stroke-width=\"1\"/>\n";
    }
    // axis title, rotated, in the quantity's colour
    out << "<text transform=\"translate(" << 22 << ',' << y0 + panel_h / 2 << ") rotate(-90)\" font-size=\"14\" "
        << "font-weight=\"bold\" text-anchor=\"middle\" fill=\"" << q[p].colour << "\">" << q[p].title << " [" << q[p].unit
        << "]</text>\n";
    // event lines
    for (const auto& m : rec.marks()) {
      double x = X(static_cast<double>(m.at) * 1e-6);
      out << "<line x1=\"" << x << "\" y1=\"" << y0 << "\" x2=\"" << x << "\" y2=\"" << y0 + panel_h << "\" stroke=\""
          << mark_style(m.kind).colour << "\" stroke-opacity=\"0.45\" stroke-dasharray=\"3,3\"/>\n";
    }
    // series
    for (std::size_t m = 0; m < motors; ++m) {
      Series s = decimate(tsec, ys[m], tx.lo, tx.hi, plot_w);
      if (s.t.empty()) continue;
      out << "<polyline fill=\"none\" stroke=\"" << q[p].colour << "\" stroke-width=\"2\" stroke-linejoin=\"round\"";
      if (m > 0) out << " stroke-dasharray=\"" << dashes[m % 4] << "\"";
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
  for (const auto& m : rec.marks()) {
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
    out << "<path transform=\"translate(" << x << ',' << top - 8 - 13 * level << ")\" d=\"" << st.glyph << "\" fill=\"" << st.colour
        << "\"><title>" << seconds(m.at) << " s: " << xml(mark_name(m.kind))
        << (m.label.empty() ? "" : ": " + xml(m.label)) << (m.motor >= 0 ? " (motor " + std::to_string(m.motor) + ")" : "")
        << "</title></path>\n";
  }

  // time axis
  const int yb = top + 3 * panel_h + 2 * gap;
  for (double t = tx.lo; t <= tx.hi + tx.step * 1e-6; t += tx.step) {
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
