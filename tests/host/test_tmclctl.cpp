// tmclctl end to end against the virtual module: `tmclrun --serve pty` and `--serve tcp` run as
// separate processes, tmclctl is run as a user would, and exit status and output are checked.
// Covers download and verify of a program filling the USB-2-SD's memory, upload giving the
// identical .bin, run/stop/step/reset/status, monitor rows, parameters by name, scan on a bus of
// three modules, every fault kind of --faults recovered or reported, Ctrl-C during a download,
// a silent module, exclusive ports and atomic output files.
#include <algorithm>
#include <cstdio>

#include "check.hpp"
#include "tmclctl_test.hpp"
#include "tmcl/asm/assembler.hpp"
#include "tmcl/faults.hpp"
#include "tmcl/host/client.hpp"
#include "tmcl/host/port.hpp"
#include "tmcl/host/scan.hpp"
#include "tmcl/image.hpp"

using hosttest::Output;
using hosttest::Server;

namespace {

using namespace hosttest;

// 577 instructions: the whole program memory of the USB-2-SD, every one different.
std::string full_memory_source() {
  std::string s;
  for (int i = 0; i < 576; ++i) s += "SAP 4, 0, " + std::to_string(1000 + i * 7) + "\n";
  return s + "STOP\n";
}

std::vector<std::uint8_t> assembled_bin(const std::string& path) {
  tmcl::AsmOptions opt;
  opt.profile = tmcl::find_profile("usb-2-sd");
  tmcl::DiskReader reader;
  tmcl::AsmResult r = tmcl::assemble({path}, opt, reader);
  return tmcl::write_bin(r.program);
}

void download_upload_round_trip(const std::vector<std::string>& serve) {
  Server server(kRun, serve);
  CHECK(!server.port().empty());
  const std::string src = write_temp("full.tmc", full_memory_source());
  Output d = ctl({"-t", "usb-2-sd", server.port(), "download", src});
  show(d);
  CHECK_EQ(d.status, 0);
  CHECK(has(d.out, "wrote 577 instructions to module 1"));
  CHECK(has(d.out, "verified 577 instructions"));
  CHECK(d.err.empty());  // no progress bar when standard error is not a terminal
  const std::string up = temp_dir() + "/up-" + std::to_string(serve.size()) + ".bin";
  Output u = ctl({"-t", "usb-2-sd", server.port(), "upload", "-o", up});
  show(u);
  CHECK_EQ(u.status, 0);
  CHECK(has(u.out, "read 577 instructions"));
  const std::string got = slurp(up);
  const auto want = assembled_bin(src);
  CHECK_EQ(got.size(), want.size());
  CHECK(got == std::string(want.begin(), want.end()));
}

TEST(download_verify_upload_full_memory_pty) { download_upload_round_trip({"--serve", "pty", "-t", "usb-2-sd"}); }

TEST(download_verify_upload_full_memory_tcp) {
  download_upload_round_trip({"--serve", "tcp:127.0.0.1:0", "-t", "usb-2-sd", "--time-scale", "1"});
}

TEST(download_too_large_is_bad_input) {
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});
  const std::string src = write_temp("toolarge.tmc", full_memory_source() + "STOP\n");
  Output d = ctl({"-t", "usb-2-sd", server.port(), "download", src});
  CHECK_EQ(d.status, 65);
  CHECK(has(d.err, "578 instructions"));
}

TEST(run_stop_step_reset_status) {
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});
  const std::string src = write_temp("loop.tmc", "loop: CALC ADD, 1\nJA loop\n");
  const std::string& p = server.port();
  CHECK_EQ(ctl({"-t", "usb-2-sd", "-q", p, "download", "--run", src}).status, 0);
  Output s = ctl({p, "status"});
  CHECK_EQ(s.status, 0);
  CHECK(has(s.out, "mode:             running"));
  CHECK(has(s.out, "firmware:         0015V114 (0x000F010E), USB-2-SD (firmware 1.14)"));
  CHECK_EQ(ctl({p, "stop"}).status, 0);
  s = ctl({p, "status"});
  CHECK(has(s.out, "mode:             stopped"));
  CHECK_EQ(ctl({p, "reset"}).status, 0);
  s = ctl({p, "status"});
  CHECK(has(s.out, "mode:             reset"));
  CHECK(has(s.out, "program counter:  0\n"));
  CHECK(has(s.out, "accumulator:      0\n"));
  CHECK_EQ(ctl({p, "step"}).status, 0);
  s = ctl({p, "status"});
  CHECK(has(s.out, "mode:             step"));
  CHECK(has(s.out, "program counter:  1\n"));
  CHECK(has(s.out, "accumulator:      1\n"));
  CHECK_EQ(ctl({p, "run", "1"}).status, 0);
  CHECK(has(ctl({p, "status"}).out, "mode:             running"));
  Output auto_start = ctl({"-t", "usb-2-sd", p, "download", "--autostart", src});
  CHECK_EQ(auto_start.status, 0);
  CHECK(has(auto_start.out, "autostart on (global parameter 77 = 1, stored)"));
  CHECK_EQ(ctl({"-t", "usb-2-sd", p, "get", "gp", "77"}).out, "1\n");
  Output bad = ctl({p, "run", "9"});  // outside the program: status 4
  CHECK_EQ(bad.status, 2);
  CHECK(has(bad.err, "answered 4 (invalid value)"));
}

