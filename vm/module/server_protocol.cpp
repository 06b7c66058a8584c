// The protocol engine of the virtual module (server.hpp): framing and resynchronisation,
// addresses, status codes, reply suppression, download mode and position-reached events. The
// control commands themselves are in server_control.cpp; the I/O loop in server_io.cpp.
//
// Framing (docs/virtual-module.md, "Resynchronisation"; errata S1): bytes are taken nine at a
// time. A window whose checksum matches is a frame. A window whose checksum does not match is
// either garbage before a frame or a corrupted frame:
//   - if a frame addressed to this module starts 1..8 bytes later (all of its 9 bytes already
//     received, checksum right), the bytes before it are garbage and are dropped silently;
//   - otherwise, once 17 bytes are buffered (every later start has been seen) or the line has
//     been quiet for the resynchronisation gap, the window is a corrupted frame: it is dropped
//     and, if its first byte is this module's address, answered with status 1 and value 0.
// So a torn frame, a garbage burst or a single corrupted byte costs at most the frames it
// overlaps, and the stream realigns on the next intact frame without any timing on the host.
#include <algorithm>

#include "tmcl/codec.hpp"
#include "tmcl/image.hpp"
#include "tmcl/params.hpp"
#include "tmcl/server.hpp"

namespace tmcl {
namespace {

constexpr std::size_t kFrame = kFrameSize;

bool checksum_ok(const std::uint8_t* p) { return frame_checksum_ok(p); }

}  // namespace

TmclModule::TmclModule(Vm& vm, ProtocolOptions options) : vm_(vm), options_(options) {
  apply_address_overrides();
  rx_.reserve(4096);
  out_.reserve(4096);
}

void TmclModule::apply_address_overrides() {
  if (options_.module_address) {
    if (vm_.profile->global_param(0, kGpSerialAddress))
      vm_.bank0[kGpSerialAddress] = *options_.module_address;
    else
      fallback_module_ = *options_.module_address;
  }
  if (options_.host_address) {
    if (vm_.profile->global_param(0, kGpSerialHostAddress))
      vm_.bank0[kGpSerialHostAddress] = *options_.host_address;
    else
      fallback_host_ = *options_.host_address;
  }
}

std::uint8_t TmclModule::module_address() const {
  if (vm_.profile->global_param(0, kGpSerialAddress)) return static_cast<std::uint8_t>(vm_.bank0[kGpSerialAddress]);
  return fallback_module_;
}

std::uint8_t TmclModule::host_address() const {
  if (vm_.profile->global_param(0, kGpSerialHostAddress)) return static_cast<std::uint8_t>(vm_.bank0[kGpSerialHostAddress]);
  return fallback_host_;
}

// ---- framing ----

void TmclModule::receive(const std::uint8_t* data, std::size_t n) {
  rx_.insert(rx_.end(), data, data + n);
  parse();
}

void TmclModule::drop_partial() {
  counters_.skipped_bytes += rx_.size() - head_;
  rx_.clear();
  head_ = 0;
}

bool TmclModule::window_pending() const { return !step_held_ && rx_.size() - head_ >= kFrame; }

void TmclModule::gap_elapsed() {
  if (!window_pending()) return;
  const std::uint8_t* p = rx_.data() + head_;
  ++counters_.bad_checksum;
  if (p[0] == module_address()) {
    reply_module_ = module_address();
    reply_host_ = host_address();
    reply(kStatusWrongChecksum, p[1], 0);
  }
  head_ += kFrame;
  parse();
}

void TmclModule::parse() {
  if (step_held_) return;  // S24: the bytes wait until the step is answered
  for (;;) {
    const std::size_t avail = rx_.size() - head_;
    if (avail < kFrame) break;
    const std::uint8_t* p = rx_.data() + head_;
    if (checksum_ok(p)) {
      head_ += kFrame;
      handle_frame(p);  // may append to out_, never to rx_
      continue;
    }
    const std::uint8_t self = module_address();
    std::size_t skip = 0;
    for (std::size_t k = 1; k < kFrame && k + kFrame <= avail; ++k)
      if (p[k] == self && checksum_ok(p + k)) {
        skip = k;
        break;
      }
    if (skip != 0) {
      head_ += skip;
      counters_.skipped_bytes += skip;
      continue;
    }
    if (avail < 2 * kFrame - 1) break;  // a later start may still complete: wait (or the gap)
    ++counters_.bad_checksum;
    if (p[0] == self) {
      reply_module_ = self;
      reply_host_ = host_address();
      reply(kStatusWrongChecksum, p[1], 0);
    }
    head_ += kFrame;
  }
  // Keep the buffer small: move the unparsed tail to the front once the parsed part dominates.
  if (head_ == rx_.size()) {
    rx_.clear();
    head_ = 0;
  } else if (head_ > 4096 && head_ * 2 > rx_.size()) {
    rx_.erase(rx_.begin(), rx_.begin() + static_cast<std::ptrdiff_t>(head_));
    head_ = 0;
  }
}

void TmclModule::handle_frame(const std::uint8_t* frame) {
  const std::uint8_t self = module_address();
  if (frame[0] != self) {
    ++counters_.foreign;
    return;
  }
  ++counters_.frames;
  std::copy(frame, frame + 9, request_.begin());
  request_pending_ = true;
  reply_module_ = self;
  reply_host_ = host_address();
  execute(decode_request(frame).ins);
}

// ---- replies ----

// Global 255 (where the profile has it) suppresses every reply but those of GAP, GGP and GIO.
bool TmclModule::suppressed(std::uint8_t op) const {
  if (op == static_cast<std::uint8_t>(Op::GAP) || op == static_cast<std::uint8_t>(Op::GGP) ||
      op == static_cast<std::uint8_t>(Op::GIO))
    return false;
  return vm_.profile->global_param(0, kGpSuppressReply) != nullptr && vm_.bank0[kGpSuppressReply] != 0;
}

void TmclModule::reply(std::uint8_t status, std::uint8_t op, std::int32_t value) {
  const Frame r = encode_reply(Reply{reply_host_, reply_module_, status, op, value});
  exchange(r, false, !suppressed(op));
  if (suppressed(op)) return;
  out_.insert(out_.end(), r.begin(), r.end());
}

void TmclModule::reply_raw(const std::array<std::uint8_t, 9>& bytes, std::uint8_t op) {
  exchange(bytes, true, !suppressed(op));
  if (suppressed(op)) return;
  out_.insert(out_.end(), bytes.begin(), bytes.end());
}

void TmclModule::note(const std::string& text) {
  if (on_message) on_message(text);
}

// The first reply to a request is its answer; later ones (position-reached events) are not.
void TmclModule::exchange(const Frame& reply, bool special, bool sent) {
  if (!request_pending_) return;
  request_pending_ = false;
  if (!on_exchange) return;
  const tmcl::Reply r = decode_reply(reply.data());
  on_exchange(Exchange{vm_.now, reply_module_, reply_host_, decode_request(request_.data()).ins,
                       special ? kStatusOk : r.status, r.value, sent, reply, special});
}

// ---- ordinary commands ----

// Direct-mode commands that write the EEPROM (refused with status 5 when it is locked).
bool TmclModule::writes_eeprom(const Instruction& ins) const {
  switch (static_cast<Op>(ins.op)) {
    case Op::STAP:
    case Op::STGP: return true;
    case Op::SCO:
    case Op::ACO: return ins.motor == 255;  // the bank-255 forms copy coordinates to the EEPROM
    case Op::SGP: {  // an auto-stored (A) parameter of bank 0, or of bank 3 in a user's profile
      if (ins.motor != 0 && ins.motor != 3) return false;
      const ParamInfo* p = vm_.profile->global_param(ins.motor, ins.type);
      return p != nullptr && (p->access & kAutoStore) != 0;
    }
    default: return false;
  }
}

void TmclModule::execute(const Instruction& ins) {
  const OpInfo* info = op_info(ins.op);
  const bool is_control = info != nullptr && info->control;
  if (download_ && !is_control) {
    store(ins);
    return;
  }
  if (is_control) {
    if (!vm_.profile->has_command(ins.op)) {
      reply(kStatusNotAvailable, ins.op, 0);
      return;
    }
    control(ins);
    return;
  }
  if (options_.eeprom_locked && writes_eeprom(ins)) {
    reply(kStatusEepromLocked, ins.op, ins.value);
    return;
  }
  const DirectReply r = vm_.execute_direct(ins);
  // S25: a firmware whose direct reads load the accumulator while the program is not running.
  if (options_.variants.direct_read_sets_a && r.status == kStatusOk && vm_.status != AppStatus::Running &&
      (ins.op == static_cast<std::uint8_t>(Op::GAP) || ins.op == static_cast<std::uint8_t>(Op::GGP) ||
       ins.op == static_cast<std::uint8_t>(Op::GIO)))
    vm_.acc = r.value;
  if (r.status == kStatusOk && (ins.op == static_cast<std::uint8_t>(Op::MVP) || ins.op == static_cast<std::uint8_t>(Op::MVPA)) &&
      ins.motor < 32) {
    // 138: this move is announced when it arrives if its motor is in a mask (S8). A move that
    // is not announced cancels an announcement still pending for its motor.
    const std::uint32_t bit = std::uint32_t{1} << ins.motor;
    if ((every_mvp_mask_ | next_mvp_mask_) & bit)
      waiting_mask_ |= bit;
    else
      waiting_mask_ &= ~bit;
    next_mvp_mask_ = 0;
  }
  reply(r.status, ins.op, r.value);
  check_events();  // an ideal core arrives at once: the event follows the reply
}

// ---- download mode ----

void TmclModule::store(const Instruction& ins) {
  if (ins.op == 0) {
    // End marker (S7): program memory ends here, as an opcode-0 word ends it in an EEPROM.
    if (static_cast<std::size_t>(download_ptr_) < pending_.size()) {
      pending_.resize(static_cast<std::size_t>(download_ptr_));
      pending_dirty_ = true;
    }
    reply(kStatusLoaded, ins.op, ins.value);
    return;
  }
  const int memory = vm_.profile->program_memory;
  if (download_ptr_ < 0 || (memory > 0 && download_ptr_ >= memory)) {
    reply(kStatusInvalidValue, ins.op, ins.value);  // S6: program memory full
    return;
  }
  const auto at = static_cast<std::size_t>(download_ptr_);
  if (at >= pending_.size()) pending_.resize(at + 1, Instruction{});
  pending_[at] = ins;
  pending_dirty_ = true;
  ++download_ptr_;
  reply(kStatusLoaded, ins.op, ins.value);
}

void TmclModule::commit_download() {
  if (!pending_dirty_) return;
  pending_dirty_ = false;
  vm_.load(pending_);
  vm_.store_program();  // a module with program EEPROM keeps what was downloaded (errata E55)
}

// ---- time and events ----

void TmclModule::advance(SimTime until) {
  if (until <= vm_.now) {
    check_events();
    return;
  }
  if (step_held_) {
    finish_held_step(until);
    if (step_held_) {
      check_events();
      return;
    }
  }
  if (run_program) {  // a debugger runs the program (and moves time while it holds it)
    run_program(until);
    check_events();
    return;
  }
  // Without a program running, the scenario's timed lines (a load, a switch) still come at their
  // instants of the serving clock, not with the next request: the world is run to each in turn.
  while (vm_.status != AppStatus::Running && vm_.next_input_at() <= until) {
    run_to(std::max(vm_.now, vm_.next_input_at()));
    vm_.apply_due_inputs();
  }
  run_to(until);
  check_events();
}

void TmclModule::run_to(SimTime until) {
  if (vm_.status == AppStatus::Running || vm_.motion_pending()) {
    const RunResult r = vm_.run(Limits{UINT64_MAX, until});
    if (r.halt == Halt::Fault) {
      if (!fault_reported_) note("program fault: " + r.message);
      fault_reported_ = true;
    } else {
      fault_reported_ = false;
    }
  }
  // Nothing left to simulate: time simply passes (timers only matter while a program runs).
  if (vm_.status != AppStatus::Running && !vm_.motion_pending() && vm_.now < until) vm_.now = until;
}

// S24: the WAIT a held 130 met runs to its end (a due interrupt is entered first, as a step
// would); no further instruction runs. Then the step is answered and the requests that came
// meanwhile are read.
void TmclModule::finish_held_step(SimTime until) {
  Limits lim;
  lim.max_steps = vm_.steps;
  lim.until = until;
  lim.to_instruction = true;
  const RunResult r = vm_.run(lim);
  if (r.halt == Halt::Fault) note("program fault: " + r.message);
  if (vm_.status == AppStatus::Running && vm_.wait.active) return;
  if (vm_.status == AppStatus::Running) vm_.status = AppStatus::Step;
  step_held_ = false;
  reply_module_ = held_module_;
  reply_host_ = held_host_;
  reply(kStatusOk, static_cast<std::uint8_t>(Op::StepApplication), 0);
  parse();
}

SimTime TmclModule::next_wakeup() const {
  if (vm_.status == AppStatus::Running && !run_program) {  // (a debugger paces its own runs)
    if (!vm_.wait.active) return vm_.now;  // executing instructions: run in slices
    return vm_.next_wakeup();
  }
  return run_program ? vm_.motion->next_event() : std::min(vm_.motion->next_event(), vm_.next_input_at());
}

// 138 events: the announced motor has arrived (target reached and at rest). Polled after every
// command and every time slice; the core reports arrival as an event, so advance() always runs
// to the arrival instant before this looks.
void TmclModule::check_events() {
  if (waiting_mask_ == 0) return;
  for (int m = 0; m < vm_.profile->motors && m < 32; ++m) {
    const std::uint32_t bit = std::uint32_t{1} << m;
    if (!(waiting_mask_ & bit) || !vm_.motion->target_reached(m)) continue;
    waiting_mask_ &= ~bit;
    reply_module_ = module_address();
    reply_host_ = host_address();
    reply(kStatusPositionReached, static_cast<std::uint8_t>(Op::PositionReachedEvent), static_cast<std::int32_t>(bit));
  }
}

bool TmclModule::take_power_cycle() {
  const bool r = power_cycled_;
  power_cycled_ = false;
  return r;
}

// 255 (and 137): like switching the module off and on. Program memory survives (it is EEPROM on
// a module and in the image, errata E55; a RAM one is kept too, as a host would download it
// again), so does the EEPROM image; every register, parameter and variable starts over from
// the defaults and what the EEPROM restores, simulated time restarts at 0, and global 77 may
// start the program.
void TmclModule::power_cycle(bool clear_eeprom) {
  commit_download();
  download_ = false;
  EepromImage image = clear_eeprom ? EepromImage{} : vm_.eeprom;
  // 137 resets "all settings stored in the EEPROM" (TMCM-1110 manual 4.5.38): the
  // program is no setting and stays (errata E55).
  if (clear_eeprom) image.program = vm_.eeprom.program;
  vm_.power_on(&image);
  if (clear_eeprom) vm_.eeprom_dirty = true;
  apply_address_overrides();
  every_mvp_mask_ = next_mvp_mask_ = waiting_mask_ = 0;
  fault_reported_ = false;
  power_cycled_ = true;
  if (vm_.profile->global_param(0, kGpAutoStart) && vm_.bank0[kGpAutoStart] != 0 && vm_.program_size > 0) vm_.start(0);
}

}  // namespace tmcl
