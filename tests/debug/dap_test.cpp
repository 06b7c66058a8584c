// A DAP test client: drives run_dap through every request the adapter supports, a refused
// request, a runtime fault and reverse steps, and checks the responses and events (type,
// success, reasons, values) as a client would see them; and checks that the stepping rules'
// DAP golden transcripts stop where their command-line twins stop.
#include "check.hpp"
#include "os_test.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tmcl/debug_cli.hpp"
#include "tmcl/json.hpp"

using namespace tmcl;
using tmcl::json::Value;

namespace {

const char* kDapProgram = R"(        VECT 0, tick
        SGP 0, 3, 10
        EI 0
        EI 255
main:   SGP 1, 2, 0
loop:   CSUB bump
        GGP 1, 2
        COMP 3
        JC LT, loop
        JA 99
bump:   GGP 1, 2
        CALC ADD, 1
        AGP 1, 2
        RSUB
tick:   RETI
)";

struct Session {
  std::vector<Value> messages;  // everything the adapter sent, in order
  const Value* response(const std::string& command, int nth = 0) const {
    for (const auto& m : messages)
      if (m["type"].as_string() == "response" && m["command"].as_string() == command && nth-- == 0) return &m;
    return nullptr;
  }
  std::vector<const Value*> events(const std::string& name) const {
    std::vector<const Value*> out;
    for (const auto& m : messages)
      if (m["type"].as_string() == "event" && m["event"].as_string() == name) out.push_back(&m);
    return out;
  }
};

Session parse_session(const std::string& all);

Session run(const std::vector<std::string>& requests) {
  std::FILE* in = tmcl_test::scratch_file();
  std::FILE* out = tmcl_test::scratch_file();
  CHECK(in && out);
  if (!in || !out) return {};
  int seq = 0;
  for (const auto& r : requests) {
    std::string body = "{\"seq\":" + std::to_string(++seq) + ",\"type\":\"request\"," + r + "}";
    std::fprintf(in, "Content-Length: %zu\r\n\r\n%s", body.size(), body.c_str());
  }
  std::rewind(in);
  debug::DapSetup setup;
  setup.target = "usb-2-sd";
  debug::run_dap(setup, in, out);
  std::rewind(out);
  std::string all;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, out)) > 0;) all.append(buf, n);
  std::fclose(in);
  std::fclose(out);
  if (std::getenv("DAP_TEST_DUMP")) std::fputs(all.c_str(), stderr);
  return parse_session(all);
}

// The messages of an adapter's output (Content-Length framed JSON), in order.
Session parse_session(const std::string& all) {
  Session s;
  for (std::size_t pos = 0; (pos = all.find("Content-Length: ", pos)) != std::string::npos;) {
    std::size_t len = std::stoul(all.substr(pos + 16));
    std::size_t body = all.find("\r\n\r\n", pos) + 4;
    Value v;
    json::Error err;
    CHECK(json::parse(all.substr(body, len), v, err));
    s.messages.push_back(v);
    if (std::getenv("DAP_TEST_DUMP")) std::fprintf(stderr, "\n[%s %s %s]\n", v["type"].as_string().c_str(), v["command"].as_string().c_str(), json::write(v).substr(0, 60).c_str());
    pos = body + len;
  }
  return s;
}

std::string program_file() {
  std::string path = "dap_test_prog.tmc";
  std::ofstream(path) << kDapProgram;
  return path;
}

}  // namespace

