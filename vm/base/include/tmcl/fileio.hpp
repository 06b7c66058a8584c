// Whole-file reading and crash-safe writing shared by the tools, and how their large buffers
// are backed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tmcl {

// Input files are bounded (docs/limits.md): programs and images, scenarios, EEPROM files.
inline constexpr std::size_t kMaxInputBytes = 64u << 20;
inline constexpr std::size_t kMaxScenarioBytes = 16u << 20;
inline constexpr std::size_t kMaxEepromBytes = 1u << 20;

// Reads a whole file ("-" = standard input) of at most `max_bytes`. False with `error` set when
// it cannot, or when the file is larger ("'x' is larger than the limit of 16 MiB").
// The lines of a text file's contents, without their line breaks (a CR before the LF dropped);
// a final line without a line break counts, an empty text has none.
std::vector<std::string> split_lines(const std::string& text);
bool read_file(const std::string& path, std::vector<std::uint8_t>& out, std::string& error,
               std::size_t max_bytes = kMaxInputBytes);
// Writes through a temporary file in the same folder and a rename, so that a reader never sees
// a half-written file and an old file survives a failed or killed write. With `durable` the data
// is also flushed to the disk before the rename (survives a power cut; costs milliseconds).
// "-" = standard output; an existing device or pipe is written into directly.
bool write_file_atomic(const std::string& path, const std::vector<std::uint8_t>& data, std::string& error,
                       bool durable = false);

// Flushes standard output; false with `error` set ("cannot write standard output: No space left
// on device") when it or any earlier write to it failed. The tools call it before they exit, so
// that a full disk or a closed pipe is exit status 74, never a silent success.
bool flush_stdout(std::string& error);

// Asks the kernel to back the buffer [data, data + bytes) with huge pages where it can (Linux
// transparent huge pages; elsewhere nothing). Call it on a freshly reserved buffer before it is
// first written: a program of a million lines touches tens of megabytes once, and faulting them
// in 4 KiB at a time costs more than assembling them on a virtual machine.
void prefer_huge_pages(const void* data, std::size_t bytes);

// The same for the next `bytes` the heap will hand out: a block is taken from the heap, advised
// and given back untouched, so that what is allocated next comes from advised memory. Only where
// the heap is neither trimmed nor bypassed for big blocks (tmclasm's main sets glibc so); elsewhere
// nothing.
void prefer_huge_pages_for_next(std::size_t bytes);

}  // namespace tmcl
