// Motion recording and its CSV (motion_plot.hpp); the SVG is the plot of plot.hpp with three
// panels (position, velocity, acceleration) and one line per motor.
#include "tmcl/motion_plot.hpp"

#include <algorithm>
#include <limits>
#include <utility>

#include "plot_text.hpp"

namespace tmcl {

MotionRecorder::MotionRecorder(int motors, SimTime period) : motors_(motors), period_(period > 0 ? period : 1000) {}

void MotionRecorder::sample_until(const MotionCore& core, SimTime to) {
  for (; next_ <= to; next_ += period_) {
    times_.push_back(next_);
    for (int m = 0; m < motors_; ++m) {
      samples_.push_back(core.sample_at(m, next_));
      for (int p : params_) param_samples_.push_back(core.sample_param(m, p, next_));
    }
  }
}

std::vector<int> MotionRecorder::shown_motors() const {
  if (shown_) return *shown_;
  std::vector<int> all;
  for (int m = 0; m < motors_; ++m) all.push_back(m);
  return all;
}

void MotionRecorder::mark(SimTime at, int motor, Mark kind, std::string label, std::optional<std::int64_t> position) {
  marks_.push_back({at, motor, kind, std::move(label), position});
}

void MotionRecorder::motion_event(const MotionEvent& ev) {
  Mark k = ev.kind == MotionEventKind::TargetReached ? Mark::TargetReached
           : ev.kind == MotionEventKind::Rebased      ? Mark::Rebased
           : ev.kind == MotionEventKind::Stall        ? Mark::Stall
           : ev.kind == MotionEventKind::Contact      ? Mark::Contact
           : ev.kind != MotionEventKind::SwitchChanged ? Mark::Other
           : ev.input == SwitchInput::Home           ? Mark::HomeSwitch
                                                     : Mark::StopSwitch;
  mark(ev.at, ev.motor, k, motion_event_text(ev), ev.position);
  if (ev.kind == MotionEventKind::Rebased) rebase(ev.at, ev.motor, -std::int64_t{ev.value});  // the reference point is 0 now
}

std::string_view plot_series_name(int param) {
  switch (param) {
    case 206: return "load value";
    case 180: return "actual current";
    default: return {};
  }
}

namespace {

using report::fixed;
using report::seconds;

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// "move issued: MVP ABS, 0, 5000"; a core's event is just its name ("velocity reached"), a
// switch's its own ("left switch on", "home switch closed").
std::string event_text(const RecordedMark& m) {
  std::string kind(mark_name(m.kind));
  if (m.label.empty() || m.label == kind) return kind;
  if (m.kind == Mark::Other || m.kind == Mark::StopSwitch || m.kind == Mark::HomeSwitch || m.kind == Mark::Rebased ||
      m.kind == Mark::Stall || m.kind == Mark::Contact)
    return m.label;  // "left switch closed", "position re-based: ..."
  return kind + ": " + m.label;
}

// "hard stop left -20000": a scenario's hard stop, in the position count the scenario gives.
std::string hard_stop_text(const RecordedHardStop& h) {
  return "hard stop " + std::string(switch_input_name(h.side)) + " " + std::to_string(h.position);
}

// Where a hard stop is in its motor's count after each re-base of that count: (from when, where).
std::vector<std::pair<SimTime, std::int64_t>> wall_moves(const MotionRecorder& rec, const RecordedHardStop& h) {
  std::vector<std::pair<SimTime, std::int64_t>> moves;
  std::int64_t at = h.position;
  for (const auto& r : rec.rebases())
    if (r.motor == h.motor) moves.emplace_back(r.at, at += r.delta);
  return moves;
}

bool is_shown(const MotionRecorder& rec, int motor) {
  const auto motors = rec.shown_motors();
  return std::find(motors.begin(), motors.end(), motor) != motors.end();
}

}  // namespace

namespace {
// "load_value_206": a sampled parameter's CSV column, its plot name in words and its number.
std::string series_column(int param) {
  std::string name(plot_series_name(param));
  if (name.empty()) name = "parameter";
  std::replace(name.begin(), name.end(), ' ', '_');
  return name + "_" + std::to_string(param);
}
}  // namespace

void write_csv(std::ostream& out, const MotionRecorder& rec, std::string_view units_note) {
  out << "# time in s, position in microsteps, velocity in pps, acceleration in pps^2; sample period "
      << seconds(rec.period()) << " s\n";
  if (!units_note.empty()) out << "# " << units_note << '\n';
  for (const auto& h : rec.hard_stops()) {
    if (!is_shown(rec, h.motor)) continue;
    out << "# " << hard_stop_text(h) << " (motor " << h.motor << ")\n";
    for (const auto& [from, at] : wall_moves(rec, h))
      out << "# " << hard_stop_text(h) << " (motor " << h.motor << ") at " << at << " from " << seconds(from)
          << " s, the position count re-based\n";
  }
  const auto& times = rec.times();
  const auto motors = static_cast<std::size_t>(rec.motors());
  const auto shown = rec.shown_motors();
  // After `event`, so that the first six columns are the same in every file: the shaft when it
  // parted from the counter in the run (steps lost), and the parameters sampled with the motion.
  bool shaft_column = false;
  for (std::size_t i = 0; i < times.size() && !shaft_column; ++i)
    for (int m : shown)
      if (static_cast<std::size_t>(m) < motors && rec.samples()[i * motors + static_cast<std::size_t>(m)].shaft) shaft_column = true;
  const auto& params = rec.sampled_params();
  out << "time_s,motor,position,velocity_pps,acceleration_pps2,event";
  if (shaft_column) out << ",shaft_position";
  for (int p : params) out << ',' << series_column(p);
  out << '\n';
  const std::string no_extras(static_cast<std::size_t>(shaft_column) + params.size(), ',');
  const auto& marks = rec.marks();
  std::vector<std::size_t> order(marks.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return marks[a].at < marks[b].at; });
  auto mark_row = [&](const RecordedMark& m) {
    out << seconds(m.at) << ',' << (m.motor >= 0 ? std::to_string(m.motor) : std::string()) << ','
        << (m.position ? std::to_string(*m.position) : std::string()) << ",,," << csv_field(event_text(m)) << no_extras
        << '\n';
  };
  std::size_t k = 0;
  for (std::size_t i = 0; i <= times.size(); ++i) {
    // events at an instant come after that instant's samples
    SimTime limit = i < times.size() ? times[i] : std::numeric_limits<SimTime>::max();
    for (; k < order.size() && marks[order[k]].at < limit; ++k) mark_row(marks[order[k]]);
    if (i == times.size()) break;
    for (int m_shown : shown) {
      const auto m = static_cast<std::size_t>(m_shown);
      if (m >= motors) continue;
      const MotionSample& s = rec.samples()[i * motors + m];
      out << seconds(times[i]) << ',' << m << ',' << s.position << ',' << fixed(s.velocity, 3) << ','
          << fixed(s.acceleration, 3) << ',';
      if (shaft_column) out << ',' << s.shaft.value_or(s.position);
      for (std::size_t p = 0; p < params.size(); ++p) {
        out << ',';
        if (const auto& v = rec.param_samples()[(i * motors + m) * params.size() + p]) out << *v;
      }
      out << '\n';
    }
    // marks exactly at this sample instant
    for (; k < order.size() && marks[order[k]].at == times[i]; ++k) mark_row(marks[order[k]]);
  }
}

