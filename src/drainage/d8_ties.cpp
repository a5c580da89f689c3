#include "drainage/d8_ties.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <chrono>
#include <climits>
#include <limits>
#include <thread>
#include <utility>

#include "core/parallel_chunks.hpp"
#include "core/radix_sort.hpp"
#include "drainage/d8_steepest.hpp"
#include "drainage/depression_drainage.hpp"
#include "drainage/flat_resolution.hpp"
#include "drainage/priority_flood.hpp"
#include "drainage/radix_heap.hpp"

namespace penink {

namespace {

struct Ties {
    const std::vector<float>& filled;
    const std::vector<std::uint8_t>& flags;
    const CellWords& orig;  // every cell's original elevation (float bits: complete_originals)
    const GridShape& g;
    D8Steps st;
    std::vector<std::uint8_t>& dir;  // written only by settle
    const CellWords& flat_mask;  // flat gradients as int32 (flat_resolution.hpp)
    int depth;

    float original(std::size_t n) const { return std::bit_cast<float>(orig[n]); }
    std::int32_t gradient(std::size_t i) const { return std::int32_t(flat_mask[i]); }
    bool flat_cell(std::size_t i) const {
        return (flags[i] & flat_seen_low) && !(flags[i] & fill_raised) && gradient(i) != INT32_MIN;
    }
    // Settling order: lower cells first; on one level D8 cells, then flat cells nearer the exit,
    // then by index: (key, index) ascending, key = the filled elevation's order key above the
    // rank (0 for a D8 cell; for a flat cell its gradient's order, 1 and up).
    std::uint64_t order_key(std::size_t i) const {
        return std::uint64_t(float_order_key(filled[i])) << 32 | rank(i);
    }
    std::uint32_t rank(std::size_t i) const {
        return flat_cell(i) ? std::uint32_t(gradient(i)) ^ 0x80000000u : 0;  // gradient > INT32_MIN
    }

    // Asks the cache for the rows around cell i that the first steps of choose read (original
    // elevations, directions; a hint: settling follows elevation, not memory order).
    void prefetch(std::size_t i) const {
        const std::size_t cols = std::size_t(g.cols), n = filled.size();
        for (const std::size_t r : {i >= cols ? i - cols : i, i, i + cols < n ? i + cols : i}) {
            __builtin_prefetch(&orig[r]);
            __builtin_prefetch(&dir[r]);
        }
    }

    // Bit k set for every admissible neighbour k with the steepest slope (stage rules above).
    unsigned steepest_set(std::size_t i) const {
        if (flat_cell(i)) return flat_candidates(filled, g, flags, flat_mask, i);
        const int c = int(i % std::size_t(g.cols)), r = int(i / std::size_t(g.cols));
        const float zi = original(i), level = filled[i];
        const bool raised = flags[i] & fill_raised;
        auto zn = [&](std::size_t n) { return original(n); };
        auto ok = [&](std::size_t n) { return raised ? original(n) < zi : filled[n] < level; };
        return d8_steepest(zi, g, c, r, st, zn, ok).steepest;
    }

    // The neighbours break_d8_ties chooses among for tie i: steepest_set, none for an outflow cell
    // (it keeps its direction). Reads no direction.
    unsigned candidates(std::size_t i) const { return flags[i] & depression_outflow ? 0u : steepest_set(i); }

    // Of the neighbours in `set`, the one whose path comes first: the original elevations along
    // each path, `depth` entries (past the grid's edge: -inf), compared lexicographically; equal:
    // the lowest code; as an ESRI code. The paths are walked side by side, each step keeping
    // those at the step's least elevation, until one is left; paths at one cell at one step (or
    // both past the edge) are equal from there on, and only the lowest code of them is kept.
    // (What comparing the paths two at a time finds, with no path walked twice.)
    std::uint8_t choose(std::size_t i, unsigned set) const {
        constexpr float past = -std::numeric_limits<float>::infinity();
        std::array<int, 8> code;  // the paths still in, lowest code first, ...
        std::array<std::size_t, 8> at;  // ... where each is (out: past the edge)
        std::array<bool, 8> out;
        int m = 0;
        for (unsigned rest = set; rest; rest &= rest - 1, ++m) {
            code[m] = std::countr_zero(rest);
            at[m] = std::size_t(std::ptrdiff_t(i) + st.off[code[m]]), out[m] = false;
        }
        for (int j = 0; j < depth && m > 1; ++j) {
            std::array<float, 8> z;
            float least = std::numeric_limits<float>::infinity();
            for (int q = 0; q < m; ++q) least = std::min(least, z[q] = out[q] ? past : original(at[q]));
            int kept = 0;
            for (int q = 0; q < m; ++q) {
                if (!(z[q] == least)) continue;
                bool same = false;  // as a path kept before it
                for (int p = 0; p < kept; ++p) same |= out[p] ? out[q] : !out[q] && at[p] == at[q];
                if (same) continue;
                code[kept] = code[q], at[kept] = at[q], out[kept] = out[q], ++kept;
            }
            m = kept;
            for (int q = 0; q < m; ++q)
                if (!out[q]) dir[at[q]] ? void(at[q] = d8_target(g, at[q], dir[at[q]])) : void(out[q] = true);
        }
        return std::uint8_t(1u << code[0]);
    }

