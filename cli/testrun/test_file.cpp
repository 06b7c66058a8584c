// Reading a test file (format in tmcl/testrun.hpp, docs/testing.md). Every line is checked and
// every error collected with its column, like the assembler's: a misspelt directive, kind of
// expectation or module gets a "did you mean". Scenario lines go to the scenario reader itself
// (tmcl/scenario.hpp), so a test file accepts exactly what a --scenario file does. Expressions
// need the program's labels, so bind_expectations parses them once the program is loaded.
#include <algorithm>
#include <cctype>
#include <filesystem>

#include "tmcl/duration.hpp"
#include "tmcl/fileio.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/numbers.hpp"
#include "tmcl/profile.hpp"
#include "tmcl/scenario.hpp"
#include "tmcl/targets.hpp"
#include "tmcl/testrun.hpp"
#include "tmcl/os_files.hpp"

namespace tmcl::testrun {

std::string_view compare_text(Compare c) {
  static constexpr std::string_view kText[] = {"=", "!=", "<", "<=", ">", ">="};
  return kText[static_cast<int>(c)];
}

std::string_view end_name(End e) {
  static constexpr std::string_view kNames[] = {"stop", "fault", "max-time", "blocked"};
  return kNames[static_cast<int>(e)];
}

namespace {

constexpr std::string_view kDirectives[] = {"program", "target", "motion",   "instr-time", "max-time", "define",
                                            "skip",    "at",     "switch", "hardstop",   "load",     "expect"};
constexpr std::string_view kExpectForms[] = {"at", "never", "no", "stall"};
constexpr std::string_view kTolerance = "\xC2\xB1";  // ±

std::string hint_of(std::string_view word, const std::vector<std::string_view>& names) {
  std::string hint = closest_match(word, names);
  return hint.empty() ? std::string() : "; did you mean '" + hint + "'?";
}

bool blank(char c) { return c == ' ' || c == '\t'; }

// The column just after the last word of `line`, where a missing word would go.
int end_col(const std::string& line) { return static_cast<int>(line.find_last_not_of(" \t")) + 2; }

// The text of `line` from column `col` (1-based) on, without the blanks around it, and the
// column where that text starts.
std::string rest_of(const std::string& line, int col, int& start) {
  std::size_t b = static_cast<std::size_t>(col - 1);
  while (b < line.size() && blank(line[b])) ++b;
  std::size_t e = line.size();
  while (e > b && blank(line[e - 1])) --e;
  start = static_cast<int>(b) + 1;
  return line.substr(b, e - b);
}

class LineReader {
 public:
  LineReader(const std::string& path, TestFile& out, std::vector<FileDiag>& diags) : path_(path), t_(out), diags_(diags) {}

  void error(int col, int len, const std::string& msg) {
    diags_.push_back({path_, line_no_, col, std::max(1, len), msg, source_});
  }
  void error_at(const LineWord& w, const std::string& msg) { error(w.col, static_cast<int>(w.text.size()), msg); }