TEST(a_whole_session_through_every_supported_request) {
  std::string prog = program_file();
  Session s = run({
      R"("command":"initialize","arguments":{"adapterID":"tmcl"})",
      R"("command":"launch","arguments":{"program":")" + prog + R"(","stopOnEntry":true})",
      R"("command":"setBreakpoints","arguments":{"source":{"path":")" + prog + R"("},"breakpoints":[{"line":12},{"line":7,"condition":"v[1] == 2"},{"line":500}]})",
      R"("command":"setFunctionBreakpoints","arguments":{"breakpoints":[{"name":"tick"},{"name":"nowhere"}]})",
      R"("command":"setInstructionBreakpoints","arguments":{"breakpoints":[]})",
      R"("command":"setExceptionBreakpoints","arguments":{"filters":["fault"]})",
      R"("command":"dataBreakpointInfo","arguments":{"name":"v[1]"})",
      R"("command":"setDataBreakpoints","arguments":{"breakpoints":[]})",
      R"("command":"configurationDone")",
      R"("command":"threads")",
      R"("command":"continue","arguments":{"threadId":1})",
      R"("command":"stackTrace","arguments":{"threadId":1})",
      R"("command":"scopes","arguments":{"frameId":0})",
      R"("command":"variables","arguments":{"variablesReference":1})",
      R"("command":"variables","arguments":{"variablesReference":2})",
      R"("command":"evaluate","arguments":{"expression":"bump + 1","context":"hover"})",
      R"("command":"next","arguments":{"threadId":1})",
      R"("command":"stepIn","arguments":{"threadId":1})",
      R"("command":"stepOut","arguments":{"threadId":1})",
      R"("command":"stepBack","arguments":{"threadId":1})",
      R"("command":"reverseContinue","arguments":{"threadId":1})",
      R"("command":"setVariable","arguments":{"variablesReference":2,"name":"v[7]","value":"41 + 1"})",
      R"("command":"evaluate","arguments":{"expression":"v[7]"})",
      R"("command":"disassemble","arguments":{"memoryReference":"10","instructionOffset":0,"instructionCount":2})",
      R"("command":"gotoTargets","arguments":{"source":{"path":")" + prog + R"("},"line":5})",
      R"("command":"goto","arguments":{"threadId":1,"targetId":4})",
      R"("command":"pause","arguments":{"threadId":1})",
      R"("command":"modules")",
      R"("command":"setFunctionBreakpoints","arguments":{"breakpoints":[]})",
      R"("command":"setBreakpoints","arguments":{"source":{"path":")" + prog + R"("},"breakpoints":[]})",
      R"("command":"continue","arguments":{"threadId":1})",
      R"("command":"stepBack","arguments":{"threadId":1})",
      R"("command":"restart")",
      R"("command":"disconnect")",
  });
  const Value* init = s.response("initialize");
  CHECK(init && (*init)["success"].as_bool());
  if (init) CHECK((*init)["body"]["supportsStepBack"].as_bool());
  CHECK(s.events("initialized").size() == 1);
  const Value* bps = s.response("setBreakpoints");
  CHECK(bps != nullptr);
  if (bps) {
    const Value& list = (*bps)["body"]["breakpoints"];
    CHECK_EQ(list.size(), std::size_t{3});
    CHECK(list.at(0)["verified"].as_bool());
    CHECK(list.at(1)["verified"].as_bool());
    CHECK(!list.at(2)["verified"].as_bool());  // no code at line 500
  }
  const Value* fbs = s.response("setFunctionBreakpoints");
  CHECK(fbs && (*fbs)["body"]["breakpoints"].at(0)["verified"].as_bool() && !(*fbs)["body"]["breakpoints"].at(1)["verified"].as_bool());
  auto stops = s.events("stopped");
  CHECK(stops.size() >= 8);
  if (stops.size() >= 2) {
    CHECK_EQ((*stops[0])["body"]["reason"].as_string(), std::string("entry"));
    CHECK_EQ((*stops[1])["body"]["reason"].as_string(), std::string("breakpoint"));  // the timer's handler or bump
  }
  const Value* trace = s.response("stackTrace");
  CHECK(trace && (*trace)["body"]["stackFrames"].size() >= 1);
  const Value* hover = s.response("evaluate");
  CHECK(hover && (*hover)["body"]["result"].as_string() == "11");
  const Value* set = s.response("setVariable");
  CHECK(set && (*set)["success"].as_bool() && (*set)["body"]["value"].as_string() == "42");
  const Value* seven = s.response("evaluate", 1);
  CHECK(seven && (*seven)["body"]["result"].as_string() == "42");
  const Value* dis = s.response("disassemble");
  CHECK(dis && (*dis)["body"]["instructions"].at(0)["instruction"].as_string() == "GGP 1, 2");
  const Value* mods = s.response("modules");
  CHECK(mods && !(*mods)["success"].as_bool());
  CHECK(mods && (*mods)["message"].as_string().find("does not support") != std::string::npos);
  // The run to the end faults (JA 99): an exception stop; a step back from it is a step stop.
  bool fault = false, back = false;
  for (std::size_t i = 0; i < stops.size(); ++i) {
    std::string reason = (*stops[i])["body"]["reason"].as_string();
    if (reason == "exception") fault = true;
    if (fault && reason == "step") back = true;
  }
  CHECK(fault);
  CHECK(back);
  const Value* disc = s.response("disconnect");
  CHECK(disc && (*disc)["success"].as_bool());
  std::remove(prog.c_str());
}

