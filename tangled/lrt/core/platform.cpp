// lrt/core/platform.cpp: tangled from chapters/07-fast-bvh.md. Edit the chapter, not this file.
#include "lrt/core/platform.h"

#include <cstdlib>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace lrt {

// Large Array Definitions
constexpr size_t largePageSize = size_t(2) << 20;
constexpr size_t largePageThreshold = 4 * largePageSize;

void *AllocateLargeArray(size_t bytes, size_t alignment) {
#if defined(__linux__)
    if (bytes >= largePageThreshold) {
        if (bytes > size_t(-1) - largePageSize) throw std::bad_alloc();
        size_t rounded = (bytes + largePageSize - 1) / largePageSize *
                         largePageSize;
        void *p = std::aligned_alloc(largePageSize, rounded);
        if (!p) throw std::bad_alloc();
        (void)madvise(p, rounded, MADV_HUGEPAGE);
        return p;
    }
#endif
    return ::operator new(bytes, std::align_val_t(alignment));
}

void FreeLargeArray(void *p, size_t bytes, size_t alignment) {
#if defined(__linux__)
    if (bytes >= largePageThreshold) {
        std::free(p);
        return;
    }
#endif
    ::operator delete(p, std::align_val_t(alignment));
}

}  // namespace lrt