TEST(parameters_by_number_and_name) {
  Server server(kRun, {"--serve", "tcp:127.0.0.1:0", "-t", "usb-2-sd"});
  const std::string& p = server.port();
  Output s = ctl({"-t", "usb-2-sd", p, "set", "maximum positioning speed", "1234"});
  show(s);
  CHECK_EQ(s.status, 0);
  Output g = ctl({"-t", "usb-2-sd", p, "get", "ap", "4", "0"});
  CHECK_EQ(g.out, "1234\n");
  g = ctl({"-t", "usb-2-sd", p, "get", "ap:4:0"});
  CHECK_EQ(g.out, "1234\n");
  Output send = ctl({"-t", "usb-2-sd", p, "send", "GAP 4, 0"});
  CHECK_EQ(send.out, "100 success, value 1234\n");
  Output raw = ctl({"-t", "usb-2-sd", "--raw", p, "send", "GAP 4, 0"});
  CHECK_EQ(raw.out, "> 01 88 00 00 00 00 00 00 89\n< 02 30 30 31 35 56 31 31 34\n"  // 136 on connect: 0015V114
                    "> 01 06 04 00 00 00 00 00 0B\n< 02 01 64 06 00 00 04 D2 43\n100 success, value 1234\n");
  Output unknown = ctl({"-t", "usb-2-sd", p, "get", "maximum positoning speed"});
  CHECK_EQ(unknown.status, 64);
  CHECK(has(unknown.err, "did you mean 'Maximum positioning speed'?"));
  Output range = ctl({"-t", "usb-2-sd", p, "set", "ap", "4", "0", "-5"});
  CHECK_EQ(range.status, 65);
  CHECK(has(range.err, "takes 0 to"));
  Output bad_src = ctl({"-t", "usb-2-sd", p, "send", "SAP 4, 0"});
  CHECK_EQ(bad_src.status, 65);
  CHECK(has(bad_src.err, "<command line>:1:"));
  Output store = ctl({"-t", "usb-2-sd", p, "store", "ap", "4", "0"});  // no EEPROM copy on this module
  CHECK_EQ(store.status, 65);
  CHECK(has(store.err, "axis parameter 4 (Maximum positioning speed), motor 0 is not stored in the EEPROM on usb-2-sd"));
  CHECK_EQ(ctl({"-t", "usb-2-sd", p, "store", "auto start mode"}).status, 0);
  Output fw = ctl({p, "send", ".raw 136, 0, 0, 0"});
  CHECK_EQ(fw.out, "firmware 0015V114\n");
}

TEST(monitor_rows_as_csv) {
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});
  const std::string csv = temp_dir() + "/monitor.csv";
  Output m = ctl({"-t", "usb-2-sd", server.port(), "monitor", "ap:4", "gp:128", "--every", "50ms", "--for", "200ms", "--csv", csv});
  show(m);
  CHECK_EQ(m.status, 0);
  const std::string text = slurp(csv);
  CHECK(text.rfind("time_s,Maximum positioning speed [0],TMCL application status\n", 0) == 0);
  int rows = 0;
  for (char c : text) rows += c == '\n';
  CHECK_EQ(rows, 5);  // header and rows at 0, 50, 100, 150 ms
  CHECK(has(text, "0.150,"));
  Output out = ctl({"-t", "usb-2-sd", server.port(), "monitor", "ap:4", "--every", "10ms", "--for", "30ms"});
  CHECK_EQ(out.status, 0);
  CHECK(out.out.rfind("time_s,Maximum positioning speed [0]\n0.000,", 0) == 0);
}

