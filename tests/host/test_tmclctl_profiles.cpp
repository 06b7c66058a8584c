// tmclctl and module profiles, against the virtual module (`tmclrun --serve -t NAME`): the
// module's reply to 136 on connect picks its profile (parameter names of a TMCM-1110 without
// -t), -t naming another module is warned about, a firmware no profile knows is noted (generic is
// used), download checks the program as tmclasm -Werror does and honours its first line, autostart
// on a module that keeps its program in RAM is warned about, and `probe` drafts a profile that
// agrees with the bundled one on which parameters exist.
#include <set>
#include <sstream>
#include <utility>

#include "check.hpp"
#include "tmclctl_test.hpp"
#include "tmcl/host/probe.hpp"
#include "tmcl/profile.hpp"
#include "tmcl/profile_file.hpp"

using namespace hosttest;

namespace {
// Without -t, tmclctl names the module's parameters by its reply to 136: `name` reads `value`,
// and the status shows the module's title.
void named_by_136(const std::string& port, const char* name, const char* value, const char* title) {
  Output g = ctl({port, "get", name});
  show(g);
  CHECK_EQ(g.status, 0);
  CHECK_EQ(g.out, value);
  CHECK(g.err.empty());
  CHECK(has(ctl({port, "status"}).out, title));
}
}  // namespace

TEST(the_reply_to_136_picks_the_profile) {
  Server server(kRun, {"--serve", "tcp:127.0.0.1:0", "-t", "tmcm-1110"});
  const std::string& p = server.port();
  // "Pulse divisor" is a TMCM-1110 parameter (154); generic would not know the name.
  named_by_136(p, "pulse divisor", "3\n", "TMCM-1110 stepRocker (firmware 1.03)");
  CHECK(has(ctl({p, "status"}).out, "firmware:         1110V103"));
  // -t naming another module: it is used, with a warning.
  Output w = ctl({"-t", "usb-2-sd", p, "get", "ap", "4"});
  CHECK_EQ(w.status, 0);
  CHECK(has(w.err, "warning: module 1 reports firmware 1110V103 (TMCM-1110 stepRocker (firmware 1.03)), not USB-2-SD (firmware 1.14) (-t usb-2-sd is used)"));
  // -t naming the same module, or generic: no word.
  CHECK(ctl({"-t", "tmcm-1110", p, "get", "ap", "4"}).err.empty());
  CHECK(ctl({"-t", "generic", p, "get", "ap", "4"}).err.empty());
}

// The TMCM-1290 and TMCM-3216 by their replies to 136 (module numbers 1290, 3216): their names
// without -t ("Velocity V2" is theirs, axis parameter 35).
TEST(the_reply_to_136_picks_the_tmcm_1290_and_3216) {
  for (const auto& [name, title] : {std::pair{"tmcm-1290", "TMCM-1290 (firmware 1.01)"},
                                    std::pair{"tmcm-3216", "TMCM-3216 (3 axes, TMCM-1290 firmware family)"}}) {
    Server server(kRun, {"--serve", "tcp:127.0.0.1:0", "-t", name});
    named_by_136(server.port(), "velocity v2", "0\n", title);
  }
}

// Two modules of one parameter set (tmcm-3351 is based on tmcm-3312): the module number of the
// reply picks each one's own profile, with a name only these modules have (129, closed loop).
TEST(the_reply_to_136_tells_the_tmcm3351_from_the_tmcm3312) {
  for (const auto& [name, number] : {std::pair{"tmcm-3351", "3351"}, std::pair{"tmcm-3312", "3312"}}) {
    Server server(kRun, {"--serve", "tcp:127.0.0.1:0", "-t", name});
    named_by_136(server.port(), "closed loop", "0\n", (std::string("TMCM-") + number + " (3 axes)").c_str());
    CHECK(has(ctl({server.port(), "status"}).out, std::string("firmware:         ") + number + "V100"));
  }
}