TEST(requests_before_launch_and_a_bad_launch_get_error_responses) {
  Session s = run({R"("command":"initialize","arguments":{})", R"("command":"threads")",
                   R"("command":"launch","arguments":{"program":"no-such-file.tmc"})", R"("command":"disconnect")"});
  const Value* threads = s.response("threads");
  CHECK(threads && !(*threads)["success"].as_bool());
  const Value* launch = s.response("launch");
  CHECK(launch && !(*launch)["success"].as_bool());
  CHECK(launch && (*launch)["message"].as_string().find("no-such-file.tmc") != std::string::npos);
}

TEST(a_program_run_to_stop_ends_with_exited_and_terminated) {
  std::string path = "dap_test_stop.tmc";
  std::ofstream(path) << "SGP 1, 2, 5\nSTOP\n";
  Session s = run({R"("command":"initialize","arguments":{})", R"("command":"launch","arguments":{"program":")" + path + R"("})",
                   R"("command":"configurationDone")", R"("command":"disconnect")"});
  auto exited = s.events("exited");
  CHECK_EQ(exited.size(), std::size_t{1});
  if (!exited.empty()) CHECK_EQ((*exited[0])["body"]["exitCode"].as_int(), 0);
  CHECK_EQ(s.events("terminated").size(), std::size_t{1});
  std::remove(path.c_str());
}

// pause of a running program: the adapter runs the program in slices and reads requests between
// them, so an endless loop without a breakpoint is paused (stopped, reason "pause") and runs on
// after continue; threads is answered while it runs, anything needing it stopped is refused,
// and disconnect ends the adapter with the program still running. Where the pause lands depends
// on the slice, so the test checks the events and that the program went on, not an address.
TEST(pause_stops_an_endless_loop_and_continue_runs_it_on) {
  std::string path = "dap_test_endless.tmc";
  std::ofstream(path) << "        SGP 1, 2, 0\nloop:   GGP 1, 2\n        CALC ADD, 1\n        AGP 1, 2\n        JA loop\n";
  Session s = run({R"("command":"initialize","arguments":{})", R"("command":"launch","arguments":{"program":")" + path + R"("})",
                   R"("command":"configurationDone")", R"("command":"threads")", R"("command":"pause","arguments":{"threadId":1})",
                   R"("command":"stackTrace","arguments":{"threadId":1})", R"("command":"evaluate","arguments":{"expression":"v[1]"})",
                   R"("command":"continue","arguments":{"threadId":1})", R"("command":"evaluate","arguments":{"expression":"v[1]"})",
                   R"("command":"pause","arguments":{"threadId":1})", R"("command":"evaluate","arguments":{"expression":"v[1]"})",
                   R"("command":"continue","arguments":{"threadId":1})", R"("command":"disconnect")"});
  auto stops = s.events("stopped");
  CHECK_EQ(stops.size(), std::size_t{2});
  for (const Value* st : stops) CHECK_EQ((*st)["body"]["reason"].as_string(), std::string("pause"));
  // threads was answered while the program ran: before the first stop.
  std::size_t threads_at = 0, first_stop_at = 0;
  for (std::size_t i = 0; i < s.messages.size(); ++i) {
    const Value& m = s.messages[i];
    if (m["type"].as_string() == "response" && m["command"].as_string() == "threads") threads_at = i;
    if (!first_stop_at && m["type"].as_string() == "event" && m["event"].as_string() == "stopped") first_stop_at = i;
  }
  CHECK(threads_at > 0 && threads_at < first_stop_at);
  const Value* trace = s.response("stackTrace");
  CHECK(trace && (*trace)["success"].as_bool());
  if (trace) {
    const Value& top = (*trace)["body"]["stackFrames"].at(0);
    CHECK(top["line"].as_int() >= 2 && top["line"].as_int() <= 5);  // somewhere in the loop
    CHECK_EQ(top["source"]["path"].as_string(), path);
  }
  const Value* first = s.response("evaluate", 0);
  const Value* running = s.response("evaluate", 1);
  const Value* second = s.response("evaluate", 2);
  CHECK(first && second && running);
  if (first && second && running) {
    CHECK((*first)["success"].as_bool() && (*second)["success"].as_bool());
    CHECK(!(*running)["success"].as_bool());  // asked while running
    CHECK((*running)["message"].as_string().find("running") != std::string::npos);
    // The program ran on after continue: the counter grew.
    CHECK(std::stoll((*second)["body"]["result"].as_string()) > std::stoll((*first)["body"]["result"].as_string()));
    CHECK(std::stoll((*first)["body"]["result"].as_string()) > 0);
  }
  const Value* disc = s.response("disconnect");
  CHECK(disc && (*disc)["success"].as_bool());
  CHECK(s.events("exited").empty());  // disconnected while it ran: no exit to report
  std::remove(path.c_str());
}