  // One line: `line` without its comment, `source` as written.
  void read(int line_no, const std::string& source, const std::string& line) {
    line_no_ = line_no;
    source_ = source;
    std::vector<LineWord> w = split_words(line);
    if (w.empty()) return;
    const std::string& d = w[0].text;
    if (is_scenario_line(d)) return;  // a scenario line (timed, a switch, hard stop or load at positions): the scenario reader's
    if (d == "expect") return expect(line, w);
    if (d == "skip") {
      int start = 0;
      t_.skipped = true;
      t_.skip = w.size() > 1 ? rest_of(line, w[1].col, start) : std::string("skipped in the test file");
      return;
    }
    bool known = false;
    for (auto k : kDirectives) known = known || d == k;
    if (!known) {
      std::vector<std::string_view> names(std::begin(kDirectives), std::end(kDirectives));
      return error_at(w[0], "unknown line '" + d + "' (program, target, motion, instr-time, max-time, define, skip, " +
                                "at, switch, hardstop, load, expect)" + hint_of(d, names));
    }
    if (w.size() < 2) return error(end_col(line), 1, "'" + d + "' needs a value");
    int start = 0;
    std::string value = rest_of(line, w[1].col, start);
    if (d == "define") {
      auto eq = value.find('=');
      if (eq == std::string::npos || eq == 0)
        return error(start, static_cast<int>(value.size()), "expected 'define NAME=VALUE', as tmclasm's -D");
      t_.defines.push_back({value.substr(0, eq), value.substr(eq + 1), line_no, start + static_cast<int>(eq) + 1});
      return;
    }
    if (!once(d)) return;
    if (d == "program") {
      t_.program = value;
      t_.program_line = line_no;
      program_col_ = start;
      program_len_ = static_cast<int>(value.size());
      program_source_ = source;
    } else if (d == "target" || d == "motion") {
      if (w.size() > 2) return error_at(w[2], "unexpected '" + w[2].text + "' after the " + d + " name");
      if (d == "target") {
        t_.target = w[1].text;
        t_.target_line = line_no;
        target_word_ = w[1];
        target_source_ = source;
      } else {
        std::vector<std::string> cores = motion_core_names();
        std::vector<std::string_view> names(cores.begin(), cores.end());
        if (std::find(cores.begin(), cores.end(), w[1].text) == cores.end()) {
          std::string list;
          for (const auto& c : cores) list += (list.empty() ? "" : ", ") + c;
          return error_at(w[1], "unknown motion core '" + w[1].text + "' (" + list + ")" + hint_of(w[1].text, names));
        }
        t_.motion = w[1].text;
      }
    } else {  // instr-time, max-time
      if (w.size() > 2) return error_at(w[2], "unexpected '" + w[2].text + "' after the duration");
      std::string why;
      auto t = parse_duration(w[1].text, why);
      if (!t) return error_at(w[1], "bad duration: " + why);
      if (d == "max-time" && *t <= 0) return error_at(w[1], "max-time must be greater than 0");
      if (d == "instr-time") {
        t_.instr_time = *t;
      } else {
        t_.max_time = *t;
        t_.max_time_given = true;
      }
    }
  }

  // The motor of each stall expectation, where it was written: checked against the module.
  struct StallMotor {
    LineWord word;
    int line;
    std::string source;
  };
  const std::vector<StallMotor>& stall_motors() const { return stall_motors_; }

  // After the last line: the program and the module (TestFile::module), which are the file's
  // `program` and `target` lines, or, without a `target` line, the module a plain tmclrun would
  // take for the program. Returns the module's profile, or null.
  const Profile* finish(const std::string& default_target, bool target_given) {
    if (t_.program.empty() && !t_.skipped)
      diags_.push_back({path_, 1, 0, 1, "no 'program' line: a test names the program it runs (program FILE)", ""});
    // The program is found relative to the test file ("tests/../prog.tmc" is "prog.tmc").
    if (!t_.program.empty() && !os::is_absolute(t_.program)) {
      const auto slash = os::last_separator(path_);
      if (slash != std::string::npos)
        t_.program = std::filesystem::path(path_.substr(0, slash + 1) + t_.program).lexically_normal().generic_string();
    }
    std::string why;
    if (!t_.target.empty()) {  // a profile file is found relative to the test file, as the program
      t_.module = t_.target;
      const std::size_t slash = os::last_separator(path_);
      if (is_profile_path(t_.module) && !os::is_absolute(t_.module) && slash != std::string::npos)
        t_.module = path_.substr(0, slash + 1) + t_.module;
      const Profile* p = test_profile(t_, &why);
      if (!p) diags_.push_back({path_, t_.target_line, target_word_.col, static_cast<int>(target_word_.text.size()), why, target_source_});
      return p;
    }
    // tmclrun's rule, with tmclrun's own function: -t, else the program's first line, else -t's default.
    t_.module = target_given || t_.program.empty() ? default_target : target_named_by_file(t_.program, default_target);
    if (const Profile* p = test_profile(t_, &why)) return p;
    if (t_.module != default_target)  // named by the program: shown at the `program` line
      diags_.push_back({path_, t_.program_line, program_col_, program_len_,
                        "the program's first line names the target '" + t_.module + "': " + why, program_source_});
    else
      diags_.push_back({path_, 1, 0, 1, why, ""});
    return nullptr;
  }