TEST(silent_module_is_named) {
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});
  Output o = ctl({"-a", "9", "--timeout", "100ms", "--retries", "1", server.port(), "get", "ap", "1", "0"}, 5000);
  CHECK_EQ(o.status, 69);
  CHECK(has(o.err, "no reply within 100 ms to GAP 1, 0 [09 06 01 00 00 00 00 00 10] to module 9 on " + server.port() +
                       " (2 attempts)"));
  const std::string out = temp_dir() + "/never.bin";
  Output u = ctl({"-a", "9", "--timeout", "50ms", "--retries", "0", server.port(), "upload", "-o", out}, 5000);
  CHECK_EQ(u.status, 69);
  CHECK(!exists(out));  // never a half-written output file
}

// One option parser for every tool (issue 28, item 12): --opt=value and -oVALUE like everywhere.
TEST(every_form_of_an_option_value) {
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});
  const std::string csv = temp_dir() + "/forms.csv";
  Output m = ctl({"-tusb-2-sd", server.port(), "monitor", "ap:4", "--every=50ms", "--for=100ms", "--csv=" + csv});
  show(m);
  CHECK_EQ(m.status, 0);
  CHECK(slurp(csv).rfind("time_s,Maximum positioning speed [0]\n", 0) == 0);
  Output o = ctl({"-a9", "--timeout=100ms", "--retries=0", server.port(), "get", "ap", "1", "0"}, 5000);
  CHECK_EQ(o.status, 69);
  CHECK(has(o.err, "no reply within 100 ms to GAP 1, 0 [09 06 01 00 00 00 00 00 10] to module 9 on " + server.port() + "\n"));
}

TEST(port_errors) {
  Output o = ctl({"/nonexistent/tty", "status"});
  CHECK_EQ(o.status, 74);
  CHECK(has(o.err, "/nonexistent/tty: No such file or directory"));
  Output f = ctl({"/dev/null", "status"});
  CHECK_EQ(f.status, 74);
  CHECK(has(f.err, "not a serial port"));
  Server server(kRun, {"--serve", "pty"});
  std::string err;
  auto held = tmcl::host::Port::open(server.port(), 9600, 1000, err);
  CHECK(held != nullptr);
  Output busy = ctl({server.port(), "status"});
  CHECK_EQ(busy.status, 74);
  CHECK(has(busy.err, "port in use by another program"));
  CHECK_EQ(ctl({"tcp:127.0.0.1:1", "status"}).status, 74);
  CHECK_EQ(ctl({"--baud", "1234", server.port(), "status"}).status, 64);
  CHECK_EQ(ctl({server.port(), "frobnicate"}).status, 64);
}

TEST(second_tcp_client_is_told_the_module_is_busy) {
  Server server(kRun, {"--serve", "tcp:127.0.0.1:0", "-t", "usb-2-sd"});
  std::string err;
  auto first = tmcl::host::Port::open(server.port(), 9600, 5000, err);
  CHECK(first != nullptr);
  if (!first) return;
  tmcl::host::ClientOptions opt;
  opt.timeout_ms = 5000;
  tmcl::host::Client one(*first, opt);
  const tmcl::Instruction version{static_cast<std::uint8_t>(tmcl::Op::GetFirmwareVersion), 1, 0, 0};
  CHECK(one.request(version).ok());  // served: the server has taken this client
  // tmclctl as the second client says why, instead of "Connection reset by peer".
  Output busy = ctl({server.port(), "status"});
  CHECK_EQ(busy.status, 74);
  CHECK(has(busy.err, "tmclctl: error: " + server.port() + ": module busy with another client (the server said \"busy: "));
  CHECK(!has(busy.err, "reset"));
  // The library's client: the request fails as a port error, and so does every later one.
  auto second = tmcl::host::Port::open(server.port(), 9600, 5000, err);
  CHECK(second != nullptr);
  if (!second) return;
  tmcl::host::Client two(*second, opt);
  for (int i = 0; i < 2; ++i) {
    const tmcl::host::Result r = two.request(version);
    CHECK(r.fail == tmcl::host::Fail::Port);
    CHECK(has(r.error, "module busy with another client"));
  }
  CHECK(one.request(version).ok());  // the first client is undisturbed
  first.reset();
  Output after = ctl({server.port(), "status"});  // and once it has gone, the next is served
  show(after);
  CHECK_EQ(after.status, 0);
}

