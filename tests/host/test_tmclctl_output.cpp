// What tmclctl writes, end to end against `tmclrun --serve pty`: monitor --plot (a well-formed SVG
// with one panel and one line per parameter that reads back as the polled values, written
// atomically), the progress bars (download, scan) and live table on a terminal and plain text
// through a pipe, and
// standard output that cannot be written (/dev/full) giving exit status 74.
#include <dirent.h>

#include <cmath>
#include <cstdlib>
#include <map>

#include "check.hpp"
#include "tmclctl_test.hpp"

namespace {

using namespace hosttest;

// ---- a small XML well-formedness check (elements nest and close, attributes are quoted,
// '&' only in entities, '<' never in text or values) ----

bool entity_at(const std::string& s, std::size_t i) {
  for (const char* e : {"&amp;", "&lt;", "&gt;", "&quot;", "&apos;"})
    if (s.compare(i, std::string(e).size(), e) == 0) return true;
  return false;
}

// Empty when `s` is well-formed XML with one root element; else what is wrong and where.
std::string xml_problem(const std::string& s) {
  std::vector<std::string> open;
  int roots = 0;
  for (std::size_t i = 0; i < s.size();) {
    if (s[i] == '&' && !entity_at(s, i)) return "bare '&' at " + std::to_string(i);
    if (s[i] != '<') {
      if (open.empty() && !std::isspace(static_cast<unsigned char>(s[i]))) return "text outside the root at " + std::to_string(i);
      ++i;
      continue;
    }
    const std::size_t end = s.find('>', i);
    if (end == std::string::npos) return "unclosed tag at " + std::to_string(i);
    std::string tag = s.substr(i + 1, end - i - 1);
    i = end + 1;
    if (tag.rfind("?", 0) == 0 || tag.rfind("!--", 0) == 0) continue;
    if (tag.rfind("/", 0) == 0) {
      if (open.empty() || open.back() != tag.substr(1)) return "</" + tag.substr(1) + "> closes nothing open";
      open.pop_back();
      continue;
    }
    const bool empty = !tag.empty() && tag.back() == '/';
    if (empty) tag.pop_back();
    std::size_t k = tag.find_first_of(" \n\t");
    const std::string name = tag.substr(0, k);
    if (name.empty() || !std::isalpha(static_cast<unsigned char>(name[0]))) return "bad element name '" + name + "'";
    // attributes: name="value" ...
    while (k != std::string::npos && k < tag.size()) {
      k = tag.find_first_not_of(" \n\t", k);
      if (k == std::string::npos) break;
      const std::size_t eq = tag.find('=', k);
      if (eq == std::string::npos || tag[eq + 1] != '"') return "unquoted attribute in <" + name + ">";
      const std::size_t close = tag.find('"', eq + 2);
      if (close == std::string::npos) return "unclosed attribute value in <" + name + ">";
      const std::string value = tag.substr(eq + 2, close - eq - 2);
      for (std::size_t v = 0; v < value.size(); ++v)
        if (value[v] == '<' || (value[v] == '&' && !entity_at(value, v))) return "bad character in an attribute of <" + name + ">";
      k = close + 1;
    }
    if (open.empty()) ++roots;
    if (!empty) open.push_back(name);
  }
  if (!open.empty()) return "<" + open.back() + "> never closed";
  return roots == 1 ? "" : std::to_string(roots) + " root elements";
}

// ---- reading the plot back: panel k's tick labels give the value scale, its polyline the points ----

std::string attr(const std::string& element, const std::string& name) {
  const std::size_t at = element.find(" " + name + "=\"");
  if (at == std::string::npos) return "";
  const std::size_t b = at + name.size() + 3;
  return element.substr(b, element.find('"', b) - b);
}

double tick_value(const std::string& label) {
  double v = std::atof(label.c_str());
  if (label.back() == 'k') v *= 1e3;
  if (label.back() == 'M') v *= 1e6;
  return v;
}

struct Panel {
  std::map<double, double> ticks;  // y on the page -> value
  std::vector<std::pair<double, double>> points;  // x, y
  int polylines = 0;
  // The value a point at page height y stands for, from the outermost ticks.
  double value_at(double y) const {
    const auto& [y1, v1] = *ticks.begin();
    const auto& [y2, v2] = *ticks.rbegin();
    return v1 + (y - y1) * (v2 - v1) / (y2 - y1);
  }
  double value_per_px() const { return std::fabs((ticks.rbegin()->second - ticks.begin()->second) / (ticks.rbegin()->first - ticks.begin()->first)); }
};

std::vector<Panel> panels_of(const std::string& svg) {
  std::vector<Panel> panels;
  for (std::size_t g = svg.find("<g>"); g != std::string::npos; g = svg.find("<g>", g + 1)) {
    const std::string block = svg.substr(g, svg.find("</g>", g) - g);
    Panel p;
    for (std::size_t t = block.find("<text"); t != std::string::npos; t = block.find("<text", t + 1)) {
      const std::string element = block.substr(t, block.find('>', t) - t);
      if (attr(element, "text-anchor") != "end") continue;
      const std::size_t b = block.find('>', t) + 1;
      p.ticks[std::atof(attr(element, "y").c_str()) - 4] = tick_value(block.substr(b, block.find('<', b) - b));
    }
    for (std::size_t l = block.find("<polyline"); l != std::string::npos; l = block.find("<polyline", l + 1)) {
      ++p.polylines;
      std::istringstream pts(attr(block.substr(l, block.find('>', l) - l), "points"));
      double x = 0, y = 0;
      char comma = 0;
      while (pts >> x >> comma >> y) p.points.emplace_back(x, y);
    }
    panels.push_back(p);
  }
  return panels;
}

std::vector<std::vector<long>> csv_rows(const std::string& csv) {
  std::vector<std::vector<long>> rows;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<long> row;
    std::istringstream cells(line);
    std::string cell;
    std::getline(cells, cell, ',');  // time
    while (std::getline(cells, cell, ',')) row.push_back(std::atol(cell.c_str()));
    rows.push_back(row);
  }
  return rows;
}