 private:
  // A directive that may appear once; false after reporting a second one.
  bool once(const std::string& d) {
    for (const auto& [name, line] : seen_)
      if (name == d) {
        error(1, static_cast<int>(d.size()), "a second '" + d + "' line (the first is line " + std::to_string(line) + ")");
        return false;
      }
    seen_.emplace_back(d, line_no_);
    return true;
  }

  void expect(const std::string& line, const std::vector<LineWord>& w) {
    if (w.size() < 2) return error(end_col(line), 1, "expected 'expect at TIME ...', 'expect at end ...', 'expect never fault', 'expect no warnings' or 'expect no notes'");
    Expectation e;
    e.line = line_no_;
    e.col = w[1].col;
    int start = 0;
    e.text = rest_of(line, w[1].col, start);
    const std::string& form = w[1].text;
    if (form == "stall" || (form == "never" && w.size() > 2 && w[2].text == "stall")) return stall(line, w, std::move(e));
    if (form == "never" || form == "no") {
      // `no notes`: the run says nothing it does not simulate (docs/testing.md; issue 41).
      const std::string want = form == "never" ? "fault" : w.size() >= 3 && w[2].text == "notes" ? "notes" : "warnings";
      if (w.size() < 3 || w[2].text != want) {
        const std::string expected = form == "never" ? "'never fault'" : "'no warnings' or 'no notes'";
        if (w.size() < 3) return error(end_col(line), 1, "expected " + expected);
        const std::vector<std::string_view> words =
            form == "never" ? std::vector<std::string_view>{"fault"} : std::vector<std::string_view>{"warnings", "notes"};
        return error_at(w[2], "expected " + expected + ", found '" + w[2].text + "'" + hint_of(w[2].text, words));
      }
      if (w.size() > 3) return error_at(w[3], "unexpected '" + w[3].text + "' after '" + form + " " + want + "'");
      e.kind = form == "never" ? Expectation::NeverFault : want == "notes" ? Expectation::NoNotes : Expectation::NoWarnings;
      t_.expects.push_back(std::move(e));
      return;
    }
    if (form != "at") {
      std::vector<std::string_view> names(std::begin(kExpectForms), std::end(kExpectForms));
      return error_at(w[1], "unknown expectation '" + form + "' (at TIME, at end, never fault, no warnings, no notes, stall MOTOR at TIME, never stall MOTOR)" + hint_of(form, names));
    }
    if (w.size() < 3) return error(end_col(line), 1, "'expect at' needs an instant (1.5s) or 'end'");
    int cond_col = 0;
    e.when = w[2].text;
    if (w[2].text == "end") {
      e.kind = Expectation::AtEnd;
    } else {
      std::string why;
      auto t = parse_duration(w[2].text, why);
      if (!t) {
        std::string hint = closest_match(w[2].text, {"end"}).empty() ? "" : "; did you mean 'end'?";
        return error_at(w[2], "bad instant '" + w[2].text + "': " + why + " (or 'end')" + hint);
      }
      e.at = *t;
    }
    if (w.size() < 4) return error(end_col(line), 1, "expected a condition after '" + w[2].text + "' (e.g. v[3] = 7)");
    std::string cond = rest_of(line, w[3].col, cond_col);
    if (e.kind == Expectation::AtEnd && w[3].text == "halted" && !has_comparison(cond)) {
      if (w.size() < 5) return error(end_col(line), 1, "'halted' needs how the run ended: stop, fault, max-time or blocked");
      if (w.size() > 5) return error_at(w[5], "unexpected '" + w[5].text + "' after '" + w[4].text + "'");
      std::vector<std::string_view> names;
      for (int i = 0; i < 4; ++i) names.push_back(end_name(static_cast<End>(i)));
      for (int i = 0; i < 4; ++i)
        if (w[4].text == names[static_cast<std::size_t>(i)]) {
          e.kind = Expectation::Halted;
          e.halted = static_cast<End>(i);
          e.right = w[4].text;
          e.right_col = w[4].col;
          t_.expects.push_back(std::move(e));
          return;
        }
      return error_at(w[4], "unknown end '" + w[4].text + "' (stop, fault, max-time, blocked)" + hint_of(w[4].text, names));
    }
    if (condition(cond, cond_col, e)) t_.expects.push_back(std::move(e));
  }