TEST(scan_bus_of_three) {
  const std::string a = write_temp("a.tmc", "SAP 4, 0, 111\nSTOP\n");
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd", "--module", "1:" + a, "--module", "3", "--module", "4/tmc2300-eval"});
  // A module that is there must answer within the scan's timeout: 1 s instead of the default
  // 50 ms, so that a loaded machine cannot hide one. Every absent address costs that second, so
  // the range holds one gap (2) and one address past the last module (5), not more.
  Output s = ctl({"--timeout", "1s", server.port(), "scan", "--range", "1-5"});
  show(s);
  CHECK_EQ(s.status, 0);
  CHECK_EQ(s.out,
           "address   1: firmware 0015V114 (0x000F010E), USB-2-SD (firmware 1.14)\n"
           "address   3: firmware 0015V114 (0x000F010E), USB-2-SD (firmware 1.14)\n"
           "address   4: firmware 2300V100 (0x17000100), TMC2300-MOTOR-EVAL (firmware 1.00)\n"
           "3 modules found\n");
  // Each its own VM: a parameter set on one is not seen on another.
  CHECK_EQ(ctl({"-a", "3", server.port(), "set", "ap", "4", "0", "777"}).status, 0);
  CHECK_EQ(ctl({"-a", "3", server.port(), "get", "ap", "4", "0"}).out, "777\n");
  CHECK_EQ(ctl({"-a", "1", server.port(), "get", "ap", "4", "0"}).out != "777\n", true);
  Output none = ctl({"--timeout", "50ms", server.port(), "scan", "--range", "10-12"});  // nobody there: no wait can help
  CHECK_EQ(none.status, 69);
  CHECK(has(none.out, "0 modules found"));
}

TEST(scan_waits_less_on_tcp_and_still_finds_a_slow_module) {
  // The chosen defaults: 50 ms per address on a serial port, 10 ms on TCP.
  Server tcp(kRun, {"--serve", "tcp:127.0.0.1:0", "-t", "usb-2-sd", "--faults", "delay=30ms"});
  Server pty(kRun, {"--serve", "pty"});
  std::string err;
  auto t = tmcl::host::Port::open(tcp.port(), 9600, 5000, err);
  auto p = tmcl::host::Port::open(pty.port(), 9600, 5000, err);
  CHECK(t && p);
  if (!t || !p) return;
  CHECK_EQ(tmcl::host::default_scan_timeout_ms(*t), 10);
  CHECK_EQ(tmcl::host::default_scan_timeout_ms(*p), 50);
  t.reset();
  p.reset();
  // Every reply 30 ms late, beyond the 10 ms: the module is found by its late reply, asked
  // again, and the wait per address doubles (said on standard error). No --timeout here.
  Output s = run({kCtl, tcp.port(), "scan", "--range", "1-60"});
  show(s);
  CHECK_EQ(s.status, 0);
  CHECK_EQ(s.out, "address   1: firmware 0015V114 (0x000F010E), USB-2-SD (firmware 1.14)\n1 module found\n");
  CHECK(has(s.err, "tmclctl: note: module 1 answered after the timeout; now 20 ms per address"));
  // With --timeout the wait stays as given; the late module is still found.
  Output g = run({kCtl, "--timeout", "10ms", tcp.port(), "scan", "--range", "1-60"});
  CHECK_EQ(g.status, 0);
  CHECK(has(g.out, "address   1: "));
  CHECK(has(g.err, "now 10 ms per address"));
}

// One request under each fault kind: recovered with retries, reported without.
void fault_case(const std::string& spec, const std::vector<std::string>& ctl_opts, int want_status, const std::string& want_err,
                const std::string& transport = "pty") {
  Server server(kRun, {"--serve", transport, "-t", "usb-2-sd", "--faults", spec});
  std::vector<std::string> args = ctl_opts;
  args.insert(args.end(), {server.port(), "get", "ap", "4", "0"});
  Output o = ctl(args, 10000);
  if (o.status != want_status) std::fprintf(stderr, "  fault %s: status %d, stderr %s\n", spec.c_str(), o.status, o.err.c_str());
  CHECK_EQ(o.status, want_status);
  if (!want_err.empty()) CHECK(has(o.err, want_err));
  if (want_status == 0) CHECK(!o.out.empty());
}