std::vector<std::string> dir_entries(const std::string& dir) {
  std::vector<std::string> names;
  if (DIR* d = ::opendir(dir.c_str())) {
    while (dirent* e = ::readdir(d))
      if (std::string(e->d_name) != "." && std::string(e->d_name) != "..") names.push_back(e->d_name);
    ::closedir(d);
  }
  return names;
}

TEST(monitor_plot_holds_the_polled_values) {
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});
  const std::string& p = server.port();
  // One constant parameter and one that moves: motor 0 rotating, its actual position climbing.
  CHECK_EQ(ctl({"-t", "usb-2-sd", p, "set", "ap", "4", "0", "1234"}).status, 0);
  CHECK_EQ(ctl({"-t", "usb-2-sd", p, "send", "ROR 0, 1000"}).status, 0);
  const std::string csv = temp_dir() + "/plot.csv", svg = temp_dir() + "/plot.svg";
  Output m = ctl({"-t", "usb-2-sd", p, "monitor", "ap:4", "actual position", "--every", "50ms", "--for", "500ms", "--csv", csv,
                  "--plot", svg});
  show(m);
  CHECK_EQ(m.status, 0);
  const std::string text = slurp(svg);
  CHECK_EQ(xml_problem(text), std::string());
  CHECK(text.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0) == 0);
  CHECK(has(text, "tmclctl monitor: module 1 on " + p + ", every 50ms"));
  CHECK(has(text, ">Maximum positioning speed [0]</text>"));  // the legend names each parameter
  CHECK(has(text, ">Actual position [0]</text>"));
  CHECK(has(text, ">ap:4:0</text>"));  // and each panel's axis
  CHECK(has(text, ">ap:1:0</text>"));
  CHECK(has(text, ">time [s]</text>"));

  const auto rows = csv_rows(slurp(csv));
  CHECK_EQ(rows.size(), std::size_t{10});
  const std::vector<Panel> panels = panels_of(text);
  CHECK_EQ(panels.size(), std::size_t{2});
  if (rows.size() != 10 || panels.size() != 2) return;
  CHECK(rows.back()[1] > rows.front()[1]);  // the motor did move
  for (std::size_t k = 0; k < 2; ++k) {
    const Panel& panel = panels[k];
    CHECK_EQ(panel.polylines, 1);
    CHECK(panel.ticks.size() >= 2);
    CHECK_EQ(panel.points.size(), rows.size());  // ten polls, far fewer than pixel columns: none merged
    if (panel.ticks.size() < 2 || panel.points.size() != rows.size()) continue;
    CHECK_EQ(panel.points.front().first, 96.0);    // the first poll at time 0, the plot's left edge
    CHECK_EQ(panel.points.back().first, 1072.0);   // the last at its right edge
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double got = panel.value_at(panel.points[i].second), want = static_cast<double>(rows[i][k]);
      // Points are written to 0.1 px: the value is right within what 0.05 px (and the ticks'
      // rounding) stands for.
      const double tolerance = 0.08 * panel.value_per_px();
      if (std::fabs(got - want) > tolerance) std::fprintf(stderr, "  panel %zu row %zu: plotted %g, polled %g\n", k, i, got, want);
      CHECK(std::fabs(got - want) <= tolerance);
    }
  }
}