  // `expect stall MOTOR at TIME [± TOLERANCE]` and `expect never stall MOTOR`: the stall event
  // of a motor (stop on stall), at an instant or never. The motor is checked against the module.
  void stall(const std::string& line, const std::vector<LineWord>& w, Expectation e) {
    const bool never = w[1].text == "never";
    const std::size_t m = never ? 3 : 2;  // the motor's word
    static const char* kShape = "expected 'stall MOTOR at TIME' (± TOLERANCE) or 'never stall MOTOR'";
    if (w.size() <= m) return error(end_col(line), 1, std::string(kShape) + ": the motor is missing");
    std::int64_t motor = 0;
    if (!parse_int(w[m].text, 0, 255, motor)) return error_at(w[m], "bad motor number '" + w[m].text + "' (0..255)");
    e.motor = static_cast<int>(motor);
    const StallMotor named{w[m], line_no_, source_};
    if (never) {
      if (w.size() > 4) return error_at(w[4], "unexpected '" + w[4].text + "' after the motor");
      e.kind = Expectation::NeverStall;
      stall_motors_.push_back(named);
      t_.expects.push_back(std::move(e));
      return;
    }
    if (w.size() < 5 || w[3].text != "at") {
      if (w.size() < 4) return error(end_col(line), 1, std::string(kShape) + ": 'at TIME' is missing");
      return error_at(w[3], std::string(kShape) + ": 'at' expected here");
    }
    std::string why;
    auto t = parse_duration(w[4].text, why);
    if (!t) return error_at(w[4], "bad instant '" + w[4].text + "': " + why);
    e.kind = Expectation::Stall;
    e.at = *t;
    e.when = e.right = w[4].text;
    e.right_col = w[4].col;
    if (w.size() > 5) {
      if (w[5].text != kTolerance && w[5].text != "+/-")
        return error_at(w[5], "unexpected '" + w[5].text + "' after the instant (a tolerance is '± DURATION')");
      if (w.size() < 7) return error(end_col(line), 1, "a tolerance is missing after '" + w[5].text + "'");
      if (w.size() > 7) return error_at(w[7], "unexpected '" + w[7].text + "' after the tolerance");
      auto tol = parse_duration(w[6].text, why);
      if (!tol) return error_at(w[6], "bad tolerance '" + w[6].text + "': " + why);
      e.within = *tol;
      e.tolerance = w[6].text;
      e.tolerance_col = w[6].col;
    }
    stall_motors_.push_back(named);
    t_.expects.push_back(std::move(e));
  }

