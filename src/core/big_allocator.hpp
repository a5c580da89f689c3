// Allocators for the large per-cell arrays of a grid (millions of elements): blocks of 2 MiB and
// more are mapped 2 MiB-aligned and advised for transparent huge pages (madvise MADV_HUGEPAGE),
// so first touch takes one page fault per 2 MiB instead of one per 4 KiB (the kernel's THP mode
// "madvise", Debian's default; elsewhere the advice is harmless). Smaller blocks come from
// operator new. BigAllocator value-initialises like std::allocator; UninitAllocator leaves a
// trivial element made by resize untouched (the threads that fill it then fault in parallel).
#pragma once
#include <cstddef>
#include <memory>
#include <new>
#include <utility>

namespace penink {

inline constexpr std::size_t big_block_bytes = std::size_t(2) << 20;

// Throws std::bad_alloc when the memory cannot be had.
void* allocate_big(std::size_t bytes);
void deallocate_big(void* p, std::size_t bytes) noexcept;
// Gives the memory of bytes [from, to) of a block of `bytes` from allocate_big back to the
// system (the whole pages inside; they read as zeros after): an array consumed front to back
// shrinks as it goes. A block under big_block_bytes (from operator new) keeps its memory.
void release_big_pages(void* p, std::size_t bytes, std::size_t from, std::size_t to) noexcept;

// Advises the whole 2 MiB pages inside [p, p + bytes) of any memory for transparent huge pages
// (MADV_HUGEPAGE); takes effect for pages not yet touched.
void advise_huge_pages(void* p, std::size_t bytes) noexcept;
// The opposite, for a block from allocate_big (UninitAllocator) that is filled sparsely, by
// blocks of cells where they are read: its pages not advised for huge pages (MADV_NOHUGEPAGE),
// so a part written takes 4 KiB pages, not the 2 MiB around it. Call before first touch.
void advise_small_pages(void* p, std::size_t bytes) noexcept;
// v (a std::vector of a trivial type, empty or not) sized to n elements, its new storage advised
// for transparent huge pages before it is first touched (reserve, advise_huge_pages, then
// resize): an array then filled whole faults once per 2 MiB instead of once per 4 KiB. Not for
// an array whose parts are filled sparsely (its pages are taken 2 MiB at a time).
template <class V> void resize_in_huge_pages(V& v, std::size_t n) {
    if (n > v.capacity()) {
        V fresh;
        fresh.reserve(n);
        advise_huge_pages(fresh.data(), n * sizeof(typename V::value_type));
        fresh.assign(v.begin(), v.end());
        v.swap(fresh);
    }
    v.resize(n);
}

template <class T> struct BigAllocator {
    using value_type = T;
    BigAllocator() = default;
    template <class U> BigAllocator(const BigAllocator<U>&) noexcept {}
    T* allocate(std::size_t n) {
        if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
        return static_cast<T*>(allocate_big(n * sizeof(T)));
    }
    void deallocate(T* p, std::size_t n) noexcept { deallocate_big(p, n * sizeof(T)); }
    template <class U> bool operator==(const BigAllocator<U>&) const noexcept { return true; }
};

template <class T> struct UninitAllocator : BigAllocator<T> {
    template <class U> struct rebind {
        using other = UninitAllocator<U>;
    };
    UninitAllocator() = default;
    template <class U> UninitAllocator(const UninitAllocator<U>&) noexcept {}
    template <class U, class... A> void construct(U* p, A&&... args) {
        if constexpr (sizeof...(A) == 0) ::new (static_cast<void*>(p)) U;
        else ::new (static_cast<void*>(p)) U(std::forward<A>(args)...);
    }
};

}  // namespace penink
