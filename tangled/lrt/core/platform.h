// lrt/core/platform.h: tangled from chapters/07-fast-bvh.md. Edit the chapter, not this file.
#pragma once

#include <cstddef>
#include <new>
#include <vector>

// Define the LRT_ALWAYS_INLINE macro
#if defined(__GNUC__) || defined(__clang__)
#define LRT_ALWAYS_INLINE inline __attribute__((always_inline))
#define LRT_ALWAYS_INLINE_LAMBDA __attribute__((always_inline))
#else
#define LRT_ALWAYS_INLINE inline
#define LRT_ALWAYS_INLINE_LAMBDA
#endif
// Define the LRT_PREFETCH macro
#if defined(__GNUC__) || defined(__clang__)
#define LRT_PREFETCH(address) __builtin_prefetch(address)
#else
#define LRT_PREFETCH(address) ((void)(address))
#endif

namespace lrt {

// Large Array Declarations
void *AllocateLargeArray(size_t bytes, size_t alignment);
void FreeLargeArray(void *p, size_t bytes, size_t alignment);

template <typename T>
struct LargeArrayAllocator {
    using value_type = T;
    LargeArrayAllocator() = default;
    template <typename U>
    LargeArrayAllocator(const LargeArrayAllocator<U> &) {}
    T *allocate(size_t n) {
        if (n > size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
        return static_cast<T *>(AllocateLargeArray(n * sizeof(T), alignof(T)));
    }
    void deallocate(T *p, size_t n) {
        FreeLargeArray(p, n * sizeof(T), alignof(T));
    }
    template <typename U>
    bool operator==(const LargeArrayAllocator<U> &) const { return true; }
    template <typename U>
    bool operator!=(const LargeArrayAllocator<U> &) const { return false; }
};

template <typename T>
using LargeArray = std::vector<T, LargeArrayAllocator<T>>;

}  // namespace lrt
