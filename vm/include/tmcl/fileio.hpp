// Whole-file reading and crash-safe writing shared by the tools.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tmcl {

// Reads a whole file ("-" = standard input). False with `error` set when it cannot.
bool read_file(const std::string& path, std::vector<std::uint8_t>& out, std::string& error);
// Writes through a temporary file in the same folder and a rename, so that a reader never sees
// a half-written file and an old file survives a failed or killed write. With `durable` the data
// is also flushed to the disk before the rename (survives a power cut; costs milliseconds).
// "-" = standard output; an existing device or pipe is written into directly.
bool write_file_atomic(const std::string& path, const std::vector<std::uint8_t>& data, std::string& error,
                       bool durable = false);

}  // namespace tmcl
