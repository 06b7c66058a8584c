// The platform layer, files: what opening, syncing and replacing a file, and finding the user's
// configuration folder, mean on this system. One implementation per system, chosen when CMake
// configures (os_files_posix.cpp, os_files_windows.cpp); the callers (fileio.cpp, targets.cpp)
// stay the same everywhere.
#pragma once

#include <sys/stat.h>

#include <string>
#include <string_view>
#include <vector>

namespace tmcl::os {

// Flags added to every open(): bytes as they are (Windows' C library would otherwise turn
// "\n" into "\r\n"), and not inherited by child processes.
extern const int kOpenFlags;

// The name to open for `path`: on Windows "/dev/null" is "NUL" (what scripts written for a
// POSIX shell, and the tests, pass); elsewhere `path` itself.
std::string native_path(const std::string& path);
// Paths as this system spells them. POSIX: '/' between folders, absolute from '/'. Windows: '/'
// or '\' between folders, absolute from either or from a drive ("C:\a", "C:/a", "\\server\s").
bool is_separator(char c);
bool has_separator(std::string_view path);
bool is_absolute(std::string_view path);
// The position of the path's last folder separator, or npos.
std::size_t last_separator(std::string_view path);
// NAME in FOLDER ("" is the current folder), with the separator FOLDER already uses: on Windows
// "C:\work" and "lib\a.inc" make "C:\work\lib\a.inc", not a mix; elsewhere '/'.
std::string join_path(const std::string& folder, const std::string& name);
// A path written on Windows, as an #include of a TMCL-IDE program is ("lib\motor.inc"), as this
// system reads it: on POSIX every '\' is a folder separator '/' (a file name with a backslash in
// it cannot be included); on Windows the path as it is.
std::string portable_path(std::string path);
// PATH without "." and "x/.." steps, as a diagnostic names a file: with '/' between folders, but
// on Windows with '\' when the path has one ("C:\work\lib/../a.inc" is "C:\work\a.inc").
std::string normal_path(const std::string& path);
// Whether PATH names a device by a reserved name, not a file: on Windows NUL, CON, AUX, PRN,
// COM1-9 and LPT1-9, in any case, with a "\\.\" before or a ':' after ("nul", "\\.\NUL");
// never elsewhere (there stat() tells).
bool is_device_name(std::string_view path);
// Splits a search path such as TMCL_PROFILE_PATH into its folders (empty ones dropped): at ':'
// on POSIX; on Windows at ';' and at a ':' that does not follow a drive letter ("C:\a;D:\b",
// "lib:C:/x").
std::vector<std::string> split_path_list(const std::string& list);
// Flushes the file's data to the disk (fsync). False with errno set.
bool sync_file(int fd);
// Renames `from` to `to`, replacing `to` if it exists, in one step a reader never sees half of.
// False with errno set.
bool replace_file(const std::string& from, const std::string& to);
// The file's absolute name with links resolved (realpath), or "" when it cannot be had.
std::string real_path(const std::string& path);
// A file's modification time in nanoseconds since the epoch (as precise as the system keeps it).
long long modified_ns(const struct stat& st);
// The user's folders for tmcl's configuration `leaf` (e.g. "profiles"), in search order:
// $XDG_CONFIG_HOME/tmcl/LEAF or ~/.config/tmcl/LEAF; on Windows %APPDATA%\tmcl\LEAF first.
std::vector<std::string> config_dirs(const std::string& leaf);

}  // namespace tmcl::os
