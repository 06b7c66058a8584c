// The firmware variants of the virtual module (server.hpp, FirmwareVariants): behaviours no
// manual settles, where module firmware may differ and a debugger on the module must cope with
// either. One table names them for tmclrun --variant, its --help and docs/virtual-module.md;
// the reasons for each default are errata S24-S27.
#include <algorithm>

#include "tmcl/server.hpp"

namespace tmcl {

const std::vector<VariantInfo>& firmware_variant_table() {
  static const std::vector<VariantInfo> table{
      {"step-waits", "130 in a WAIT answers when the wait is over", &FirmwareVariants::step_waits},
      {"direct-read-sets-a", "a direct GAP/GGP/GIO while stopped loads A", &FirmwareVariants::direct_read_sets_a},
      {"reset-reports-stopped", "status 0, not 3, after 131", &FirmwareVariants::reset_reports_stopped},
      {"read-past-memory-zero", "134 past memory reads opcode 0, not status 4", &FirmwareVariants::read_past_memory_zero},
  };
  return table;
}

bool parse_firmware_variants(std::string_view list, FirmwareVariants& out, std::string& error) {
  std::size_t at = 0;
  while (at <= list.size()) {
    const std::size_t comma = std::min(list.find(',', at), list.size());
    const std::string_view name = list.substr(at, comma - at);
    const VariantInfo* found = nullptr;
    for (const VariantInfo& v : firmware_variant_table())
      if (v.name == name) found = &v;
    if (!found) {
      std::string names;
      for (const VariantInfo& v : firmware_variant_table()) names += (names.empty() ? "" : ", ") + std::string(v.name);
      error = "unknown firmware variant '" + std::string(name) + "' (known: " + names + ")";
      return false;
    }
    out.*(found->field) = true;
    at = comma + 1;
  }
  return true;
}

}  // namespace tmcl