  struct Op {
    std::size_t at, len;
    Compare c;
  };
  // The comparisons outside parentheses and brackets (<< and >> are shifts, not comparisons).
  static std::vector<Op> comparisons(const std::string& s) {
    std::vector<Op> ops;
    int depth = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const char c = s[i], n = i + 1 < s.size() ? s[i + 1] : '\0';
      if (c == '(' || c == '[') ++depth;
      else if (c == ')' || c == ']') --depth;
      if (depth != 0) continue;
      if ((c == '<' || c == '>') && n == c) {
        ++i;
      } else if (c == '=') {
        ops.push_back({i, n == '=' ? 2u : 1u, Compare::Eq});
        if (n == '=') ++i;
      } else if (c == '!' && n == '=') {
        ops.push_back({i++, 2, Compare::Ne});
      } else if (c == '<' || c == '>') {
        const bool eq = n == '=';
        ops.push_back({i, eq ? 2u : 1u, c == '<' ? (eq ? Compare::Le : Compare::Lt) : (eq ? Compare::Ge : Compare::Gt)});
        if (eq) ++i;
      }
    }
    return ops;
  }
  static bool has_comparison(const std::string& s) { return !comparisons(s).empty(); }

  // LEFT OP RIGHT [± TOLERANCE] starting at column `col`.
  bool condition(const std::string& s, int col, Expectation& e) {
    std::vector<Op> ops = comparisons(s);
    if (ops.empty()) {
      error(col, static_cast<int>(s.size()), "expected a comparison: EXPRESSION = VALUE (or !=, <, <=, >, >=)");
      return false;
    }
    if (ops.size() > 1 && ops[0].len == 1 && ops[1].at == ops[0].at + 1 && ops[1].len == 1 && ops[0].c == Compare::Eq) {
      const std::string wrote = s.substr(ops[0].at, 2), meant = std::string(1, wrote[1]) + "=";
      error(col + static_cast<int>(ops[0].at), 2, "'" + wrote + "' is not a comparison; did you mean '" + meant + "'?");
      return false;
    }
    if (ops.size() > 1) {
      error(col + static_cast<int>(ops[1].at), static_cast<int>(ops[1].len),
            "a second comparison (an expectation compares once; parentheses make a comparison a value)");
      return false;
    }
    const Op op = ops[0];
    e.op = op.c;
    auto side = [&](std::size_t from, std::size_t to, std::string& text, int& text_col) {
      std::size_t b = from, end = to;
      while (b < end && blank(s[b])) ++b;
      while (end > b && blank(s[end - 1])) --end;
      text = s.substr(b, end - b);
      text_col = col + static_cast<int>(b);
    };
    side(0, op.at, e.left, e.left_col);
    if (e.left.empty()) {
      error(col + static_cast<int>(op.at), static_cast<int>(op.len), "nothing before '" + s.substr(op.at, op.len) + "'");
      return false;
    }
    std::size_t right_end = s.size(), tol = std::string::npos, tol_len = 0;
    for (std::string_view mark : {kTolerance, std::string_view("+/-")}) {
      auto p = s.find(mark, op.at + op.len);
      if (p != std::string::npos && p < tol) {
        tol = p;
        tol_len = mark.size();
      }
    }
    if (tol != std::string::npos) {
      right_end = tol;
      if (e.op != Compare::Eq) {
        error(col + static_cast<int>(tol), static_cast<int>(tol_len), "a tolerance goes only with '=' (VALUE ± TOLERANCE)");
        return false;
      }
      side(tol + tol_len, s.size(), e.tolerance, e.tolerance_col);
      if (e.tolerance.empty()) {
        error(col + static_cast<int>(tol), static_cast<int>(tol_len), "a tolerance is missing after '" + s.substr(tol, tol_len) + "'");
        return false;
      }
    }
    side(op.at + op.len, right_end, e.right, e.right_col);
    if (e.right.empty()) {
      error(col + static_cast<int>(op.at), static_cast<int>(op.len), "no value after '" + s.substr(op.at, op.len) + "'");
      return false;
    }
    return true;
  }

  const std::string& path_;
  TestFile& t_;
  std::vector<FileDiag>& diags_;
  int line_no_ = 0;
  std::string source_;
  LineWord target_word_{"", 0};
  std::string target_source_;
  int program_col_ = 0, program_len_ = 0;
  std::string program_source_;
  std::vector<std::pair<std::string, int>> seen_;
  std::vector<StallMotor> stall_motors_;
};

}  // namespace