    // Tie i with candidates `set` re-aimed (one left with fewer than two, kept); whether its
    // direction changed.
    bool settle(std::size_t i, unsigned set) const {
        if ((set & (set - 1)) == 0) return false;
        const std::uint8_t code = choose(i, set);
        return std::exchange(dir[i], code) != code;
    }
};

// The ties in settling order, each with its candidates (Ties::candidates).
struct SortedTies {
    std::vector<std::uint32_t>& cells;
    std::vector<std::uint8_t> sets;
};

// The ties settled one by one in the given order (ties.cells[position(k)] for k = 0..n-1),
// wait(k) called before the k-th and done(k) after it; the cells a few places ahead asked of the
// cache. Returns how many changed direction.
template <class Position, class Wait, class Done>
std::size_t settle_in_order(const Ties& t, const SortedTies& ties, std::size_t n, Position&& position, Wait&& wait,
                            Done&& done) {
    constexpr std::size_t ahead = 16;
    std::size_t changed = 0;
    for (std::size_t k = 0; k < n; ++k) {
        if (k + ahead < n) t.prefetch(ties.cells[position(k + ahead)]);
        wait(k);
        const std::size_t p = position(k);
        changed += t.settle(ties.cells[p], ties.sets[p]);
        done(k);
    }
    return changed;
}

// Progress in one slot (a strip's top or bottom band, a run of `segment_cols` columns): the
// position (in the settling order) of the slot's next tie not yet settled, on a cache line of its
// own.
struct alignas(64) SlotProgress {
    std::atomic<std::uint64_t> next{UINT64_MAX};
};

// Returns once `next` is past p: spinning a little, then yielding, then sleeping 20 us at a time
// (a thread whose neighbour is not running lets it run instead of burning the core).
void wait_until_past(const std::atomic<std::uint64_t>& next, std::uint64_t p) {
    for (int spins = 0; next.load(std::memory_order_acquire) < p; ++spins)
        if (spins >= 256) std::this_thread::sleep_for(std::chrono::microseconds(20));
        else if (spins >= 64) std::this_thread::yield();
}

// The ties (in settling order) settled on `threads` threads with the same result as one by one:
// the rows cut into strips of `strip_rows` (> depth) dealt round-robin to the threads, each
// settling its strips' ties in the settling order. A tie reads directions only within `depth`
// cells of itself (its neighbours' paths, Chebyshev distance) and writes only its own, so ties of
// two strips interact only when both lie within `depth` rows of the strips' common edge (band
// ties) and within `depth` columns of each other: in the same or the next slot (bands cut into
// runs of `segment_cols` >= depth columns). Before a band tie at position p a thread waits until
// the neighbouring strip has settled its ties before p in the three facing slots; that strip's
// thread waits for it likewise: every tie reads the directions it would one by one. The first
// band tie not yet settled never waits, so the threads always progress.
std::size_t settle_in_strips(const Ties& t, const SortedTies& sorted, unsigned threads, int strip_rows,
                             int segment_cols) {
    const std::vector<std::uint32_t>& ties = sorted.cells;
    const std::uint64_t cols = std::uint64_t(t.g.cols), span = std::uint64_t(strip_rows) * cols;
    const int depth = t.depth, strips = (t.g.rows + strip_rows - 1) / strip_rows;
    const int segments = (t.g.cols + segment_cols - 1) / segment_cols;
    // slot of strip s, edge e (0 top, 1 bottom), segment g
    auto slot = [&](int s, int e, int g) { return (std::size_t(s) * 2 + std::size_t(e)) * std::size_t(segments) + std::size_t(g); };
    // Where tie cell i lies: its strip, segment, and whether in the top / bottom band.
    struct Place {
        int strip, segment;
        bool top, bottom;
    };
    auto place_of = [&](std::uint64_t i) {
        const int r = int(i / cols), c = int(i % cols), s = r / strip_rows, local = r - s * strip_rows;
        return Place{s, c / segment_cols, local < depth, local >= strip_rows - depth};
    };
    std::vector<SlotProgress> progress(std::size_t(strips) * 2 * std::size_t(segments));
    // each thread's ties in order: positions, the top bit set on band ties; for its band ties in
    // order, the position of the next tie in the same top and bottom slot (UINT32_MAX: none)
    constexpr std::uint32_t band_bit = 0x80000000u, none = UINT32_MAX;
    const double per_span = 1.0 / double(span);
    const std::uint64_t band = std::uint64_t(depth) * cols;
    std::vector<std::vector<std::uint32_t>> lists(threads);
    std::vector<std::vector<std::array<std::uint32_t, 2>>> next_in_slot(threads);
    parallel_chunks(threads, 1, [&](std::size_t m0, std::size_t m1) {
        for (std::size_t me = m0; me < m1; ++me) {
            std::vector<std::uint32_t>& mine = lists[me];
            for (std::size_t p = 0; p < ties.size(); ++p) {
                const std::uint64_t i = ties[p];
                std::uint64_t strip = std::uint64_t(double(i) * per_span);  // i / span, corrected below
                strip -= strip * span > i, strip += (strip + 1) * span <= i;
                const std::uint64_t off = i - strip * span;
                if (strip % threads == me) mine.push_back(std::uint32_t(p) | (off < band || off + band >= span ? band_bit : 0));
            }
            std::vector<std::uint32_t> later(progress.size(), none);  // backwards: next position per slot
            std::vector<std::array<std::uint32_t, 2>>& next = next_in_slot[me];
            for (std::size_t k = mine.size(); k-- > 0;) {
                if (!(mine[k] & band_bit)) continue;
                const std::uint32_t p = mine[k] & ~band_bit;
                const Place x = place_of(ties[p]);
                std::array<std::uint32_t, 2> n{none, none};
                for (int e = 0; e < 2; ++e)
                    if (e ? x.bottom : x.top) n[std::size_t(e)] = std::exchange(later[slot(x.strip, e, x.segment)], p);
                next.push_back(n);
            }
            std::reverse(next.begin(), next.end());
            for (std::size_t q = 0; q < later.size(); ++q)  // this thread's slots: their first tie
                if (later[q] != none) progress[q].next.store(later[q], std::memory_order_relaxed);
        }
    });
    std::vector<std::size_t> changed(threads, 0);
    auto run = [&](unsigned me) {  // allocates nothing: the others wait on it
        const std::vector<std::uint32_t>& mine = lists[me];
        const std::vector<std::array<std::uint32_t, 2>>& next = next_in_slot[me];
        std::size_t band_k = 0;  // band ties settled so far
        changed[me] = settle_in_order(
            t, sorted, mine.size(), [&](std::size_t k) { return mine[k] & ~band_bit; },
            [&](std::size_t k) {
                if (!(mine[k] & band_bit)) return;
                const std::uint64_t p = mine[k] & ~band_bit;
                const Place x = place_of(ties[p]);
                for (int e = 0; e < 2; ++e) {
                    const int facing = e ? x.strip + 1 : x.strip - 1;
                    if (!(e ? x.bottom : x.top) || facing < 0 || facing >= strips) continue;
                    for (int g = std::max(0, x.segment - 1); g <= std::min(segments - 1, x.segment + 1); ++g)
                        wait_until_past(progress[slot(facing, 1 - e, g)].next, p);
                }
            },
            [&](std::size_t k) {
                if (!(mine[k] & band_bit)) return;
                const Place x = place_of(ties[mine[k] & ~band_bit]);
                for (int e = 0; e < 2; ++e)
                    if (e ? x.bottom : x.top) {
                        const std::uint32_t n = next[band_k][std::size_t(e)];
                        progress[slot(x.strip, e, x.segment)].next.store(n == none ? UINT64_MAX : n,
                                                                         std::memory_order_release);
                    }
                ++band_k;
            });
    };
    std::vector<std::thread> others;
    for (unsigned me = 1; me < threads; ++me) others.emplace_back(run, me);
    run(0);
    for (std::thread& th : others) th.join();
    std::size_t total = 0;
    for (const std::size_t c : changed) total += c;
    return total;
}

// What the order keys of a list of ties span (Ties::order_key): the filled elevations' order
// keys (least, greatest, the bits where any differs from `first`'s) and the flat cells' ranks
// (least, greatest; none: UINT32_MAX, 0).
struct KeySpan {
    std::uint32_t first = 0, z_min = UINT32_MAX, z_max = 0, z_differ = 0, rank_min = UINT32_MAX, rank_max = 0;
    void add(std::uint32_t z, std::uint32_t rank) {
        z_min = std::min(z_min, z), z_max = std::max(z_max, z), z_differ |= z ^ first;
        if (rank) rank_min = std::min(rank_min, rank), rank_max = std::max(rank_max, rank);
    }
    void add(const KeySpan& o) {
        z_min = std::min(z_min, o.z_min), z_max = std::max(z_max, o.z_max), z_differ |= o.z_differ;
        rank_min = std::min(rank_min, o.rank_min), rank_max = std::max(rank_max, o.rank_max);
    }
};

// Each tie's settling order, candidates and cell in one 64-bit word, most significant first:
// the filled elevation's order key less the least (its bits below the lowest that differs
// dropped: DEMs in whole metres leave many), the rank less the least flat one plus one (0: a
// D8 cell), the cell's index, its candidates (8 bits). The words then order as (order key,
// index). Usable where these fit in 64 bits (`usable`).
struct PackedKeys {
    int z_shift = 0, rank_bits = 0, index_bits = 0, key_bits = 0;
    std::uint32_t z_min = 0, rank_min = 0;
    bool usable = false;
    PackedKeys(const KeySpan& s, std::size_t cells) {
        z_shift = s.z_differ ? std::countr_zero(s.z_differ) : 0, z_min = s.z_min;
        rank_min = s.rank_max ? s.rank_min : 0;
        rank_bits = s.rank_max ? std::bit_width(s.rank_max - rank_min + 1) : 0;
        index_bits = std::bit_width(std::max<std::size_t>(cells, 2) - 1);
        key_bits = std::bit_width((s.z_max - s.z_min) >> z_shift) + rank_bits;
        usable = key_bits + index_bits + 8 <= 64;
    }
    int key_from() const { return index_bits + 8; }  // the key's lowest bit
    std::uint64_t word(std::uint32_t z, std::uint32_t rank, std::uint32_t i, unsigned set) const {
        const std::uint64_t r = rank ? rank - rank_min + 1 : 0;
        return ((std::uint64_t(z - z_min) >> z_shift << rank_bits | r) << index_bits | i) << 8 | set;
    }
};

// arrays.ties, each cell once, in settling order (Ties::order_key, then index), with their
// candidates: a bit per cell drops the duplicates and lists the cells in index order, so keys
// and candidates are found reading the arrays forwards (in parallel blocks of 2^12 words). Then
// sorted by key: as PackedKeys by their key bits (stable: equal keys stay in index order) where
// they fit, else as (key, index) pairs and the candidates found again in the new order (in
// parallel chunks).
SortedTies sort_ties(const Ties& t, std::size_t cells, std::vector<std::uint32_t>& ties) {
    std::vector<std::uint64_t> seen((cells + 63) / 64, 0);
    for (const std::uint32_t i : ties) seen[i >> 6] |= std::uint64_t(1) << (i & 63);
    constexpr std::size_t block = std::size_t(1) << 12;
    const std::size_t blocks = (seen.size() + block - 1) / block;
    std::vector<std::size_t> start(blocks + 1, 0);
    for (std::size_t b = 0; b < blocks; ++b) {
        std::size_t n = 0;
        for (std::size_t w = b * block; w < std::min(seen.size(), (b + 1) * block); ++w) n += std::popcount(seen[w]);
        start[b + 1] = start[b] + n;
    }
    SortedTies sorted{ties, {}};
    if (ties.empty()) return sorted;
    KeySpan span;
    span.first = float_order_key(t.filled[ties.front()]);
    ties.resize(start[blocks]);
    sorted.sets.resize(ties.size());
    std::vector<KeySpan> spans(blocks, span);
    auto each_block = [&](auto&& f) {  // f(block, position, cell) for the cells in order
        parallel_chunks(blocks, 16, [&](std::size_t b0, std::size_t b1) {
            for (std::size_t b = b0; b < b1; ++b) {
                std::size_t at = start[b];
                for (std::size_t w = b * block; w < std::min(seen.size(), (b + 1) * block); ++w)
                    for (std::uint64_t bits = seen[w]; bits; bits &= bits - 1)
                        f(b, at++, w * 64 + std::size_t(std::countr_zero(bits)));
            }
        });
    };
    each_block([&](std::size_t b, std::size_t at, std::size_t i) {
        ties[at] = std::uint32_t(i), sorted.sets[at] = std::uint8_t(t.candidates(i));
        spans[b].add(float_order_key(t.filled[i]), t.rank(i));
    });
    for (const KeySpan& s : spans) span.add(s);
    const PackedKeys packed(span, cells);
    if (packed.usable) {
        std::vector<std::uint64_t, UninitAllocator<std::uint64_t>> words(ties.size()), scratch;
        each_block([&](std::size_t, std::size_t at, std::size_t i) {
            words[at] = packed.word(float_order_key(t.filled[i]), t.rank(i), std::uint32_t(i), sorted.sets[at]);
        });
        radix_sort_bits(words, scratch, packed.key_from(), packed.key_from() + packed.key_bits);
        scratch = {};
        const std::uint64_t index_mask = (std::uint64_t(1) << packed.index_bits) - 1;
        parallel_chunks(words.size(), 1 << 16, [&](std::size_t k0, std::size_t k1) {
            for (std::size_t k = k0; k < k1; ++k)
                ties[k] = std::uint32_t(words[k] >> 8 & index_mask), sorted.sets[k] = std::uint8_t(words[k]);
        });
        return sorted;
    }
    std::vector<std::uint64_t, UninitAllocator<std::uint64_t>> keys(ties.size());
    each_block([&](std::size_t, std::size_t at, std::size_t i) { keys[at] = t.order_key(i); });
    radix_sort_pairs(keys.data(), ties.data(), ties.size());
    keys = {};
    parallel_chunks(ties.size(), 1 << 16, [&](std::size_t k0, std::size_t k1) {
        for (std::size_t k = k0; k < k1; ++k) sorted.sets[k] = std::uint8_t(t.candidates(ties[k]));
    });
    return sorted;
}

// The original elevations of the cells the fill did not raise (their filled ones) written into
// orig_bits beside those of the raised cells, so that a path step reads one array, not flags
// and then one of two (parallel chunks of cells).
void complete_originals(const std::vector<float>& filled, const std::vector<std::uint8_t>& flags, CellWords& orig_bits) {
    parallel_chunks(filled.size(), std::size_t(1) << 16, [&](std::size_t i0, std::size_t i1) {
        for (std::size_t i = i0; i < i1; ++i)
            if (!(flags[i] & fill_raised)) orig_bits[i] = std::bit_cast<std::uint32_t>(filled[i]);
    });
}

}  // namespace

std::size_t break_d8_ties(const RoutingGrid& grid, RoutingArrays& arrays, const CellWords& flat_mask, int depth,
                          TieThreads split) {
    std::vector<std::uint32_t>& ties = arrays.ties;
    complete_originals(arrays.z, arrays.flags, arrays.orig_bits);
    Ties t{arrays.z, arrays.flags, arrays.orig_bits, grid.shape, d8_steps(grid.shape, grid.dx, grid.dy), arrays.dir, flat_mask,
           std::clamp(depth, 1, 64)};
    const SortedTies sorted = sort_ties(t, grid.shape.size(), ties);
    const int rows = grid.shape.rows;
    // automatic: all cores from four up; on two the threads mostly wait for each other whenever
    // other work shares the cores (j29m crop, load 6: 1.0-2.5 s on two threads, 1.0-1.7 s on one;
    // j29, 18.5 M ties, load 4-5: 6.6-9.5 s on one, 7.4-14.2 s on two in 16 or in 2 strips)
    const unsigned hardware = unsigned(core_count());
    const unsigned threads = split.threads ? split.threads : hardware >= 4 ? hardware : 1u;
    const int strip_rows = std::max(split.strip_rows ? split.strip_rows : std::clamp(rows / int(8 * threads), 8 * t.depth, 1024), t.depth + 1);
    std::size_t changed;
    if (threads < 2 || rows <= strip_rows || ties.size() >= (std::size_t(1) << 31) || (!split.threads && ties.size() < (std::size_t(1) << 16)))
        changed = settle_in_order(t, sorted, ties.size(), [](std::size_t k) { return k; }, [](std::size_t) {}, [](std::size_t) {});
    else
        changed = settle_in_strips(t, sorted, threads, strip_rows, std::max(split.segment_cols ? split.segment_cols : 32, t.depth));
    return changed;
}

}  // namespace penink