TEST(terminate_while_running_ends_the_program) {
  std::string path = "dap_test_endless2.tmc";
  std::ofstream(path) << "loop:   JA loop\n";
  Session s = run({R"("command":"initialize","arguments":{})", R"("command":"launch","arguments":{"program":")" + path + R"("})",
                   R"("command":"configurationDone")", R"("command":"terminate")", R"("command":"disconnect")"});
  const Value* term = s.response("terminate");
  CHECK(term && (*term)["success"].as_bool());
  CHECK_EQ(s.events("terminated").size(), std::size_t{1});
  CHECK(s.events("stopped").empty());
  const Value* disc = s.response("disconnect");
  CHECK(disc && (*disc)["success"].as_bool());
  std::remove(path.c_str());
}

// The stepping rules (docs/debugger.md, "Stepping") hold over DAP as on the command line: the
// same engine behind stepIn/next/stepOut/stepBack as behind step/next/finish/reverse-step. A timer
// fires during a WAIT; its handler calls a subroutine. Each stop's line and instant over DAP
// equal the command line's, and both are the stops the rules give (a step from the WAIT enters
// the handler at its first instruction; a next from the RETI ends after the WAIT, the later
// interrupts stepped over; stepBack retraces them). Before the rules, DAP's stepIn from the WAIT
// landed on the handler's second instruction and its next skipped both CALCV lines.
namespace {
const char* kStepProgram = R"(        VECT 0, Tick
        SGP 0, 3, 100
        EI 0
        EI 255
        MVP ABS, 0, 10000
        WAIT POS, 0, 0
        CALCV ADD, 5, 1
        CALCV ADD, 5, 1
        STOP
Tick:   CSUB Count
        RETI
Count:  GGP 6, 2
        CALC ADD, 1
        AGP 6, 2
        RSUB
)";

struct Place {
  std::int64_t line;
  std::string time;
  bool operator==(const Place&) const = default;
};
std::string text_of(const std::vector<Place>& ps) {
  std::string s;
  for (const auto& p : ps) s += std::to_string(p.line) + "@" + p.time + " ";
  return s;
}

// The command line's stops for the same moves: `p time` and the line of `p pc` after each.
std::vector<Place> cli_places(const std::string& path, const std::vector<std::string>& moves) {
  const Profile& profile = *find_profile("usb-2-sd");
  debug::ProgramInfo info;
  std::string messages;
  CHECK(debug::load_program_info(path, profile, AsmOptions{}, "", info, messages));
  debug::Setup setup;
  setup.profile = &profile;
  setup.core_name = std::string(profile.default_motion);
  debug::ProgramInfo copy = info;
  debug::Engine engine(setup, std::move(copy), make_motion_core(setup.core_name));
  std::FILE* out = tmcl_test::scratch_file();
  CHECK(out != nullptr);
  if (!out) return {};
  debug::CommandLine cli(engine, out, false, false);
  std::vector<Place> places;
  auto value = [&](const std::string& expr) {
    std::fflush(out);
    long at = std::ftell(out);
    cli.line("p " + expr);
    std::fflush(out);
    std::fseek(out, at, SEEK_SET);
    char buf[256] = {};
    std::string got = std::fgets(buf, sizeof buf, out) ? buf : "";
    std::fseek(out, 0, SEEK_END);
    return got.substr(got.find('=') + 2, got.find('\n') - got.find('=') - 2);
  };
  cli.line("break 6");
  cli.line("run");
  for (const auto& m : moves) {
    cli.line(m);
    std::size_t pc = std::stoul(value("pc"));
    places.push_back({pc < info.lines.size() ? info.lines[pc].line : -1, value("time")});
  }
  std::fclose(out);
  return places;
}
}  // namespace

