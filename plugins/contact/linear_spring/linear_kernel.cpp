// linear_spring's batch loop for one instruction set: compiled once per set (LANE_KERNELS in
// CMakeLists.txt), each object defining its own linear_kernel_<set>.
#include "shard/lanes/lane_type.hpp"
#include "linear_kernels.hpp"

namespace shard::linear {

contact::LawKernel<LinearLaw> SHARD_LANE_KERNEL(linear)(contact::EffectSwitches on) {
  return contact::kernel_for<lanes::LaneType, LinearLaw>(on);
}

}  // namespace shard::linear
