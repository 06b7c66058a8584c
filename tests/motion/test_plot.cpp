// Recorder, CSV and SVG: the CSV format on one move and a structural check of the SVG. The golden
// CSVs of the manuals' example programs are golden cases (tests/golden/motion/, motion_csv.cpp).
#include <cstdlib>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <string>

#include "check.hpp"
#include "recording.hpp"
#include "tmcl/motion_recording.hpp"

using mt::Runner;

// USB-2-SD manual, section 7.2, one pass of the main loop: the SVG has its three panels and marks.
TEST(svg_usb2sd_main_loop) {
  Runner r("tmc4361", "usb-2-sd", 20000);
  mt::usb2sd_main_loop(r);
  std::ostringstream svg;
  tmcl::write_svg(svg, r.rec, {"USB-2-SD: MVP ABS 5000, MVP ABS 0", 1100, 780});
  std::string s = svg.str();
  CHECK(s.rfind("<svg", 0) == 0);
  CHECK(s.find("</svg>") != std::string::npos);
  CHECK(s.find("position [µsteps]") != std::string::npos);
  CHECK(s.find("velocity [pps]") != std::string::npos);
  CHECK(s.find("acceleration [pps²]") != std::string::npos);
  CHECK(s.find("time [s]") != std::string::npos);
  std::size_t polylines = 0, pos = 0;
  while ((pos = s.find("<polyline", pos)) != std::string::npos) ++polylines, ++pos;
  CHECK_EQ(polylines, std::size_t{3});
  CHECK(s.find("move issued: MVP ABS, 0, 5000") != std::string::npos);
  CHECK(s.find("target reached") != std::string::npos);
  if (std::getenv("TMCL_PLOT_OUT")) std::ofstream(std::getenv("TMCL_PLOT_OUT")) << s;
}

TEST(csv_format) {
  Runner r("tmc4361", "usb-2-sd", 250000);
  r.mvp(100000);
  r.wait_pos();
  std::ostringstream csv;
  tmcl::write_csv(csv, r.rec);
  std::string s = csv.str();
  CHECK(s.find("time_s,motor,position,velocity_pps,acceleration_pps2,event\n") != std::string::npos);
  CHECK(s.find("0.000000,0,0,,,\"move issued: MVP ABS, 0, 100000\"\n") != std::string::npos);
  CHECK(s.find("1.000000,0,25600,51200.000,0.000,\n") != std::string::npos);
  CHECK(s.find("2.953125,0,100000,,,target reached\n") != std::string::npos);
}

TEST(svg_many_motors_and_empty) {
  tmcl::MotionRecorder empty(1, 1000);
  std::ostringstream svg;
  tmcl::write_svg(svg, empty);
  CHECK(svg.str().find("</svg>") != std::string::npos);
}

namespace {

// A plot of six lines over 22 s with every kind of mark, and a 100 ms timer's interrupts.
tmcl::Plot busy_plot() {
  tmcl::Plot p;
  for (tmcl::SimTime t = 0; t <= 21'900'000; t += 100'000) p.times.push_back(t);
  for (const char* q : {"position", "velocity", "acceleration"}) {
    tmcl::PlotPanel panel{q, "unit", std::string(tmcl::plot_colour(p.panels.size())), "", false, {}, {}};
    for (int m = 0; m < 6; ++m) {
      std::vector<double> line;
      for (std::size_t i = 0; i < p.times.size(); ++i) line.push_back(static_cast<double>(i * static_cast<std::size_t>(m + 1)));
      panel.lines.push_back(line);
    }
    p.panels.push_back(panel);
  }
  for (int m = 0; m < 6; ++m) p.line_names.push_back("motor " + std::to_string(m));
  for (tmcl::SimTime t = 100'000; t <= 21'900'000; t += 100'000) p.marks.push_back({t, -1, tmcl::Mark::Interrupt, "TI_TIMER0", {}});
  p.marks.push_back({1'000'000, 0, tmcl::Mark::MoveIssued, "move to 5", 0});
  p.marks.push_back({2'000'000, 0, tmcl::Mark::TargetReached, "target reached", 5});
  p.marks.push_back({3'000'000, 0, tmcl::Mark::StopSwitch, "left switch on", 5});
  p.marks.push_back({4'000'000, 0, tmcl::Mark::Other, "velocity reached", 5});
  p.marks.push_back({6'000'000, -1, tmcl::Mark::Interrupt, "TI_STOPL0", {}});
  return p;
}

// Every number of an attribute `name="..."` in the SVG.
std::vector<double> attribute_values(const std::string& svg, const std::string& name) {
  std::vector<double> v;
  const std::string key = " " + name + "=\"";
  for (std::size_t at = svg.find(key); at != std::string::npos; at = svg.find(key, at + 1))
    v.push_back(std::strtod(svg.c_str() + at + key.size(), nullptr));
  return v;
}

std::size_t count(const std::string& s, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t at = s.find(part); at != std::string::npos; at = s.find(part, at + 1)) ++n;
  return n;
}

}  // namespace

