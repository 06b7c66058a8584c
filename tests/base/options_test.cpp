// Unit tests of the tools' option parser (tmcl/options.hpp): every form of an option and its
// value, operands anywhere, the errors (unknown with did-you-mean, missing value, a value for a
// flag, a handler's), the generated --help layout, --list-options, and shell completion.
#include "check.hpp"
#include "tmcl/options.hpp"

using tmcl::cli::Option;
using tmcl::cli::Result;
using tmcl::cli::Tool;
using tmcl::cli::Values;

namespace {

// A small tool with every kind of option, recording what its handlers saw.
struct Seen {
  std::vector<std::string> log;
};

Tool sample(Seen& seen) {
  auto record = [&seen](std::string what) {
    return [&seen, what](const std::string& v) {
      seen.log.push_back(what + "=" + v);
      return std::string();
    };
  };
  Tool t;
  t.name = "sample";
  t.usage = "usage: sample [options] FILE...\n\noptions:\n";
  t.epilogue = "\nexit status: 0\n";
  t.column = 21;
  t.options = {
      {"-o", "FILE", "output file; -o - writes to standard output\n(default: beside the input)", record("o"),
       Values::files({"bin"}), "a file name"},
      {"-f, --format", "FMT", "bin (default)\nlisting", record("format"), Values::words({"bin", "listing"})},
      {"--trace", "", "a line per step", record("trace")},
      {"--checkpoint-memory", "MIB", "memory for reverse execution", record("mib")},
      {"-I", "DIR", "search DIR", record("I"), Values::dirs()},
      {"-Werror", "", "", record("Werror")},
      {"-Werror=", "NAME", "warnings are errors", record("Werror="), Values::words({"unreachable"})},
      {"-Wno-", "NAME", "do not report the warning NAME", record("Wno"), Values::words({"unreachable", "reti"})},
      {"-W", "NAME", "", record("W"), Values::words({"unreachable", "reti"}), {}, true},
      {"--secret", "", "", record("secret"), {}, {}, true},
      {"--bad", "N", "always refused", [](const std::string& v) { return "bad value '" + v + "'"; }, {}, {}, false,
       "group:"},
      {"--also", "", "in the group too", record("also"), {}, {}, false, "group:"},
      {"--other", "FILE", "in another group", record("other"), {}, {}, false, "grp2:"},
  };
  t.operands = [](const std::vector<std::string>& before, const std::vector<std::string>& given) {
    if (!given.empty() && given.back() == "--secret") return Values::dirs();
    return before.empty() ? Values::words({"send", "get"}) : Values::files({"tmc"});
  };
  return t;
}

Result run(const std::vector<std::string>& args, Seen& seen) { return tmcl::cli::parse(sample(seen), args); }

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : " ") + x;
  return s;
}

}  // namespace

TEST(every_form_of_a_value) {
  Seen seen;
  Result r = run({"-o", "a.bin", "-ob.bin", "--format=listing", "--format", "bin", "-flisting", "-f", "bin",
                  "--checkpoint-memory=8", "--checkpoint-memory", "9", "-I", "inc", "-Iinc2"},
                 seen);
  CHECK(r.status == Result::Status::Run);
  CHECK_EQ(joined(seen.log),
           "o=a.bin o=b.bin format=listing format=bin format=listing format=bin mib=8 mib=9 I=inc I=inc2");
  CHECK_EQ(joined(r.given), "-o -o --format --format --format --format --checkpoint-memory --checkpoint-memory -I -I");
  CHECK(r.has("--format"));
  CHECK(!r.has("--trace"));
}

TEST(prefixes_and_flags) {
  Seen seen;
  Result r = run({"-Werror", "-Werror=reti", "-Wno-unreachable", "-Wreti", "--trace", "--secret"}, seen);
  CHECK(r.status == Result::Status::Run);
  CHECK_EQ(joined(seen.log), "Werror= Werror==reti Wno=unreachable W=reti trace= secret=");
}

TEST(operands_anywhere) {
  Seen seen;
  Result r = run({"a.tmc", "--trace", "-", "-5", "b.tmc", "--", "--trace", "-o"}, seen);
  CHECK(r.status == Result::Status::Run);
  CHECK_EQ(joined(r.operands), "a.tmc - -5 b.tmc --trace -o");
  CHECK_EQ(joined(seen.log), "trace=");
  // A value may start with a dash ("-o -" is standard output).
  Seen s2;
  r = run({"-o", "-", "--format", "-x"}, s2);
  CHECK_EQ(joined(s2.log), "o=- format=-x");
}

TEST(unknown_option_with_a_guess) {
  Seen seen;
  Result r = run({"a.tmc", "--fromat", "bin"}, seen);
  CHECK(r.status == Result::Status::Error);
  CHECK_EQ(r.error, "unknown option '--fromat' (did you mean '--format'?)");
  CHECK_EQ(run({"--tarce"}, seen).error, "unknown option '--tarce' (did you mean '--trace'?)");
  CHECK_EQ(run({"--fromat=listing"}, seen).error, "unknown option '--fromat' (did you mean '--format'?)");
  CHECK_EQ(run({"--frobnicate"}, seen).error, "unknown option '--frobnicate'");
  CHECK_EQ(run({"-x"}, seen).error, "unknown option '-x'");
  // Hidden options are not guessed.
  CHECK_EQ(run({"--secrte"}, seen).error, "unknown option '--secrte'");
}

