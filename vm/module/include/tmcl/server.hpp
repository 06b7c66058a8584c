// The virtual module: TMCL direct mode (9-byte requests and replies, USB-2-SD manual 3.1, 3.2)
// spoken over TCP, a pseudo-terminal or standard input/output, against a running Vm.
//
// Two layers:
//   TmclModule  the protocol engine: bytes in, bytes out. Framing and resynchronisation,
//               checksums, module and host addresses, status codes, reply suppression (global
//               255), the control commands 128..138 and 255, download mode, position-reached
//               events (138). It neither reads a clock nor touches a file descriptor: the
//               caller says how far simulated time has come (advance) and when the line has
//               been quiet for the resynchronisation gap (gap_elapsed). Unit tests drive it
//               directly.
//   serve()     the I/O loop: one transport, one client at a time, wall-clock pacing of
//               simulated time (the only place in the project that reads the wall clock),
//               SIGINT/SIGTERM shutdown that saves the EEPROM file.
//
// Where the manuals are silent, the choices are recorded in docs/errata.md (S1, S2, ...)
// and explained for users in docs/virtual-module.md.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "tmcl/faults.hpp"
#include "tmcl/vm.hpp"

namespace tmcl {

// Status codes of the protocol: params.hpp (through vm.hpp).

// Behaviours no manual settles and module firmware may differ in, which a debugger on the module
// must cope with (issue 39; docs/virtual-module.md, "Firmware variants"; errata S24-S27). Each
// is off by default: the documented or, where nothing is documented, the chosen behaviour.
struct FirmwareVariants {
  bool step_waits = false;             // 130 during a WAIT answers when the wait is over (S24)
  bool direct_read_sets_a = false;     // a direct GAP/GGP/GIO while not running loads A (S25)
  bool reset_reports_stopped = false;  // after 131 the application status is 0, not 3 (S26)
  bool read_past_memory_zero = false;  // 134 beyond program memory reads opcode 0, not status 4 (S27)
};

// The variants by name, one row each: what tmclrun --variant takes, its --help and the docs.
struct VariantInfo {
  std::string_view name;
  std::string_view meaning;  // with the variant on, in a few words (--help; the docs say more)
  bool FirmwareVariants::*field;
};
const std::vector<VariantInfo>& firmware_variant_table();
// "step-waits,reset-reports-stopped" (names of the table, comma-separated) into `out` (adding
// to what is set); false with `error` naming an unknown name.
bool parse_firmware_variants(std::string_view list, FirmwareVariants& out, std::string& error);

struct ProtocolOptions {
  // Override the module's serial address (global 66) and host address (global 76). Written into
  // the RAM copy of the parameter at start and after every reset, never into the EEPROM; a
  // profile without the parameter keeps the value here. Unset: what the VM holds (defaults 1, 2).
  std::optional<std::uint8_t> module_address;
  std::optional<std::uint8_t> host_address;
  // Refuse every direct-mode command that would write the EEPROM with status 5 (S9).
  bool eeprom_locked = false;
  FirmwareVariants variants;
};

// The protocol engine for one module. Not thread-safe; one instance per Vm.
class TmclModule {
 public:
  TmclModule(Vm& vm, ProtocolOptions options = {});

  // Bytes from the host. Complete frames are executed at once; replies go to output().
  void receive(const std::uint8_t* data, std::size_t n);
  // True when at least 9 bytes are buffered that are not a frame and more bytes could still
  // make one: the caller calls gap_elapsed() once the line has been quiet for the gap.
  bool window_pending() const;
  // The line has been quiet: a pending window is a corrupted frame (status 1 if it was
  // addressed to this module) and is dropped.
  void gap_elapsed();
  // A new connection: bytes of a torn frame from the previous one are forgotten.
  void drop_partial();

  // Runs the program and the motors up to simulated instant `until` (never backwards) and
  // queues position-reached events that became due.
  void advance(SimTime until);
  // The next simulated instant at which advance() has something to do: vm.now while a program
  // is executing instructions, kNever when nothing happens until the next request.
  SimTime next_wakeup() const;
  // True once after a software reset or factory restore: simulated time restarted at 0.
  bool take_power_cycle();

