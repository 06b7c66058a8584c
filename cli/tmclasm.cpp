// tmclasm: the command-line assembler, linker and disassembler. Declares its options (one table,
// tmcl/options.hpp), calls the assembler library, writes the output. Exit status: 0 success, 65 errors in the input, 64 usage
// errors, 74 output not written.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <unistd.h>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "tmcl/analysis.hpp"
#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/disasm.hpp"
#include "tmcl/asm/format.hpp"
#include "tmcl/asm/object.hpp"
#include "tmcl/asm/output.hpp"
#include "tmcl/fileio.hpp"
#include "tmcl/numbers.hpp"
#include "tmcl/options.hpp"
#include "tmcl/os_console.hpp"
#include "tmcl/targets.hpp"
#include "tmcl/os_files.hpp"

namespace {

constexpr int kExitInput = 65;
constexpr int kExitUsage = 64;
constexpr int kExitOutput = 74;

const char* kUsage = R"(usage: tmclasm [options] FILE...        link sources, objects and libraries
       tmclasm -c [options] FILE.tmc...   assemble each source into an object (.o)
       tmclasm -f lib -o LIB.a FILE...    bundle objects (sources are assembled) into a library
       tmclasm -d [--symbols SYM] FILE    disassemble a .bin, datagrams or an object to source
       tmclasm --dump-object FILE         show an object or library as text
       tmclasm --fmt [-i | --check] FILE  lay a source out the canonical way (tmclasm.md)
FILE may be - for standard input.

Assembles TMCL sources (.tmc) and links them with objects (.o) and libraries (.a) into a program
image. Each FILE is its own unit: its labels and constants are private unless exported
(#export NAME) and imported elsewhere (#import NAME). Units are placed one after another from
address 0 in command-line order; of a library only the members that export a name some linked
unit imports are linked, at the library's place.

options:
)";

const char* kEpilogue = R"(
examples:
  tmclasm prog.tmc                       writes prog.bin
  tmclasm -t usb-2-sd -f listing -o - prog.tmc
  tmclasm -f datagrams --address 3 -o prog.dgm prog.tmc
  tmclasm -c homing.tmc jog.tmc          writes homing.o and jog.o
  tmclasm -f lib -o libmotion.a homing.o jog.o
  tmclasm --map prog.map -o prog.bin main.tmc libmotion.a
  tmclasm -d prog.bin -o prog.tmc        source that reassembles to the identical prog.bin

exit status: 0 success, 65 errors in the input, 64 usage error, 74 output (a file or standard
             output) could not be written

documentation: the .md files named above are in share/doc/tmcl/ of the installation
               (/usr/share/doc/tmcl/ from the Debian package); also man tmclasm
)";

// PATH with its extension (from the last dot of the file name on; none for a name that starts
// with its only dot, or for "." and "..") replaced by EXT, as std::filesystem::path's
// replace_extension does: "prog.tmc" -> "prog.bin", "dir.v2/prog" -> "dir.v2/prog.bin".
std::string with_extension(const std::string& path, const char* ext) {
  const std::size_t slash = tmcl::os::last_separator(path);
  const std::size_t name = slash == std::string::npos ? 0 : slash + 1;
  const std::size_t dot = path.rfind('.');
  const bool dots_only = path.compare(name, std::string::npos, ".") == 0 || path.compare(name, std::string::npos, "..") == 0;
  if (dot == std::string::npos || dot <= name || dots_only) return path + ext;
  return path.substr(0, dot) + ext;
}

int usage_error(const std::string& msg) {
  std::fprintf(stderr, "tmclasm: %s\n(see tmclasm --help)\n", msg.c_str());
  return kExitUsage;
}

int input_error(const std::string& msg) {
  std::fprintf(stderr, "%s\n", msg.c_str());
  return kExitInput;
}


void print_failure(int errors, int warnings) {
  std::fprintf(stderr, "tmclasm: %d error%s, %d warning%s; nothing written\n", errors, errors == 1 ? "" : "s",
               warnings, warnings == 1 ? "" : "s");
}

