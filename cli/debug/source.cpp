// The debugger's source lookup for images: a .bin has no source positions of its own, so they
// come from the line table of its symbols file, and the text from the files that table names.
#include "source.hpp"

#include <filesystem>

#include "tmcl/asm/symbols.hpp"
#include "tmcl/fileio.hpp"
#include "tmcl/os_files.hpp"

namespace tmcl::debug {

bool apply_symbols(const std::string& symbols, const std::vector<std::string>& source_dirs, ProgramInfo& info,
                   std::string& messages) {
  LabelNames names;
  std::string err;
  if (!load_symbols(symbols, "tmclrun", names, err)) {
    messages += err + "\n";
    return false;
  }
  info.labels = names.labels;
  const LineTable& table = names.lines;
  if (table.empty()) return true;
  // Relative names are looked up beside the symbols file first (the two travel together), then
  // in the current folder (where tmclasm was most likely run), then in the --source-dir folders.
  const std::size_t sep = os::last_separator(symbols);
  const std::string folder = sep == std::string::npos ? "" : symbols.substr(0, sep + 1);
  for (const auto& name : table.files) {
    ProgramInfo::File f;
    f.name = name;
    std::vector<std::string> tried = {name};
    const bool relative = !os::is_absolute(name);
    if (relative) {
      if (!folder.empty()) tried.insert(tried.begin(), folder + name);
      for (const auto& dir : source_dirs) tried.push_back(os::join_path(dir, name));
    }
    for (const auto& path : tried) {
      std::vector<std::uint8_t> bytes;
      if (!read_file(path, bytes, err)) continue;
      // Absolute, as DAP clients open and match it (source.path, setBreakpoints).
      std::error_code ec;
      auto absolute = std::filesystem::absolute(path, ec);
      f.path = ec ? path : absolute.lexically_normal().string();
      f.text = split_lines(std::string(bytes.begin(), bytes.end()));
      break;
    }
    if (f.path.empty())
      messages += symbols + ": warning: source file '" + name + "' not found" +
                  (relative ? std::string(source_dirs.empty()
                                                    ? " (looked beside the symbols file and in the current folder)"
                                                    : " (looked beside the symbols file, in the current folder and in the "
                                                      "--source-dir folders)")
                                  : std::string()) +
                  "; its lines are shown without text\n";
    info.files.push_back(std::move(f));
  }
  const std::int64_t size = static_cast<std::int64_t>(info.program.size());
  if (table.end() > size)
    messages += symbols + ": warning: the line table describes addresses up to " + std::to_string(table.end() - 1) +
                " but the program has " + std::to_string(size) +
                " instructions (the symbols of another build?); those positions are ignored\n";
  info.lines.assign(info.program.size(), {});
  for (std::int64_t a = 0; a < size; ++a) {
    auto [file, line] = table.at(a);
    info.lines[static_cast<std::size_t>(a)] = {file, line};
  }
  return true;
}

}  // namespace tmcl::debug