TEST(dap_steps_stop_where_the_command_line_steps_stop) {
  std::string path = "dap_test_steps.tmc";
  std::ofstream(path) << kStepProgram;
  const std::vector<std::pair<std::string, std::string>> moves = {
      {"stepIn", "step"}, {"stepIn", "step"},          {"stepOut", "finish"},         {"stepIn", "step"},
      {"next", "next"},   {"next", "next"},            {"next", "next"},              {"stepBack", "reverse-step"},
      {"stepBack", "reverse-step"}, {"stepBack", "reverse-step"}};
  std::vector<std::string> requests = {
      R"("command":"initialize","arguments":{})", R"("command":"launch","arguments":{"program":")" + path + R"("})",
      R"("command":"setBreakpoints","arguments":{"source":{"path":")" + path + R"("},"breakpoints":[{"line":6}]})",
      R"("command":"configurationDone")"};
  std::vector<std::string> cli_moves;
  for (const auto& [dap, cli] : moves) {
    requests.push_back(R"("command":")" + dap + R"(","arguments":{"threadId":1})");
    requests.push_back(R"("command":"stackTrace","arguments":{"threadId":1})");
    requests.push_back(R"("command":"evaluate","arguments":{"expression":"time"})");
    cli_moves.push_back(cli);
  }
  requests.push_back(R"("command":"disassemble","arguments":{"memoryReference":"9","instructionOffset":0,"instructionCount":1})");
  requests.push_back(R"("command":"disconnect")");
  Session s = run(requests);
  const Value* dis = s.response("disassemble");
  CHECK(dis && (*dis)["body"]["instructions"].at(0)["instruction"].as_string() == "CSUB Count");  // the target by its label
  std::vector<Place> dap;
  for (std::size_t i = 0; i < moves.size(); ++i) {
    const Value* trace = s.response("stackTrace", static_cast<int>(i));
    const Value* time = s.response("evaluate", static_cast<int>(i));
    CHECK(trace && time);
    if (!trace || !time) break;
    dap.push_back({(*trace)["body"]["stackFrames"].at(0)["line"].as_int(), (*time)["body"]["result"].as_string()});
  }
  // Every stop is a step's: no breakpoint hit twice, nothing ran to the end.
  for (const Value* st : s.events("stopped")) {
    std::string reason = (*st)["body"]["reason"].as_string();
    CHECK(reason == "step" || reason == "breakpoint");
  }
  const std::vector<Place> expected = {{10, "100040"}, {12, "100060"}, {11, "100140"}, {10, "200040"}, {11, "200140"},
                                       {7, "883984"},  {8, "884004"},  {7, "883984"},  {11, "800140"}, {15, "800120"}};
  CHECK_EQ(text_of(dap), text_of(expected));
  CHECK_EQ(text_of(cli_places(path, cli_moves)), text_of(expected));
  std::remove(path.c_str());
}

