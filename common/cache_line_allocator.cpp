#include "common/cache_line_allocator.h"

#include <sys/mman.h>

namespace rt {

void* allocate_huge(size_t bytes) {
  constexpr size_t kPage = CacheLineAllocator<char>::kHugePage;
  const size_t rounded = (bytes + kPage - 1) / kPage * kPage;  // aligned_alloc wants a multiple
  void* p = std::aligned_alloc(kPage, rounded);
  if (!p) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  // A hint: where transparent huge pages are "madvise" only (Debian's default), this is what asks
  // for them. Refused or not, the memory is the same.
  madvise(p, rounded, MADV_HUGEPAGE);
#endif
  return p;
}

}  // namespace rt