TEST(download_checks_like_tmclasm_werror) {
  Server server(kRun, {"--serve", "tcp:127.0.0.1:0", "-t", "tmcm-1110"});
  const std::string& p = server.port();
  // A value beyond the TMC429's range is a warning of tmclasm, an error here: nothing is sent.
  const std::string bad = write_temp("bad.tmc", "SAP 4, 0, 5000\nSTOP\n");
  Output d = ctl({p, "download", bad});
  CHECK_EQ(d.status, 65);
  CHECK(has(d.err, "error: value 5000 is outside the range of axis parameter 4"));
  CHECK(has(d.err, "[-Werror=target]"));
  CHECK(has(d.err, "nothing sent"));
  // Refused for warnings alone: how to go on, for a warning new since the last download too.
  CHECK(has(d.err, "tmclctl: note: a warning counts as an error here, a new one too; fix the line, or allow the warning "
                   "there with a comment '// tmcl: allow NAME' (docs/analysis.md, \"New warnings\")"));
  // The control-flow analysis too: a subroutine without RSUB.
  const std::string flow = write_temp("flow.tmc", "CSUB Sub\nSTOP\nSub:\nSAP 4, 0, 100\n");
  d = ctl({p, "download", flow});
  CHECK_EQ(d.status, 65);
  CHECK(has(d.err, "-Werror="));
  // A true error is no warning to allow: no such note.
  const std::string wrong = write_temp("wrong.tmc", "SAPP 4, 0, 100\nSTOP\n");
  d = ctl({p, "download", wrong});
  CHECK_EQ(d.status, 65);
  CHECK(!has(d.err, "tmcl: allow"));
  // A clean program goes through.
  const std::string good = write_temp("good.tmc", "SAP 4, 0, 1000\nSTOP\n");
  d = ctl({"-q", p, "download", good});
  show(d);
  CHECK_EQ(d.status, 0);
  // The program's first line names another module: used (its checks), with a warning.
  const std::string named = write_temp("named.tmc", "// tmcl-target: tmcm-1260\nSAP 4, 0, 5000\nSTOP\n");
  d = ctl({"-q", p, "download", named});
  CHECK_EQ(d.status, 0);  // 5000 pps is within the TMCM-1260's range
  CHECK(has(d.err, "warning: " + named + " is for TMCM-1260 / PD57/60-1260 (firmware 1.44), the module is TMCM-1110"));
}

TEST(autostart_on_a_module_without_eeprom_program_is_warned) {
  Server server(kRun, {"--serve", "tcp:127.0.0.1:0", "-t", "usb-2-sd"});
  const std::string prog = write_temp("auto.tmc", "SAP 4, 0, 1000\nSTOP\n");
  Output d = ctl({"-q", server.port(), "download", "--autostart", prog});
  CHECK_EQ(d.status, 0);
  CHECK(has(d.err, "warning: USB-2-SD (firmware 1.14) keeps its program in RAM: after a power cycle there is no program to start"));
  Server eeprom(kRun, {"--serve", "tcp:127.0.0.1:0", "-t", "tmcm-1110"});
  d = ctl({"-q", eeprom.port(), "download", "--autostart", prog});
  CHECK_EQ(d.status, 0);
  CHECK(!has(d.err, "warning"));
}