// Timeouts, so that the cases hold on a loaded machine (a process may wait hundreds of ms for a
// core): where a reply is to come, the timeout or the window of retries is seconds, far beyond
// any scheduling delay. Where a silent module is what is tested, the reply never comes, so a short
// timeout cannot be beaten by a slow scheduler and the expected text does not depend on timing.
// A dropped reply costs one whole timeout, so the cases that recover from one wait 250 ms with 8
// retries: the window for the answer to come is still 2 s.
TEST(faults_recovered_or_reported) {
  // Reply 1 answers the 136 tmclctl sends on connect; reply 2 is the GAP's.
  fault_case("drop@2", {"--timeout", "250ms", "--retries", "8"}, 0, "");  // waits the timeout once, then the retry is answered
  fault_case("drop@2", {"--timeout", "100ms", "--retries", "0"}, 69, "no reply within 100 ms to GAP 4, 0");
  fault_case("corrupt@2", {"--timeout", "10s"}, 0, "");  // a corrupted reply ends the wait at once
  fault_case("corrupt@2", {"--timeout", "10s", "--retries", "0"}, 69, "only a corrupted reply (wrong checksum) to GAP 4, 0");
  fault_case("delay=50ms", {"--timeout", "10s", "--retries", "0"}, 0, "");
  // Late beyond the timeout: retried until the late reply (or the one behind it) is read; 20
  // attempts of 100 ms leave seconds for the 300 ms.
  fault_case("delay=300ms@2", {"--timeout", "100ms", "--retries", "20"}, 0, "");
  fault_case("split", {"--timeout", "10s", "--retries", "0"}, 0, "");
  fault_case("split=30ms", {"--timeout", "10s", "--retries", "0"}, 0, "");
  fault_case("silence=250ms@2", {"--timeout", "200ms", "--retries", "20"}, 0, "");
  fault_case("silence=250ms@2", {"--timeout", "100ms", "--retries", "0"}, 69, "no reply within 100 ms");
  fault_case("stale", {"--timeout", "10s", "--retries", "0"}, 0, "");
  fault_case("drop@cmd=GAP", {"--timeout", "50ms", "--retries", "1"}, 69, "(2 attempts)");
  fault_case("drop@cmd=6#1", {"--timeout", "250ms", "--retries", "8"}, 0, "");
  // The same over TCP, where a frame split across writes is two segments.
  const std::string tcp = "tcp:127.0.0.1:0";
  fault_case("drop@2", {"--timeout", "250ms", "--retries", "8"}, 0, "", tcp);
  fault_case("corrupt@2", {"--timeout", "10s", "--retries", "0"}, 69, "only a corrupted reply", tcp);
  fault_case("split=30ms", {"--timeout", "10s", "--retries", "0"}, 0, "", tcp);
  fault_case("stale,delay=20ms", {"--timeout", "10s", "--retries", "0"}, 0, "", tcp);
  fault_case("silence=250ms@2", {"--timeout", "200ms", "--retries", "20"}, 0, "", tcp);
}

TEST(scan_over_several_baud_rates) {
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});  // a pty takes any rate
  // One address: an absent one would cost the whole timeout at each rate (scan_bus_of_three has them).
  Output s = ctl({"--timeout", "1s", server.port(), "scan", "--range", "1-1", "--bauds", "9600,115200"});
  CHECK_EQ(s.status, 0);
  CHECK_EQ(s.out,
           "at 9600 baud:\n"
           "address   1: firmware 0015V114 (0x000F010E), USB-2-SD (firmware 1.14)\n"
           "at 115200 baud:\n"
           "address   1: firmware 0015V114 (0x000F010E), USB-2-SD (firmware 1.14)\n"
           "2 modules found\n");
  Server tcp(kRun, {"--serve", "tcp:127.0.0.1:0"});
  CHECK_EQ(ctl({tcp.port(), "scan", "--bauds", "9600"}).status, 64);
}

TEST(download_verify_under_seeded_faults) {
  // Stale copies before every reply, and 15% of the replies corrupted or dropped: a download and
  // verify of 100 instructions still ends right, by recovery (132 again before a lost store).
  std::string src;
  for (int i = 0; i < 99; ++i) src += "SAP 4, 0, " + std::to_string(i) + "\n";
  const std::string path = write_temp("faulty.tmc", src + "STOP\n");
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd", "--faults", "stale,corrupt@p=0.1,drop@p=0.05,split@every=7,seed=7"});
  // Each dropped reply costs one timeout, so it is short: a reply comes within a millisecond or
  // two, and one later than 100 ms is only retried (a stale copy is skipped); 20 attempts give a
  // request 2 s to get through on a loaded machine.
  Output d = ctl({"-t", "usb-2-sd", "--timeout", "100ms", "--retries", "20", server.port(), "download", path}, 90000);
  show(d);
  CHECK_EQ(d.status, 0);
  CHECK(has(d.out, "verified 100 instructions"));
  const std::string up = temp_dir() + "/faulty.bin";
  CHECK_EQ(ctl({"-t", "usb-2-sd", "--timeout", "100ms", "--retries", "20", server.port(), "upload", "-o", up}, 90000).status, 0);
  const auto want = assembled_bin(path);
  CHECK(slurp(up) == std::string(want.begin(), want.end()));
}