// Issue 28 item 14: the legend stays inside the picture (it used to reach x = 1272 of 1100):
// every text's start plus its length (13 px text, about 6.8 px a character) ends inside.
TEST(svg_legend_wraps_within_the_picture) {
  std::ostringstream svg;
  tmcl::write_svg(svg, busy_plot(), {"six motors", 1100, 780});
  const std::string s = svg.str();
  int texts = 0;
  for (std::size_t at = s.find("<text x=\""); at != std::string::npos; at = s.find("<text x=\"", at + 1)) {
    const double x = std::strtod(s.c_str() + at + 9, nullptr);
    const std::size_t open = s.find('>', at), close = s.find("</text>", at);
    const std::string text = s.substr(open + 1, close - open - 1);
    if (s.substr(at, close - at).find("text-anchor") != std::string::npos) continue;  // axes, row labels
    ++texts;
    CHECK(x + 6.8 * static_cast<double>(text.size()) <= 1100);
    if (x + 6.8 * static_cast<double>(text.size()) > 1100) std::fprintf(stderr, "  outside: %s at %g\n", text.c_str(), x);
  }
  CHECK(texts > 12);
  CHECK_EQ(count(s, ">motor 5</text>"), std::size_t{1});  // every motor is in the legend
}

// Periodic interrupts: one row of ticks per interrupt (with one title counting them), never a
// dashed line over the panels each.
TEST(svg_interrupts_are_a_row_of_ticks) {
  std::ostringstream svg;
  tmcl::write_svg(svg, busy_plot());
  const std::string s = svg.str();
  CHECK_EQ(count(s, "stroke=\"#e07b00\" stroke-opacity=\"0.45\""), std::size_t{0});  // no interrupt lines
  CHECK_EQ(count(s, "stroke-dasharray=\"3,3\""), std::size_t{4 * 3});  // the four other marks, over three panels
  CHECK_EQ(count(s, "<title>TI_TIMER0: 219 interrupts, 0.100000 s to 21.900000 s</title>"), std::size_t{1});
  CHECK_EQ(count(s, "<title>TI_STOPL0: 1 interrupt at 6.000000 s</title>"), std::size_t{1});
  CHECK_EQ(count(s, ">TI_TIMER0</text>"), std::size_t{1});
  CHECK(count(s, "<path") < 12);  // 219 interrupts drew 219 glyphs and 3 x 219 lines
}

// --plot-from/--plot-to: only the window is drawn, the time axis spans it.
TEST(svg_window_of_time) {
  tmcl::PlotOptions o;
  o.from = 5'000'000;
  o.to = 10'000'000;
  std::ostringstream svg;
  tmcl::write_svg(svg, busy_plot(), o);
  const std::string s = svg.str();
  CHECK(s.find("text-anchor=\"middle\">5.0</text>") != std::string::npos);  // the first time tick
  CHECK(s.find("text-anchor=\"middle\">10.0</text>") != std::string::npos);  // the last
  CHECK(s.find("text-anchor=\"middle\">0</text>") == std::string::npos);
  CHECK(s.find("TI_TIMER0: 51 interrupts, 5.000000 s to 10.000000 s") != std::string::npos);
  CHECK(s.find("move to 5") == std::string::npos);   // at 1 s: outside
  CHECK(s.find("TI_STOPL0") != std::string::npos);   // at 6 s: inside
  for (double x : attribute_values(s, "x1")) CHECK(x >= 96 - 1e-9 && x <= 1100 - 28 + 1e-9);
}

