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

// RadixHeap whose equal keys leave in the order they came (first in, first out), so it pops by
// (key, insertion order) with the 8-byte entries of a 32-bit key. Why it is exact:
//  - Every entry lies in bucket slot(key ^ last_), a function of its key while last_ stands.
//    refill moves last_ to the least key of the first non-empty bucket k; the new last_ agrees
//    with the old above bit k-1, so entries of the buckets above k keep their bucket and bucket
//    k's entries go to buckets below k. Hence all entries of one key lie in one bucket.
//  - Within a bucket, the entries of one key stand in insertion order: push appends the newest,
//    and refill copies bucket k front to back into lower buckets, none of which held those keys
//    (they all lay in bucket k).
//  - Bucket 0 holds only keys equal to last_ and is read from the front (head_), pushes of
//    last_ joining at its back: entries of the least key leave oldest first. refill runs only
//    when bucket 0 is used up, and every key it moves is above the old last_.
template <class Key> class FifoRadixHeap {
public:
    struct Entry {
        Key key;
        std::uint32_t cell;
    };
    bool empty() const { return count_ == 0; }
    Key last() const { return last_; }  // the last key popped (0 before any)
    void push(Key key, std::uint32_t cell) {
        const int k = slot(key ^ last_);
        bucket_[k].push_back({key, cell}), nonempty_ |= std::uint64_t(1) << k, ++count_;
    }
    // The oldest entry with the least key.
    Entry pop() {
        if (head_ == bucket_[0].size()) refill();
        --count_;
        return bucket_[0][head_++];
    }
    // The entry the next pop returns unless a lower key is pushed first, when it is cheap to
    // know (bucket 0's next, else the least of the next non-empty bucket if it holds at most
    // `scan` entries); else null. Lets a caller prefetch what that entry's visit reads.
    const Entry* upcoming(std::size_t scan = 8) const {
        if (head_ < bucket_[0].size()) return &bucket_[0][head_];
        const std::uint64_t rest = nonempty_ & ~std::uint64_t(1);
        if (!rest) return nullptr;
        const std::vector<Entry>& b = bucket_[std::countr_zero(rest)];
        if (b.size() > scan) return nullptr;
        const Entry* least = &b.front();
        for (const Entry& e : b) least = e.key < least->key ? &e : least;
        return least;
    }

private:
    static constexpr int bits = std::numeric_limits<Key>::digits;
    // Bucket k holds keys whose highest bit differing from last_ is bit k-1 (0: equal to last_).
    static int slot(Key x) { return x ? bits - std::countl_zero(x) : 0; }
    // Empties bucket 0, moves last_ to the first non-empty bucket's least key and spreads that
    // bucket out, front to back.
    void refill() {
        bucket_[0].clear(), head_ = 0;
        const int k = std::countr_zero(nonempty_ & ~std::uint64_t(1));
        Key least = bucket_[k].front().key;
        for (const Entry& e : bucket_[k]) least = std::min(least, e.key);
        last_ = least;
        for (const Entry& e : bucket_[k]) {
            const int j = slot(e.key ^ last_);
            bucket_[j].push_back(e), nonempty_ |= std::uint64_t(1) << j;
        }
        bucket_[k].clear(), nonempty_ &= ~(std::uint64_t(1) << k);
    }
    static_assert(bits < 64);
    std::vector<Entry> bucket_[bits + 1];
    std::uint64_t nonempty_ = 0;  // bit k set: bucket k may hold entries (k >= 1: exactly when it does)
    std::size_t head_ = 0;  // next entry of bucket 0 to pop
    Key last_ = 0;
    std::size_t count_ = 0;
};

}  // namespace penink