TEST(bad_fault_specs_are_usage_errors) {
  Output o = hosttest::run({kRun, "--serve", "pty", "--faults", "explode@3"});
  CHECK_EQ(o.status, 64);
  CHECK(has(o.err, "--faults: 'explode@3': unknown fault"));
  o = hosttest::run({kRun, "--serve", "pty", "--faults", "delay@3"});
  CHECK(has(o.err, "delay needs a duration"));
  o = hosttest::run({kRun, "--faults", "drop", "x.tmc"});
  CHECK(has(o.err, "--faults goes with --serve"));
  o = hosttest::run({kRun, "--serve", "pty", "--module", "1", "--module", "1"});
  CHECK_EQ(o.status, 64);
  CHECK(has(o.err, "two modules with address 1"));
}

TEST(fault_injector_is_deterministic_per_seed) {
  auto hits = [](std::uint64_t seed) {
    tmcl::FaultPlan plan;
    std::string err;
    CHECK(tmcl::parse_faults("drop@p=0.3,seed=" + std::to_string(seed), plan, err));
    tmcl::FaultInjector f(plan, 1.0);
    std::string pattern;
    const std::uint8_t frame[9] = {2, 1, 100, 6, 0, 0, 0, 0, 109};
    for (int i = 0; i < 64; ++i) {
      std::vector<std::uint8_t> out;
      f.reply(frame, 9, 6, i);
      f.release(i, out);
      pattern += out.empty() ? 'x' : '.';
    }
    return pattern;
  };
  CHECK_EQ(hits(7), hits(7));
  CHECK(hits(7) != hits(8));
  const std::string p = hits(7);
  const auto dropped = std::count(p.begin(), p.end(), 'x');
  CHECK(dropped > 5 && dropped < 40);
}

TEST(ctrl_c_during_download_stops_cleanly) {
  // Every reply 3 ms late: 577 stores take nearly two seconds. SIGINT goes once the server's log
  // shows 30 requests answered (not after a fixed time, which a loaded machine may spend before
  // the download even starts), so it lands in the middle with over a second to spare.
  const std::string log = temp_dir() + "/ctrl-c.log";
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd", "--faults", "delay=3ms", "--trace", "--log", log});
  const std::string src = write_temp("full2.tmc", full_memory_source());
  Output d = hosttest::run({kCtl, "-t", "usb-2-sd", server.port(), "download", src}, 60000, 0, [&](pid_t pid) {
    const std::string text = slurp(log);
    if (std::count(text.begin(), text.end(), '\n') < 30) return false;
    ::kill(pid, SIGINT);
    return true;
  });
  CHECK_EQ(d.status, 130);
  CHECK(has(d.err, "interrupted after "));
  CHECK(has(d.err, "resume with: tmclctl -t usb-2-sd " + server.port() + " download --from "));
  const auto at = d.err.find("download --from ");
  CHECK(at != std::string::npos);
  if (at == std::string::npos) return;
  const int from = std::atoi(d.err.c_str() + at + 16);
  CHECK(from > 0 && from < 577);
  // Out of download mode: the module answers normally.
  Output s = ctl({server.port(), "status"});
  CHECK_EQ(s.status, 0);
  CHECK(!has(s.out, "download\n"));
  // Resume where it stopped: the whole program verifies.
  Output r = ctl({"-t", "usb-2-sd", server.port(), "download", "--from", std::to_string(from), src}, 60000);
  show(r);
  CHECK_EQ(r.status, 0);
  CHECK(has(r.out, "verified 577 instructions"));
}

