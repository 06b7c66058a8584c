// Unit tests of -t NAME|PATH (vm/isa/targets.cpp): the search path and its order, a user's
// profile read again when it changes, based-on a hidden profile of the same name, cycles of
// based-on lines, the list of targets and the first-line comment.
#include "check.hpp"
#include "os_test.hpp"


#include <cstdlib>
#include <fstream>
#include <string>

#include "tmcl/targets.hpp"

namespace {

struct TempDir {
  std::string path;
  TempDir() {
    path = tmcl_test::make_temp_dir("tmcl-targets");
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const std::string p = path + "/" + name;
    std::ofstream(p) << text;
    return p;
  }
};

std::string profile_text(const std::string& name, int motors, const std::string& extra = "") {
  return "tmcl-profile 1\nname " + name + "\nfirmware 0042V100\nmotors " + std::to_string(motors) +
         "\nprogram-memory 100\ncommands 1-6\n" + extra;
}

}  // namespace

TEST(a_path_is_read_and_a_name_is_searched_in_order) {
  TempDir a, b;
  a.write("mod.profile", profile_text("mod", 2));
  b.write("mod.profile", profile_text("mod", 3));
  b.write("other.profile", profile_text("other", 4));
  tmcl::TargetSearch s{{a.path, b.path}};
  auto r = tmcl::resolve_target("mod", s);
  CHECK(r.profile && r.profile->motors == 2);  // the first folder wins
  r = tmcl::resolve_target("other", s);
  CHECK(r.profile && r.profile->motors == 4);
  r = tmcl::resolve_target(b.path + "/mod.profile", s);
  CHECK(r.profile && r.profile->motors == 3);
  CHECK_EQ(r.profile->origin, b.path + "/mod.profile");
  r = tmcl::resolve_target("usb-2-sd", s);  // then the bundled ones
  CHECK(r.profile && r.profile->origin == "bundled");
  r = tmcl::resolve_target("moe", s);
  CHECK(!r.profile && r.usage);
  // The message names no list of targets: a new profile changes no message (issue 35).
  CHECK_EQ(r.error, "unknown target 'moe'; did you mean 'mod'? (see tmclasm --list-targets; or a profile file, docs/profiles.md)");
  r = tmcl::resolve_target("", s);
  CHECK(!r.profile && r.usage);
}

TEST(a_changed_file_is_read_again_and_the_old_profile_stays_valid) {
  TempDir d;
  const std::string path = d.write("mod.profile", profile_text("mod", 2));
  tmcl::TargetSearch s{{}};
  const tmcl::Profile* first = tmcl::resolve_target(path, s).profile;
  CHECK(first && first->motors == 2);
  CHECK_EQ(tmcl::resolve_target(path, s).profile, first);  // the same file: read once
  d.write("mod.profile", profile_text("mod", 5, "# now longer\n"));
  const tmcl::Profile* second = tmcl::resolve_target(path, s).profile;
  CHECK(second && second->motors == 5);
  CHECK(first != second);
  CHECK_EQ(first->name, "mod");  // still readable
  d.write("mod.profile", "tmcl-profile 1\nmotors x\n");
  auto bad = tmcl::resolve_target(path, s);
  CHECK(!bad.profile && !bad.usage && !bad.diags.empty());
  CHECK(bad.message().find("mod.profile:2:8: error: expected a motor count") != std::string::npos);
}

TEST(based_on_its_own_name_means_the_hidden_one) {
  TempDir d;
  d.write("usb-2-sd.profile", "tmcl-profile 1\nname usb-2-sd\nbased-on usb-2-sd\nmotors 3\n");
  d.write("a.profile", "tmcl-profile 1\nname a\nbased-on b\n");
  d.write("b.profile", "tmcl-profile 1\nname b\nbased-on a\n");
  tmcl::TargetSearch s{{d.path}};
  auto r = tmcl::resolve_target("usb-2-sd", s);
  CHECK(r.profile && r.profile->motors == 3 && r.profile->program_memory == 577);
  r = tmcl::resolve_target("a", s);  // a cycle: an error at the based-on line, not a hang
  CHECK(!r.profile);
  CHECK(r.message().find("a.profile:3:10: error: based-on cycle: a -> b -> a\n") != std::string::npos);
  r = tmcl::resolve_target("b", s);  // told from b
  CHECK(r.message().find("b.profile:3:10: error: based-on cycle: b -> a -> b\n") != std::string::npos);
}

