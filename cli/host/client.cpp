// Request and reply matching for the host side of the TMCL protocol (client.hpp). Frames are
// encoded and decoded with the project's one codec (tmcl/codec.hpp).
#include "tmcl/host/client.hpp"

#include <cctype>
#include <cstdio>

#include "tmcl/asm/disasm.hpp"
#include "tmcl/codec.hpp"
#include "tmcl/params.hpp"

namespace tmcl::host {
namespace {

constexpr std::size_t kFrame = 9;
constexpr auto kQuietGap = std::chrono::milliseconds(20);  // a lone bad window is a corrupted reply after this

bool checksum_ok(const std::uint8_t* p) { return frame_checksum_ok(p); }

bool known_status(std::uint8_t s) { return (s >= kStatusWrongChecksum && s <= kStatusNotAvailable) || s == kStatusOk || s == kStatusLoaded || s == kStatusPositionReached; }


bool special_134(const Instruction& ins) { return ins.op == static_cast<std::uint8_t>(Op::ReadProgramMemory) && ins.type == 0; }
bool special_136(const Instruction& ins) { return ins.op == static_cast<std::uint8_t>(Op::GetFirmwareVersion) && ins.type == 0; }

}  // namespace

std::string hex(const std::uint8_t* p, std::size_t n) {
  std::string s;
  char b[4];
  for (std::size_t i = 0; i < n; ++i) {
    std::snprintf(b, sizeof b, i ? " %02X" : "%02X", p[i]);
    s += b;
  }
  return s;
}

std::string status_text(std::uint8_t status) {
  switch (status) {
    case kStatusWrongChecksum: return "wrong checksum";
    case kStatusInvalidCommand: return "invalid command";
    case kStatusWrongType: return "wrong type";
    case kStatusInvalidValue: return "invalid value";
    case kStatusEepromLocked: return "configuration EEPROM locked";
    case kStatusNotAvailable: return "command not available";
    case kStatusOk: return "success";
    case kStatusLoaded: return "command loaded";
    case kStatusPositionReached: return "position reached";
    default: return "status " + std::to_string(status);
  }
}

std::string Client::describe(const Instruction& ins) const {
  const Frame d = encode_request(opt_.module, ins);
  const OpInfo* info = op_info(ins.op);
  std::string text = info && info->control ? std::to_string(ins.op) + " (" + std::string(info->meaning) + ") type " +
                                                 std::to_string(ins.type) + ", value " + std::to_string(ins.value)
                                           : format_instruction(ins);
  return text + " [" + hex(d.data(), d.size()) + "] to module " + std::to_string(opt_.module) + " on " + port_.name();
}

std::vector<Reply> Client::take_events() {
  std::vector<Reply> e;
  e.swap(events_);
  return e;
}

bool Client::send(const Instruction& ins, std::string& error) {
  const Frame d = encode_request(opt_.module, ins);
  if (opt_.on_frame) opt_.on_frame(true, d.data(), d.size());
  return port_.write_all(d.data(), d.size(), Clock::now() + std::chrono::milliseconds(opt_.timeout_ms), error);
}

// Looks at the buffered bytes: drops what is not the reply to `ins`, keeps events, and finds the
// reply (the last matching one buffered). Corrupt: a window that cannot be a frame was dropped.
Client::Scan Client::scan(const Instruction& ins, Reply& found) {
  Scan result = Scan::Need;
  std::size_t head = 0;
  auto frame_to_host = [&](const std::uint8_t* p) { return checksum_ok(p) && p[0] == opt_.host; };
  auto ordinary_elsewhere = [&](const std::uint8_t* p) { return p[1] != opt_.module && known_status(p[2]); };
  while (rx_.size() - head >= kFrame) {
    const std::uint8_t* p = rx_.data() + head;
    if (special_136(ins) && p[0] == opt_.host) {
      bool text = true;
      for (std::size_t i = 1; i < kFrame; ++i) text = text && std::isprint(p[i]);
      if (text) {
        found = Reply{kStatusOk, ins.op, 0, {}, {}, std::string(p + 1, p + kFrame)};
        std::copy(p, p + kFrame, found.bytes.begin());
        if (opt_.on_frame) opt_.on_frame(false, p, kFrame);
        result = Scan::Found;
        head += kFrame;
        continue;
      }
    }
    if (checksum_ok(p) && p[0] == opt_.host) {
      if (opt_.on_frame) opt_.on_frame(false, p, kFrame);
      const bool from_module = p[1] == opt_.module;
      const bool ordinary = from_module && known_status(p[2]);
      if (ordinary && p[2] == kStatusPositionReached && p[3] == static_cast<std::uint8_t>(Op::PositionReachedEvent)) {
        const tmcl::Reply r = decode_reply(p);
        Reply ev{r.status, r.op, r.value, {}, {}, {}};
        std::copy(p, p + kFrame, ev.bytes.begin());
        events_.push_back(ev);
        ++stats_.events;
      } else if (ordinary && p[3] == ins.op) {
        const tmcl::Reply r = decode_reply(p);
        found = Reply{r.status, r.op, r.value, {}, {}, {}};
        std::copy(p, p + kFrame, found.bytes.begin());
        result = Scan::Found;
      } else if (special_134(ins) && !ordinary) {
        // The stored instruction in place of module address, status and command. A frame that
        // reads as an ordinary reply to another command is a stale one, not memory contents.
        found = Reply{kStatusOk, ins.op, 0, {}, decode7(p + 1), {}};
        std::copy(p, p + kFrame, found.bytes.begin());
        result = Scan::Found;
      } else {
        ++stats_.drained;  // another module, another command, or stale
        if (ordinary_elsewhere(p)) {
          if (strays_.size() >= 64) strays_.erase(strays_.begin());
          const tmcl::Reply r = decode_reply(p);
          strays_.push_back(Reply{r.status, r.op, r.value, {}, {}, {}});
          std::copy(p, p + kFrame, strays_.back().bytes.begin());
        }
      }
      head += kFrame;
      continue;
    }
    if (checksum_ok(p)) {  // a frame for another host (a request on a shared bus, an echo)
      ++stats_.drained;
      head += kFrame;
      continue;
    }
    // A bad window: garbage before a frame, or a corrupted frame.
    std::size_t skip = 0;
    for (std::size_t k = 1; k < kFrame && head + k + kFrame <= rx_.size(); ++k)
      if (frame_to_host(p + k)) {
        skip = k;
        break;
      }
    if (skip) {
      head += skip;
      continue;
    }
    if (rx_.size() - head < 2 * kFrame - 1) break;  // a later start may still complete
    ++stats_.corrupted;
    if (result != Scan::Found) result = Scan::Corrupt;
    head += kFrame;
  }
  rx_.erase(rx_.begin(), rx_.begin() + static_cast<std::ptrdiff_t>(head));
  return result;
}

std::vector<Reply> Client::take_strays() {
  std::vector<Reply> s;
  s.swap(strays_);
  return s;
}

void Client::listen(Clock::time_point until) {
  std::uint8_t buf[512];
  std::string error;
  long n;
  Reply none;
  while ((n = port_.read_some(buf, sizeof buf, until, error)) > 0) {
    rx_.insert(rx_.end(), buf, buf + n);
    scan(Instruction{0, 0, 0, 0}, none);
  }
  unclean_ = true;
}

void Client::drain_now() {
  std::uint8_t buf[512];
  std::string error;
  long n;
  while ((n = port_.read_some(buf, sizeof buf, Clock::time_point{}, error)) > 0) rx_.insert(rx_.end(), buf, buf + n);
  // Route events, count the rest as stale: nothing was asked yet.
  Reply none;
  scan(Instruction{0, 0, 0, 0}, none);
  stats_.drained += rx_.empty() ? 0 : 1;
  rx_.clear();
}

void Client::settle(Clock::time_point until) {
  std::uint8_t buf[512];
  std::string error;
  while (port_.read_some(buf, sizeof buf, until, error) > 0) {
  }
  rx_.clear();
}

Result Client::request(const Instruction& ins, bool retry) {
  Result res;
  ++stats_.requests;
  const bool no_reply = ins.op == static_cast<std::uint8_t>(Op::RestoreFactorySettings) && ins.value == 1234;
  const int attempts = retry ? 1 + (opt_.retries > 0 ? opt_.retries : 0) : 1;
  std::string last_problem = "no reply";
  std::uint8_t buf[512];
  for (int attempt = 1; attempt <= attempts; ++attempt) {
    res.attempts = attempt;
    if (attempt > 1) ++stats_.retries;
    // Bytes waiting before a request are late or stale replies: only possible once something
    // went wrong (a timeout, a corrupted or unmatched frame), so a clean line skips the syscall.
    if (unclean_ || attempt > 1) drain_now();
    unclean_ = true;  // until this request ends cleanly
    if (!send(ins, res.error)) {
      res.fail = res.error == "interrupted" ? Fail::Cancelled : Fail::Port;
      return res;
    }
    if (no_reply) {
      res.reply = Reply{kStatusOk, ins.op, ins.value, {}, {}, {}};
      return res;
    }
    const auto deadline = Clock::now() + std::chrono::milliseconds(opt_.timeout_ms);
    const auto drained_before = stats_.drained, corrupted_before = stats_.corrupted;
    auto last_byte = Clock::now();
    bool corrupt = false;
    for (;;) {
      // A bad window with nothing after it: once the line is quiet it is a corrupted reply.
      const bool pending_bad = rx_.size() >= kFrame;
      const auto wait_until = pending_bad ? std::min(deadline, last_byte + kQuietGap) : deadline;
      const long n = port_.read_some(buf, sizeof buf, wait_until, res.error);
      if (n == -2) {
        res.fail = Fail::Cancelled;
        res.error = "interrupted";
        return res;
      }
      if (n < 0) {
        res.fail = Fail::Port;
        return res;
      }
      if (n > 0) {
        last_byte = Clock::now();
        rx_.insert(rx_.end(), buf, buf + n);
      } else if (pending_bad && Clock::now() < deadline) {
        rx_.resize(rx_.size() + kFrame - 1, 0);  // pad: the window is judged now, not at 17 bytes
        if (scan(ins, res.reply) == Scan::Found) return res;
        rx_.clear();
        corrupt = true;
        break;
      }
      const Scan s = scan(ins, res.reply);
      if (s == Scan::Found) {
        // A later matching reply already here wins: a stale copy may precede the real one. Part
        // of a frame after the match is one on its way: wait for it (at most the quiet gap).
        long more = 0;
        while (!rx_.empty() && (more = port_.read_some(buf, sizeof buf, Clock::now() + kQuietGap, res.error)) > 0) {
          rx_.insert(rx_.end(), buf, buf + more);
          scan(ins, res.reply);
        }
        res.error.clear();
        unclean_ = attempt > 1 || stats_.drained != drained_before || stats_.corrupted != corrupted_before;
        return res;
      }
      if (s == Scan::Corrupt) {
        corrupt = true;
        rx_.clear();
        break;
      }
      if (Clock::now() >= deadline) break;
    }
    last_problem = corrupt ? "only a corrupted reply (wrong checksum)" : "no reply within " + std::to_string(opt_.timeout_ms) + " ms";
    if (!corrupt && attempt < attempts) {
      const int s = std::min(opt_.settle_ms, opt_.timeout_ms);
      settle(Clock::now() + std::chrono::milliseconds(s));
    }
  }
  res.fail = Fail::NoReply;
  res.error = last_problem + " to " + describe(ins) + (res.attempts > 1 ? " (" + std::to_string(res.attempts) + " attempts)" : "");
  return res;
}

}  // namespace tmcl::host