TEST(a_firmware_no_profile_knows_is_noted) {
  // A module of the user's own (tests/golden/profiles/my-module.profile, firmware 4242V201) that
  // no bundled profile knows: without -t generic is used and tmclctl says so, naming the command
  // that drafts a profile; -q keeps it quiet; on the search path, or with -t, its profile is used.
  const std::string profiles = TMCL_TEST_PROFILES;
  Server server(kRun, {"--serve", "tcp:127.0.0.1:0", "-t", profiles + "/my-module.profile"});
  const std::string& p = server.port();
  // No profile path from the environment, and a home without ~/.config/tmcl/profiles.
  auto ctl_with = [&](const std::string& profile_path, const std::vector<std::string>& args) {
    std::vector<std::string> argv{"/usr/bin/env", "-u", "TMCL_PROFILE_PATH", "HOME=" + temp_dir()};
    if (!profile_path.empty()) argv.push_back("TMCL_PROFILE_PATH=" + profile_path);
    argv.insert(argv.end(), {kCtl, "--timeout", "5s"});
    argv.insert(argv.end(), args.begin(), args.end());
    return hosttest::run(argv);
  };
  Output g = ctl_with("", {p, "get", "ap", "4"});
  show(g);
  CHECK_EQ(g.status, 0);
  CHECK_EQ(g.out, "100\n");
  CHECK_EQ(g.err, "tmclctl: note: no profile knows firmware 4242V201; using generic (`tmclctl " + p +
                      " probe -o NAME.profile` drafts one)\n");
  Output q = ctl_with("", {"-q", p, "get", "ap", "4"});
  CHECK_EQ(q.status, 0);
  CHECK(q.err.empty());
  // Its own parameter name, which generic does not have, once its profile is found.
  Output named = ctl_with(profiles, {p, "get", "maximum speed"});
  show(named);
  CHECK_EQ(named.status, 0);
  CHECK_EQ(named.out, "100\n");
  CHECK(named.err.empty());
  Output given = ctl_with("", {"-t", profiles + "/my-module.profile", p, "get", "maximum speed"});
  CHECK_EQ(given.status, 0);
  CHECK(given.err.empty());
}

TEST(probe_drafts_a_profile_that_agrees_on_which_parameters_exist) {
  Server server(kRun, {"--serve", "pty", "-t", "tmcm-6110"});
  const std::string out = temp_dir() + "/probed-6110.profile";
  Output o = ctl({server.port(), "probe", "-o", out});
  show(o);
  CHECK_EQ(o.status, 0);
  CHECK(has(o.out, "wrote " + out + ": "));
  CHECK(has(o.out, "6 motors; every fact unverified"));
  std::vector<tmcl::FileDiag> diags;
  auto draft = tmcl::parse_profile(slurp(out), out, out, diags);
  CHECK(draft != nullptr);
  if (!draft) {
    std::fputs(tmcl::render_file_diags(diags, 0).c_str(), stderr);
    return;
  }
  const tmcl::Profile& d = draft->profile;
  const tmcl::Profile& b = *tmcl::find_profile("tmcm-6110");
  auto numbers = [](std::span<const tmcl::ParamInfo> t) {
    std::set<int> s;
    for (const auto& p : t) s.insert(p.number);
    return s;
  };
  CHECK(numbers(d.axis_params) == numbers(b.axis_params));
  CHECK(numbers(d.bank0) == numbers(b.bank0));
  CHECK(numbers(d.bank3) == numbers(b.bank3));
  CHECK_EQ(d.name, "probed-6110");
  CHECK_EQ(d.firmware, b.firmware);
  CHECK_EQ(d.motors, b.motors);
  CHECK_EQ(d.program_memory, b.program_memory);
  CHECK_EQ(d.user_vars, b.user_vars);
  CHECK_EQ(d.coords, b.coords);
  CHECK_EQ(d.default_motion, "tmc429");  // it has the TMC429's pulse divisor
  // The values read are the defaults, every fact unverified.
  CHECK_EQ(d.axis_param(154)->default_value, b.axis_param(154)->default_value);
  for (const auto& p : d.axis_params) CHECK_EQ(p.unverified, 0xFF);
  // A silent port: nothing written.
  Output none = ctl({"--timeout", "50ms", "--retries", "0", "-a", "9", server.port(), "probe", "-o", out + ".none"});
  CHECK_EQ(none.status, 69);
  CHECK(!exists(out + ".none"));
  CHECK_EQ(ctl({server.port(), "probe"}).status, 64);  // -o is needed
}