const Profile* test_profile(const TestFile& test, std::string* error) {
  const TargetResult r = resolve_target(test.module);
  if (!r.profile && error) *error = r.diags.empty() ? r.error : r.message(0);
  return r.profile;
}

bool parse_test_file(const std::string& text, const std::string& path, const std::string& default_target,
                     TestFile& out, std::vector<FileDiag>& diags, bool target_given) {
  out = TestFile{};
  out.path = path;
  const std::size_t before = diags.size();
  std::vector<FileDiag> mine;
  LineReader reader(path, out, mine);
  std::string scenario;  // the scenario lines in their places, every other line empty
  out.lines = split_lines(text);
  for (std::size_t i = 0; i < out.lines.size(); ++i) {
    std::string line = out.lines[i];
    if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::vector<LineWord> w = split_words(line);
    scenario += (!w.empty() && is_scenario_line(w[0].text) ? out.lines[i] : std::string()) + "\n";
    reader.read(static_cast<int>(i) + 1, out.lines[i], line);
  }
  const Profile* profile = reader.finish(default_target, target_given);
  if (profile)  // a stall expectation's motor must be one the module has, as a scenario line's
    for (const auto& named : reader.stall_motors()) {
      std::int64_t m = 0;
      (void)parse_int(named.word.text, 0, 255, m);
      if (m >= profile->motors)
        mine.push_back({path, named.line, named.word.col, static_cast<int>(named.word.text.size()),
                        std::string(profile->name) + " has no motor " + named.word.text + " (0.." +
                            std::to_string(profile->motors - 1) + ")",
                        named.source});
    }
  ScenarioOptions sopts;
  sopts.motors = profile ? profile->motors : 256;
  sopts.profile = profile;
  sopts.module = profile ? std::string(profile->name) : std::string();
  if (profile) {  // the core the file names, else the module's (a --motion given at run time: the VM refuses)
    auto core = out.motion.empty() ? make_profile_motion_core(*profile) : make_motion_core(out.motion);
    if (core && !core->models_encoder(*profile)) sopts.no_encoder = std::string(core->name());
  }
  sopts.error_limit = 0;
  parse_scenario(scenario, path, out.inputs, mine, sopts);
  std::stable_sort(mine.begin(), mine.end(),
                   [](const FileDiag& a, const FileDiag& b) { return a.line != b.line ? a.line < b.line : a.col < b.col; });
  diags.insert(diags.end(), mine.begin(), mine.end());
  return diags.size() == before;
}

