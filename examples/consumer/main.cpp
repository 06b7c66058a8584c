// The consumer of tmcl's CMake package (examples/consumer/CMakeLists.txt): assembles a small
// program for the USB-2-SD module with the assembler library, including the bundled
// TMCLParam.tmc, runs it on the virtual machine with the module's own motion core, and prints
// where the motor ended up and when. Exit status 0 when the program reached STOP at 1000.
#include <cstdio>
#include <memory>

#include "tmcl/asm/assembler.hpp"
#include "tmcl/motion.hpp"
#include "tmcl/profile.hpp"
#include "tmcl/version.hpp"
#include "tmcl/vm.hpp"

int main() {
  const tmcl::Profile* module = tmcl::find_profile("usb-2-sd");
  if (!module) {
    std::fprintf(stderr, "consumer: no usb-2-sd profile\n");
    return 1;
  }

  tmcl::MemoryReader files;
  files.files["move.tmc"] =
      "#include TMCLParam.tmc\n"
      "  SAP APMaxPositioningSpeed, Motor0, 51200\n"
      "  SAP APMaxAcceleration, Motor0, 25600\n"
      "  MVP ABS, Motor0, 1000\n"
      "  WAIT POS, Motor0, 0\n"
      "  STOP\n";
  tmcl::AsmOptions options;
  options.profile = module;
  const tmcl::AsmResult assembled = tmcl::assemble({"move.tmc"}, options, files);
  if (!assembled.ok()) {
    std::fputs(assembled.diags.render(assembled.sources).c_str(), stderr);
    return 1;
  }

  std::unique_ptr<tmcl::MotionCore> core = tmcl::make_motion_core(module->default_motion);
  tmcl::Vm vm(*module, *core);
  vm.load(assembled.program);
  vm.power_on(nullptr);
  vm.start(0);
  const tmcl::RunResult result = vm.run(tmcl::Limits{});
  const std::int32_t position = vm.axis_param(0, 1);
  std::printf("tmcl %s: %zu instructions, %.*s at %lld us, motor 0 at %d\n", tmcl::kVersion,
              assembled.program.size(), static_cast<int>(tmcl::halt_name(result.halt).size()),
              tmcl::halt_name(result.halt).data(), static_cast<long long>(vm.now), position);
  return result.halt == tmcl::Halt::Stop && position == 1000 ? 0 : 1;
}