// The file skipped is the file itself, however -t spells its path: "dir//usb-2-sd.profile" and
// "./usb-2-sd.profile" are the search path's dir/usb-2-sd.profile, not a cycle on itself. Each
// spelling in a folder of its own, as the cache knows a file once read.
TEST(based_on_its_own_name_means_the_hidden_one_whatever_the_path_spelling) {
  const std::string text = "tmcl-profile 1\nname usb-2-sd\nbased-on usb-2-sd\nmotors 3\n";
  TempDir d, e;
  d.write("usb-2-sd.profile", text);
  e.write("usb-2-sd.profile", text);
  auto r = tmcl::resolve_target(d.path + "//usb-2-sd.profile", tmcl::TargetSearch{{d.path}});
  CHECK(r.profile && r.profile->motors == 3 && r.profile->program_memory == 577);
  CHECK_EQ(r.message(), "");
  r = tmcl::resolve_target(e.path + "/./usb-2-sd.profile", tmcl::TargetSearch{{e.path + "/"}});
  CHECK(r.profile && r.profile->motors == 3 && r.profile->program_memory == 577);
  CHECK_EQ(r.message(), "");
}

// A file's error that came from a cycle depends on the other files: once a is mended, b (which
// did not change) is read again and is fine. The language server asks again at every edit.
TEST(a_mended_cycle_is_read_again) {
  TempDir d;
  d.write("a.profile", "tmcl-profile 1\nname a\nbased-on b\n");
  d.write("b.profile", "tmcl-profile 1\nname b\nbased-on a\nmotors 2\n");
  tmcl::TargetSearch s{{d.path}};
  CHECK(!tmcl::resolve_target("b", s).profile);
  d.write("a.profile", "tmcl-profile 1\nname a\nbased-on usb-2-sd\n# no longer based on b\n");
  auto r = tmcl::resolve_target("b", s);
  CHECK(r.profile && r.profile->motors == 2 && r.profile->program_memory == 577);
  // Based on itself, with no other profile of that name to mean: a cycle of one.
  d.write("self.profile", "tmcl-profile 1\nname self\nbased-on self\n");
  r = tmcl::resolve_target("self", s);
  CHECK(!r.profile && r.message().find("self.profile:3:10: error: based-on cycle: self -> self (") != std::string::npos);
}

TEST(the_file_name_and_the_name_inside_agree) {
  TempDir d;
  d.write("mod.profile", profile_text("other", 2));
  auto r = tmcl::resolve_target("mod", tmcl::TargetSearch{{d.path}});
  CHECK(!r.profile && !r.usage);
  CHECK(r.message(20, "tool").find("tool: error: ") == 0);
  CHECK(r.error.find("says 'name other'") != std::string::npos);
}

