// Download, verify and upload of program memory (transfer.hpp).
#include "tmcl/host/transfer.hpp"

#include "tmcl/asm/disasm.hpp"

namespace tmcl::host {
namespace {

constexpr std::uint8_t kDownload = static_cast<std::uint8_t>(Op::EnterDownloadMode);
constexpr std::uint8_t kEndDownload = static_cast<std::uint8_t>(Op::ExitDownloadMode);
constexpr std::uint8_t kRead = static_cast<std::uint8_t>(Op::ReadProgramMemory);

Outcome outcome_of(const Result& r) {
  switch (r.fail) {
    case Fail::None: return Outcome::Ok;
    case Fail::NoReply: return Outcome::NoReply;
    case Fail::Port: return Outcome::Port;
    case Fail::Cancelled: return Outcome::Cancelled;
  }
  return Outcome::Port;
}

TransferResult failed(const Result& r, int done) { return TransferResult{outcome_of(r), r.error, done}; }

TransferResult bad_status(const Client& c, const Instruction& ins, const Reply& reply, int done, const std::string& where) {
  return TransferResult{Outcome::BadStatus,
                        where + ": the module answered " + std::to_string(reply.status) + " (" + status_text(reply.status) +
                            ") to " + c.describe(ins),
                        done};
}

}  // namespace

Result store(Client& client, std::int32_t address, const Instruction& ins) {
  Result r;
  // A lost store reply: set the pointer again and resend, as often as other requests are retried.
  for (int attempt = 1;; ++attempt) {
    r = client.request(ins, false);
    if (r.ok() || r.fail != Fail::NoReply || attempt > client.options().retries) break;
    // The store may or may not have happened: point the module at this address again.
    const Instruction again{kDownload, 0, 0, address};
    Result p = client.request(again);
    if (!p.ok()) return p;
  }
  return r;
}

TransferResult download(Client& client, const std::vector<Instruction>& program, int from, int memory, const Progress& progress) {
  const int total = static_cast<int>(program.size());
  const Instruction enter{kDownload, 0, 0, from};
  Result r = client.request(enter);
  if (!r.ok()) return failed(r, from);
  if (r.reply.status != kStatusOk) return bad_status(client, enter, r.reply, from, "entering download mode");
  TransferResult result{Outcome::Ok, "", from};
  for (int i = from; i < total; ++i) {
    const Instruction& ins = program[static_cast<std::size_t>(i)];
    r = store(client, i, ins);
    if (!r.ok()) {
      result = failed(r, i);
      break;
    }
    if (r.reply.status != kStatusLoaded) {
      result = bad_status(client, ins, r.reply, i, "address " + std::to_string(i));
      break;
    }
    result.done = i + 1;
    if (progress) progress(i + 1, total);
  }
  // End marker (opcode 0, errata S7) where it fits: memory beyond the program reads as its end.
  if (result.outcome == Outcome::Ok && (memory <= 0 || total < memory)) {
    const Instruction end{0, 0, 0, 0};
    r = client.request(end);  // idempotent: it only ends program memory at this address
    if (!r.ok()) result = failed(r, total);
  }
  // Leave download mode in every case where the module still listens.
  if (result.outcome != Outcome::NoReply && result.outcome != Outcome::Port) {
    Result q = client.request(Instruction{kEndDownload, 0, 0, 0});
    if (result.outcome == Outcome::Ok && !q.ok()) result = failed(q, total);
  }
  return result;
}

TransferResult verify(Client& client, const std::vector<Instruction>& program, int from, int memory, const Progress& progress) {
  const int total = static_cast<int>(program.size());
  const int last = (memory <= 0 || total < memory) ? total : total - 1;  // the end marker too, where it fits
  for (int i = from; i <= last; ++i) {
    const Instruction want = i < total ? program[static_cast<std::size_t>(i)] : Instruction{};
    const Instruction read{kRead, 0, 0, i};
    Reply got;
    for (int attempt = 0; attempt < 2; ++attempt) {  // a mismatch is read once more before it counts
      Result r = client.request(read);
      if (!r.ok()) return failed(r, i);
      if (r.reply.status != kStatusOk) return bad_status(client, read, r.reply, i, "verifying address " + std::to_string(i));
      got = r.reply;
      if (i < total ? got.stored == want : got.stored.op == 0) break;
    }
    if (i < total ? !(got.stored == want) : got.stored.op != 0) {
      const std::string expected = i < total ? format_instruction(want) : "the end marker (opcode 0)";
      return TransferResult{Outcome::Mismatch,
                            "verification error at address " + std::to_string(i) + ": expected " + expected + ", read " +
                                format_instruction(got.stored),
                            i};
    }
    if (progress && i < total) progress(i + 1, total);
  }
  return TransferResult{Outcome::Ok, "", total};
}

TransferResult upload(Client& client, int memory, std::vector<Instruction>& program, const Progress& progress) {
  // 134's reply does not name the address it answers, so a stale copy of the previous reply
  // cannot be told from the right one (errata H1): every address is read until two reads agree.
  const int max_reads = 2 + client.options().retries;
  program.clear();
  for (int i = 0; memory <= 0 || i < memory; ++i) {
    const Instruction read{kRead, 0, 0, i};
    Instruction word;
    bool agreed = false, past_end = false;
    for (int n = 0; n < max_reads && !agreed; ++n) {
      Result r = client.request(read);
      if (!r.ok()) return failed(r, i);
      if (r.reply.status == 4 && r.reply.op == kRead) {  // past the end of program memory
        past_end = true;
        break;
      }
      if (r.reply.status != kStatusOk) return bad_status(client, read, r.reply, i, "reading address " + std::to_string(i));
      agreed = n > 0 && r.reply.stored == word;
      word = r.reply.stored;
    }
    if (past_end) break;
    if (!agreed)
      return TransferResult{Outcome::NoReply,
                            "address " + std::to_string(i) + " read differently " + std::to_string(max_reads) +
                                " times in a row: the line is too unreliable to upload over",
                            i};
    if (word.op == 0) break;
    program.push_back(word);
    if (progress) progress(i + 1, 0);
  }
  return TransferResult{Outcome::Ok, "", static_cast<int>(program.size())};
}

}  // namespace tmcl::host