bool write_output(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::string err;
  if (tmcl::write_file_atomic(path, bytes, err)) return true;
  std::fprintf(stderr, "tmclasm: %s\n", err.c_str());
  return false;
}

std::vector<std::uint8_t> bytes_of(const std::string& s) { return {s.begin(), s.end()}; }

enum class Mode { Link, Compile, Library, Disassemble, Dump, Fmt, Analyze };

// What the control-flow analysis adds to a link: nothing but warnings, the dot graph or the
// stack report (which then replace the program as the output).
enum class Extra { None, Dot, StackUsage };

// Runs the analysis on a linked program, adding its warnings to result.diags; returns the text
// of the extra output.
std::string analyze_program(tmcl::AsmResult& result, Extra extra, bool targets_checked) {
  // The analysis builds its tables (regions, flows, the graph of regions: about 24 bytes per
  // instruction) partly in memory no earlier phase touched, and a page touched for the first time
  // costs more than the work done in it (docs/performance.md: 3 to 8 ms per MiB in 4 KiB pages, a
  // tenth of that in huge pages). So the heap's next memory is advised as huge pages first (main
  // keeps the heap from being trimmed or bypassed). Only on programs big enough to fill a few.
  if (const std::size_t bytes = result.program.size() * 32; bytes >= (8u << 20)) tmcl::prefer_huge_pages_for_next(bytes);
  tmcl::AnalysisInput in = tmcl::analysis_input(result, targets_checked);
  tmcl::AnalysisOptions o;
  o.graph = extra == Extra::Dot;
  tmcl::Analysis a = tmcl::analyze(in, result.diags, o);
  if (extra == Extra::Dot) return tmcl::cfg_dot(a, in);
  if (extra == Extra::StackUsage) return tmcl::stack_usage_report(a, in);
  return {};
}

// Reads the image or object FILE for -d and --analyze, and with --symbols FILE the label names
// into `names` (pointed to by `o.names`). 0, or the exit status after saying what went wrong.
int read_input_image(const std::string& file, const std::string& symbols_file, std::string& bytes,
                     tmcl::LabelNames& names, tmcl::DisasmOptions& o) {
  tmcl::DiskReader disk;
  if (!disk.read(file, bytes)) {
    std::fprintf(stderr, "tmclasm: error: cannot read '%s': %s\n", file.c_str(), disk.last_error().c_str());
    return kExitInput;
  }
  if (!symbols_file.empty()) {
    std::string error;
    if (!tmcl::load_symbols(symbols_file, "tmclasm", names, error)) {
      std::fprintf(stderr, "%s\n", error.c_str());
      return kExitInput;
    }
    o.names = &names;
  }
  return 0;
}

// --analyze: an image is disassembled (with --symbols' names) and the source assembled again
// (the same instructions, tmclasm -d guarantees it) so that every warning has a line to show.
int analyze_image(const std::string& file, tmcl::AsmOptions opts, const tmcl::DisasmOptions& dopts,
                  const std::string& symbols_file, Extra extra, const std::string& output) {
  std::string bytes;
  tmcl::LabelNames names;
  tmcl::DisasmOptions o = dopts;
  if (int status = read_input_image(file, symbols_file, bytes, names, o)) return status;
  std::string shown = file == "-" ? "<stdin>" : file;
  tmcl::DisasmResult d = tmcl::disassemble(file, bytes, o);
  int derrors = 0;
  for (const auto& m : d.messages) {
    std::fprintf(stderr, "%s: %s: %s\n", shown.c_str(), m.error ? "error" : "warning", m.text.c_str());
    derrors += m.error ? 1 : 0;
  }
  if (derrors > 0) {
    print_failure(derrors, 0);
    return kExitInput;
  }
  tmcl::MemoryReader mem;
  mem.files[shown] = d.source;
  opts.append_stop = false;  // the image as it is
  opts.symbols = true;
  tmcl::AsmResult result = tmcl::assemble({shown}, opts, mem);
  // A final STOP is most likely the one tmclasm and TMCL-IDE append: not reported unreachable.
  if (!result.program.empty() && result.program.back().op == static_cast<std::uint8_t>(tmcl::Op::STOP))
    result.appended_stop = true;
  result.diags.set_kind_limit(opts.error_limit);
  std::string text = result.ok() ? analyze_program(result, extra, true) : std::string();
  std::fputs(result.diags.render(result.sources, opts.error_limit).c_str(), stderr);
  if (!result.ok()) {
    print_failure(result.diags.error_count(), result.diags.warning_count());
    return kExitInput;
  }
  if (extra == Extra::None) return 0;
  return write_output(output, bytes_of(text)) ? 0 : kExitOutput;
}

