// Example of a custom motion core: `slow` moves every motor at one constant speed (axis
// parameter 4, default 1000 pps) with no acceleration at all, in integer arithmetic.
// Register it before creating a VM:  tmcl::register_motion_core("slow", make_slow_motion_core);
#pragma once

#include <memory>

#include "tmcl/motion.hpp"

std::unique_ptr<tmcl::MotionCore> make_slow_motion_core();