TEST(console_session) {
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});
  const std::string in = write_temp("console.txt", "help\nSAP 4, 0, 99\nGAP 4, 0\n!!\nSAP 4, 0\nhistory\nquit\n");
  // Standard input from a file: no prompt, each command echoed before its reply.
  Output o = hosttest::run({"/bin/sh", "-c", kCtl + " -t usb-2-sd " + server.port() + " console < " + in});
  CHECK_EQ(o.status, 0);
  CHECK(has(o.out, "tmcl> help\nType an instruction"));
  CHECK(has(o.out, "TMCLParam.tmc, Interrupts.inc and USB-2-SD.inc are included"));
  CHECK(has(o.out, "tmcl> SAP 4, 0, 99\n100 success, value 0\ntmcl> GAP 4, 0\n100 success, value 99\n"));
  CHECK(has(o.out, "tmcl> !!\nGAP 4, 0\n100 success, value 99\n"));
  CHECK(has(o.out, "tmcl> SAP 4, 0\ntmcl> history\n"));  // the error went to standard error
  CHECK(has(o.out, "   1  SAP 4, 0, 99\n   2  GAP 4, 0\n   3  GAP 4, 0\n"));
  CHECK(has(o.out, "tmcl> quit\n"));
  CHECK(has(o.err, "<command line>:1:"));
}

TEST(console_names_kept_for_the_session) {
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});
  write_temp("limits.inc", "Fast = 2000\n");
  const std::string in = write_temp("names.txt",
                                    "Speed = 1000\n"
                                    "SAP APMaxPositioningSpeed, Motor0, Speed\n"  // TMCLParam.tmc
                                    "GAP AP_MaxPositioningSpeed, 0\n"             // USB-2-SD.inc
                                    "#include limits.inc\n"
                                    "SAP 4, 0, Fast / 4\n"
                                    "GAP 4, 0\n");
  // One stream for both outputs (2>&1), as a user saves a transcript: in order.
  Output o = hosttest::run({"/bin/sh", "-c", kCtl + " -t usb-2-sd -I " + temp_dir() + " " + server.port() + " console < " + in + " 2>&1"});
  show(o);
  CHECK_EQ(o.status, 0);
  CHECK_EQ(o.out,
           "tmcl> Speed = 1000\n"
           "Speed = 1000\n"
           "tmcl> SAP APMaxPositioningSpeed, Motor0, Speed\n"
           "100 success, value 0\n"
           "tmcl> GAP AP_MaxPositioningSpeed, 0\n"
           "100 success, value 1000\n"
           "tmcl> #include limits.inc\n"
           "Fast = 2000\n"
           "tmcl> SAP 4, 0, Fast / 4\n"
           "100 success, value 0\n"
           "tmcl> GAP 4, 0\n"
           "100 success, value 500\n");
  // send knows the predefined names too.
  Output s = ctl({"-t", "usb-2-sd", server.port(), "send", "GAP APMaxPositioningSpeed, Motor0"});
  CHECK_EQ(s.out, "100 success, value 500\n");
  Output d = ctl({"-t", "usb-2-sd", server.port(), "send", "Speed = 1"});
  CHECK_EQ(d.status, 65);
  CHECK(has(d.err, "'Speed = 1' is no instruction: send takes one"));
}

TEST(position_reached_events_are_routed) {
  // 138's second reply comes unasked; with the ideal core it follows the MVP's reply at once.
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd", "--motion", "ideal"});
  const std::string in = write_temp("events.txt", ".raw 138, 0, 0, 1\nMVP ABS, 0, 100\nGAP 1, 0\nMVP ABS, 0, 50\nGAP 1, 0\n");
  Output o = hosttest::run({"/bin/sh", "-c", kCtl + " -t usb-2-sd " + server.port() + " console < " + in});
  CHECK_EQ(o.status, 0);
  CHECK_EQ(o.out,
           "tmcl> .raw 138, 0, 0, 1\n"
           "100 success, value 1\n"
           "tmcl> MVP ABS, 0, 100\n"
           "100 success, value 0\n"
           "event: position reached (motor mask 0x1)\n"
           "tmcl> GAP 1, 0\n"
           "100 success, value 100\n"
           "tmcl> MVP ABS, 0, 50\n"
           "100 success, value 0\n"  // not announced: no event, and no reply out of step
           "tmcl> GAP 1, 0\n"
           "100 success, value 50\n");
}

}  // namespace

