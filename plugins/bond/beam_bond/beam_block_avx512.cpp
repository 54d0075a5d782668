// The block step in AVX-512 lanes (8 bonds), compiled with -mavx512f (CMakeLists.txt).
// Only x86-64 has it; elsewhere the file is empty and the baseline lanes run.
#if defined(__x86_64__)
#include "beam_block.hpp"

namespace shard::beam {

void evaluate_block_avx512(const BlockInput& in, BlockOutput& out, std::size_t n, const BlockConstants& c) {
  evaluate_block<xsimd::avx512f>(in, out, n, c);
}

}  // namespace shard::beam
#endif