TEST(missing_and_unwanted_values) {
  Seen seen;
  CHECK_EQ(run({"-o"}, seen).error, "-o needs a file name");  // the table's wording
  CHECK_EQ(run({"a.tmc", "--format"}, seen).error, "--format needs FMT");
  CHECK_EQ(run({"-f"}, seen).error, "-f needs FMT");
  CHECK_EQ(run({"-I"}, seen).error, "-I needs a folder");
  CHECK_EQ(run({"--trace=1"}, seen).error, "--trace takes no value");
  CHECK(seen.log.empty());
}

TEST(a_handler_error_stops_the_parse) {
  Seen seen;
  Result r = run({"--trace", "--bad", "7", "--secret"}, seen);
  CHECK(r.status == Result::Status::Error);
  CHECK_EQ(r.error, "bad value '7'");
  CHECK_EQ(joined(seen.log), "trace=");
}

TEST(help_is_generated_from_the_table) {
  Seen seen;
  CHECK_EQ(tmcl::cli::help_text(sample(seen)),
           "usage: sample [options] FILE...\n"
           "\n"
           "options:\n"
           "  -o FILE            output file; -o - writes to standard output\n"
           "                     (default: beside the input)\n"
           "  -f, --format FMT   bin (default)\n"
           "                     listing\n"
           "  --trace            a line per step\n"
           "  --checkpoint-memory MIB  memory for reverse execution\n"
           "  -I DIR             search DIR\n"
           "  -Werror, -Werror=NAME  warnings are errors\n"
           "  -Wno-NAME          do not report the warning NAME\n"
           "  group: --bad N     always refused\n"
           "         --also      in the group too\n"
           "  grp2:  --other FILE  in another group\n"
           "  --help             show this help\n"
           "  --version          show the version\n"
           "\n"
           "exit status: 0\n");
}

TEST(help_and_version_end_the_parse) {
  Seen seen;
  CHECK(run({"--trace", "--version", "--bogus"}, seen).status == Result::Status::Done);
  CHECK(run({"-h"}, seen).status == Result::Status::Done);
  CHECK_EQ(run({"--bogus", "--help"}, seen).error, "unknown option '--bogus'");
}

TEST(list_options) {
  Seen seen;
  CHECK_EQ(tmcl::cli::option_list(sample(seen)),
           "-o\tFILE\n-f, --format\tFMT\n--trace\t\n--checkpoint-memory\tMIB\n-I\tDIR\n-Werror\t\n-Werror=\tNAME\n"
           "-Wno-\tNAME\n--bad\tN\n--also\t\n--other\tFILE\n--help\t\n--version\t\n");
}

TEST(completion_of_names_and_values) {
  Seen seen;
  const Tool t = sample(seen);
  auto complete = [&t](std::vector<std::string> words) { return tmcl::cli::completion(t, words); };
  CHECK_EQ(complete({"--f"}), "words\n--format\n");
  CHECK_EQ(complete({"a.tmc", "--t"}), "words\n--trace\n");
  CHECK_EQ(complete({"-W"}), "words\n-Werror\n-Werror=\n-Wno-\n");
  CHECK_EQ(complete({"-Wno-"}), "words\n-Wno-unreachable\n-Wno-reti\n");
  CHECK_EQ(complete({"-Wno-r"}), "words\n-Wno-reti\n");
  CHECK_EQ(complete({"-Werror=u"}), "words\n-Werror=unreachable\n");
  CHECK_EQ(complete({"-Wr"}), "words\n-Wreti\n");  // the hidden -W's values, not its name
  CHECK_EQ(complete({"--format", "l"}), "words\nlisting\n");
  CHECK_EQ(complete({"-f", ""}), "words\nbin\nlisting\n");
  CHECK_EQ(complete({"--format=l"}), "words\n--format=listing\n");
  CHECK_EQ(complete({"-fl"}), "words\n-flisting\n");
  CHECK_EQ(complete({"-o", "x"}), "files bin\n");
  CHECK_EQ(complete({"-I", ""}), "dirs\n");
  CHECK_EQ(complete({"--checkpoint-memory", ""}), "words\n");  // a number: nothing to offer
  CHECK_EQ(complete({"--sec"}), "words\n");                     // hidden
  // Operands: the tool's hook, told the operands before (not option values).
  CHECK_EQ(complete({""}), "words\nsend\nget\n");
  CHECK_EQ(complete({"-o", "x.bin", "g"}), "words\nget\n");
  CHECK_EQ(complete({"port", "--trace", ""}), "files tmc\n");
  CHECK_EQ(complete({"port", "--secret", ""}), "dirs\n");  // the hook sees the options given
  CHECK_EQ(complete({"--", "--f"}), "words\n");  // an operand after "--", not an option
}

TEST(complete_as_a_hidden_option) {
  Seen seen;
  CHECK(run({"--complete", "--f"}, seen).status == Result::Status::Done);
  CHECK(run({"--list-options"}, seen).status == Result::Status::Done);
  CHECK(seen.log.empty());
}
