// A map from 32-bit keys to 32-bit values for the many small-key lookups of one pass (a grid's
// cells to a line's vertex, say): open addressing with linear probing in one array of 12-byte
// slots (the key plus one, 0 for a free slot, and the value), kept at most half full (it doubles
// when an insert would pass that), the slot found from the key's Fibonacci hash (Knuth: the key
// times 2^32 / golden ratio, its high bits). About 24 bytes an entry and no allocation per entry,
// where std::unordered_map takes about 40 and one allocation each. No erase.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace penink {

class U32Map {
public:
    explicit U32Map(std::size_t expected = 0) { grow(expected); }

    // Inserts key -> value unless the key is present (its value then kept); whether it inserted.
    bool insert(std::uint32_t key, std::uint32_t value) {
        if (2 * (size_ + 1) > slots_.size()) grow(size_ + 1);
        Slot& s = slot_of(key);
        if (s.key != 0) return false;
        s.key = std::uint64_t(key) + 1, s.value = value, ++size_;
        return true;
    }
    // The key's value, or null when absent (valid until the next insert).
    const std::uint32_t* find(std::uint32_t key) const {
        const Slot& s = const_cast<U32Map*>(this)->slot_of(key);
        return s.key != 0 ? &s.value : nullptr;
    }
    std::size_t size() const { return size_; }

private:
    struct Slot {
        std::uint64_t key = 0;  // key + 1; 0: free
        std::uint32_t value = 0;
    };
    std::vector<Slot> slots_;
    std::size_t size_ = 0;
    unsigned shift_ = 64;

    // The slot holding the key, or the free slot where it would go.
    Slot& slot_of(std::uint32_t key) {
        const std::size_t mask = slots_.size() - 1;
        std::size_t i = std::size_t((std::uint64_t(key) * 0x9e3779b97f4a7c15ull) >> shift_);
        while (slots_[i].key != 0 && slots_[i].key != std::uint64_t(key) + 1) i = (i + 1) & mask;
        return slots_[i];
    }
    // Room for n entries at most half full (at least 16 slots), the entries moved over.
    void grow(std::size_t n) {
        std::size_t want = 16;
        unsigned bits = 4;
        while (want < 2 * n) want *= 2, ++bits;
        if (want <= slots_.size()) return;
        std::vector<Slot> old(want);
        old.swap(slots_);
        shift_ = 64 - bits;
        for (const Slot& s : old)
            if (s.key != 0) slot_of(std::uint32_t(s.key - 1)) = s;
    }
};

}  // namespace penink