  // Bytes to send to the host, in order. The caller removes what it sent.
  std::vector<std::uint8_t>& output() { return out_; }

  std::uint8_t module_address() const;
  std::uint8_t host_address() const;
  bool download_mode() const { return download_; }

  // Program faults and other notes for the operator (nullptr: dropped).
  std::function<void(const std::string&)> on_message;
  // A debugger owns the program's execution (tmclrun --serve --debug): advance() calls this
  // with the instant to reach instead of running the program itself (nullptr: it runs it).
  std::function<void(SimTime until)> run_program;
  // One answered request (tmclrun --serve --trace): when, the addresses, the request, the
  // reply's status and value, and whether the reply was sent (global 255 suppresses most).
  // `reply` is the reply's nine bytes; `special` says they have the layout of 134 or 136 type 0
  // (docs/virtual-module.md), which has no status byte: `status` is then 100.
  struct Exchange {
    SimTime at;
    std::uint8_t module, host;
    Instruction request;
    std::uint8_t status;
    std::int32_t value;
    bool sent;
    Frame reply;
    bool special;
  };
  std::function<void(const Exchange&)> on_exchange;  // nullptr: nothing is reported

  // Counters, for tests and the shutdown note.
  struct Counters {
    std::uint64_t frames = 0;           // valid frames addressed to this module
    std::uint64_t foreign = 0;          // valid frames for another address (no reply)
    std::uint64_t bad_checksum = 0;     // corrupted frames (replied to when addressed here)
    std::uint64_t skipped_bytes = 0;    // garbage dropped while resynchronising
  };
  const Counters& counters() const { return counters_; }

 private:
  void parse();
  void handle_frame(const std::uint8_t* frame);
  void run_to(SimTime until);  // advance()'s program and motors, without the scenario's lines
  void execute(const Instruction& ins);
  void control(const Instruction& ins);
  void store(const Instruction& ins);
  void commit_download();
  void power_cycle(bool clear_eeprom);
  void apply_address_overrides();
  bool writes_eeprom(const Instruction& ins) const;
  bool suppressed(std::uint8_t op) const;
  void reply(std::uint8_t status, std::uint8_t op, std::int32_t value);
  void reply_raw(const std::array<std::uint8_t, 9>& bytes, std::uint8_t op);
  void check_events();
  void note(const std::string& text);
  void exchange(const Frame& reply, bool special, bool sent);

  Vm& vm_;
  ProtocolOptions options_;
  std::vector<std::uint8_t> rx_;
  std::size_t head_ = 0;  // first unparsed byte of rx_
  std::vector<std::uint8_t> out_;
  // Addresses of the request being answered (S4: a reply carries the pair the request met).
  std::uint8_t reply_module_ = 1, reply_host_ = 2;
  std::uint8_t fallback_module_ = 1, fallback_host_ = 2;  // when the profile has no 66 / 76

  // Download mode (132/133): stores go to `pending_`, which replaces program memory at once
  // when a command needs it (133, 129, 130, 131, 134, 255) — one reload instead of one per word.
  bool download_ = false;
  bool pending_dirty_ = false;
  std::int32_t download_ptr_ = 0;
  std::vector<Instruction> pending_;

  // 138: motors whose next arrival is announced (bit per motor).
  std::uint32_t every_mvp_mask_ = 0;  // type 1
  std::uint32_t next_mvp_mask_ = 0;   // type 0, consumed by the next MVP
  std::uint32_t waiting_mask_ = 0;    // an announced move is under way

  // S24 (variants.step_waits): a 130 that met a WAIT is answered when the wait is over; until
  // then requests stay unread in rx_, as a firmware busy in its step handler leaves them.
  bool step_held_ = false;
  std::uint8_t held_module_ = 1, held_host_ = 2;
  void finish_held_step(SimTime until);