// A title that would run past the width (a core in chip units names its divisors there) is set
// smaller; a short one keeps its size.
TEST(svg_long_title_fits) {
  tmcl::MotionRecorder rec(1, 1000);
  std::ostringstream short_svg, long_svg;
  tmcl::write_svg(short_svg, rec, {"p.tmc on usb-2-sd (tmc4361 motion)", 1100, 780});
  CHECK(short_svg.str().find("font-size=\"19\" font-weight=\"bold\" fill=\"#222\">p.tmc on") != std::string::npos);
  const std::string title(200, 'x');
  tmcl::write_svg(long_svg, rec, {title, 1100, 780});
  CHECK(long_svg.str().find("font-size=\"10\" font-weight=\"bold\" fill=\"#222\">" + title) != std::string::npos);
  std::ostringstream mid;
  tmcl::write_svg(mid, rec, {std::string(120, 'x'), 1100, 780});
  CHECK(mid.str().find("font-size=\"13\" font-weight=\"bold\"") != std::string::npos);  // (1100 - 96 - 16) / 72
}

// A title is XML text: markup characters are escaped and control bytes, which XML 1.0 does not
// allow, left out (a program named with one must not make the picture unreadable).
TEST(svg_title_is_escaped_xml) {
  tmcl::MotionRecorder rec(1, 1000);
  std::ostringstream svg;
  tmcl::write_svg(svg, rec, {"a<b & 'c' \x01.tmc", 1100, 780});
  CHECK(svg.str().find(">a&lt;b &amp; &apos;c&apos; .tmc</text>") != std::string::npos);
  CHECK(svg.str().find('\x01') == std::string::npos);
}

// The recording of a core in chip units: a rotation's speed in units and pps; a placed switch's
// events as marks that name the switch; the CSV's units line.
TEST(recording_in_chip_units) {
  auto core = tmcl::make_motion_core("tmc429");
  core->reset(*tmcl::find_profile("generic"), 1);
  tmcl::MotionRecorder rec(1, 100000);
  tmcl::RecordingCore rc(*core, rec);
  CHECK(rc.place_switch(0, tmcl::SwitchInput::StopLeft, INT64_MIN, -3000));
  rc.rotate(0, -1000);
  std::vector<tmcl::MotionEvent> ev;
  for (int i = 0; i < 4 && rc.next_event() != tmcl::kNever; ++i) rc.advance(rc.next_event(), ev);
  std::ostringstream csv;
  tmcl::write_csv(csv, rec, rc.units_note());
  const std::string s = csv.str();
  CHECK(s.find("move issued: rotate at -1000 (-30517.578 pps)") != std::string::npos);
  CHECK(s.find(",0,-3000,,,left switch closed\n") != std::string::npos);
  CHECK(s.find("\n# TMC429 units: pulse divisor 3, ramp divisor 7: velocity 1 = 30.5176 pps, acceleration 1 = 465.661 pps²\n") !=
        std::string::npos);
}

// Issue 34: a stop on stall is a mark of its own (a stop sign, "stall" in the legend), not a
// generic event: a TMCM-1110 driving into its hard stop with stop on stall (181) on.
TEST(stall_is_a_mark_of_its_own) {
  auto core = tmcl::make_motion_core("tmc429");
  core->reset(*tmcl::find_profile("tmcm-1110"), 1);
  tmcl::MotionRecorder rec(1, 100000);
  tmcl::RecordingCore rc(*core, rec);
  CHECK(rc.set_param(0, 140, 4) == tmcl::ParamWrite::Ok);  // 16 microsteps
  CHECK(rc.set_param(0, 5, 1000) == tmcl::ParamWrite::Ok);
  CHECK(rc.set_param(0, 181, 100) == tmcl::ParamWrite::Ok);
  CHECK(rc.place_hard_stop(0, tmcl::SwitchInput::StopLeft, -5000));
  rc.rotate(0, -400);
  std::vector<tmcl::MotionEvent> ev;
  for (int i = 0; i < 20 && rc.next_event() != tmcl::kNever; ++i) rc.advance(rc.next_event(), ev);
  std::ostringstream csv, svg;
  tmcl::write_csv(csv, rec, rc.units_note());
  tmcl::write_svg(svg, rec, {"stall", 1100, 780});
  const std::string c = csv.str(), s = svg.str();
  CHECK(c.find(",0,-5008,,,\"stall: load value 0, stopped\"\n") != std::string::npos);
  CHECK(s.find("M-2,-6 L2,-6 L5,-3 L5,1 L2,4 L-2,4 L-5,1 L-5,-3 Z\" fill=\"#c2185b\"><title>") != std::string::npos);
  CHECK(s.find(">stall</text>") != std::string::npos);  // its legend entry
  CHECK(s.find("<title>0.423363 s: stall: load value 0, stopped (motor 0)</title>") != std::string::npos);
}

