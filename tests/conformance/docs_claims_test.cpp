// The conformance tables are the one source of "modelled or not" (issue 41, 3): a "not modelled"
// claim in docs/motion.md or docs/errata.md must not name an axis parameter that the table of a
// module it speaks of marks `simulated`. A claim names its parameters in parentheses, "(21)",
// "(24, 25)", "(216-218)"; the modules it speaks of are those whose profile's motion core the
// section's heading names in backticks ("## The `tmc5160` core": the TMCM-1260), or every module
// under a heading that names no core. docs/conformance/README.md, *What checks the tables*.
#include <algorithm>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "check.hpp"
#include "conformance_table.hpp"

namespace {

struct Claim {
  std::string file;
  int line = 0;  // where its paragraph starts
  std::string text;
  std::vector<std::string> cores;  // the heading's backticked core names; empty: every module
};

// The cores of motion_cores.def (a heading that names one in backticks speaks of that core).
const std::vector<std::string>& core_names() {
  static const std::vector<std::string> names{
#define TMCL_MOTION_CORE(NAME) #NAME,
#include "tmcl/motion_cores.def"
#undef TMCL_MOTION_CORE
  };
  return names;
}

// The sentences (up to a full stop and a blank, or a paragraph's end: "5.1" goes on) that say
// "not modelled", with the line their paragraph starts on.
std::vector<Claim> claims(const std::string& name) {
  std::ifstream in(conformance::kRoot / "docs" / name);
  std::vector<Claim> out;
  std::vector<std::string> cores;
  std::string para, line;
  int para_line = 0, n = 0;
  auto flush = [&] {
    std::size_t start = 0;
    int at = para_line;
    for (std::size_t i = 0; i <= para.size(); ++i) {
      const bool end = i == para.size() || (para[i] == '.' && i + 1 < para.size() && para[i + 1] == ' ');
      if (!end) continue;
      std::string s = para.substr(start, i - start);
      std::string low = s;
      for (char& c : low) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (low.find("not modelled") != std::string::npos) out.push_back({name, at, s, cores});
      start = i + 1;
    }
    para.clear();
  };
  while (std::getline(in, line)) {
    ++n;
    if (line.rfind('#', 0) == 0) {
      flush();
      cores.clear();
      for (const auto& c : core_names())
        if (line.find("`" + c + "`") != std::string::npos) cores.push_back(c);
      continue;
    }
    const bool item = line.rfind("- ", 0) == 0 || std::regex_search(line, std::regex("^[0-9]+\\. "));
    if (conformance::trim(line).empty() || item) flush();
    if (conformance::trim(line).empty()) continue;
    if (para.empty()) para_line = n;
    para += (para.empty() ? "" : " ") + conformance::trim(line);
  }
  flush();
  return out;
}

// The parameter numbers a claim names in parentheses: lists and ranges of numbers 0..255.
std::vector<int> named(const std::string& text) {
  std::vector<int> out;
  static const std::regex group("\\(([0-9]{1,3}(?:\\s*(?:,|-|–)\\s*[0-9]{1,3})*)\\)");
  for (std::sregex_iterator it(text.begin(), text.end(), group), e; it != e; ++it) {
    const std::string g = (*it)[1];
    static const std::regex num("([0-9]{1,3})(?:\\s*(?:-|–)\\s*([0-9]{1,3}))?");
    for (std::sregex_iterator n(g.begin(), g.end(), num), ne; n != ne; ++n) {
      const int a = std::stoi((*n)[1]), b = (*n)[2].matched ? std::stoi((*n)[2]) : a;
      for (int k = a; k <= b && k <= 255; ++k) out.push_back(k);
    }
  }
  return out;
}

}  // namespace

TEST(docs_say_not_modelled_only_where_the_tables_do) {
  std::map<std::string, conformance::Table> tables;
  for (const tmcl::Profile* p : conformance::modules()) tables[std::string(p->name)] = conformance::read_table(conformance::table_file(*p));
  int checked = 0;
  for (const char* file : {"motion.md", "errata.md"})
    for (const Claim& c : claims(file))
      for (int param : named(c.text))
        for (const tmcl::Profile* p : conformance::modules()) {
          const std::string core(p->default_motion);
          if (!c.cores.empty() && std::find(c.cores.begin(), c.cores.end(), core) == c.cores.end()) continue;
          for (const conformance::Row& r : tables[std::string(p->name)].rows[conformance::Section::Axis]) {
            if (r.key != std::to_string(param)) continue;
            ++checked;
            if (r.status == "simulated")
              tmcl_test::fail(__FILE__, __LINE__,
                              "docs/" + c.file + ":" + std::to_string(c.line) + " says axis parameter " + std::to_string(param) +
                                  " is not modelled, but docs/conformance/" + std::string(p->name) + ".md:" +
                                  std::to_string(r.line) + " marks it simulated: \"" + c.text + "\"");
          }
        }
  CHECK(checked > 0);  // the claims are found at all
}
