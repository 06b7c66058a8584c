// A self-contained SVG plot of sampled time series: stacked panels over one shared time axis,
// each panel one quantity (its own scale, unit and colour) with one line per source (a motor),
// and event markers: a dashed line over the panels and a glyph on top for each move, target
// reached, switch or other event; interrupts, which a timer raises every few milliseconds, as
// one row of ticks per interrupt above the panels. The legend wraps within the picture. tmclrun --plot draws a motion recording with it (motion_plot.hpp), tmclctl
// monitor --plot the parameters it polled; neither writes SVG itself.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tmcl/sim_time.hpp"

namespace tmcl {

enum class Mark : std::uint8_t { MoveIssued, TargetReached, Interrupt, StopSwitch, HomeSwitch, Rebased, Stall, Contact, Other };
std::string_view mark_name(Mark m);

struct RecordedMark {
  SimTime at;
  int motor;  // -1: not about one motor (e.g. a timer interrupt)
  Mark kind;
  std::string label;
  std::optional<std::int64_t> position;
};

// A horizontal line across a panel at a fixed value, labelled at its right end: a hard stop on
// the position panel ("hard stop left -20000"). Where the panel's count is re-based (a reference
// search, SAP 1) the wall stands still and its value in the count moves: from each instant of
// `moves` on the line is at that value instead, a segment each.
struct PlotLevel {
  double value;
  std::string label;
  std::vector<std::pair<SimTime, double>> moves = {};  // in time order
};

struct PlotPanel {
  std::string title;       // "position": legend and axis title
  std::string unit;        // "µsteps", shown as "position [µsteps]"; empty: no unit shown
  std::string colour;      // "#1f5fbf"
  std::string axis_title;  // the rotated title beside the panel, when shorter than the legend's
  bool keep_zero = false;  // the value axis always includes 0 (velocity, acceleration)
  // lines[k][i]: line k at times[i]. Line k > 0 is dashed; with more than one line the legend
  // names them by Plot::line_names.
  std::vector<std::vector<double>> lines;
  std::vector<PlotLevel> levels;  // inside the value axis, unless a zoomed panel scales to what moves
};

struct Plot {
  std::vector<SimTime> times;  // microseconds from the start, ascending
  std::vector<PlotPanel> panels;
  std::vector<std::string> line_names;  // "motor 0", "motor 1", ...
  std::vector<RecordedMark> marks;
};

struct PlotOptions {
  std::string title = "Motion";
  int width = 1100;
  int height = 780;
  // The window of time drawn (tmclrun --plot-from, --plot-to): samples and marks outside it are
  // left out, the time axis spans it (up to the last sample or mark when `to` lies beyond).
  SimTime from = 0;
  SimTime to = kNever;
};

// Panel colours for plots of any number of quantities: the motion plot's three, then more that
// stay apart on white (cycling after eight).
std::string_view plot_colour(std::size_t index);

void write_svg(std::ostream& out, const Plot& plot, const PlotOptions& options = {});

}  // namespace tmcl
