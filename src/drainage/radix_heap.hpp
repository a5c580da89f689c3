// Monotone min-queue of (key, cell) pairs: a radix heap (Ahuja, Mehlhorn, Orlin & Tarjan 1990,
// "Faster algorithms for the shortest path problem"), exact as long as no key pushed is below
// the last key popped (last()); amortised O(bits) per entry. Keys are unsigned integers; for
// elevations use float_order_key, which orders like the float. Used by the priority-flood fill
// and the least-cost search (Key = 64 bits: elevation key above an insertion counter).
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <limits>
#include <vector>

namespace penink {

// Unsigned key ordered like the float elevation (-0 and +0 alike; NaN never occurs).
inline std::uint32_t float_order_key(float z) {
    const std::uint32_t b = std::bit_cast<std::uint32_t>(z + 0.0f);
    return (b & 0x80000000u) ? ~b : (b | 0x80000000u);
}

// The elevation a float_order_key came from (-0 comes back as +0).
inline float float_of_order_key(std::uint32_t k) {
    return std::bit_cast<float>((k & 0x80000000u) ? (k & 0x7fffffffu) : ~k);
}

template <class Key> class RadixHeap {
public:
    struct Entry {
        Key key;
        std::uint32_t cell;
    };
    bool empty() const { return count_ == 0; }
    Key last() const { return last_; }  // the last key popped (0 before any)
    void push(Key key, std::uint32_t cell) { bucket_[slot(key ^ last_)].push_back({key, cell}), ++count_; }
    // An entry with the least key (among equal keys the last pushed).
    Entry pop() {
        if (bucket_[0].empty()) refill();
        const Entry e = bucket_[0].back();
        bucket_[0].pop_back(), --count_;
        return e;
    }

private:
    static constexpr int bits = std::numeric_limits<Key>::digits;
    // Bucket k holds keys whose highest bit differing from last_ is bit k-1 (0: equal to last_).
    static int slot(Key x) { return x ? bits - std::countl_zero(x) : 0; }
    // Moves the first non-empty bucket's least key to last_ and spreads the bucket out.
    void refill() {
        int k = 1;
        while (bucket_[k].empty()) ++k;
        Key least = bucket_[k].front().key;
        for (const Entry& e : bucket_[k]) least = std::min(least, e.key);
        last_ = least;
        for (const Entry& e : bucket_[k]) bucket_[slot(e.key ^ last_)].push_back(e);
        bucket_[k].clear();
    }
    std::vector<Entry> bucket_[bits + 1];
    Key last_ = 0;
    std::size_t count_ = 0;
};

}  // namespace penink