TEST(test_files_on_the_virtual_module) {
  // tmclctl PORT test: the program downloaded and run, values polled by the wall clock; a test
  // with scenario lines skipped, `never fault` noted as not checked, a value a module cannot give
  // named, the JUnit report written; a silent module ends the run with exit 69.
  Server server(kRun, {"--serve", "pty", "-t", "usb-2-sd"});
  const std::string dir = temp_dir() + "/live";
  ::mkdir(dir.c_str(), 0700);
  write_temp("live/p.tmc", "SGP 1, 2, 5\nCALC LOAD, 42\nWAIT TICKS, 0, 30\nSGP 1, 2, 7\nSTOP\n");
  write_temp("live/a.tmctest",
             "program p.tmc\nmax-time 5s\nexpect at 100ms v[1] = 5\nexpect at 100ms acc = 42\nexpect at end v[1] = 7\n"
             "expect at end halted stop\nexpect never fault\n");
  write_temp("live/b.tmctest", "program p.tmc\nmax-time 1s\nexpect at 100ms v[1] = 6\nexpect at 200ms steps > 0\n");
  write_temp("live/c.tmctest", "program p.tmc\nat 1s input 0 = 1\nexpect at end v[1] = 7\n");
  write_temp("live/d.tmctest", "program p.tmc\ntarget generic\nexpect at end v[1] = 7\n");
  const std::string junit = temp_dir() + "/live.xml";
  Output o = ctl({"-t", "usb-2-sd", server.port(), "test", dir, "--junit", junit});
  show(o);
  CHECK_EQ(o.status, 1);
  CHECK(has(o.out, "PASS " + dir + "/a.tmctest\n  " + dir +
                       "/a.tmctest:7: note: 'never fault' is not checked on a module (a module reports no faults or warnings)\n"));
  CHECK(has(o.out, "FAIL " + dir + "/b.tmctest\n  " + dir + "/b.tmctest:3: expected v[1] = 6 at 100ms, got 5 (read at 0."));
  CHECK(has(o.out, "  " + dir + "/b.tmctest:4: cannot read steps > 0 at 200ms: 'steps' cannot be read from a module (acc, x and pc can)\n"));
  CHECK(has(o.out, "SKIP " + dir + "/c.tmctest (its scenario lines change the program's inputs, which a module's host cannot)\n"));
  CHECK(has(o.out, "SKIP " + dir + "/d.tmctest (written for generic, and the module is usb-2-sd (-t))\n"));
  CHECK(has(o.out, "1 passed, 1 failed, 2 skipped\n"));
  CHECK(has(slurp(junit), "<testsuites name=\"tmclctl\" tests=\"4\" failures=\"1\" errors=\"0\" skipped=\"2\""));
  // A silent module (no module 9 on the line): the test under way is an error naming the request,
  // the run stops there (later tests are skipped, not each left to time out) and the exit status
  // is the one of a silent module, 69, not the 65 of a bad test file.
  Output silent = ctl({"-t", "usb-2-sd", "-a", "9", "--timeout", "50ms", "--retries", "0", server.port(), "test",
                       dir + "/a.tmctest", dir + "/b.tmctest", "--junit", junit});
  show(silent);
  CHECK_EQ(silent.status, 69);
  CHECK(has(silent.out, "ERROR " + dir + "/a.tmctest\nSKIP " + dir + "/b.tmctest (not run: the module failed in an earlier test)\n"));
  CHECK(has(silent.err, dir + "/a.tmctest: error: no reply within 50 ms to "));
  CHECK(has(silent.err, " to module 9 on " + server.port()));
  CHECK(has(silent.out, "0 passed, 0 failed, 1 skipped, 1 error\n"));
  CHECK(has(slurp(junit), "tests=\"2\" failures=\"0\" errors=\"1\" skipped=\"1\""));
  // -t a profile file whose name (mymod) is no target: tests without a target line run on it,
  // and one naming that file beside it is not skipped as written for another module.
  ::mkdir((dir + "/mine").c_str(), 0700);
  write_temp("live/mine.profile", "tmcl-profile 1\nname mymod\ntitle \"mine\"\nbased-on usb-2-sd\n");
  write_temp("live/mine/e.tmctest", "program ../p.tmc\nexpect at end v[1] = 7\n");
  write_temp("live/mine/f.tmctest", "program ../p.tmc\ntarget ../mine.profile\nexpect at end v[1] = 7\n");
  Output mine = ctl({"-t", dir + "/mine.profile", server.port(), "test", dir + "/mine"});
  show(mine);
  CHECK_EQ(mine.status, 0);
  CHECK(has(mine.out, "PASS " + dir + "/mine/e.tmctest\n"));
  CHECK(has(mine.out, "PASS " + dir + "/mine/f.tmctest\n"));
  CHECK(has(mine.out, "2 passed, 0 failed\n"));
  // The options that go with it.
  CHECK_EQ(ctl({server.port(), "status", "--junit", junit}).status, 64);
  Output none = ctl({server.port(), "test"});
  CHECK_EQ(none.status, 64);
  CHECK(has(none.err, "test needs test files or folders"));
}
