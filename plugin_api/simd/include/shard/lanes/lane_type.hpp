#pragma once
// The lane type of the object being compiled (cmake/ShardPlugin.cmake, LANE_KERNELS defines one
// SHARD_LANES_<SET>), and the name its kernel function takes, so one source serves every set.
#include <xsimd/xsimd.hpp>

#include "shard/lanes/xsimd_lanes.hpp"

namespace shard::lanes {

#if defined(SHARD_LANES_AVX512)
using LaneType = xsimd::batch<double, xsimd::avx512f>;
#define SHARD_LANE_KERNEL(law) law##_kernel_avx512
#elif defined(SHARD_LANES_AVX2)
using LaneType = xsimd::batch<double, xsimd::avx2>;
#define SHARD_LANE_KERNEL(law) law##_kernel_avx2
#elif defined(SHARD_LANES_BASELINE)
using LaneType = xsimd::batch<double>;  // the target's default set: SSE2 on x86-64, NEON on arm64
#define SHARD_LANE_KERNEL(law) law##_kernel_baseline
#elif defined(SHARD_LANES_SCALAR)
using LaneType = double;  // the scalar reference
#define SHARD_LANE_KERNEL(law) law##_kernel_scalar
#else
#error "a lane kernel is compiled through LANE_KERNELS (cmake/ShardPlugin.cmake), which defines SHARD_LANES_<SET>"
#endif

}  // namespace shard::lanes