void write_svg(std::ostream& out, const MotionRecorder& rec, const PlotOptions& options) {
  Plot plot;
  plot.times = rec.times();
  plot.marks = rec.marks();
  const auto motors = static_cast<std::size_t>(rec.motors());
  std::vector<std::size_t> shown;
  for (int m : rec.shown_motors())
    if (m >= 0 && static_cast<std::size_t>(m) < motors) shown.push_back(static_cast<std::size_t>(m));
  const char* const title[3] = {"position", "velocity", "acceleration"};
  const char* const unit[3] = {"µsteps", "pps", "pps²"};
  for (int q = 0; q < 3; ++q) {
    PlotPanel panel{title[q], unit[q], std::string(plot_colour(static_cast<std::size_t>(q))), "", q > 0, {}, {}};
    panel.lines.assign(shown.size(), std::vector<double>(rec.times().size()));
    for (std::size_t i = 0; i < rec.times().size(); ++i)
      for (std::size_t k = 0; k < shown.size(); ++k) {
        const MotionSample& s = rec.samples()[i * motors + shown[k]];
        panel.lines[k][i] = q == 0 ? static_cast<double>(s.position) : q == 1 ? s.velocity : s.acceleration;
      }
    plot.panels.push_back(std::move(panel));
  }
  for (std::size_t m : shown) plot.line_names.push_back("motor " + std::to_string(m));
  // The sampled parameters (--plot-series): a panel each, one line per motor shown (none where
  // the core cannot say the value), in the parameter's raw units.
  const std::size_t np = rec.sampled_params().size();
  for (std::size_t k = 0; k < np; ++k) {
    const int param = rec.sampled_params()[k];
    const std::string name = std::string(plot_series_name(param)) + " (" + std::to_string(param) + ")";
    PlotPanel panel{name, "", std::string(plot_colour(3 + k)), "", true, {}, {}};
    for (std::size_t m : shown) {
      std::vector<double> line;
      for (std::size_t i = 0; i < rec.times().size(); ++i) {
        const auto& v = rec.param_samples()[(i * motors + m) * np + k];
        if (!v) break;
        line.push_back(static_cast<double>(*v));
      }
      if (line.size() < rec.times().size()) line.clear();  // a core that cannot say it
      panel.lines.push_back(std::move(line));
    }
    plot.panels.push_back(std::move(panel));
  }
  // The shaft where it parts from the counter (steps lost): one more line in the position panel,
  // so that a lost-step run does not look as if the carriage went through the wall (issue 41).
  for (std::size_t k = 0; k < shown.size(); ++k) {
    bool apart = false;
    for (std::size_t i = 0; i < rec.times().size() && !apart; ++i) apart = rec.samples()[i * motors + shown[k]].shaft.has_value();
    if (!apart) continue;
    std::vector<double> line(rec.times().size());
    for (std::size_t i = 0; i < line.size(); ++i) {
      const MotionSample& s = rec.samples()[i * motors + shown[k]];
      line[i] = static_cast<double>(s.shaft.value_or(s.position));
    }
    plot.panels[0].lines.push_back(std::move(line));
    for (std::size_t q = 1; q < plot.panels.size(); ++q) plot.panels[q].lines.emplace_back();  // no speed of its own
    plot.line_names.push_back("motor " + std::to_string(shown[k]) + " shaft");
  }
  // The scenario's hard stops: a line each on the position panel, named after the motor when
  // the plot shows more than one, where the wall is in the motor's count at each instant.
  for (const auto& h : rec.hard_stops()) {
    if (!is_shown(rec, h.motor)) continue;
    PlotLevel level{static_cast<double>(h.position),
                    (shown.size() > 1 ? "motor " + std::to_string(h.motor) + " " : std::string()) + hard_stop_text(h)};
    for (const auto& [from, at] : wall_moves(rec, h)) level.moves.emplace_back(from, static_cast<double>(at));
    plot.panels[0].levels.push_back(std::move(level));
  }
  write_svg(out, plot, options);
}

}  // namespace tmcl
