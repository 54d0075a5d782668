// hertz_mindlin's batch loop for one instruction set: compiled once per set (LANE_KERNELS in
// CMakeLists.txt), each object defining its own hertz_kernel_<set>.
#include "shard/lanes/lane_type.hpp"
#include "hertz_kernels.hpp"

namespace shard::hertz {

contact::LawKernel<HertzLaw> SHARD_LANE_KERNEL(hertz)(contact::EffectSwitches on) {
  return contact::kernel_for<lanes::LaneType, HertzLaw>(on);
}

}  // namespace shard::hertz
