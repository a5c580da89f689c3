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

// A queue entry: the key and the cell it orders.
template <class Key> struct RadixEntry {
    Key key;
    std::uint32_t cell;
};

template <class Key> class RadixHeap {
public:
    using Entry = RadixEntry<Key>;
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

// Radix heap whose equal keys leave in the order they came (first in, first out), so it pops by
// (key, insertion order) with the 8-byte entries of a 32-bit key. Buckets go by 4-bit digits
// (the radix heap's multi-digit variant, Ahuja et al. 1990 section 4): bucket 1 + 16 i + v holds
// the keys whose highest digit differing from last_ is digit i, with value v there; bucket 0 the
// keys equal to last_. For keys >= last_ the bucket order is the key order, and a key moves at
// most i times (each refill drops it at least one digit) instead of once per bit. Why it is exact:
//  - Every entry lies in bucket slot(key, last_), a function of its key while last_ stands.
//    refill moves last_ to the least key of the first non-empty bucket (i, v); the new last_
//    agrees with the old above digit i, so entries of buckets at higher digits keep their
//    bucket, entries at digit i with another value w != v still differ first there (with value
//    w), and bucket (i, v)'s entries go to buckets below digit i or to bucket 0. Hence all
//    entries of one key lie in one bucket.
//  - Within a bucket, the entries of one key stand in insertion order: push appends the newest,
//    and refill copies bucket (i, v) front to back into lower buckets, none of which held those
//    keys (they all lay in bucket (i, v)).
//  - Bucket 0 holds only keys equal to last_ and is read from the front (head_), pushes of
//    last_ joining at its back: entries of the least key leave oldest first. refill runs only
//    when bucket 0 is used up, and every key it moves is above the old last_.
template <class Key> class FifoRadixHeap {
public:
    using Entry = RadixEntry<Key>;
    bool empty() const { return count_ == 0; }
    Key last() const { return last_; }  // the last key popped (0 before any)
    void push(Key key, std::uint32_t cell) {
        const int b = slot(key, last_);
        bucket_[b].push_back({key, cell}), ++count_;
        if (b) mark(nonempty_, b);
    }
    // The oldest entry with the least key. A first non-empty bucket of one entry is popped
    // directly (what refill would do, less moving it through bucket 0).
    Entry pop() {
        --count_;
        if (head_ < bucket_[0].size()) return bucket_[0][head_++];
        bucket_[0].clear(), head_ = 0;
        const int k = first_nonempty();
        if (bucket_[k].size() == 1) {
            const Entry e = bucket_[k].front();
            bucket_[k].clear(), unmark(nonempty_, k), last_ = e.key;
            return e;
        }
        refill(k);
        return bucket_[0][head_++];
    }
    // The entry the next pop returns unless a lower key is pushed first, when it is cheap to
    // know (bucket 0's next, else the least of the next non-empty bucket if it holds at most
    // `scan` entries); else null. Lets a caller prefetch what that entry's visit reads.
    const Entry* upcoming(std::size_t scan = 8) const {
        if (head_ < bucket_[0].size()) return &bucket_[0][head_];
        const int k = first_nonempty();
        if (!k || bucket_[k].size() > scan) return nullptr;
        const Entry* least = &bucket_[k].front();
        for (const Entry& e : bucket_[k]) least = e.key < least->key ? &e : least;
        return least;
    }

private:
    static constexpr int bits = std::numeric_limits<Key>::digits, digit_bits = 4, radix = 1 << digit_bits;
    static constexpr int buckets = 1 + bits / digit_bits * radix, mask_words = (buckets - 1 + 63) / 64;
    static_assert(bits % digit_bits == 0);
    using Mask = std::uint64_t[mask_words];  // bit b - 1 set: bucket b >= 1 holds entries
    static int slot(Key key, Key last) {
        const Key x = key ^ last;
        if (!x) return 0;
        const int i = (bits - 1 - std::countl_zero(x)) / digit_bits;
        return 1 + i * radix + int((key >> (i * digit_bits)) & Key(radix - 1));
    }
    static void mark(Mask& m, int b) { m[(b - 1) >> 6] |= std::uint64_t(1) << ((b - 1) & 63); }
    static void unmark(Mask& m, int b) { m[(b - 1) >> 6] &= ~(std::uint64_t(1) << ((b - 1) & 63)); }
    int first_nonempty() const {  // 0 when buckets 1.. are all empty
        for (int w = 0; w < mask_words; ++w)
            if (nonempty_[w]) return 1 + 64 * w + std::countr_zero(nonempty_[w]);
        return 0;
    }
    // With bucket 0 empty: moves last_ to the least key of bucket k, the first non-empty one,
    // and spreads that bucket out, front to back.
    void refill(int k) {
        std::vector<Entry>& from = bucket_[k];
        Key least = from.front().key;
        for (const Entry& e : from) least = std::min(least, e.key);
        last_ = least;
        Mask m;
        std::copy(std::begin(nonempty_), std::end(nonempty_), std::begin(m));
        for (const Entry& e : from) {
            const int b = slot(e.key, least);
            bucket_[b].push_back(e);
            if (b) mark(m, b);
        }
        from.clear(), unmark(m, k);
        std::copy(std::begin(m), std::end(m), std::begin(nonempty_));
    }
    std::vector<Entry> bucket_[buckets];
    Mask nonempty_ = {};
    std::size_t head_ = 0;  // next entry of bucket 0 to pop
    Key last_ = 0;
    std::size_t count_ = 0;
};

}  // namespace penink