// A window of time scales each panel to the lines that change in it (issue 41): a motor standing
// at 0 does not squash one moving near 100000; the standing line is clipped to the panel.
TEST(svg_window_scales_to_the_moving_lines) {
  tmcl::Plot p;
  tmcl::PlotPanel panel{"position", "µsteps", "#1f77b4", "", false, {}, {}};
  panel.lines.assign(2, {});
  for (int i = 0; i <= 100; ++i) {
    p.times.push_back(i * 100'000);
    panel.lines[0].push_back(0);
    panel.lines[1].push_back(100000 + 10.0 * i);
  }
  p.panels.push_back(panel);
  p.line_names = {"motor 0", "motor 1"};
  tmcl::PlotOptions o;
  o.from = 2'000'000;
  o.to = 8'000'000;
  std::ostringstream svg;
  tmcl::write_svg(svg, p, o);
  const std::string s = svg.str();
  CHECK(s.find("text-anchor=\"end\">0</text>") == std::string::npos);  // no tick at 0: the axis spans 100200..100800
  CHECK(s.find("text-anchor=\"end\">100.4k</text>") != std::string::npos);
  CHECK_EQ(count(s, "clip-path=\"url(#panel0)\""), std::size_t{2});
  std::ostringstream whole;  // without a window every line counts, as before
  tmcl::write_svg(whole, p);
  CHECK(whole.str().find("text-anchor=\"end\">0</text>") != std::string::npos);
  CHECK(whole.str().find("clip-path") == std::string::npos);
}

// Steps lost at a hard stop (issue 41): the position panel draws the shaft where it parts from
// the counter, one more line named in the legend; a run that loses none draws no such line.
TEST(svg_draws_the_shaft_where_it_parts_from_the_counter) {
  for (int wall = 0; wall < 2; ++wall) {
    Runner r("tmc5160", "tmcm-1260", 20000);
    if (wall) CHECK(r.b.core->place_hard_stop(0, tmcl::SwitchInput::StopRight, 20000));
    r.mvp(60000);
    r.wait_pos();
    CHECK(r.rec.samples().back().shaft.has_value() == (wall != 0));
    if (wall) CHECK_EQ(*r.rec.samples().back().shaft, 20000);  // the counter is at 60000
    std::ostringstream svg;
    tmcl::write_svg(svg, r.rec);
    const std::string s = svg.str();
    CHECK((s.find(">motor 0 shaft</text>") != std::string::npos) == (wall != 0));
    CHECK_EQ(count(s, "<polyline"), std::size_t{wall ? 4u : 3u});
    // the CSV: a shaft column after the event in a run that lost steps, none otherwise
    std::ostringstream csv;
    tmcl::write_csv(csv, r.rec);
    const std::string c = csv.str();
    CHECK((c.find("acceleration_pps2,event,shaft_position\n") != std::string::npos) == (wall != 0));
    if (wall) CHECK(c.find(",20000\n") != std::string::npos);  // the shaft stands at the wall
  }
}

// A PD60-1260 (tmc5160) recorded every 20 ms through the recording decorator, as tmclrun records.
struct Recorded1260 {
  std::unique_ptr<tmcl::MotionCore> core = [] {
    auto c = tmcl::make_motion_core("tmc5160");
    c->reset(*tmcl::find_profile("tmcm-1260"), 1);
    return c;
  }();
  tmcl::MotionRecorder rec{1, 20000};
  tmcl::RecordingCore rc{*core, rec};
  std::vector<tmcl::MotionEvent> ev;
  void move_to(std::int32_t target) {
    rc.move_absolute(0, target);
    for (int i = 0; i < 20 && !rc.target_reached(0); ++i) rc.advance(rc.next_event(), ev);
  }
};

// SAP 1 and a reference search re-base the count, not the wall: the hard stop's line moves with
// the count from that instant on (one segment before, one after), and the CSV says where the wall
// is in the new count; a run without a re-base draws one segment.
TEST(a_re_based_count_moves_the_hard_stop_line) {
  for (int rebase = 0; rebase < 2; ++rebase) {
    Recorded1260 r;
    CHECK(r.rc.place_hard_stop(0, tmcl::SwitchInput::StopLeft, -20000));
    r.move_to(10000);
    if (rebase) CHECK(r.rc.set_param(0, tmcl::kApActualPosition, 0) == tmcl::ParamWrite::Ok);
    r.move_to(5000);
    std::ostringstream csv, svg;
    tmcl::write_csv(csv, r.rec);
    tmcl::write_svg(svg, r.rec);
    CHECK_EQ(r.rec.rebases().size(), std::size_t(rebase));
    CHECK((csv.str().find("\n# hard stop left -20000 (motor 0) at -30000 from ") != std::string::npos) == (rebase != 0));
    CHECK_EQ(count(svg.str(), "stroke=\"#8c564b\" stroke-opacity"), std::size_t(rebase ? 2 : 1));
    CHECK((svg.str().find("text-anchor=\"end\">-30k</text>") != std::string::npos) == (rebase != 0));  // the axis takes it
  }
  // a reference search's re-base: its reference point, -20000 in the old count, is 0 now
  tmcl::MotionRecorder rec(1, 10000);
  tmcl::MotionEvent ev{};
  ev.at = 5000;
  ev.kind = tmcl::MotionEventKind::Rebased;
  ev.value = -20000;
  rec.motion_event(ev);
  CHECK_EQ(rec.rebases().size(), std::size_t{1});
  if (!rec.rebases().empty()) CHECK_EQ(rec.rebases()[0].delta, std::int64_t{20000});
}

// A scenario's hard stop is a line on the motor's position panel, labelled with its side and
// position, and a comment line in the CSV (issue 41); a run without one draws none.
TEST(svg_draws_the_hard_stops_as_lines) {
  for (int wall = 0; wall < 2; ++wall) {
    Recorded1260 r;
    auto& rec = r.rec;
    if (wall) CHECK(r.rc.place_hard_stop(0, tmcl::SwitchInput::StopLeft, -20000));
    r.move_to(60000);
    std::ostringstream csv, svg;
    tmcl::write_csv(csv, rec);
    tmcl::write_svg(svg, rec);
    const std::string c = csv.str(), s = svg.str();
    CHECK((c.find("\n# hard stop left -20000 (motor 0)\n") != std::string::npos) == (wall != 0));
    CHECK((s.find("text-anchor=\"end\">hard stop left -20000</text>") != std::string::npos) == (wall != 0));
    CHECK_EQ(count(s, "stroke=\"#8c564b\""), std::size_t{wall ? 1u : 0u});
    // the wall is inside the position axis: its tick labels reach below -20000
    CHECK((s.find("text-anchor=\"end\">-20k</text>") != std::string::npos) == (wall != 0));
  }
}

// The moment of contact is an event of its own (issue 41): once, when the shaft meets a load of
// 100 % or more (here a load range) or a hard stop, before the steps lost it leads to; a CSV row,
// a trace text, and a mark with its own glyph and legend entry.
TEST(contact_is_a_mark_of_its_own) {
  for (int wall = 0; wall < 2; ++wall) {
    Recorded1260 r;
    auto& rec = r.rec;
    const auto& ev = r.ev;
    if (wall) CHECK(r.rc.place_hard_stop(0, tmcl::SwitchInput::StopRight, 20000));
    else CHECK(r.rc.place_load(0, 20000, 30000, 150));
    r.move_to(60000);
    std::size_t contacts = 0, contact_at = ev.size(), lost_at = ev.size();
    for (std::size_t i = 0; i < ev.size(); ++i) {
      if (ev[i].kind == tmcl::MotionEventKind::Contact) ++contacts, contact_at = i;
      if (ev[i].kind == tmcl::MotionEventKind::StepsLost) lost_at = i;
    }
    CHECK_EQ(contacts, std::size_t{1});
    CHECK(contact_at < lost_at && lost_at < ev.size());
    CHECK_EQ(ev[contact_at].position, 20000);
    const char* text = wall ? "contact: the shaft meets the right hard stop" : "contact: the shaft meets a load of 150 %";
    CHECK_EQ(tmcl::motion_event_text(ev[contact_at]), std::string(text));
    std::ostringstream csv, svg;
    tmcl::write_csv(csv, rec);
    tmcl::write_svg(svg, rec);
    const std::string c = csv.str(), s = svg.str();
    CHECK(c.find(",0,20000,,," + std::string(text) + ",\n") != std::string::npos);  // then the empty shaft column
    CHECK(s.find("d=\"M-6,-5 L0,-1 L-6,3 Z M2,-6 L5,-6 L5,4 L2,4 Z\" fill=\"#8c564b\"><title>") != std::string::npos);
    CHECK(s.find(">contact</text>") != std::string::npos);  // its legend entry
    CHECK(s.find(": " + std::string(text) + " (motor 0)</title>") != std::string::npos);
  }
}

// --plot-series (issue 41): the load value (206) and the actual current (180) sampled with the
// motion, as a program would read them at each sample instant (closed form, before the core
// advances there), each a panel of its own; a core that cannot say them leaves the line out.
TEST(plot_series_samples_what_a_program_reads) {
  auto core = tmcl::make_motion_core("tmc5160");
  core->reset(*tmcl::find_profile("tmcm-1260"), 1);
  tmcl::MotionRecorder rec(1, 10000);
  rec.sample_params({206, 180});
  tmcl::RecordingCore rc(*core, rec);
  CHECK(rc.set_param(0, 140, 8) == tmcl::ParamWrite::Ok);
  CHECK(rc.set_param(0, 6, 128) == tmcl::ParamWrite::Ok);
  CHECK(rc.set_param(0, 172, 1) == tmcl::ParamWrite::Ok);  // coolStep on: 180 moves
  rc.rotate(0, 51200);
  std::vector<tmcl::MotionEvent> ev;
  std::set<std::int32_t> loads, currents;
  for (tmcl::SimTime t = 10000; t <= 1000000; t += 10000) {
    while (rc.next_event() < t) rc.advance(rc.next_event(), ev);  // as the VM: through every event
    rc.advance(t, ev);  // samples up to t first, then moves there
    const std::size_t i = rec.times().size() - 1;
    CHECK_EQ(rec.times()[i], t);
    // (a sample comes before an event at its own instant, as the CSV's rows: 800 ms here)
    const bool event_now = !ev.empty() && ev.back().at == t;
    if (!event_now) CHECK_EQ(*rec.param_samples()[i * 2 + 0], rc.get_param(0, 206));
    if (!event_now) CHECK_EQ(*rec.param_samples()[i * 2 + 1], rc.get_param(0, 180));
    loads.insert(rc.get_param(0, 206));
    currents.insert(rc.get_param(0, 180));
  }
  CHECK(loads.size() > 2 && currents.size() > 2);  // both change on the way
  std::ostringstream svg;
  tmcl::write_svg(svg, rec);
  const std::string s = svg.str();
  CHECK(s.find(">load value (206)</text>") != std::string::npos);
  CHECK(s.find(">actual current (180)</text>") != std::string::npos);
  CHECK_EQ(count(s, "<polyline"), std::size_t{5});
  // in the CSV a column each after the event, the same samples; event rows leave them empty
  std::ostringstream csv;
  tmcl::write_csv(csv, rec);
  const std::string c = csv.str();
  CHECK(c.find("\ntime_s,motor,position,velocity_pps,acceleration_pps2,event,load_value_206,actual_current_180\n") !=
        std::string::npos);
  const std::string last_sample = "1.000000,0," + std::to_string(rec.samples().back().position) + ",";
  const std::size_t at = c.find(last_sample);
  CHECK(at != std::string::npos);
  if (at != std::string::npos) {
    const std::string row = c.substr(at, c.find('\n', at) - at);
    const std::string tail = "," + std::to_string(*rec.param_samples()[rec.param_samples().size() - 2]) + "," +
                             std::to_string(*rec.param_samples().back());
    CHECK_EQ(row.substr(row.size() - tail.size()), tail);
  }
  CHECK(c.find(",,,move issued: rotate at 51200 pps,,\n") != std::string::npos);
  // a core that models neither leaves its lines out, the panels stay
  Runner r("tmc4361", "usb-2-sd", 20000);
  r.rec.sample_params({206});
  mt::usb2sd_main_loop(r);
  std::ostringstream plain;
  tmcl::write_svg(plain, r.rec);
  CHECK(plain.str().find(">load value (206)</text>") != std::string::npos);
  CHECK_EQ(count(plain.str(), "<polyline"), std::size_t{3});
}
