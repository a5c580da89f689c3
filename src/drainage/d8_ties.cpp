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
    const CellWords& orig;
    const GridShape& g;
    D8Steps st;
    std::vector<std::uint8_t>& dir;  // written only by settle
    const CellWords& flat_mask;  // flat gradients as int32 (flat_resolution.hpp)
    int depth;

    float original(std::size_t n) const { return original_z(filled, flags, orig, n); }
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

    // Asks the cache for the rows around cell i that steepest_set and the first steps of
    // choose read (a hint: settling follows elevation, not memory order).
    void prefetch(std::size_t i) const {
        const std::size_t cols = std::size_t(g.cols), n = filled.size();
        for (const std::size_t r : {i >= cols ? i - cols : i, i, i + cols < n ? i + cols : i}) {
            __builtin_prefetch(&filled[r]);
            __builtin_prefetch(&flags[r]);
            __builtin_prefetch(&dir[r]);
            __builtin_prefetch(&flat_mask[r]);
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

    // Whether the original elevations along the path from a, `depth` entries (past the grid's
    // edge: -inf), come lexicographically before those from b. Walked side by side up to the
    // first difference; paths at one cell at one step (or both past the edge) are equal from
    // there on.
    bool path_before(std::size_t a, std::size_t b) const {
        constexpr float past = -std::numeric_limits<float>::infinity();
        bool a_out = false, b_out = false;
        for (int j = 0; j < depth; ++j) {
            if (a_out ? b_out : !b_out && a == b) return false;
            const float za = a_out ? past : original(a), zb = b_out ? past : original(b);
            if (za < zb) return true;
            if (zb < za) return false;
            if (!a_out) dir[a] ? void(a = d8_target(g, a, dir[a])) : void(a_out = true);
            if (!b_out) dir[b] ? void(b = d8_target(g, b, dir[b])) : void(b_out = true);
        }
        return false;
    }

    // Of the neighbours in `set`, the one whose path comes first (path_before; equal: the lowest
    // code), as an ESRI code.
    std::uint8_t choose(std::size_t i, unsigned set) const {
        int best = std::countr_zero(set);
        for (unsigned rest = set & (set - 1); rest; rest &= rest - 1) {
            const int k = std::countr_zero(rest);
            if (path_before(std::size_t(std::ptrdiff_t(i) + st.off[k]), std::size_t(std::ptrdiff_t(i) + st.off[best])))
                best = k;
        }
        return std::uint8_t(1u << best);
    }

    // Tie i re-aimed (an outflow cell, or one left with fewer than two candidates, kept);
    // whether its direction changed.
    bool settle(std::size_t i) const {
        if (flags[i] & depression_outflow) return false;
        const unsigned set = steepest_set(i);
        if ((set & (set - 1)) == 0) return false;  // fewer than two neighbours
        const std::uint8_t code = choose(i, set);
        return std::exchange(dir[i], code) != code;
    }
};

// The ties settled one by one in the given order (ties[position(k)] for k = 0..n-1),
// wait(k) called before the k-th and done(k) after it; the cells a few places ahead asked of the
// cache. Returns how many changed direction.
template <class Position, class Wait, class Done>
std::size_t settle_in_order(const Ties& t, const std::vector<std::uint32_t>& ties, std::size_t n,
                            Position&& position, Wait&& wait, Done&& done) {
    constexpr std::size_t ahead = 16;
    std::size_t changed = 0;
    for (std::size_t k = 0; k < n; ++k) {
        if (k + ahead < n) t.prefetch(ties[position(k + ahead)]);
        wait(k);
        changed += t.settle(ties[position(k)]);
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
std::size_t settle_in_strips(const Ties& t, const std::vector<std::uint32_t>& ties, unsigned threads,
                             int strip_rows, int segment_cols) {
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
            t, ties, mine.size(), [&](std::size_t k) { return mine[k] & ~band_bit; },
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

// arrays.ties, each cell once, in settling order (Ties::order_key, then index): a bit per cell
// drops the duplicates and lists the cells in index order, so the keys are made reading the
// arrays forwards (in parallel blocks of 2^12 words); then sorted by (key, index) in place.
void sort_ties(const Ties& t, std::size_t cells, std::vector<std::uint32_t>& ties) {
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
    ties.resize(start[blocks]);
    std::vector<std::uint64_t, UninitAllocator<std::uint64_t>> keys(ties.size());
    parallel_chunks(blocks, 16, [&](std::size_t b0, std::size_t b1) {
        std::size_t at = start[b0];
        for (std::size_t w = b0 * block; w < std::min(seen.size(), b1 * block); ++w)
            for (std::uint64_t bits = seen[w]; bits; bits &= bits - 1) {
                const std::size_t i = w * 64 + std::size_t(std::countr_zero(bits));
                ties[at] = std::uint32_t(i), keys[at] = t.order_key(i), ++at;
            }
    });
    radix_sort_pairs(keys.data(), ties.data(), ties.size());
}

}  // namespace

std::size_t break_d8_ties(const RoutingGrid& grid, RoutingArrays& arrays, const CellWords& flat_mask, int depth,
                          TieThreads split) {
    std::vector<std::uint32_t>& ties = arrays.ties;
    Ties t{arrays.z, arrays.flags, arrays.orig_bits, grid.shape, d8_steps(grid.shape, grid.dx, grid.dy), arrays.dir, flat_mask,
           std::clamp(depth, 1, 64)};
    sort_ties(t, grid.shape.size(), ties);
    const int rows = grid.shape.rows;
    // automatic: all cores from four up; on two the threads mostly wait for each other whenever
    // other work shares the cores (j29m crop, load 6: 1.0-2.5 s on two threads, 1.0-1.7 s on one)
    const unsigned hardware = std::thread::hardware_concurrency();
    const unsigned threads = split.threads ? split.threads : hardware >= 4 ? std::min(hardware, 16u) : 1u;
    const int strip_rows = std::max(split.strip_rows ? split.strip_rows : std::clamp(rows / int(8 * threads), 8 * t.depth, 1024), t.depth + 1);
    std::size_t changed;
    if (threads < 2 || rows <= strip_rows || ties.size() >= (std::size_t(1) << 31) || (!split.threads && ties.size() < (std::size_t(1) << 16)))
        changed = settle_in_order(t, ties, ties.size(), [](std::size_t k) { return k; }, [](std::size_t) {}, [](std::size_t) {});
    else
        changed = settle_in_strips(t, ties, threads, strip_rows, std::max(split.segment_cols ? split.segment_cols : 32, t.depth));
    return changed;
}

}  // namespace penink
