// Direct mode: one command from a host, executed against the same state a running program sees
// (USB-2-SD manual 7.6). Reads reply with the value and leave the accumulator and flags alone
// (load<true> in vm_ops.hpp); arithmetic works on the registers as in a program; flow-control
// commands have no effect (E14). Control commands (128..138, 255) belong to the server that
// speaks the protocol; here they answer "invalid command".
#include "tmcl/vm.hpp"
#include "vm_ops.hpp"

namespace tmcl {

DirectReply Vm::execute_direct(const Instruction& ins) {
  const OpInfo* info = op_info(ins.op);
  if (!info || info->control) return {kStatusInvalidCommand, 0};
  if (!profile->has_command(ins.op)) return {kStatusNotAvailable, 0};
  bool known = false;
  DirectReply r = ops::dispatch<true>(*this, ins, known);
  if (!known) return {kStatusInvalidCommand, 0};
  return r;
}

}  // namespace tmcl
