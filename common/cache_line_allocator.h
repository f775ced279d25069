// Memory for the arrays a traversal reads at random (a BVH's nodes, a mesh's triangle packs): on
// cache-line boundaries, and in huge pages once an array is large.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>

namespace rt {

// Memory of `bytes` on 2 MiB boundaries, in huge pages where the system grants them; free() frees it.
void* allocate_huge(size_t bytes);

// Allocates on 64-byte boundaries (C++17 aligned new), so that each sibling pair of nodes, which
// starts at an even index, is exactly one cache line. An array of 2 MiB or more (a large mesh's
// nodes and packs) goes into huge pages instead: an incoherent ray on the 10^6-triangle mesh
// touches nodes and packs all over 80 MB, and with 4 KiB pages nearly every one of those reads also
// misses the TLB (the page table's cache). Measured in alternated runs of accel_scaling, the 4-wide
// tree there traces in 4.4-4.9 instead of 8.7-10.6 us per ray (docs/stage3.md, ladder step 10).
// Embree asks for huge pages on Linux by default too.
template <class T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlignment{64};
  static constexpr size_t kHugePage = size_t(2) << 20;
  CacheLineAllocator() = default;
  template <class U>
  CacheLineAllocator(const CacheLineAllocator<U>&) {}
  T* allocate(size_t n) {
    if (n * sizeof(T) >= kHugePage) return static_cast<T*>(allocate_huge(n * sizeof(T)));
    return static_cast<T*>(::operator new(n * sizeof(T), kAlignment));
  }
  void deallocate(T* p, size_t n) {
    if (n * sizeof(T) >= kHugePage) return std::free(p);
    ::operator delete(p, kAlignment);
  }
  friend bool operator==(const CacheLineAllocator&, const CacheLineAllocator&) { return true; }
};

}  // namespace rt
