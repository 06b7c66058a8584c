// The bundled include files: those of include_files/ (compiled in when CMake configures) and, for
// each bundled module that has no file of its own there, one generated from its profile
// (TMCM-1260.inc: tmcl/param_names.hpp), so every module's parameters have names a program can
// #include and the names follow the profile, the one source of the parameters.
#include "tmcl/asm/assembler.hpp"
#include "tmcl/param_names.hpp"
#include "tmcl/profile.hpp"

namespace tmcl {

const std::map<std::string, std::string_view>& bundled_includes() {
  static const auto* files = [] {
    static std::vector<std::string> generated;  // owns the texts the map points into
    auto* all = new std::map<std::string, std::string_view>(include_file_texts());
    std::vector<std::pair<std::string, std::string>> made;
    for (const Profile* p : all_profiles())
      if (!p->any_parameter && p->include_file.empty()) made.emplace_back(parameter_include_name(*p), parameter_include_text(*p));
    generated.reserve(made.size());
    for (auto& [name, text] : made) {
      generated.push_back(std::move(text));
      all->emplace(name, generated.back());
    }
    return all;
  }();
  return *files;
}

}  // namespace tmcl
