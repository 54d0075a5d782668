// The block step in the build's own lanes (x86-64-v2: SSE4.2, 2 bonds), and the run-time choice
// among the instruction sets the plugin was compiled for.
#include "beam_block.hpp"

namespace shard::beam {

#if defined(__x86_64__)
void evaluate_block_avx2(const BlockInput& in, BlockOutput& out, std::size_t n, const BlockConstants& c);
void evaluate_block_avx512(const BlockInput& in, BlockOutput& out, std::size_t n, const BlockConstants& c);
#endif

namespace {

void evaluate_block_baseline(const BlockInput& in, BlockOutput& out, std::size_t n, const BlockConstants& c) {
  evaluate_block<xsimd::default_arch>(in, out, n, c);
}

}  // namespace

const char* name_of(BlockIsa isa) {
  switch (isa) {
    case BlockIsa::Avx512: return "avx512f";
    case BlockIsa::Avx2: return "avx2";
    case BlockIsa::Baseline: break;
  }
  return xsimd::default_arch::name();
}

// A plain CPU test rather than an ifunc, which may run before the sanitizer runtime is initialised.
bool runs_here(BlockIsa isa) {
#if defined(__x86_64__)
  switch (isa) {
    case BlockIsa::Avx512: return __builtin_cpu_supports("avx512f");
    case BlockIsa::Avx2: return __builtin_cpu_supports("avx2");
    case BlockIsa::Baseline: break;
  }
#endif
  return isa == BlockIsa::Baseline;
}

BlockFunction block_function(BlockIsa isa) {
  switch (isa) {
#if defined(__x86_64__)
    case BlockIsa::Avx512: return evaluate_block_avx512;
    case BlockIsa::Avx2: return evaluate_block_avx2;
#endif
    default: return evaluate_block_baseline;
  }
}

BlockIsa widest_block_isa() {
  for (const BlockIsa isa : {BlockIsa::Avx512, BlockIsa::Avx2})
    if (runs_here(isa)) return isa;
  return BlockIsa::Baseline;
}

}  // namespace shard::beam