// The stepping rules' golden transcripts (tests/golden/debug/stepping/): each NAME-dap.golden
// (stackTrace, then evaluate time, at every stop) stops at the lines and instants its NAME.golden
// (the command line's) stops at, in the same order. The command line makes a few stops more
// (`until`, `run` again, reverse-next), so the DAP stops are a subsequence of them; both golden
// files are pinned byte for byte, and this keeps an update of one from leaving the other behind.
namespace {

std::string golden_stdout(const std::string& name) {
  std::ifstream f(std::string(TMCL_GOLDEN_DIR) + "/debug/stepping/" + name + ".golden", std::ios::binary);
  std::stringstream text;
  text << f.rdbuf();
  const std::string all = text.str();
  const std::size_t from = all.find("--- stdout\n");
  CHECK(from != std::string::npos);
  return from == std::string::npos ? std::string() : all.substr(from + 11);
}

bool all_digits(const std::string& s) {
  return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}

// A stop line of the command line: "address 5 at interrupt.tmc:8, time 0.000100s", "Breakpoint
// 1, Count (address 11) at ...": after an optional "Breakpoint N, ", text that starts with none
// of '[', '(' and '#', then " at FILE:LINE, time S.UUUUUUs" (FILE without spaces). (Parsed by
// hand: std::regex trips GCC 12's -Wmaybe-uninitialized in the sanitizer build.)
bool stop_of(std::string l, Place& p) {
  if (l.rfind("Breakpoint ", 0) == 0) {
    const std::size_t comma = l.find(", ");
    if (comma == std::string::npos || !all_digits(l.substr(11, comma - 11))) return false;
    l.erase(0, comma + 2);
  }
  const std::size_t time = l.rfind(", time ");
  if (l.empty() || l[0] == '[' || l[0] == '(' || l[0] == '#' || time == std::string::npos || l.back() != 's') return false;
  const std::size_t at = l.rfind(" at ", time);
  if (at == std::string::npos || at == 0) return false;
  const std::string where = l.substr(at + 4, time - at - 4), seconds = l.substr(time + 7, l.size() - time - 8);
  const std::size_t colon = where.rfind(':'), dot = seconds.find('.');
  if (where.find(' ') != std::string::npos || colon == std::string::npos || colon == 0 || dot == std::string::npos) return false;
  const std::string line = where.substr(colon + 1), whole = seconds.substr(0, dot), micro = seconds.substr(dot + 1);
  if (!all_digits(line) || !all_digits(whole) || !all_digits(micro) || micro.size() != 6) return false;
  p = {std::stoll(line), std::to_string(std::stoll(whole) * 1000000 + std::stoll(micro))};
  return true;
}

std::vector<Place> cli_golden_stops(const std::string& name) {
  std::vector<Place> out;
  std::istringstream lines(golden_stdout(name));
  for (std::string l; std::getline(lines, l);)
    if (Place p; stop_of(l, p)) out.push_back(p);
  return out;
}

std::vector<Place> dap_golden_stops(const std::string& name) {
  Session s = parse_session(golden_stdout(name));
  std::vector<Place> out;
  for (std::size_t i = 0; i < s.messages.size(); ++i) {
    const Value& m = s.messages[i];
    if (m["type"].as_string() != "response" || m["command"].as_string() != "stackTrace") continue;
    const Value& next = i + 1 < s.messages.size() ? s.messages[i + 1] : m;
    CHECK(next["command"].as_string() == "evaluate");  // the time, right after
    out.push_back({m["body"]["stackFrames"].at(0)["line"].as_int(), next["body"]["result"].as_string()});
  }
  return out;
}

bool in_order_within(const std::vector<Place>& part, const std::vector<Place>& whole) {
  std::size_t at = 0;
  for (const auto& p : part) {
    while (at < whole.size() && !(whole[at] == p)) ++at;
    if (at++ >= whole.size()) return false;
  }
  return true;
}

}  // namespace

TEST(dap_stepping_goldens_stop_where_the_command_line_goldens_stop) {
  const struct {
    const char* name;
    std::size_t stops;  // at least this many in the DAP transcript
    bool same;          // the command line makes exactly these stops
  } kPairs[] = {{"step-wait", 11, true}, {"breakpoint-once", 7, false}, {"step-interrupt", 15, true}};
  for (const auto& pair : kPairs) {
    const std::vector<Place> cli = cli_golden_stops(pair.name), dap = dap_golden_stops(std::string(pair.name) + "-dap");
    CHECK(dap.size() >= pair.stops);
    if (pair.same) CHECK_EQ(text_of(dap), text_of(cli));
    if (!in_order_within(dap, cli)) CHECK_EQ(text_of(dap), text_of(cli));
  }
}
