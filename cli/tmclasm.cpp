// tmclasm: the command-line assembler, linker and disassembler. Parses arguments, calls the
// assembler library, writes the output. Exit status: 0 success, 65 errors in the input, 64 usage
// errors, 74 output not written.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

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
#include "tmcl/version.hpp"

namespace {

constexpr int kExitInput = 65;
constexpr int kExitUsage = 64;
constexpr int kExitOutput = 74;

const char* kUsage = R"(usage: tmclasm [options] FILE...        link sources, objects and libraries
       tmclasm -c [options] FILE.tmc...   assemble each source into an object (.o)
       tmclasm -f lib -o LIB.a FILE...    bundle objects (sources are assembled) into a library
       tmclasm -d [--symbols SYM] FILE    disassemble a .bin, datagrams or an object to source
       tmclasm --dump-object FILE         show an object or library as text
       tmclasm --fmt [-i | --check] FILE  lay a source out the canonical way (docs/tmclasm.md)
FILE may be - for standard input.

Assembles TMCL sources (.tmc) and links them with objects (.o) and libraries (.a) into a program
image. Each FILE is its own unit: its labels and constants are private unless exported
(#export NAME) and imported elsewhere (#import NAME). Units are placed one after another from
address 0 in command-line order; of a library only the members that export a name some linked
unit imports are linked, at the library's place.

options:
  -o FILE            output file; -o - writes to standard output
                     (default: the first input with the format's extension, beside it;
                      standard output when reading standard input, for -d and --dump-object)
  -f, --format FMT   bin (default)  TMCL-IDE .bin, 8 bytes per instruction
                     datagrams      one 9-byte TMCL request per instruction (.dgm)
                     listing        addresses, bytes, source lines (.lst)
                     symbols        labels, constants and line table, tab-separated (.sym)
                     dot            the control-flow graph for Graphviz (.dot; docs/analysis.md)
                     lib            a library of the inputs (needs -o)
  -c                 assemble each source into a relocatable object (FILE.o)
  --map FILE         also write a link map: input address ranges, every symbol's address
  -d, --disassemble  turn the FILE (.bin, .dgm datagrams, object) into .tmc source
  --symbols FILE     with -d: label names and file:line comments from a symbols file
                     (tmclasm -f symbols)
  --from FMT         with -d: read FILE as bin, datagrams or object (default: by its contents
                     and extension)
  --dump-object      show an object or a library (every member) as text
  --fmt              write the sources in the canonical layout (to standard output, or -o FILE)
  -i                 with --fmt: rewrite each FILE in place
  --check            with --fmt: write nothing; exit 65 naming each FILE not in the layout
  --address N        module address in datagrams (default 1)
  -t, --target NAME  usb-2-sd | tmc2300-eval | generic (default)
  -I DIR             search DIR for #include files (after the including file's folder)
  -D NAME=VALUE      define a constant (VALUE is an expression)
  -Werror            treat warnings as errors
  -Werror=NAME       treat the warning NAME as an error
  -Wno-NAME          do not report the warning NAME (names: docs/analysis.md, tmclasm.md)
  --stack-usage      write the call-stack report (per subroutine and handler: its maximum
                     depth and deepest chain) instead of the program (.su)
  --analyze          FILE is a .bin or datagrams image: disassemble it and check its control
                     flow (positions are lines of tmclasm -d FILE; --symbols names labels)
  --no-analysis      do not analyse the control flow after linking (docs/analysis.md)
  --no-append-stop   do not append STOP when the program does not end in one
  --error-limit N    show at most N errors (default 20, 0 = all), then how many more there were
  --help             show this help
  --version          show the version

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
)";

// PATH with its extension (from the last dot of the file name on; none for a name that starts
// with its only dot, or for "." and "..") replaced by EXT, as std::filesystem::path's
// replace_extension does: "prog.tmc" -> "prog.bin", "dir.v2/prog" -> "dir.v2/prog.bin".
std::string with_extension(const std::string& path, const char* ext) {
  const std::size_t slash = path.rfind('/');
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

int run(int argc, char** argv) {
  tmcl::AsmOptions opts;
  std::vector<std::string> files;
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
  std::vector<std::string> args(argv + 1, argv + argc);

  auto set_mode = [&](Mode m, const char* name) {
    if (mode != Mode::Link && mode != m) return false;
    (void)name;
    mode = m;
    return true;
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&](const std::string& opt, std::string& out) -> bool {
      if (a.size() > opt.size() && a.rfind(opt, 0) == 0 && opt.size() == 2) {  // -IDIR, -DX=1, -oFILE
        out = a.substr(2);
        return true;
      }
      if (i + 1 >= args.size()) return false;
      out = args[++i];
      return true;
    };
    std::string v;
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (a == "--version") {
      std::puts(tmcl::version_line("tmclasm").c_str());
      return 0;
    } else if (a == "-o" || (a.rfind("-o", 0) == 0 && a.size() > 2 && a[2] != '-')) {
      if (!value("-o", v)) return usage_error("-o needs a file name");
      output = v;
      have_output = true;
    } else if (a == "-f" || a == "--format") {
      if (!value(a, v)) return usage_error(a + " needs a format");
      have_format = true;
      make_lib = false;
      if (v == "bin") format = tmcl::OutputFormat::Bin;
      else if (v == "datagrams") format = tmcl::OutputFormat::Datagrams;
      else if (v == "listing") format = tmcl::OutputFormat::Listing;
      else if (v == "symbols") format = tmcl::OutputFormat::Symbols;
      else if (v == "dot") extra = Extra::Dot;
      else if (v == "lib") make_lib = true;
      else return usage_error("unknown format '" + v + "' (bin, datagrams, listing, symbols, dot, lib)");
      if (v != "dot" && extra == Extra::Dot) extra = Extra::None;
    } else if (a == "-c") {
      if (!set_mode(Mode::Compile, "-c")) return usage_error("-c cannot be combined with -d or --dump-object");
    } else if (a == "-d" || a == "--disassemble") {
      if (!set_mode(Mode::Disassemble, "-d")) return usage_error("-d cannot be combined with -c or --dump-object");
    } else if (a == "--fmt") {
      if (!set_mode(Mode::Fmt, "--fmt")) return usage_error("--fmt cannot be combined with -c, -d, --analyze or --dump-object");
    } else if (a == "-i") {
      fmt_in_place = true;
    } else if (a == "--check") {
      fmt_check = true;
    } else if (a == "--dump-object") {
      if (!set_mode(Mode::Dump, "--dump-object")) return usage_error("--dump-object cannot be combined with -c or -d");
    } else if (a == "--stack-usage") {
      extra = Extra::StackUsage;
    } else if (a == "--no-analysis") {
      analysis = false;
    } else if (a == "--analyze") {
      if (!set_mode(Mode::Analyze, "--analyze")) return usage_error("--analyze cannot be combined with -c, -d or --dump-object");
    } else if (a == "--map") {
      if (!value(a, v)) return usage_error("--map needs a file name");
      map_file = v;
    } else if (a == "--symbols") {
      if (!value(a, v)) return usage_error("--symbols needs a file name");
      symbols_file = v;
    } else if (a == "--from") {
      if (!value(a, v)) return usage_error("--from needs a format");
      if (v == "bin") dopts.kind = tmcl::ImageKind::Bin;
      else if (v == "datagrams") dopts.kind = tmcl::ImageKind::Datagrams;
      else if (v == "object") dopts.kind = tmcl::ImageKind::Object;
      else return usage_error("unknown input format '" + v + "' for --from (bin, datagrams, object)");
    } else if (a == "-t" || a == "--target") {
      if (!value(a, v)) return usage_error(a + " needs a target name");
      opts.profile = tmcl::find_profile(v);
      if (!opts.profile) return usage_error("unknown target '" + v + "' (usb-2-sd, tmc2300-eval, generic)");
    } else if (a == "--address") {
      if (!value(a, v)) return usage_error("--address needs a number");
      char* end = nullptr;
      long n = std::strtol(v.c_str(), &end, 0);
      if (v.empty() || *end || n < 0 || n > 255) return usage_error("--address must be a number from 0 to 255");
      address = static_cast<int>(n);
    } else if (a.rfind("-I", 0) == 0) {
      if (!value("-I", v)) return usage_error("-I needs a folder");
      opts.include_dirs.push_back(v);
    } else if (a.rfind("-D", 0) == 0) {
      if (!value("-D", v)) return usage_error("-D needs NAME=VALUE");
      auto eq = v.find('=');
      std::string name = v.substr(0, eq);
      if (!tmcl::is_valid_name(name)) return usage_error("-D " + v + ": '" + name + "' is not a valid name");
      opts.defines.emplace_back(name, eq == std::string::npos ? "1" : v.substr(eq + 1));
    } else if (a.rfind("-W", 0) == 0) {
      std::string error;
      if (!opts.warnings.parse(a, error))
        return usage_error(error.empty() ? "unknown option '" + a + "'" : error);
      if (a == "-Werror") dopts.warnings_are_errors = true;
    } else if (a == "--no-append-stop") {
      opts.append_stop = false;
    } else if (a == "--error-limit") {
      if (!value(a, v)) return usage_error("--error-limit needs a number");
      std::int64_t n = 0;
      if (!tmcl::parse_int(v, 0, 1'000'000'000, n))
        return usage_error("bad error limit '" + v + "' for --error-limit (a number, 0 for no limit)");
      opts.error_limit = static_cast<int>(n);
    } else if (a == "-") {
      files.push_back(a);
    } else if (a.size() > 1 && a[0] == '-') {
      return usage_error("unknown option '" + a + "'");
    } else {
      files.push_back(a);
    }
  }
  if (files.empty()) return usage_error("no input files");
  if ((fmt_in_place || fmt_check) && mode != Mode::Fmt) return usage_error("-i and --check go with --fmt");
  if (mode == Mode::Fmt) {
    if (fmt_in_place && fmt_check) return usage_error("--fmt takes -i or --check, not both");
    if (have_output && (fmt_in_place || fmt_check || files.size() != 1))
      return usage_error("-o with --fmt names the output of one source (not with -i or --check)");
    return format_sources(files, fmt_in_place, fmt_check, have_output ? output : "-");
  }
  if (make_lib && mode != Mode::Link) return usage_error("-f lib cannot be combined with -c, -d or --dump-object");
  if (!map_file.empty() && (mode != Mode::Link || make_lib)) return usage_error("--map needs a link (not -c, -d, -f lib)");
  if ((!symbols_file.empty() || dopts.kind != tmcl::ImageKind::Auto) && mode != Mode::Disassemble && mode != Mode::Analyze)
    return usage_error("--symbols and --from need -d or --analyze");
  if (extra != Extra::None && (mode == Mode::Compile || make_lib || !analysis))
    return usage_error("-f dot and --stack-usage need a linked program and the analysis (not -c, -f lib, --no-analysis)");
  if (mode == Mode::Analyze) {
    if (files.size() != 1) return usage_error("--analyze takes one image file");
    std::string out = have_output ? output : "-";
    return analyze_image(files[0], opts, dopts, symbols_file, extra, out);
  }
  if (mode == Mode::Disassemble || mode == Mode::Dump) {
    if (files.size() != 1)
      return usage_error(std::string(mode == Mode::Dump ? "--dump-object" : "-d") + " takes one input file");
    if (have_format) return usage_error("-f does not apply to -d or --dump-object (they write text)");
    std::string out = have_output ? output : "-";
    return mode == Mode::Dump ? dump(files[0], out) : disassemble(files[0], out, dopts, symbols_file);
  }

  tmcl::DiskReader reader;
  if (make_lib) {
    if (!have_output) return usage_error("-f lib needs -o LIBRARY");
    tmcl::LibraryResult lib = tmcl::make_library(files, opts, reader);
    std::fputs(lib.messages.c_str(), stderr);
    if (!lib.ok()) {
      print_failure(lib.errors, lib.warnings);
      return kExitInput;
    }
    return write_output(output, tmcl::write_library(lib.library)) ? 0 : kExitOutput;
  }

  if (mode == Mode::Compile) {
    if (have_format) return usage_error("-c writes objects; -f does not apply");
    if (have_output && files.size() > 1) return usage_error("-o with -c names one object; give one source file");
    // Every source is assembled and reported; objects are written only when all succeed.
    std::vector<std::pair<std::string, std::vector<std::uint8_t>>> objects;
    int errors = 0, warnings = 0;
    opts.relocatable = true;
    for (const auto& file : files) {
      tmcl::AsmResult r = tmcl::assemble({file}, opts, reader);
      std::fputs(r.diags.render(r.sources, opts.error_limit).c_str(), stderr);
      errors += r.diags.error_count();
      warnings += r.diags.warning_count();
      if (!r.ok() || !r.object) continue;
      std::string out = have_output ? output
                        : file == "-" ? std::string("-")
                                      : with_extension(file, ".o");
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

  // Label names: for the symbols format, the map, the analysis' pictures and its messages. On a
  // million-line program they cost the assembler 2 % (docs/performance.md): collected in the one
  // assembly whenever they may be needed, never by assembling twice.
  opts.symbols = format == tmcl::OutputFormat::Symbols || !map_file.empty() || extra != Extra::None || analysis;
  tmcl::AsmResult result = tmcl::assemble(files, opts, reader);
  // At most --error-limit warnings of each kind are shown: the rest are only counted.
  result.diags.set_kind_limit(opts.error_limit);
  std::string extra_text;
  if (analysis && result.ok()) extra_text = analyze_program(result, extra, true);
  std::string text = result.diags.render(result.sources, opts.error_limit);
  std::fputs(text.c_str(), stderr);
  if (!result.ok()) {
    print_failure(result.diags.error_count(), result.diags.warning_count());
    return kExitInput;
  }

  if (!have_output) {
    if (files[0] == "-") {
      output = "-";
    } else {
      static const char* ext[] = {".bin", ".dgm", ".lst", ".sym"};
      output = with_extension(files[0], extra == Extra::Dot          ? ".dot"
                                        : extra == Extra::StackUsage ? ".su"
                                                                     : ext[static_cast<int>(format)]);
    }
  }
  if (extra != Extra::None) return write_output(output, bytes_of(extra_text)) ? 0 : kExitOutput;
  const tmcl::Profile& profile = result.profile ? *result.profile : tmcl::generic_profile();
  auto bytes = tmcl::format_output(format, result, profile, static_cast<std::uint8_t>(address));
  if (!map_file.empty() && !write_output(map_file, bytes_of(tmcl::format_map(result)))) return kExitOutput;
  if (!write_output(output, bytes)) return kExitOutput;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
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