namespace {

// Reads nothing: evaluating a constant index (v[3], position 2, ap(4, 1 + 1)) fails at any read.
class NoReads : public ExprReader {
 public:
  int motors() const override { return 256; }
  bool reg(Reg, std::int64_t&, std::string&) override { return false; }
  bool var(int, std::int64_t&, std::string&) override { return false; }
  bool axis(int, int, std::int64_t&, std::string&) override { return false; }
  bool global(int, int, std::int64_t&, std::string&) override { return false; }
  bool port(int, int, std::int64_t&, std::string&) override { return false; }
};

// A motor or user variable the module lacks, named by a constant, is a mistake in the file, as a
// switch on a missing motor is: the first such index of `expr`, as an error at its place.
bool index_in_range(const Expr& expr, const Profile& profile, const std::string& path, int line, int col,
                    const std::string& source, std::vector<FileDiag>& diags) {
  auto constant = [&](int i, std::int64_t& v) {
    if (i < 0) return false;
    Expr sub = expr;
    sub.root = i;
    NoReads none;
    std::string ignored;
    return eval_expr(sub, none, v, ignored);
  };
  for (const Expr::Node& n : expr.nodes) {
    const bool var = n.kind == Expr::Node::Var, axis = n.kind == Expr::Node::Ap;
    if (!var && !axis) continue;
    const int index = var ? n.a : n.b;
    const std::int64_t limit = var ? profile.user_vars : profile.motors;
    std::int64_t v = 0;
    if (!constant(index, v) || (v >= 0 && v < limit)) continue;
    const Expr::Node& at = expr.nodes[static_cast<std::size_t>(index)];
    diags.push_back({path, line, col + static_cast<int>(at.at), std::max(1, static_cast<int>(at.len)),
                     std::string(profile.name) + " has no " + (var ? "user variable " : "motor ") + std::to_string(v) +
                         " (0.." + std::to_string(limit - 1) + ")",
                     source});
    return false;
  }
  return true;
}

// Parses each expression of each expectation against `info` into `bound` (the expectations of
// `test`, or null), with a diagnostic for the first one of an expectation that does not parse.
// `any_name` (no program at hand, `info` empty): every name is taken for one the program has.
void parse_expectations(const TestFile& test, const ProgramInfo& program, std::vector<Expectation>* bound, bool any_name,
                        std::vector<FileDiag>& diags) {
  ProgramInfo names;  // any_name: the names met so far
  const ProgramInfo& info = any_name ? names : program;
  const Profile* profile = test_profile(test, nullptr);
  for (std::size_t i = 0; i < test.expects.size(); ++i) {
    const Expectation& e = test.expects[i];
    if (e.kind != Expectation::At && e.kind != Expectation::AtEnd) continue;
    const std::string& source = test.lines[static_cast<std::size_t>(e.line - 1)];
    Expectation* out = bound ? &(*bound)[i] : nullptr;
    for (auto [text, col, which] : {std::tuple{&e.left, e.left_col, 0}, std::tuple{&e.right, e.right_col, 1},
                                    std::tuple{&e.tolerance, e.tolerance_col, 2}}) {
      if (text->empty()) continue;
      Expr scratch;
      Expr* expr = !out ? &scratch : which == 0 ? &out->left_expr : which == 1 ? &out->right_expr : &out->tolerance_expr;
      std::string error;
      std::size_t at = 0;
      bool ok = parse_expr(*text, info, *expr, error, &at);
      // Where the parser stopped at a name it does not know, the name becomes a known one (0)
      // and the parse goes on to the mistakes after it; each name once, so this ends.
      while (!ok && any_name && at < text->size() && (std::isalpha(static_cast<unsigned char>((*text)[at])) || (*text)[at] == '_')) {
        std::size_t end = at;
        while (end < text->size() && (std::isalnum(static_cast<unsigned char>((*text)[end])) || (*text)[end] == '_')) ++end;
        const std::string name = text->substr(at, end - at);
        if (info.symbol(name)) break;
        names.constants.emplace_back(name, 0);
        ok = parse_expr(*text, info, *expr, error, &at);
      }
      if (ok) {
        if (profile && !index_in_range(*expr, *profile, test.path, e.line, col, source, diags)) break;
        continue;
      }
      // The parser's message ends with " in 'TEXT'"; the caret shows where instead.
      if (auto in = error.rfind(" in '"); in != std::string::npos) error.resize(in);
      // Underline the word (or the character) where the parser stopped; a register's with its $.
      std::size_t end = at < text->size() && (*text)[at] == '$' ? at + 1 : at;
      while (end < text->size() && (std::isalnum(static_cast<unsigned char>((*text)[end])) || (*text)[end] == '_')) ++end;
      diags.push_back({test.path, e.line, col + static_cast<int>(at), std::max<int>(1, static_cast<int>(end - at)), error, source});
      break;
    }
  }
}

}  // namespace

bool bind_expectations(TestFile& test, const ProgramInfo& info, std::vector<FileDiag>& diags) {
  const std::size_t before = diags.size();
  parse_expectations(test, info, &test.expects, false, diags);
  return diags.size() == before;
}

bool check_expectations(const TestFile& test, std::vector<FileDiag>& diags) {
  const std::size_t before = diags.size();
  parse_expectations(test, ProgramInfo{}, nullptr, true, diags);
  return diags.size() == before;
}

}  // namespace tmcl::testrun
