// The programs tests run, each loaded once: a suite of a hundred tests of one program assembles
// it once, not a hundred times (the runner in one process must beat a process per test). A .tmc
// is assembled with its line table, labels and constants (ProgramInfo, as the debugger loads
// it); a .bin or .dgm is read by the one image reader and has neither. The control-flow analysis
// gives the interrupt handlers' code (run-time warnings as tmclrun gives them) and the
// subroutines and handlers that coverage reports as functions.
#include <filesystem>
#include <map>
#include <mutex>

#include "tmcl/analysis.hpp"
#include "tmcl/fileio.hpp"
#include "tmcl/program_image.hpp"
#include "tmcl/testrun.hpp"

namespace tmcl::testrun {

// A source that did not assemble: the assembler's diagnostics, rendered for each test that runs
// it (program_errors), since a `define` of a test is shown at that test's line.
struct AsmFailure {
  SourceSet sources;
  Diagnostics diags;
};

namespace {

bool is_image(const std::string& path) {
  auto ends = [&](std::string_view suffix) {
    if (path.size() < suffix.size()) return false;
    for (std::size_t i = 0; i < suffix.size(); ++i)
      if (std::tolower(static_cast<unsigned char>(path[path.size() - suffix.size() + i])) != suffix[i]) return false;
    return true;
  };
  return ends(".bin") || ends(".dgm");
}

// A file's absolute path for coverage reports, or "" when it is not on disk (bundled includes).
std::string absolute_path(const std::string& path) {
  if (path.empty() || path[0] == '<') return "";
  std::error_code ec;
  auto p = std::filesystem::absolute(path, ec);
  return ec ? path : p.lexically_normal().generic_string();  // '/' on Windows too, as shown()
}

// Loads `path` into `p`; false with the rendered diagnostics in `error`, or those of a source that
// did not assemble in `failed`.
bool load(const std::string& path, const Profile& profile, AsmOptions options, Program& p, std::string& error,
          std::shared_ptr<const AsmFailure>& failed) {
  p.profile = &profile;
  if (is_image(path)) {
    std::vector<std::uint8_t> bytes;
    if (!read_file(path, bytes, error)) {
      error = path + ": error: " + error + "\n";
      return false;
    }
    std::string messages;
    if (!read_program_image(path, bytes, p.info.program, messages)) {
      error = messages;
      return false;
    }
    p.messages = messages;
  } else {
    DiskReader reader;
    options.profile = &profile;
    options.symbols = true;
    AsmResult res = assemble({path}, options, reader);
    if (!res.ok()) {
      failed = std::make_shared<AsmFailure>(AsmFailure{std::move(res.sources), std::move(res.diags)});
      return false;
    }
    if (!res.diags.all().empty()) p.messages = res.diags.render(res.sources, options.error_limit);
    p.info.program = res.program;
    for (const auto& f : res.sources.files) {
      p.info.files.push_back({f.name, split_lines(f.text)});
      p.paths.push_back(absolute_path(f.path));
    }
    for (const auto& li : res.lines) p.info.lines.push_back({li.file, li.line});
    for (const auto& s : res.symbols)
      (s.kind == SymbolKind::Label ? p.info.labels : p.info.constants).emplace_back(s.name, s.value);
  }
  if (p.info.program.empty()) {
    error = path + ": error: the program is empty\n";
    return false;
  }
  if (profile.program_memory > 0 && p.info.program.size() > static_cast<std::size_t>(profile.program_memory)) {
    error = path + ": error: " + std::to_string(p.info.program.size()) + " instructions do not fit the " +
            std::to_string(profile.program_memory) + " of " + std::string(profile.name) + " program memory\n";
    return false;
  }
  for (std::size_t a = 0; a < p.info.program.size(); ++a) p.places.push_back(p.info.place(static_cast<std::int32_t>(a)));
  AnalysisInput in;
  in.program = p.info.program;
  in.profile = &profile;
  Diagnostics ignored;  // tmclasm reports them; tests need only the regions
  Analysis a = analyze(in, ignored);
  for (const Region& r : a.regions) {
    if (r.kind == RegionKind::Main) continue;
    if (r.kind == RegionKind::Handler && p.handler_code.empty()) {
      p.handler_code.assign(p.info.program.size(), 0);
      for (std::size_t i = 0; i < p.info.program.size(); ++i) {
        const int owner = a.owner[i];
        p.handler_code[i] = owner >= 0 && a.regions[static_cast<std::size_t>(owner)].kind == RegionKind::Handler;
      }
    }
    std::string name = p.info.function_of(r.entry);
    p.functions.push_back({name.empty() || name.find('+') != std::string::npos ? r.name : name, r.entry});
  }
  return true;
}

// The diagnostics of a program that did not assemble, for one test. The values of the test's
// `define` lines are sources of their own to the assembler ("<command line -D NAME>", after
// the -D options'): an error in one becomes the test file's, at that line and the column in the
// value, with a note at the same place (a did-you-mean) joined to its message; a note that
// points at one (a constant the program defines again) points at the line. The rest are
// rendered as the assembler renders them.
std::string program_errors(const AsmFailure& f, const TestFile& test, std::size_t cli_defines, int error_limit,
                           std::vector<FileDiag>& test_diags) {
  std::map<int, const Define*> define_of;  // source -> the test's define; the k-th such source is the k-th -D
  std::size_t k = 0;
  for (std::size_t i = 0; i < f.sources.files.size(); ++i) {
    if (f.sources.files[i].name.rfind("<command line -D ", 0) != 0) continue;
    if (k >= cli_defines && k - cli_defines < test.defines.size())
      define_of[static_cast<int>(i)] = &test.defines[k - cli_defines];
    ++k;
  }
  if (define_of.empty()) return f.diags.render(f.sources, error_limit);
  // Those sources show the test file, so that a note at a define shows the define's line.
  SourceSet sources = f.sources;
  SourceSet test_text;
  SourceFile tf;
  tf.name = tf.path = test.path;
  for (const std::string& line : test.lines) tf.text += line + "\n";
  test_text.add(std::move(tf));
  for (const auto& [index, define] : define_of) sources.files[static_cast<std::size_t>(index)] = test_text.files[0];
  auto remap = [&](SourceLoc& loc) {
    auto it = define_of.find(loc.file);
    if (it == define_of.end()) return false;
    loc.line = it->second->line;
    loc.col = it->second->col + std::max(1, loc.col) - 1;
    return true;
  };
  Diagnostics rest;
  for (const Diagnostic& d : f.diags.all()) {
    SourceLoc loc = d.loc;
    if (remap(loc) && d.severity == Severity::Error) {
      std::string message = d.message;
      for (const Diagnostic& n : d.notes)
        if (n.loc.file == d.loc.file && n.loc.col == d.loc.col) message += "; " + n.message;
      test_diags.push_back({test.path, loc.line, loc.col, loc.len, message, test.lines[static_cast<std::size_t>(loc.line - 1)]});
      continue;
    }
    if (d.severity == Severity::Note) continue;  // only notes of a diagnostic are made
    Diagnostic& copy = d.severity == Severity::Error ? rest.error(loc, d.message) : rest.warning(loc, d.message);
    copy.name = d.name;
    copy.notes = d.notes;
    for (Diagnostic& n : copy.notes)
      if (remap(n.loc) && n.message == "first defined on the command line") n.message = "first defined here";
  }
  return rest.all().empty() ? std::string() : rest.render(sources, error_limit);
}

}  // namespace

struct ProgramCache::Impl {
  struct Entry {
    std::once_flag once;
    std::shared_ptr<const Program> program;
    std::string error;
    std::shared_ptr<const AsmFailure> failed;
  };
  std::mutex lock;
  // By profile (its address: two user profiles may share a name, and profiles live as long as
  // the program), then the program and the test's defines.
  std::map<std::pair<const Profile*, std::string>, std::shared_ptr<Entry>> entries;
};

ProgramCache::ProgramCache() : impl_(std::make_unique<Impl>()) {}
ProgramCache::~ProgramCache() = default;

std::shared_ptr<const Program> ProgramCache::get(const TestFile& test, const Profile& profile, const RunOptions& options,
                                                 std::string& error, std::vector<FileDiag>& test_diags) {
  std::pair<const Profile*, std::string> key{&profile, test.program};
  for (const Define& d : test.defines) key.second += '\n' + d.name + '=' + d.value;
  std::shared_ptr<Impl::Entry> entry;
  {
    std::lock_guard<std::mutex> g(impl_->lock);
    auto& slot = impl_->entries[key];
    if (!slot) slot = std::make_shared<Impl::Entry>();
    entry = slot;
  }
  // The first test to need a program loads it; the others wait for it, then share it.
  std::call_once(entry->once, [&] {
    AsmOptions asm_options = options.asm_options;
    asm_options.error_limit = options.error_limit;
    for (const Define& d : test.defines) asm_options.defines.emplace_back(d.name, d.value);
    auto p = std::make_shared<Program>();
    if (load(test.program, profile, asm_options, *p, entry->error, entry->failed)) entry->program = std::move(p);
  });
  error = entry->failed ? program_errors(*entry->failed, test, options.asm_options.defines.size(), options.error_limit, test_diags)
                        : entry->error;
  return entry->program;
}

}  // namespace tmcl::testrun