// -d: one image or object in, source out.
int disassemble(const std::string& file, const std::string& output, const tmcl::DisasmOptions& options,
                const std::string& symbols_file) {
  std::string bytes;
  tmcl::LabelNames names;
  tmcl::DisasmOptions o = options;
  if (int status = read_input_image(file, symbols_file, bytes, names, o)) return status;
  tmcl::DisasmResult r = tmcl::disassemble(file, bytes, o);
  int errors = 0, warnings = 0;
  std::string shown = file == "-" ? "<stdin>" : file;
  for (const auto& m : r.messages) {
    std::fprintf(stderr, "%s: %s: %s%s\n", shown.c_str(), m.error ? "error" : "warning", m.text.c_str(),
                 m.error && options.warnings_are_errors && m.text.find("checksum") != std::string::npos ? " [-Werror]"
                                                                                                          : "");
    ++(m.error ? errors : warnings);
  }
  if (errors > 0) {
    print_failure(errors, warnings);
    return kExitInput;
  }
  return write_output(output, bytes_of(r.source)) ? 0 : kExitOutput;
}

int dump(const std::string& file, const std::string& output) {
  tmcl::DiskReader reader;
  std::string bytes, error, text;
  if (!reader.read(file, bytes)) {
    std::fprintf(stderr, "tmclasm: error: cannot read '%s': %s\n", file.c_str(), reader.last_error().c_str());
    return kExitInput;
  }
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
  std::string shown = file == "-" ? "<stdin>" : file;
  switch (tmcl::sniff_file(bytes)) {
    case tmcl::FileKind::Object: {
      tmcl::ObjectFile obj;
      if (!tmcl::read_object(data, bytes.size(), obj, error)) {
        std::fprintf(stderr, "%s: error: invalid object: %s\n", shown.c_str(), error.c_str());
        return kExitInput;
      }
      text = tmcl::dump_object(obj);
      break;
    }
    case tmcl::FileKind::Library: {
      tmcl::Library lib;
      if (!tmcl::read_library(data, bytes.size(), lib, error)) {
        std::fprintf(stderr, "%s: error: invalid library: %s\n", shown.c_str(), error.c_str());
        return kExitInput;
      }
      text = tmcl::dump_library(lib);
      break;
    }
    case tmcl::FileKind::Source:
      std::fprintf(stderr, "%s: error: not an object or library (no tmcl object magic)\n", shown.c_str());
      return kExitInput;
  }
  return write_output(output, bytes_of(text)) ? 0 : kExitOutput;
}

// --fmt: each source formatted (format.hpp) to `output`, in place, or only checked.
int format_sources(const std::vector<std::string>& files, bool in_place, bool check, const std::string& output) {
  int status = 0;
  for (const auto& file : files) {
    std::string text;
    tmcl::DiskReader reader;
    if (!reader.read(file, text)) {
      std::fprintf(stderr, "tmclasm: error: %s: %s\n", file.c_str(), reader.last_error().c_str());
      status = kExitInput;
      continue;
    }
    tmcl::FormatResult r = tmcl::format_source(text);
    if (!r.ok) {
      std::fprintf(stderr, "%s:%s (not formatted)\n", file.c_str(), r.error.c_str());
      status = kExitInput;
      continue;
    }
    if (check) {
      if (r.text != text) {
        std::fprintf(stderr, "%s: not in the canonical layout (tmclasm --fmt -i %s)\n", file.c_str(), file.c_str());
        status = kExitInput;
      }
    } else if (in_place && file != "-") {
      if (r.text != text && !write_output(file, bytes_of(r.text))) return kExitOutput;
    } else if (!write_output(output, bytes_of(r.text))) {
      return kExitOutput;
    }
  }
  return status;
}

