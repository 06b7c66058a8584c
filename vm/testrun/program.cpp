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

// Loads `path` into `p`; false with the rendered diagnostics in `error`.
bool load(const std::string& path, const Profile& profile, AsmOptions options, Program& p, std::string& error) {
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
      error = res.diags.render(res.sources, options.error_limit);
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

}  // namespace

struct ProgramCache::Impl {
  struct Entry {
    std::once_flag once;
    std::shared_ptr<const Program> program;
    std::string error;
  };
  std::mutex lock;
  std::map<std::string, std::shared_ptr<Entry>> entries;
};

ProgramCache::ProgramCache() : impl_(std::make_unique<Impl>()) {}
ProgramCache::~ProgramCache() = default;

std::shared_ptr<const Program> ProgramCache::get(const TestFile& test, const Profile& profile, const RunOptions& options,
                                                 std::string& error) {
  std::string key = test.program + '\n' + std::string(profile.name);
  for (const auto& [name, value] : test.defines) key += '\n' + name + '=' + value;
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
    for (const auto& d : test.defines) asm_options.defines.push_back(d);
    auto p = std::make_shared<Program>();
    if (load(test.program, profile, asm_options, *p, entry->error)) entry->program = std::move(p);
  });
  error = entry->error;
  return entry->program;
}

}  // namespace tmcl::testrun