TEST(monitor_plot_write_failure_is_74_and_leaves_no_file) {
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});
  const std::string& p = server.port();
  Output missing = ctl({p, "monitor", "ap:4", "--every", "10ms", "--for", "30ms", "--plot", "/nonexistent-dir/m.svg"});
  CHECK_EQ(missing.status, 74);
  CHECK(has(missing.err, "tmclctl: error: "));
  CHECK(has(missing.err, "/nonexistent-dir/m.svg"));
  CHECK(missing.out.rfind("time_s,", 0) == 0);  // the rows were shown all the same
  // The name taken by a folder: refused, and nothing is left beside it.
  const std::string dir = temp_dir() + "/plotdir";
  ::mkdir(dir.c_str(), 0755);
  ::mkdir((dir + "/taken.svg").c_str(), 0755);
  Output taken = ctl({p, "monitor", "ap:4", "--every", "10ms", "--for", "30ms", "--plot", dir + "/taken.svg"});
  CHECK_EQ(taken.status, 74);
  CHECK(has(taken.err, "taken.svg"));
  CHECK_EQ(dir_entries(dir).size(), std::size_t{1});
  CHECK(dir_entries(dir + "/taken.svg").empty());
  // A device that refuses the bytes.
  if (exists("/dev/full")) CHECK_EQ(ctl({p, "monitor", "ap:4", "--for", "10ms", "--plot", "/dev/full"}).status, 74);
  // --plot and --csv belong to monitor.
  Output usage = ctl({p, "status", "--plot", temp_dir() + "/status.svg"});
  CHECK_EQ(usage.status, 64);
  CHECK(has(usage.err, "--csv and --plot go with monitor"));
  CHECK(!exists(temp_dir() + "/status.svg"));
}

TEST(monitor_into_a_closed_pipe_keeps_its_plot) {
  // `| head -c 1` takes the first byte of the CSV and goes; the next row cannot be written. The
  // monitor ends with status 74 and writes its --plot with the rows polled, instead of dying of
  // SIGPIPE and losing it. The shell writes tmclctl's own status to a file.
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});
  const std::string dir = temp_dir();
  const std::string svg = dir + "/piped.svg", status = dir + "/piped.status";
  const std::string cmd = "{ " + kCtl + " " + server.port() + " monitor ap:4 --every 20ms --for 20s --plot " + svg +
                          "; echo $? > " + status + "; } | head -c 1 > /dev/null";
  Output o = hosttest::run({"/bin/sh", "-c", cmd}, 30000);
  CHECK_EQ(o.status, 0);
  CHECK_EQ(slurp(status), std::string("74\n"));
  CHECK(has(o.err, "tmclctl: error: cannot write standard output"));
  CHECK(slurp(svg).rfind("<svg ", 0) == 0);
}

// A program of n instructions to download.
std::string program_of(int n) {
  std::string s;
  for (int i = 1; i < n; ++i) s += "SAP 4, 0, " + std::to_string(i) + "\n";
  return s + "STOP\n";
}

TEST(progress_bar_and_live_table_on_a_terminal) {
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});
  const std::string& p = server.port();
  const std::string src = write_temp("bar.tmc", program_of(200));
  Output d = run_on_pty({kCtl, "--timeout", "5s", "-t", "usb-2-sd", p, "download", src});
  CHECK_EQ(d.status, 0);
  CHECK(has(d.out, "\rWriting   | "));
  CHECK(has(d.out, "##################################################" " | 100% "));
  CHECK(has(d.out, "\rReading   | "));
  CHECK(has(d.out, "wrote 200 instructions to module 1"));
  CHECK(has(d.out, "verified 200 instructions"));
  if (d.status != 0) std::fprintf(stderr, "  pty: %s\n", d.out.c_str());
  // -q: no bar on a terminal either.
  Output q = run_on_pty({kCtl, "--timeout", "5s", "-q", "-t", "usb-2-sd", p, "download", src});
  CHECK_EQ(q.status, 0);
  CHECK(!has(q.out, "Writing"));
  CHECK(!has(q.out, "\r"));

  Output m = run_on_pty({kCtl, "--timeout", "5s", "-t", "usb-2-sd", p, "monitor", "ap:4", "gp:128", "--every", "20ms", "--for", "60ms"});
  CHECK_EQ(m.status, 0);
  char header[80];
  std::snprintf(header, sizeof header, "%10s %14s %14s\n", "time (s)", "ap:4:0", "gp:128:0");
  CHECK(m.out.rfind(header, 0) == 0);
  CHECK(has(m.out, "\n     0.000 "));
  CHECK(has(m.out, "\n     0.040 "));
  CHECK(!has(m.out, "time_s"));
  if (m.status != 0 || !has(m.out, "  time (s)")) std::fprintf(stderr, "  pty: %s\n", m.out.c_str());
}

