// tmclasm: the command-line assembler. Parses arguments, calls the assembler library, writes the
// output. Exit status: 0 success, 65 errors in the input, 64 usage errors, 74 output not written.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "tmcl/asm/assembler.hpp"
#include "tmcl/asm/output.hpp"
#include "tmcl/fileio.hpp"

namespace {

constexpr int kExitInput = 65;
constexpr int kExitUsage = 64;
constexpr int kExitOutput = 74;

const char* kUsage = R"(usage: tmclasm [options] FILE...        FILE may be - for standard input

Assembles TMCL sources (.tmc) into a program image. Each FILE is its own unit: its labels and
constants are private unless exported (#export NAME) and imported elsewhere (#import NAME).
Units are placed one after another from address 0.

options:
  -o FILE            output file; -o - writes to standard output
                     (default: the first input with the format's extension, beside it;
                      standard output when reading standard input)
  -f, --format FMT   bin (default)  TMCL-IDE .bin, 8 bytes per instruction
                     datagrams      one 9-byte TMCL request per instruction (.dgm)
                     listing        addresses, bytes, source lines (.lst)
                     symbols        labels and constants, tab-separated (.sym)
  --address N        module address in datagrams (default 1)
  -t, --target NAME  usb-2-sd | tmc2300-eval | generic (default)
  -I DIR             search DIR for #include files (after the including file's folder)
  -D NAME=VALUE      define a constant (VALUE is an expression)
  -Werror            treat warnings as errors
  --no-append-stop   do not append STOP when the program does not end in one
  --help             show this help
  --version          show the version

examples:
  tmclasm prog.tmc                       writes prog.bin
  tmclasm -t usb-2-sd -f listing -o - prog.tmc
  tmclasm -f datagrams --address 3 -o prog.dgm prog.tmc

exit status: 0 success, 65 errors in the input, 64 usage error, 74 output could not be written
)";

int usage_error(const std::string& msg) {
  std::fprintf(stderr, "tmclasm: %s\n(see tmclasm --help)\n", msg.c_str());
  return kExitUsage;
}

bool valid_name(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  tmcl::AsmOptions opts;
  std::vector<std::string> files;
  std::string output;
  bool have_output = false;
  tmcl::OutputFormat format = tmcl::OutputFormat::Bin;
  int address = 1;
  std::vector<std::string> args(argv + 1, argv + argc);

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
      std::puts("tmclasm 0.1.0");
      return 0;
    } else if (a == "-o" || (a.rfind("-o", 0) == 0 && a.size() > 2 && a[2] != '-')) {
      if (!value("-o", v)) return usage_error("-o needs a file name");
      output = v;
      have_output = true;
    } else if (a == "-f" || a == "--format") {
      if (!value(a, v)) return usage_error(a + " needs a format");
      if (v == "bin") format = tmcl::OutputFormat::Bin;
      else if (v == "datagrams") format = tmcl::OutputFormat::Datagrams;
      else if (v == "listing") format = tmcl::OutputFormat::Listing;
      else if (v == "symbols") format = tmcl::OutputFormat::Symbols;
      else return usage_error("unknown format '" + v + "' (bin, datagrams, listing, symbols)");
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
      if (!valid_name(name)) return usage_error("-D " + v + ": '" + name + "' is not a valid name");
      opts.defines.emplace_back(name, eq == std::string::npos ? "1" : v.substr(eq + 1));
    } else if (a == "-Werror") {
      opts.warnings_are_errors = true;
    } else if (a == "--no-append-stop") {
      opts.append_stop = false;
    } else if (a == "-") {
      files.push_back(a);
    } else if (a.size() > 1 && a[0] == '-') {
      return usage_error("unknown option '" + a + "'");
    } else {
      files.push_back(a);
    }
  }
  if (files.empty()) return usage_error("no input files");

  tmcl::DiskReader reader;
  tmcl::AsmResult result = tmcl::assemble(files, opts, reader);
  std::string text = result.diags.render(result.sources);
  std::fputs(text.c_str(), stderr);
  if (!result.ok()) {
    std::fprintf(stderr, "tmclasm: %d error%s, %d warning%s; nothing written\n", result.diags.error_count(),
                 result.diags.error_count() == 1 ? "" : "s", result.diags.warning_count(),
                 result.diags.warning_count() == 1 ? "" : "s");
    return kExitInput;
  }

  if (!have_output) {
    if (files[0] == "-") {
      output = "-";
    } else {
      static const char* ext[] = {".bin", ".dgm", ".lst", ".sym"};
      output = std::filesystem::path(files[0]).replace_extension(ext[static_cast<int>(format)]).string();
    }
  }
  const tmcl::Profile& profile = opts.profile ? *opts.profile : tmcl::generic_profile();
  auto bytes = tmcl::format_output(format, result, profile, static_cast<std::uint8_t>(address));
  std::string err;
  if (!tmcl::write_file_atomic(output, bytes, err)) {
    std::fprintf(stderr, "tmclasm: %s\n", err.c_str());
    return kExitOutput;
  }
  return 0;
}
