// The platform layer, serial ports: what is the same on every system (os_serial.hpp).
#include <string>

#include "tmcl/os_serial.hpp"

namespace tmcl::os::serial {

std::string baud_rates_text() {
  std::string out;
  const std::size_t n = std::size(kBaudRates);
  for (std::size_t i = 0; i < n; ++i) out += (i == 0 ? "" : i + 1 == n ? " or " : ", ") + std::to_string(kBaudRates[i]);
  return out;
}

bool is_com_name(std::string_view name) {
  if (name.size() < 4) return false;
  for (std::size_t i = 0; i < 3; ++i)
    if ((name[i] | 0x20) != "com"[i]) return false;
  return name.find_first_not_of("0123456789", 3) == std::string_view::npos;
}

}  // namespace tmcl::os::serial