// Everything the command line sets.
struct Settings {
  tmcl::AsmOptions opts;
  std::string target, show_target;  // -t, --show-target: resolved after the options (profile files)
  std::string show_include;          // --show-include: a bundled include file to print
  bool list_targets = false;
  std::string output, map_file, symbols_file;
  bool have_output = false, have_format = false;
  tmcl::OutputFormat format = tmcl::OutputFormat::Bin;
  Extra extra = Extra::None;
  bool analysis = true;
  Mode mode = Mode::Link;
  bool make_lib = false;
  bool fmt_in_place = false, fmt_check = false;
  tmcl::DisasmOptions dopts;
  int address = 1;
};

bool ends_with(const std::string& s, const char* suffix) {
  const std::size_t n = std::strlen(suffix);
  return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

// -f FMT. A source file where a format belongs (`--format prog.tmc`) most likely meant --fmt.
std::string set_format(Settings& s, const std::string& v) {
  s.have_format = true;
  s.make_lib = false;
  if (v == "bin") s.format = tmcl::OutputFormat::Bin;
  else if (v == "datagrams") s.format = tmcl::OutputFormat::Datagrams;
  else if (v == "listing") s.format = tmcl::OutputFormat::Listing;
  else if (v == "symbols") s.format = tmcl::OutputFormat::Symbols;
  else if (v == "dot") s.extra = Extra::Dot;
  else if (v == "lib") s.make_lib = true;
  else {
    std::string error = "unknown format '" + v + "' (bin, datagrams, listing, symbols, dot, lib)";
    if (ends_with(v, ".tmc") || ends_with(v, ".inc") || ::access(v.c_str(), F_OK) == 0)
      error += "; did you mean '--fmt " + v + "', which lays out a source?";
    return error;
  }
  if (v != "dot" && s.extra == Extra::Dot) s.extra = Extra::None;
  return {};
}

// -c, -d, --fmt, --dump-object, --analyze: one of them at most.
std::string set_mode(Settings& s, Mode m, const char* conflicts) {
  if (s.mode != Mode::Link && s.mode != m) return conflicts;
  s.mode = m;
  return {};
}

// The options, each declared once: --help, the errors, the man-page check and bash completion
// follow from this table (tmcl/options.hpp).
tmcl::cli::Tool command_line(Settings& s) {
  using tmcl::cli::flag, tmcl::cli::set, tmcl::cli::Values;
  auto ok = [](auto&& apply) {
    return [apply](const std::string& v) {
      apply(v);
      return std::string();
    };
  };
  auto warning = [&s](const char* prefix) {
    return [&s, prefix](const std::string& v) {
      std::string error, arg = prefix + v;
      if (!s.opts.warnings.parse(arg, error)) return error.empty() ? "unknown option '" + arg + "'" : error;
      if (arg == "-Werror") s.dopts.warnings_are_errors = true;
      return std::string();
    };
  };
  const Values warnings = Values::words(tmcl::warning_names());
  tmcl::cli::Tool t;
  t.name = "tmclasm";
  t.usage = kUsage;
  t.epilogue = kEpilogue;
  t.column = 21;
  t.options = {
      {"-o", "FILE",
       "output file; -o - writes to standard output\n"
       "(default: the first input with the format's extension, beside it;\n"
       " standard output when reading standard input, for -d and --dump-object)",
       ok([&s](const std::string& v) { s.output = v, s.have_output = true; }), Values::files(), "a file name"},
      {"-f, --format", "FMT",
       "bin (default)  TMCL-IDE .bin, 8 bytes per instruction\n"
       "datagrams      one 9-byte TMCL request per instruction (.dgm)\n"
       "listing        addresses, bytes, source lines (.lst)\n"
       "symbols        labels, constants and line table, tab-separated (.sym)\n"
       "dot            the control-flow graph for Graphviz (.dot; analysis.md)\n"
       "lib            a library of the inputs (needs -o)",
       [&s](const std::string& v) { return set_format(s, v); },
       Values::words({"bin", "datagrams", "listing", "symbols", "dot", "lib"}), "a format"},
      {"-c", "", "assemble each source into a relocatable object (FILE.o)",
       [&s](const std::string&) { return set_mode(s, Mode::Compile, "-c cannot be combined with -d or --dump-object"); }},
      {"--map", "FILE", "also write a link map: input address ranges, every symbol's address",
       set(s.map_file), Values::files({"map"}), "a file name"},
      {"-d, --disassemble", "", "turn the FILE (.bin, .dgm datagrams, object) into .tmc source",
       [&s](const std::string&) { return set_mode(s, Mode::Disassemble, "-d cannot be combined with -c or --dump-object"); }},
      {"--symbols", "FILE", "with -d: label names and file:line comments from a symbols file\n(tmclasm -f symbols)",
       set(s.symbols_file), Values::files({"sym"}), "a file name"},
      {"--from", "FMT", "with -d: read FILE as bin, datagrams or object (default: by its contents\nand extension)",
       [&s](const std::string& v) {
         if (v == "bin") s.dopts.kind = tmcl::ImageKind::Bin;
         else if (v == "datagrams") s.dopts.kind = tmcl::ImageKind::Datagrams;
         else if (v == "object") s.dopts.kind = tmcl::ImageKind::Object;
         else return "unknown input format '" + v + "' for --from (bin, datagrams, object)";
         return std::string();
       },
       Values::words({"bin", "datagrams", "object"}), "a format"},
      {"--dump-object", "", "show an object or a library (every member) as text",
       [&s](const std::string&) { return set_mode(s, Mode::Dump, "--dump-object cannot be combined with -c or -d"); }},
      {"--fmt", "", "write the sources in the canonical layout (to standard output, or -o FILE)",
       [&s](const std::string&) {
         return set_mode(s, Mode::Fmt, "--fmt cannot be combined with -c, -d, --analyze or --dump-object");
       }},
      {"-i", "", "with --fmt: rewrite each FILE in place", flag(s.fmt_in_place)},
      {"--check", "", "with --fmt: write nothing; exit 65 naming each FILE not in the layout",
       flag(s.fmt_check)},
      {"--address", "N", "module address in datagrams (default 1)",
       [&s](const std::string& v) {
         char* end = nullptr;
         const long n = std::strtol(v.c_str(), &end, 0);
         if (v.empty() || *end || n < 0 || n > 255) return std::string("--address must be a number from 0 to 255");
         s.address = static_cast<int>(n);
         return std::string();
       }},
      {"-t, --target", "NAME",
       "the module: a bundled target (tmcm-1110, usb-2-sd, ...; --list-targets),\n"
       "NAME.profile in $TMCL_PROFILE_PATH or ~/.config/tmcl/profiles, or a\n"
       "profile file (PATH with a '/' or ending in .profile). Default: what the\n"
       "first line names (// tmcl-target: NAME), else generic",
       set(s.target), Values::words([] { return tmcl::target_names(); }, {"profile"}), "a target name or a profile file"},
      {"--list-targets", "", "list every target found and where it comes from", flag(s.list_targets)},
      {"--show-target", "NAME", "print the target's profile file (a start for a module of your own)",
       set(s.show_target), Values::words([] { return tmcl::target_names(); }, {"profile"}), "a target name or a profile file"},
      {"--show-include", "FILE", "print a bundled include file (TMCLParam.tmc, TMCM-1260.inc, ...)",
       set(s.show_include),
       // A function, not its result: the list is made only when completing (generating every
       // module's include file at each start cost 20 M instructions, most of a small run).
       Values::words([] {
         std::vector<std::string> names;
         for (const auto& [name, text] : tmcl::bundled_includes()) names.push_back(name);
         return names;
       }),
       "a bundled include file"},
      {"-I", "DIR", "search DIR for #include files (after the including file's folder)",
       tmcl::cli::append(s.opts.include_dirs), Values::dirs()},
      {"-D", "NAME=VALUE", "define a constant (VALUE is an expression)",
       [&s](const std::string& v) {
         const auto eq = v.find('=');
         const std::string name = v.substr(0, eq);
         if (!tmcl::is_valid_name(name)) return "-D " + v + ": '" + name + "' is not a valid name";
         s.opts.defines.emplace_back(name, eq == std::string::npos ? "1" : v.substr(eq + 1));
         return std::string();
       }},
      {"-Wall", "", "report every warning (all are on by default; a -Wno-NAME still holds)",
       [warning](const std::string&) { return warning("-W")("all"); }},
      {"-Werror", "", "treat warnings as errors", warning("-Werror")},
      {"-Werror=", "NAME", "treat the warning NAME as an error", warning("-Werror="), warnings},
      {"-Wno-", "NAME", "do not report the warning NAME (names: analysis.md)", warning("-Wno-"), warnings},
      {"-W", "NAME", "", warning("-W"), warnings, {}, true},
      {"--stack-usage", "",
       "write the call-stack report (per subroutine and handler: its maximum\n"
       "depth and deepest chain) instead of the program (.su)",
       ok([&s](const std::string&) { s.extra = Extra::StackUsage; })},
      {"--analyze", "",
       "FILE is a .bin or datagrams image: disassemble it and check its control\n"
       "flow (positions are lines of tmclasm -d FILE; --symbols names labels)",
       [&s](const std::string&) {
         return set_mode(s, Mode::Analyze, "--analyze cannot be combined with -c, -d or --dump-object");
       }},
      {"--no-analysis", "", "do not analyse the control flow after linking (analysis.md)",
       ok([&s](const std::string&) { s.analysis = false; })},
      {"--no-append-stop", "", "do not append STOP when the program does not end in one",
       ok([&s](const std::string&) { s.opts.append_stop = false; })},
      {"--error-limit", "N", "show at most N errors (default 20, 0 = all), then how many more there were",
       [&s](const std::string& v) {
         std::int64_t n = 0;
         if (!tmcl::parse_int(v, 0, 1'000'000'000, n))
           return "bad error limit '" + v + "' for --error-limit (a number, 0 for no limit)";
         s.opts.error_limit = static_cast<int>(n);
         return std::string();
       }},
  };
  t.operands = [](const std::vector<std::string>&, const std::vector<std::string>& given) {
    for (const auto& g : given) {
      if (g == "--disassemble" || g == "--analyze") return Values::files({"bin", "dgm", "o"});
      if (g == "--dump-object") return Values::files({"o", "a"});
    }
    return Values::files({"tmc", "inc", "o", "a"});
  };
  return t;
}

// -c: every source is assembled and reported; objects are written only when all succeed.
int compile(const std::vector<std::string>& files, Settings& s, tmcl::FileReader& reader) {
  if (s.have_format) return usage_error("-c writes objects; -f does not apply");
  if (s.have_output && files.size() > 1) return usage_error("-o with -c names one object; give one source file");
  std::vector<std::pair<std::string, std::vector<std::uint8_t>>> objects;
  int errors = 0, warnings = 0;
  s.opts.relocatable = true;
  for (const auto& file : files) {
    tmcl::AsmResult r = tmcl::assemble({file}, s.opts, reader);
    std::fputs(r.diags.render(r.sources, s.opts.error_limit).c_str(), stderr);
    errors += r.diags.error_count();
    warnings += r.diags.warning_count();
    if (!r.ok() || !r.object) continue;
    std::string out = s.have_output ? s.output : file == "-" ? std::string("-") : with_extension(file, ".o");
    objects.emplace_back(out, tmcl::write_object(*r.object));
  }
  if (errors > 0) {
    print_failure(errors, warnings);
    return kExitInput;
  }
  for (const auto& [path, bytes] : objects)
    if (!write_output(path, bytes)) return kExitOutput;
  return 0;
}

// A link into one program (or its analysis' dot graph or stack report).
int link(const std::vector<std::string>& files, Settings& s, tmcl::FileReader& reader) {
  // Label names: for the symbols format, the map, the analysis' pictures and its messages. On a
  // million-line program they cost the assembler 2 % (docs/performance.md): collected in the one
  // assembly whenever they may be needed, never by assembling twice.
  tmcl::AsmOptions& opts = s.opts;
  opts.symbols = s.format == tmcl::OutputFormat::Symbols || !s.map_file.empty() || s.extra != Extra::None || s.analysis;
  tmcl::AsmResult result = tmcl::assemble(files, opts, reader);
  // At most --error-limit warnings of each kind are shown: the rest are only counted.
  result.diags.set_kind_limit(opts.error_limit);
  std::string extra_text;
  if (s.analysis && result.ok()) extra_text = analyze_program(result, s.extra, true);
  std::string text = result.diags.render(result.sources, opts.error_limit);
  std::fputs(text.c_str(), stderr);
  if (!result.ok()) {
    print_failure(result.diags.error_count(), result.diags.warning_count());
    return kExitInput;
  }

  std::string output = s.output;
  if (!s.have_output) {
    if (files[0] == "-") {
      output = "-";
    } else {
      static const char* ext[] = {".bin", ".dgm", ".lst", ".sym"};
      output = with_extension(files[0], s.extra == Extra::Dot          ? ".dot"
                                        : s.extra == Extra::StackUsage ? ".su"
                                                                       : ext[static_cast<int>(s.format)]);
    }
  }
  if (s.extra != Extra::None) return write_output(output, bytes_of(extra_text)) ? 0 : kExitOutput;
  const tmcl::Profile& profile = result.profile ? *result.profile : tmcl::generic_profile();
  auto bytes = tmcl::format_output(s.format, result, profile, static_cast<std::uint8_t>(s.address));
  if (!s.map_file.empty() && !write_output(s.map_file, bytes_of(tmcl::format_map(result)))) return kExitOutput;
  if (!write_output(output, bytes)) return kExitOutput;
  return 0;
}

int run(int argc, char** argv) {
  Settings s;
  const tmcl::cli::Result cl = tmcl::cli::parse(command_line(s), argc, argv);
  if (cl.status == tmcl::cli::Result::Status::Done) return 0;
  if (cl.status == tmcl::cli::Result::Status::Error) return usage_error(cl.error);
  if (s.list_targets) return write_output("-", bytes_of(tmcl::format_target_list(tmcl::list_targets()))) ? 0 : kExitOutput;
  if (!s.show_include.empty()) {
    // Names are matched as #include matches bundled files: ignoring case.
    auto upper = [](std::string t) {
      for (char& c : t) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      return t;
    };
    for (const auto& [name, text] : tmcl::bundled_includes())
      if (upper(name) == upper(s.show_include)) return write_output("-", bytes_of(std::string(text))) ? 0 : kExitOutput;
    // include_files/ by name, the generated ones by the rule: their list grows with every profile.
    std::string names;
    for (const auto& [name, text] : tmcl::include_file_texts()) names += name + ", ";
    return usage_error("--show-include: no bundled include file '" + s.show_include + "' (" + names +
                       "and NAME.inc of each other bundled module of --list-targets)");
  }
  for (const std::string* v : {&s.show_target, &s.target}) {
    if (v->empty()) continue;
    const tmcl::TargetResult t = tmcl::resolve_target(*v);
    if (!t.profile) return t.usage ? usage_error(t.message()) : input_error(t.message(s.opts.error_limit, "tmclasm"));
    if (v == &s.show_target) return write_output("-", bytes_of(std::string(t.profile->text))) ? 0 : kExitOutput;
    s.opts.profile = t.profile;
  }
  const std::vector<std::string>& files = cl.operands;
  const Mode mode = s.mode;
  const std::string out = s.have_output ? s.output : "-";
  if (files.empty()) return usage_error("no input files");
  if ((s.fmt_in_place || s.fmt_check) && mode != Mode::Fmt) return usage_error("-i and --check go with --fmt");
  if (mode == Mode::Fmt) {
    if (s.fmt_in_place && s.fmt_check) return usage_error("--fmt takes -i or --check, not both");
    if (s.have_output && (s.fmt_in_place || s.fmt_check || files.size() != 1))
      return usage_error("-o with --fmt names the output of one source (not with -i or --check)");
    return format_sources(files, s.fmt_in_place, s.fmt_check, out);
  }
  if (s.make_lib && mode != Mode::Link) return usage_error("-f lib cannot be combined with -c, -d or --dump-object");
  if (!s.map_file.empty() && (mode != Mode::Link || s.make_lib)) return usage_error("--map needs a link (not -c, -d, -f lib)");
  if ((!s.symbols_file.empty() || s.dopts.kind != tmcl::ImageKind::Auto) && mode != Mode::Disassemble &&
      mode != Mode::Analyze)
    return usage_error("--symbols and --from need -d or --analyze");
  if (s.extra != Extra::None && (mode == Mode::Compile || s.make_lib || !s.analysis))
    return usage_error("-f dot and --stack-usage need a linked program and the analysis (not -c, -f lib, --no-analysis)");
  if (mode == Mode::Analyze) {
    if (files.size() != 1) return usage_error("--analyze takes one image file");
    return analyze_image(files[0], s.opts, s.dopts, s.symbols_file, s.extra, out);
  }
  if (mode == Mode::Disassemble || mode == Mode::Dump) {
    if (files.size() != 1)
      return usage_error(std::string(mode == Mode::Dump ? "--dump-object" : "-d") + " takes one input file");
    if (s.have_format) return usage_error("-f does not apply to -d or --dump-object (they write text)");
    return mode == Mode::Dump ? dump(files[0], out) : disassemble(files[0], out, s.dopts, s.symbols_file);
  }

  tmcl::DiskReader reader;
  if (s.make_lib) {
    if (!s.have_output) return usage_error("-f lib needs -o LIBRARY");
    tmcl::LibraryResult lib = tmcl::make_library(files, s.opts, reader);
    std::fputs(lib.messages.c_str(), stderr);
    if (!lib.ok()) {
      print_failure(lib.errors, lib.warnings);
      return kExitInput;
    }
    return write_output(s.output, tmcl::write_library(lib.library)) ? 0 : kExitOutput;
  }
  return mode == Mode::Compile ? compile(files, s, reader) : link(files, s, reader);
}

}  // namespace

int main(int argc, char** argv) {
  tmcl::os::init_console();  // Windows: bytes as they are, UTF-8 (os_console.hpp)
#if defined(__GLIBC__)
  // tmclasm is a short process whose big buffers come and go in phases (the assembler's, then
  // the analysis', then the output's). Kept in the heap instead of unmapped at each free, a later
  // phase reuses the pages an earlier one already faulted in: on a million-line program the
  // analysis then costs no page faults at all (docs/performance.md, issue 13).
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
  int status = run(argc, argv);
  // Every write is checked, standard output included (--help, --version, -o -).
  if (std::string err; !tmcl::flush_stdout(err)) {
    std::fprintf(stderr, "tmclasm: error: %s\n", err.c_str());
    return kExitOutput;
  }
  return status;
}
