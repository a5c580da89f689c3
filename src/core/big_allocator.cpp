#include "core/big_allocator.hpp"

#include <algorithm>
#include <cstdint>

#include <sys/mman.h>

namespace penink {

namespace {

std::size_t mapped_bytes(std::size_t bytes) {  // whole 2 MiB blocks
    return (bytes + big_block_bytes - 1) / big_block_bytes * big_block_bytes;
}

}  // namespace

// Maps one block more than needed and unmaps the unaligned head and the tail, so the array starts
// on a 2 MiB boundary (a huge page can only back an aligned 2 MiB range).
void* allocate_big(std::size_t bytes) {
    if (bytes < big_block_bytes) return ::operator new(bytes == 0 ? 1 : bytes);
    const std::size_t size = mapped_bytes(bytes);
    if (size < bytes) throw std::bad_alloc();
    void* m = ::mmap(nullptr, size + big_block_bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (m == MAP_FAILED) throw std::bad_alloc();
    const auto base = reinterpret_cast<std::uintptr_t>(m);
    const std::uintptr_t start = (base + big_block_bytes - 1) / big_block_bytes * big_block_bytes;
    if (start > base) ::munmap(m, start - base);
    if (const std::size_t tail = base + size + big_block_bytes - (start + size)) ::munmap(reinterpret_cast<void*>(start + size), tail);
    void* p = reinterpret_cast<void*>(start);
#ifdef MADV_HUGEPAGE  // Linux; elsewhere plain pages
    ::madvise(p, size, MADV_HUGEPAGE);
#endif
    return p;
}

void deallocate_big(void* p, std::size_t bytes) noexcept {
    if (bytes < big_block_bytes) return ::operator delete(p);
    ::munmap(p, mapped_bytes(bytes));
}

void release_big_pages(void* p, std::size_t bytes, std::size_t from, std::size_t to) noexcept {
    if (bytes < big_block_bytes) return;
    constexpr std::size_t page = 4096;
    const std::size_t a = (std::min(from, bytes) + page - 1) / page * page, b = std::min(to, bytes) / page * page;
    if (b > a) ::madvise(static_cast<char*>(p) + a, b - a, MADV_DONTNEED);
}

void advise_huge_pages(void* p, std::size_t bytes) noexcept {
#ifdef MADV_HUGEPAGE
    const auto at = reinterpret_cast<std::uintptr_t>(p);
    const std::uintptr_t a = (at + big_block_bytes - 1) / big_block_bytes * big_block_bytes,
                         b = (at + bytes) / big_block_bytes * big_block_bytes;
    if (b > a) ::madvise(reinterpret_cast<void*>(a), b - a, MADV_HUGEPAGE);
#else
    (void)p, (void)bytes;
#endif
}

void advise_small_pages(void* p, std::size_t bytes) noexcept {
#ifdef MADV_NOHUGEPAGE
    constexpr std::uintptr_t page = 4096;
    const auto at = reinterpret_cast<std::uintptr_t>(p);
    const std::uintptr_t a = at / page * page, b = (at + bytes + page - 1) / page * page;
    if (bytes >= big_block_bytes) ::madvise(reinterpret_cast<void*>(a), b - a, MADV_NOHUGEPAGE);
#else
    (void)p, (void)bytes;
#endif
}

}  // namespace penink
