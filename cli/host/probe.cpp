// identify and probe (probe.hpp). Probing only reads: GAP, GGP, GCO and 134 never change a module,
// so `tmclctl PORT probe` is safe on a machine that is set up.
#include "tmcl/host/probe.hpp"

#include <algorithm>
#include <memory>

#include "tmcl/profile_file.hpp"
#include "tmcl/targets.hpp"

namespace tmcl::host {
namespace {

std::string module_number(const std::string& version) {
  const std::size_t v = version.find('V');
  return v == std::string::npos ? std::string() : version.substr(0, v);
}

Instruction ins(Op op, int type, int motor, std::int32_t value = 0) {
  return Instruction{static_cast<std::uint8_t>(op), static_cast<std::uint8_t>(type), static_cast<std::uint8_t>(motor), value};
}

}  // namespace

const Profile* profile_for_firmware(const std::string& version) {
  if (version.empty()) return nullptr;
  const std::vector<const Profile*> candidates = found_profiles();
  for (const Profile* p : candidates)
    if (p->firmware == version) return p;
  const std::string number = module_number(version);
  if (number.empty() || number == "0000") return nullptr;  // 0000: no real module (generic)
  for (const Profile* p : candidates)
    if (module_number(std::string(p->firmware)) == number) return p;
  return nullptr;
}

Identity identify(Client& client) {
  Identity id;
  client.set_retries(0);
  Result r = client.request(ins(Op::GetFirmwareVersion, 0, 0));
  if (!r.ok() || r.reply.version.empty()) return id;
  id.answered = true;
  id.version = r.reply.version;
  id.profile = profile_for_firmware(id.version);
  return id;
}

ProbeResult probe(Client& client, const std::string& name, const Progress& progress) {
  ProbeResult out;
  auto store = std::make_unique<ProfileStore>();
  Profile& p = store->profile;
  const int total = 1 + 256 * 3 + 256 + 256 + 256 + 17;
  int done = 0;
  auto step = [&] {
    if (progress) progress(++done, total);
  };
  bool failed = false;
  // One request; false (and `out` says why) when the module is silent or the port broke.
  auto ask = [&](const Instruction& i, Reply& reply) {
    Result r = client.request(i);
    step();
    if (r.ok()) {
      reply = r.reply;
      return true;
    }
    out.outcome = r.fail == Fail::Cancelled ? Outcome::Cancelled : r.fail == Fail::Port ? Outcome::Port : Outcome::NoReply;
    out.message = r.error;
    failed = true;
    return false;
  };
  auto exists = [](const Reply& r) { return r.status == kStatusOk; };

  Reply reply;
  if (!ask(ins(Op::GetFirmwareVersion, 0, 0), reply)) return out;
  const std::string version = reply.version.size() == 8 ? reply.version : "0000V100";
  p.firmware = store->strings.emplace_back(version);
  p.name = store->strings.emplace_back(name);
  p.title = store->strings.emplace_back(name + " (probed, firmware " + version + ")");

  // Parameters: every number of the axis parameters (motor 0) and of banks 0 and 3.
  auto scan = [&](std::vector<ParamInfo>& table, Op op, int bank) {
    for (int n = 0; n < 256 && !failed; ++n) {
      if (!ask(ins(op, n, bank), reply)) return;
      if (!exists(reply)) continue;
      const std::string label = (op == Op::GAP ? "Axis parameter " : bank == 0 ? "Global parameter " : "Interrupt setting ") + std::to_string(n);
      ParamInfo info{static_cast<std::uint16_t>(n), store->strings.emplace_back(label), INT32_MIN, INT32_MAX,
                     static_cast<std::uint8_t>(kRead | kWrite), reply.value, {}, {}, 0xFF};
      if (bank == 3 && reply.value < 0) info.max = 4294967295LL;  // a period read as its unsigned value
      table.push_back(info);
    }
  };
  scan(store->axis, Op::GAP, 0);
  scan(store->bank0, Op::GGP, 0);
  scan(store->bank3, Op::GGP, 3);
  // Motors: the first motor number GAP 1 (actual position) refuses.
  int motors = 1;
  for (int m = 1; m < 256 && !failed; ++m) {
    if (!ask(ins(Op::GAP, 1, m), reply)) break;
    if (!exists(reply)) break;
    motors = m + 1;
  }
  // User variables (bank 2) and coordinates of motor 0: how many answer, from 0.
  int vars = 0, coords = 0;
  for (int n = 0; n < 256 && !failed; ++n) {
    if (!ask(ins(Op::GGP, n, 2), reply)) break;
    if (!exists(reply)) break;
    vars = n + 1;
  }
  for (int n = 0; n < 256 && !failed; ++n) {
    if (!ask(ins(Op::GCO, n, 0), reply)) break;
    if (!exists(reply)) break;
    coords = n + 1;
  }
  // Program memory: the first address 134 refuses, by bisection below 65536 (0: no limit found);
  // a module that does not answer 134 at all gets the usual 2048.
  int memory = 2048;
  if (!failed && ask(ins(Op::ReadProgramMemory, 0, 0, 0), reply) && exists(reply)) {
    int lo = 0, hi = 65536;  // lo answers; hi does not (or is the cap)
    while (hi - lo > 1 && !failed) {
      const int mid = lo + (hi - lo) / 2;
      if (!ask(ins(Op::ReadProgramMemory, 0, 0, mid), reply)) break;
      if (exists(reply)) lo = mid;
      else hi = mid;
    }
    memory = hi >= 65536 ? 0 : hi;
  }
  if (failed) return out;
  if (progress) progress(total, total);

  p.motors = motors;
  p.user_vars = vars;
  p.eeprom_user_vars = 0;  // finding out would overwrite the variables with RSGP
  p.coords = coords;
  p.standalone = true;
  p.program_memory = memory;
  p.any_parameter = false;
  // Commands cannot be probed without running them: those of the TMCM firmware.
  for (int c : {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 19, 20, 21, 22, 23, 24, 25, 26, 27, 28, 30, 31, 32, 33, 34,
                35, 36, 37, 38, 39, 64, 65, 66, 67, 68, 69, 70, 71, 128, 129, 130, 131, 132, 133, 134, 135, 136, 137, 138, 255})
    p.commands.set(static_cast<std::size_t>(c));
  const bool tmc429 = std::any_of(store->axis.begin(), store->axis.end(), [](const ParamInfo& i) { return i.number == 154; });
  p.default_motion = tmc429 ? "tmc429" : "linear";
  p.fallback_motion = tmc429 ? "linear" : "";
  // Interrupt vectors: those the bank 3 settings imply (timers, switches, inputs), target reached
  // for each motor, and the global switch.
  auto vector = [&](int n, const std::string& vname, const std::string& meaning) {
    store->vectors.push_back({static_cast<std::uint8_t>(n), store->strings.emplace_back(vname), store->strings.emplace_back(meaning)});
  };
  if (!store->bank3.empty()) {
    for (const ParamInfo& i : store->bank3) {
      const int n = i.number;
      if (n <= 2) vector(n, "TI_TIMER" + std::to_string(n), "Timer " + std::to_string(n));
      else if (n >= 27 && n <= 38) vector(n, std::string(n % 2 ? "TI_STOPL" : "TI_STOPR") + std::to_string((n - 27) / 2), "Stop switch");
      else if (n >= 39 && n <= 46) vector(n, "TI_INPUT" + std::to_string(n - 39), "Input change " + std::to_string(n - 39));
    }
    for (int m = 0; m < std::min(motors, 6); ++m) vector(3 + m, "TI_TARGET" + std::to_string(m), "Target position reached");
    vector(255, "TI_GLOBAL", "Global interrupt enable");
  } else {
    for (int c : {25, 26, 37, 38}) p.commands.reset(static_cast<std::size_t>(c));  // no interrupts to serve
  }
  if (coords == 0) for (int c : {30, 31, 32, 39}) p.commands.reset(static_cast<std::size_t>(c));
  std::sort(store->vectors.begin(), store->vectors.end(), [](const auto& a, const auto& b) { return a.number < b.number; });
  p.axis_params = store->axis;
  p.bank0 = store->bank0;
  p.bank3 = store->bank3;
  p.vectors = store->vectors;
  for (const char* key : {"firmware", "motors", "standalone", "program-memory", "user-variables", "coordinates", "commands", "motion"})
    store->unverified.emplace_back(key);
  p.unverified = store->unverified;
  out.axis = static_cast<int>(store->axis.size());
  out.bank0 = static_cast<int>(store->bank0.size());
  out.bank3 = static_cast<int>(store->bank3.size());
  out.motors = motors;
  out.text = format_profile(p, "A draft profile written by tmclctl probe from what the module answered (docs/profiles.md,\n"
                               "\"Your own module\"). Every fact is unverified: the names, ranges and access are\n"
                               "placeholders, the defaults the values read. Check them against the module's manual, mark\n"
                               "each source (src=) and drop the unverified marks you have confirmed.");
  return out;
}

}  // namespace tmcl::host
