#pragma once
// Large per-particle, per-bond and per-pair arrays on transparent huge pages (2 MB) where the
// system hands them out on request (Linux's default "madvise" mode). The force pass reads the
// larger ends of bonds and pairs a jump away along the Morton curve: with 4 kB pages nearly each
// such row would also miss the TLB (the seed beam's arrays are ~400 MB; the TLB maps a few MB). The
// advice is given before the first write, so the pages are huge from the start. Elsewhere, or when
// the system refuses, the arrays are ordinary and every value the same.
#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace shard {

// Below this an array is cheap to map whatever the page size.
inline constexpr std::size_t kHugeArrayBytes = std::size_t{4} << 20;

// Asks for huge pages over the whole pages of [data, data + bytes); a hint, its failure harmless.
inline void advise_huge_pages([[maybe_unused]] void* data, [[maybe_unused]] std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kPage = 4096;
  const auto begin = (reinterpret_cast<std::uintptr_t>(data) + kPage - 1) & ~(kPage - 1);
  const auto end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kPage - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#endif
}

// v.resize(n), a large array that has to grow taking fresh storage advised for huge pages before
// anything is written to it (its old elements are copied over).
template <class T, class A>
void resize_on_huge_pages(std::vector<T, A>& v, std::size_t n) {
  if (n > v.capacity() && n * sizeof(T) >= kHugeArrayBytes) {
    std::vector<T, A> fresh;
    fresh.reserve(n);  // mapped, not yet touched
    advise_huge_pages(fresh.data(), n * sizeof(T));
    fresh.assign(v.begin(), v.end());
    v.swap(fresh);
  }
  v.resize(n);
}

// v.assign(n, value) on the same terms.
template <class T, class A>
void assign_on_huge_pages(std::vector<T, A>& v, std::size_t n, const T& value) {
  if (n > v.capacity() && n * sizeof(T) >= kHugeArrayBytes) {
    std::vector<T, A>().swap(v);
    v.reserve(n);
    advise_huge_pages(v.data(), n * sizeof(T));
  }
  v.assign(n, value);
}

}  // namespace shard
