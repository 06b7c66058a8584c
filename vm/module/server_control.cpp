// The TMCL control commands of the virtual module (USB-2-SD manual 3.6.47, 3.6.48, table 13):
// 128 stop, 129 run, 130 step, 131 reset, 132/133 download mode, 134 read program memory,
// 135 application status, 136 firmware version, 137 factory settings, 138 position-reached
// event, 255 software reset. Reply layouts of 134, 135 and 136 are documented in
// docs/virtual-module.md; choices where the manual is silent in docs/errata.md.
#include <cctype>

#include "tmcl/image.hpp"
#include "tmcl/server.hpp"

namespace tmcl {
namespace {

constexpr std::int32_t kMagic = 1234;  // value 137 and 255 insist on

// 136 type 1: the version string "MMMMVmnn" packed as in Trinamic's firmware: byte 3 the first
// two digits of the module number, byte 2 the last two, byte 1 the major version, byte 0 the
// two-digit minor version ("0015V114" -> 0x000F010E).
std::int32_t binary_version(std::string_view s) {
  auto digit = [&](std::size_t i) -> std::uint32_t {
    return i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])) ? static_cast<std::uint32_t>(s[i] - '0') : 0;
  };
  const std::uint32_t b3 = digit(0) * 10 + digit(1), b2 = digit(2) * 10 + digit(3), b1 = digit(5),
                      b0 = digit(6) * 10 + digit(7);
  return static_cast<std::int32_t>(b3 << 24 | b2 << 16 | b1 << 8 | b0);
}

}  // namespace