  bool power_cycled_ = false;
  bool fault_reported_ = false;
  Counters counters_;
  std::array<std::uint8_t, 9> request_{};  // the frame being answered, for on_exchange
  bool request_pending_ = false;           // its reply has not been reported yet
};

// ---- the I/O loop ----

enum class Transport : std::uint8_t { Tcp, Pty, Stdio, Serial };

// A further module on the same line (tmclrun --module): its own VM (profile, program, EEPROM)
// and protocol options, the address above all (bus.hpp).
struct BusModule {
  Vm* vm = nullptr;
  ProtocolOptions protocol;
};

struct ServeOptions {
  Transport transport = Transport::Tcp;
  std::string host = "127.0.0.1";  // Tcp: address to listen on (IPv4 or IPv6 literal or name)
  int port = 2001;                 // Tcp: 0 picks a free port (announced)
  int in_fd = 0, out_fd = 1;       // Stdio: where frames come from and replies go
  std::string serial_port;         // Serial: the device ("COM5", "\\.\COM12", "/dev/ttyUSB0")
  long serial_baud = 9600;         // Serial: raw 8N1 at this rate
  ProtocolOptions protocol;
  double time_scale = 1.0;         // simulated seconds per wall-clock second (> 0)
  bool autostart = false;          // start the program at address 0 (also: global 77 = 1)
  std::string eeprom_path;         // non-empty: saved there at shutdown (save_eeprom_file)
  int resync_gap_ms = 20;          // quiet time after which a stuck 9-byte window is dropped
  int spin_us = 100;               // after a request, poll for the next one this long (0: never)
  bool handle_signals = true;      // SIGINT/SIGTERM stop the loop (handlers restored on return)
  int stop_fd = -1;                // readable (or closed) => stop, for embedders and tests
  std::int64_t max_wall_ms = 0;    // > 0: stop by itself after this long (tests, CI)
  // Called once when the transport is ready: "127.0.0.1:2001", "[::1]:2001", the pty's path,
  // the serial port's name, or "stdio". serve() also prints it (see `announce`).
  std::function<void(const std::string&)> on_ready;
  std::ostream* announce = nullptr;  // where the ready line goes; nullptr: stdout (stderr for stdio)
  std::ostream* log = nullptr;       // notes and errors; nullptr: stderr
  bool quiet = false;                // no announce line, no notes (errors still go to `log`)
  std::vector<BusModule> bus;        // more modules on the line, each answering its own address
  FaultPlan faults;                  // faults injected into the replies (faults.hpp)
  std::function<void(const TmclModule::Exchange&)> on_exchange;  // every module's answers (--trace)
  // A debugger sharing the loop (tmclrun --serve --debug): runs the primary module's program
  // (TmclModule::run_program), and SIGINT calls on_interrupt instead of stopping the server.
  std::function<void(SimTime until)> run_program;
  std::function<void()> on_interrupt;
};

// Serves until SIGINT/SIGTERM, stop_fd, max_wall_ms, or end of input (stdio). The caller has
// loaded the program and powered the VM on (with the EEPROM image). Returns an exit status:
// 0 clean shutdown, 71 the transport could not be set up (message on `log`), 74 the EEPROM
// file could not be written.
int serve(Vm& vm, const ServeOptions& options);

// serve() as an object, for a front end that shares the thread with the module (tmclrun
// --serve --debug): serve() is open(), poll_once() until it returns false, then close().
class ServeLoop {
 public:
  ServeLoop(Vm& vm, const ServeOptions& options);
  ~ServeLoop();
  ServeLoop(const ServeLoop&) = delete;
  ServeLoop& operator=(const ServeLoop&) = delete;
  // Sets up the transport and announces it: 0, or 71 (the message went to the log).
  int open();
  // One round: brings the module up to the wall clock, sends replies, waits at most
  // `max_wait_ms` (-1: as long as the module has nothing to do) for a request, a client, a
  // signal or `extra_fd` to become readable, and handles what came. False: stop serving
  // (a signal, stop_fd, max_wall_ms, end of stdio input).
  bool poll_once(int max_wait_ms = -1, int extra_fd = -1);
  // Whether extra_fd was readable (or closed) in the last poll_once.
  bool extra_ready() const;
  // Shuts down: pending replies, the connection, the EEPROM file. Returns serve()'s status.
  int close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Parses a --serve argument: "tcp:HOST:PORT" (HOST may be "[v6]"; "tcp:PORT" means
// 127.0.0.1), "pty" or "stdio". Returns false with a message on error.
bool parse_serve_spec(std::string_view spec, ServeOptions& options, std::string& error);

}  // namespace tmcl