#ifndef _WIN32
TEST(the_search_path_comes_from_the_environment) {
  tmcl_test::set_env("TMCL_PROFILE_PATH", "/a::/b");
  tmcl_test::set_env("HOME", "/home/u");
  tmcl_test::unset_env("XDG_CONFIG_HOME");
  auto s = tmcl::TargetSearch::from_environment();
  CHECK(s.dirs == (std::vector<std::string>{"/a", "/b", "/home/u/.config/tmcl/profiles"}));
  tmcl_test::set_env("XDG_CONFIG_HOME", "/x");
  tmcl_test::unset_env("TMCL_PROFILE_PATH");
  s = tmcl::TargetSearch::from_environment();
  CHECK(s.dirs == (std::vector<std::string>{"/x/tmcl/profiles"}));
  tmcl_test::set_env("XDG_CONFIG_HOME", "relative");  // not absolute: ignored, as the XDG rules say
  s = tmcl::TargetSearch::from_environment();
  CHECK(s.dirs == (std::vector<std::string>{"/home/u/.config/tmcl/profiles"}));
}
#else
// Windows: the list is separated by ';' (or ':' that does not follow a drive letter), and
// %APPDATA%\tmcl\profiles comes before the folder of HOME or XDG_CONFIG_HOME (docs/profiles.md).
TEST(the_search_path_comes_from_the_environment) {
  tmcl_test::set_env("TMCL_PROFILE_PATH", "C:\\a;;D:\\b:E:/c");
  tmcl_test::set_env("APPDATA", "C:\\Users\\u\\AppData\\Roaming");
  tmcl_test::set_env("HOME", "C:/home/u");
  tmcl_test::unset_env("XDG_CONFIG_HOME");
  auto s = tmcl::TargetSearch::from_environment();
  CHECK(s.dirs == (std::vector<std::string>{"C:\\a", "D:\\b", "E:/c", "C:\\Users\\u\\AppData\\Roaming\\tmcl\\profiles",
                                            "C:/home/u/.config/tmcl/profiles"}));
  tmcl_test::unset_env("APPDATA");
  tmcl_test::unset_env("TMCL_PROFILE_PATH");
  tmcl_test::set_env("XDG_CONFIG_HOME", "C:/x");
  s = tmcl::TargetSearch::from_environment();
  CHECK(s.dirs == (std::vector<std::string>{"C:/x/tmcl/profiles"}));
}
#endif

TEST(list_targets_shows_every_profile_and_what_hides_what) {
  TempDir d;
  d.write("usb-2-sd.profile", "tmcl-profile 1\nname usb-2-sd\ntitle \"mine\"\nbased-on usb-2-sd\n");
  d.write("bad.profile", "tmcl-profile 1\nmotors 0\n");
  d.write("notes.txt", "not a profile");
  auto list = tmcl::list_targets(tmcl::TargetSearch{{d.path}});
  bool mine = false, hidden = false, bad = false, pd60 = false;
  for (const auto& e : list) {
    mine = mine || (e.name == "usb-2-sd" && e.title == "mine" && e.shadowed_by.empty());
    hidden = hidden || (e.name == "usb-2-sd" && e.origin == "bundled" && e.shadowed_by == d.path + "/usb-2-sd.profile");
    bad = bad || (e.name == "bad" && !e.error.empty());
    pd60 = pd60 || e.name == "notes";
  }
  CHECK(mine && hidden && bad && !pd60);
  CHECK(list.size() == tmcl::all_profiles().size() + 2 + [] {
          std::size_t aliases = 0;
          for (const auto* p : tmcl::all_profiles()) aliases += p->aliases.size();
          return aliases;
        }());
  const std::string table = tmcl::format_target_list(list);
  CHECK(table.rfind("NAME", 0) == 0);
  CHECK(table.find("(hidden by " + d.path + "/usb-2-sd.profile)") != std::string::npos);
}

TEST(the_first_line_names_a_target) {
  auto c = tmcl::target_comment("// tmcl-target: tmcm-1110\n  SAP 4, 0, 1\n");
  CHECK(c && c->name == "tmcm-1110" && c->col == 17);
  c = tmcl::target_comment("\xEF\xBB\xBF  //tmcl-target:   my.profile  // more\r\n");
  CHECK(c && c->name == "my.profile" && c->col == 20);
  CHECK(!tmcl::target_comment("SAP 4, 0, 1 // tmcl-target: x\n"));
  CHECK(!tmcl::target_comment("\n// tmcl-target: x\n"));  // the first line only
  CHECK(!tmcl::target_comment("// tmcl-target:\n"));
  CHECK(!tmcl::target_comment("// TMCL-TARGET: x\n"));
  CHECK(!tmcl::target_comment(""));
  TempDir d;
  CHECK_EQ(tmcl::target_named_by_file(d.write("p.tmc", "// tmcl-target: usb-2-sd\nSTOP\n"), "generic"), "usb-2-sd");
  CHECK_EQ(tmcl::target_named_by_file(d.write("q.tmc", "STOP\n"), "generic"), "generic");
  CHECK_EQ(tmcl::target_named_by_file(d.path + "/none.tmc", "generic"), "generic");
  CHECK_EQ(tmcl::target_named_by_file("-", "generic"), "generic");
}