TEST(scan_progress_on_a_terminal_only) {
  Server server(kRun, {"--serve", "tcp:127.0.0.1:0", "-t", "usb-2-sd"});
  // The default wait per address (no --timeout): the scan of a range runs to its end.
  Output t = run_on_pty({kCtl, server.port(), "scan", "--range", "1-30"});
  if (t.status != 0) std::fprintf(stderr, "  pty: %s\n", t.out.c_str());
  CHECK_EQ(t.status, 0);
  CHECK(has(t.out, "\rScanning  | "));
  CHECK(has(t.out, "##################################################" " | 100% "));
  CHECK(has(t.out, "address   1: firmware 0015V114 (0x000F010E), USB-2-SD (firmware 1.14)\n"));
  CHECK(has(t.out, "1 module found"));
  Output q = run_on_pty({kCtl, "-q", server.port(), "scan", "--range", "1-3"});
  CHECK_EQ(q.status, 0);
  CHECK(!has(q.out, "Scanning"));
  Output p = run({kCtl, server.port(), "scan", "--range", "1-3"});  // a pipe: the list alone
  CHECK_EQ(p.status, 0);
  CHECK_EQ(p.out, "address   1: firmware 0015V114 (0x000F010E), USB-2-SD (firmware 1.14)\n1 module found\n");
  CHECK_EQ(p.err, std::string());
}

TEST(plain_text_through_a_pipe) {
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});
  const std::string& p = server.port();
  const std::string src = write_temp("nobar.tmc", program_of(200));
  Output d = ctl({"-t", "usb-2-sd", p, "download", src});
  CHECK_EQ(d.status, 0);
  CHECK(d.err.empty());  // no bar
  CHECK(!has(d.out, "\r") && !has(d.out, "|"));
  CHECK(has(d.out, "wrote 200 instructions to module 1"));  // the summary only
  Output q = ctl({"-q", "-t", "usb-2-sd", p, "download", src});
  CHECK_EQ(q.status, 0);
  CHECK_EQ(q.out + q.err, std::string());  // quiet: nothing at all
  Output m = ctl({"-t", "usb-2-sd", p, "monitor", "ap:4", "gp:128", "--every", "20ms", "--for", "60ms"});
  CHECK_EQ(m.status, 0);
  CHECK(m.out.rfind("time_s,Maximum positioning speed [0],TMCL application status\n0.000,", 0) == 0);
  CHECK(!has(m.out, "time (s)"));
}

// Standard output on /dev/full (through sh, as a user redirects it).
Output to_dev_full(const std::string& args) {
  return run({"/bin/sh", "-c", kCtl + " " + args + " > /dev/full"}, 30000);
}

TEST(standard_output_that_cannot_be_written_is_74) {
  if (!exists("/dev/full")) {
    std::printf("skipped: this system has no /dev/full\n");
    return;
  }
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});
  const std::string& p = server.port();
  for (const std::string& args : std::vector<std::string>{p + " status", p + " get ap 4 0", "--help", "--version"}) {
    Output o = to_dev_full(args);
    if (o.status != 74) std::fprintf(stderr, "  tmclctl %s > /dev/full: %d %s\n", args.c_str(), o.status, o.err.c_str());
    CHECK_EQ(o.status, 74);
    CHECK(has(o.err, "tmclctl: error: cannot write standard output: No space left on device"));
  }
  // A monitor without --for stops at the first row it cannot write, instead of polling on.
  Output m = to_dev_full(p + " monitor ap:4 --every 10ms");
  CHECK_EQ(m.status, 74);
  CHECK(has(m.err, "cannot write standard output"));
  // Said once, not again at exit.
  CHECK_EQ(m.err.find("cannot write"), m.err.rfind("cannot write"));
}

}  // namespace