// tmclctl knows a module by its reply to 136, found among the profiles (none is listed by hand):
// every bundled module's own string picks its profile, and so does another version of its module
// number (a newer firmware); no two bundled modules share a module number, so the pick is never a
// guess between two.
TEST(every_bundled_modules_firmware_reply_picks_its_profile) {
  std::set<std::string> numbers;
  int modules = 0;
  for (const tmcl::Profile* p : tmcl::all_profiles()) {
    const std::string fw(p->firmware);
    const auto v = fw.find('V');
    if (p->any_parameter || v == std::string::npos) continue;
    ++modules;
    CHECK(numbers.insert(fw.substr(0, v)).second);
    CHECK(tmcl::host::profile_for_firmware(fw) == p);
    const std::string other = fw.substr(0, v) + (fw.substr(v) == "V999" ? "V998" : "V999");
    const tmcl::Profile* q = tmcl::host::profile_for_firmware(other);
    if (q != p) tmcl_test::fail(__FILE__, __LINE__, other + " picks " + (q ? std::string(q->name) : "nothing") + ", not " + std::string(p->name));
  }
  CHECK(modules >= 17);
}

// What the vendor's Python library sends in its rotate demo of these modules (PyTrinamic
// examples/modules/TMCM1240/TMCL/rotate_demo.py, the same for the -1241, -1260, -1270, -1276 and
// -1278: currents 6 and 7, 256 microsteps, speed 4 and acceleration 5, relative moves from the
// actual position (127 = 1), the position cleared, ROR, MST, MVP REL, position reached 8 polled,
// MVP ABS back to 0), sent to `tmclrun --serve -t NAME` of every module on the TMC5160 core with
// no -t on tmclctl's side: the reply to 136 names the module, and every command succeeds. The
// library itself is not installable here, so its requests are replayed, not its script run.
TEST(the_vendors_rotate_demo_runs_on_every_tmc5160_module) {
  int modules = 0;
  for (const tmcl::Profile* p : tmcl::all_profiles()) {
    if (p->default_motion != "tmc5160") continue;
    ++modules;
    const std::string name(p->name);
    Server server(kRun, {"--serve", "tcp:127.0.0.1:0", "-t", name, "--time-scale", "20"});
    const std::string& port = server.port();
    auto send = [&](const std::string& ins) {
      Output o = ctl({port, "send", ins});
      if (o.status != 0 || o.out.rfind("100 success", 0) != 0)
        tmcl_test::fail(__FILE__, __LINE__, name + ": " + ins + ": " + o.out + o.err);
      const auto at = o.out.find("value ");
      return at == std::string::npos ? 0 : std::stoi(o.out.substr(at + 6));
    };
    for (const char* ins : {"SAP 6, 0, 50", "SAP 7, 0, 0", "SAP 140, 0, 8", "SAP 4, 0, 20000", "SAP 5, 0, 40000",
                            "SAP 127, 0, 1", "SAP 1, 0, 0", "ROR 0, 20000"})
      send(ins);
    CHECK(send("GAP 2, 0") == 20000);
    send("MST 0");
    for (int i = 0; i < 200 && send("GAP 3, 0") != 0; ++i) {
    }  // the motor ramps down (the demo sleeps 2 s)
    const int stopped = send("GAP 1, 0");
    send("MVP REL, 0, " + std::to_string(stopped));
    int reached = 0;
    for (int i = 0; i < 200 && !reached; ++i) reached = send("GAP 8, 0");
    CHECK(reached == 1);
    CHECK_EQ(send("GAP 1, 0"), 2 * stopped);
    send("MVP ABS, 0, 0");
    reached = 0;
    for (int i = 0; i < 200 && !reached; ++i) reached = send("GAP 8, 0");
    CHECK_EQ(send("GAP 1, 0"), 0);
    CHECK(has(ctl({port, "status"}).out, std::string(p->title)));
  }
  CHECK(modules >= 8);  // the TMCM-1260 and the seven of its family
}