void TmclModule::control(const Instruction& ins) {
  const std::uint8_t op = ins.op;
  switch (static_cast<Op>(op)) {
    case Op::StopApplication:  // 128: the program stops; motors finish what they were told
      commit_download();
      vm_.stop_application();
      reply(kStatusOk, op, 0);
      return;

    case Op::RunApplication: {  // 129
      commit_download();
      if (ins.type > 1) {
        reply(kStatusWrongType, op, ins.value);
        return;
      }
      std::int32_t from = vm_.pc;
      if (ins.type == 1) {
        if (ins.value < 0 || ins.value >= vm_.program_size) {
          reply(kStatusInvalidValue, op, ins.value);
          return;
        }
        from = ins.value;
      }
      download_ = false;  // S5: running ends download mode
      vm_.start(from);
      fault_reported_ = false;
      reply(kStatusOk, op, ins.value);
      return;
    }

    case Op::StepApplication: {  // 130: exactly one instruction, then the program waits in Step
      commit_download();
      download_ = false;
      // A debugger's breakpoint at pc (tmclrun --serve --debug) must not swallow the host's step.
      const std::int32_t at = vm_.pc;
      const bool trapped = vm_.trapped(at);
      if (trapped) vm_.set_trap(at, false);
      const RunResult r = vm_.step();
      if (trapped) vm_.set_trap(at, true);
      if (r.halt == Halt::Fault) note("program fault: " + r.message);
      if (options_.variants.step_waits && !run_program && vm_.wait.active && vm_.status == AppStatus::Step) {
        // S24: this firmware answers when the wait is over; advance() runs it to its end.
        step_held_ = true;
        held_module_ = reply_module_;
        held_host_ = reply_host_;
        vm_.status = AppStatus::Running;
        return;
      }
      reply(kStatusOk, op, 0);
      check_events();
      return;
    }

    case Op::ResetApplication:  // 131: stop, pc, stacks, registers and flags to zero
      commit_download();
      vm_.reset_application();
      if (options_.variants.reset_reports_stopped) vm_.status = AppStatus::Stopped;  // S26
      reply(kStatusOk, op, 0);
      return;

    case Op::EnterDownloadMode: {  // 132: store following commands from the address in value
      const int memory = vm_.profile->program_memory;
      if (options_.eeprom_locked) {
        reply(kStatusEepromLocked, op, ins.value);
        return;
      }
      if (ins.value < 0 || (memory > 0 && ins.value >= memory)) {
        reply(kStatusInvalidValue, op, ins.value);
        return;
      }
      if (!download_) {
        pending_.assign(vm_.program.begin(), vm_.program.begin() + vm_.program_size);
        pending_dirty_ = false;
      }
      download_ = true;
      download_ptr_ = ins.value;
      vm_.stop_application();  // S5
      reply(kStatusOk, op, ins.value);
      return;
    }

    case Op::ExitDownloadMode:  // 133
      commit_download();
      download_ = false;
      reply(kStatusOk, op, 0);
      return;

    case Op::ReadProgramMemory: {  // 134
      commit_download();
      const int memory = vm_.profile->program_memory;
      if (ins.type > 2) {
        reply(kStatusWrongType, op, ins.value);
        return;
      }
      const bool beyond = memory > 0 && ins.value >= memory;
      if (ins.value < 0 || (beyond && !options_.variants.read_past_memory_zero)) {  // S27
        reply(kStatusInvalidValue, op, ins.value);
        return;
      }
      // Past the end of the program, memory reads as opcode 0: the end marker.
      Instruction word{};
      if (ins.value < vm_.program_size) word = vm_.program[static_cast<std::size_t>(ins.value)];
      if (ins.type == 1) {  // opcode, type, motor packed in the value
        reply(kStatusOk, op, static_cast<std::int32_t>(word.op | word.type << 8 | word.motor << 16));
      } else if (ins.type == 2) {  // the value alone
        reply(kStatusOk, op, word.value);
      } else {  // type 0, the classic special reply: host, then the 7 instruction bytes, checksum
        const auto e = encode7(word);
        std::array<std::uint8_t, 9> r{reply_host_, e[0], e[1], e[2], e[3], e[4], e[5], e[6], 0};
        r[8] = sum8(r.data(), 8);
        reply_raw(r, op);
      }
      return;
    }

    case Op::GetApplicationStatus: {  // 135
      const std::uint32_t mode = download_ ? 4u : static_cast<std::uint32_t>(vm_.status);
      const std::uint32_t wait = vm_.wait.active ? 1u : 0u;
      switch (ins.type) {
        case 0:
          reply(kStatusOk, op, static_cast<std::int32_t>(mode << 24 | wait << 16 | (static_cast<std::uint32_t>(download_ptr_) & 0xFFFF)));
          return;
        case 1:
          reply(kStatusOk, op, static_cast<std::int32_t>(mode << 24 | wait << 16 | (static_cast<std::uint32_t>(vm_.pc) & 0xFFFF)));
          return;
        case 2: reply(kStatusOk, op, vm_.acc); return;
        case 3: reply(kStatusOk, op, vm_.x); return;
        default: reply(kStatusWrongType, op, ins.value); return;
      }
    }

    case Op::GetFirmwareVersion: {  // 136
      const std::string_view fw = vm_.profile->firmware;
      if (ins.type == 0) {  // special reply: host address and the 8 characters, no checksum
        std::array<std::uint8_t, 9> r{reply_host_, ' ', ' ', ' ', ' ', ' ', ' ', ' ', ' '};
        for (std::size_t i = 0; i < 8 && i < fw.size(); ++i) r[i + 1] = static_cast<std::uint8_t>(fw[i]);
        reply_raw(r, op);
      } else if (ins.type == 1) {
        reply(kStatusOk, op, binary_version(fw));
      } else {
        reply(kStatusWrongType, op, ins.value);
      }
      return;
    }

    case Op::RestoreFactorySettings:  // 137: no reply when it is done (manual, table 13)
      if (ins.value != kMagic) {
        reply(kStatusInvalidValue, op, ins.value);
        return;
      }
      if (options_.eeprom_locked) {
        reply(kStatusEepromLocked, op, ins.value);
        return;
      }
      note("restore factory settings: EEPROM settings cleared (program memory kept), module restarted");
      power_cycle(true);
      return;

    case Op::PositionReachedEvent: {  // 138
      if (ins.type > 1) {
        reply(kStatusWrongType, op, ins.value);
        return;
      }
      const int motors = vm_.profile->motors < 32 ? vm_.profile->motors : 32;
      const std::uint32_t all = motors >= 32 ? 0xFFFFFFFFu : (std::uint32_t{1} << motors) - 1;
      const auto mask = static_cast<std::uint32_t>(ins.value);
      if (mask & ~all) {
        reply(kStatusInvalidValue, op, ins.value);
        return;
      }
      if (ins.type == 1)
        every_mvp_mask_ = mask;
      else
        next_mvp_mask_ = mask;
      reply(kStatusOk, op, ins.value);
      return;
    }

    case Op::SoftwareReset:  // 255: the reply goes out first, then the module restarts
      if (ins.value != kMagic) {
        reply(kStatusInvalidValue, op, ins.value);
        return;
      }
      reply(kStatusOk, op, ins.value);
      power_cycle(false);
      return;

    default: reply(kStatusInvalidCommand, op, 0); return;
  }
}

}  // namespace tmcl
