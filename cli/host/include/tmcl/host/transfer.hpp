// Program memory transfers over a Client: download (132, one store per instruction, an opcode-0
// end marker, 133), verify (134 type 0 at every address, compared), upload (134 from address 0
// up to the end marker) — the sequences of the TMCL-IDE, PyTrinamic's LoadTMCLBinary.py and
// go-tmcl's tmcl-flash, with recovery: a store whose reply is lost is not simply resent (that
// would store it twice) but the download pointer is set again with 132 first.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tmcl/host/client.hpp"
#include "tmcl/isa.hpp"

namespace tmcl::host {

enum class Outcome : std::uint8_t { Ok, NoReply, Port, BadStatus, Mismatch, Cancelled };

struct TransferResult {
  Outcome outcome = Outcome::Ok;
  std::string message;  // what went wrong, naming the address
  int done = 0;         // instructions stored, verified or read when it ended
};

// Called after each instruction with (done, total); total is 0 when unknown (upload).
using Progress = std::function<void(int done, int total)>;

// In download mode with the pointer at `address` (132 sent): stores `ins` there. A store whose
// reply is lost is not simply sent again (it would be stored twice, at the next address): 132
// sets the pointer back to `address` first, as often as the client retries. The reply's status
// is the caller's to check (101: stored).
Result store(Client& client, std::int32_t address, const Instruction& ins);
// Stores program[from..] at addresses from.. and leaves download mode (also when cancelled or
// failing, if the module still answers). `memory` is the module's program memory in instructions
// (0: unknown): the end marker is sent only where it fits.
TransferResult download(Client& client, const std::vector<Instruction>& program, int from, int memory, const Progress& progress);
// Reads addresses from..size-1 back and compares; then, if it fits in `memory`, the end marker.
TransferResult verify(Client& client, const std::vector<Instruction>& program, int from, int memory, const Progress& progress);
// Reads program memory from address 0 until the end marker, the end of memory (`memory` > 0) or
// status 4 (an address past the end).
TransferResult upload(Client& client, int memory, std::vector<Instruction>& program, const Progress& progress);

}  // namespace tmcl::host
