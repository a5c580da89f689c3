#include "drainage/tiled_fill.hpp"

#include <algorithm>
#include <cstring>
#include <future>
#include <atomic>
#include <bit>
#include <mutex>
#include <stdexcept>

#include "core/parallel_chunks.hpp"
#include "drainage/band_passes.hpp"

namespace penink {

namespace {

// One band read with its neighbouring rows (where the grid has them) and flooded on its own.
struct BandWindow {
    int r0 = 0, r1 = 0;  // the band's rows in the grid
    int w0 = 0, w1 = 0;  // the rows read: [r0 - 1, r1 + 1) within the grid
    std::vector<float> z;
    std::vector<std::uint8_t> valid, flags;
    std::vector<std::uint32_t> level, labels;
    FillStats stats;

    std::size_t at(int r, int c, int cols) const { return std::size_t(r - w0) * std::size_t(cols) + std::size_t(c); }
    float local(std::size_t i) const { return flags[i] & fill_raised ? std::bit_cast<float>(level[i]) : z[i]; }
    // Grid row r's labels, valid flags and local levels.
    auto row(int r, int cols) const {
        const std::size_t a = at(r, 0, cols);
        return flood::LabelledRow{labels.data() + a, valid.data() + a, [this, a](int c) { return local(a + std::size_t(c)); }};
    }
};

BandWindow flood_band(const FillBands& bands, int b, const FillRowReader& read) {
    if (b < 0 || b >= bands.count()) throw std::out_of_range("tiled fill: no such band");
    BandWindow w;
    w.r0 = bands.first_row(b), w.r1 = bands.end_row(b);
    w.w0 = std::max(0, w.r0 - 1), w.w1 = std::min(bands.rows, w.r1 + 1);
    const std::size_t n = std::size_t(w.w1 - w.w0) * std::size_t(bands.cols);
    if (n >= (std::size_t(1) << 32)) throw std::length_error("tiled fill: a band of 2^32 cells or more");
    w.z.resize(n), w.valid.resize(n), w.flags.assign(n, 0), w.level.resize(n), w.labels.resize(n);
    read(w.w0, w.w1, w.z.data(), w.valid.data());
    const GridShape g{bands.cols, w.w1 - w.w0, w.valid.data()};
    // The window's first row is the grid's first one, or a row of the band above: seed_band then
    // takes its rows r0 - w0 .. r1 - w0 alone, seeding the window's border rows only where they
    // are the grid's.
    w.stats = flood::flood_labelled_band(w.z.data(), g, w.flags.data(), w.level.data(), w.labels.data(), w.r0 - w.w0,
                                         w.r1 - w.w0, w.r0 > 0, w.r1 < bands.rows, b);
    return w;
}

}  // namespace

int fill_band_rows_of_cells(int cols, int strip) {
    strip = std::max(strip, 1);
    return std::max(strip, int(std::uint64_t(4) << 20) / std::max(cols, 1) / strip * strip);
}

std::uint64_t fill_band_bytes(int cols, int band_rows) {
    // z 4, valid 1, flags 1, level 4, label 4; the flood's queue (8 a cell queued), pit stack (8 a
    // cell raised) and trace (4 a cell) at their worst, every cell
    return std::uint64_t(cols) * std::uint64_t(band_rows + 2) * 34;
}

BandSurvey survey_fill_band(const FillBands& bands, int b, const FillRowReader& read) {
    const BandWindow w = flood_band(bands, b, read);
    const int cols = bands.cols;
    BandSurvey s;
    s.band = b, s.stats = w.stats;
    flood::Spills spills;
    {
        flood::SpillRun out{spills};
        for (int r = w.r0; r < w.r1; ++r) {
            const bool next = r + 1 < w.r1;  // the pairs across to the next band: fill_water_levels
            flood::row_pair_spills(cols, w.row(r, cols), w.row(next ? r + 1 : r, cols), next, out);
        }
    }
    s.spills.assign(spills.begin(), spills.end());
    std::sort(s.spills.begin(), s.spills.end());
    auto keep = [&](int r, std::vector<std::uint32_t>& labels, std::vector<float>& levels, std::vector<std::uint8_t>& valid) {
        const std::size_t a = w.at(r, 0, cols);
        labels.assign(w.labels.begin() + std::ptrdiff_t(a), w.labels.begin() + std::ptrdiff_t(a + std::size_t(cols)));
        valid.assign(w.valid.begin() + std::ptrdiff_t(a), w.valid.begin() + std::ptrdiff_t(a + std::size_t(cols)));
        levels.resize(std::size_t(cols));
        for (int c = 0; c < cols; ++c) levels[std::size_t(c)] = w.local(a + std::size_t(c));
    };
    keep(w.r0, s.first_labels, s.first_levels, s.first_valid);
    keep(w.r1 - 1, s.last_labels, s.last_levels, s.last_valid);
    return s;
}

std::vector<float> fill_water_levels(const FillBands& bands, const std::vector<BandSurvey>& surveys) {
    const int n = bands.count();
    std::vector<const BandSurvey*> by_band(std::size_t(n), nullptr);
    for (const BandSurvey& s : surveys) {
        if (s.band < 0 || s.band >= n || by_band[std::size_t(s.band)])
            throw std::invalid_argument("tiled fill: surveys must cover each band once");
        by_band[std::size_t(s.band)] = &s;
    }
    flood::Spills spills;
    for (const BandSurvey* s : by_band) {
        if (!s) throw std::invalid_argument("tiled fill: a band's survey is missing");
        for (const auto& [key, w] : s->spills) flood::note_spill(spills, std::uint32_t(key >> 32), std::uint32_t(key), w);
    }
    flood::SpillRun out{spills};
    for (int b = 0; b + 1 < n; ++b) {
        const BandSurvey& a = *by_band[std::size_t(b)];
        const BandSurvey& d = *by_band[std::size_t(b) + 1];
        const flood::LabelledRow last{a.last_labels.data(), a.last_valid.data(), [&a](int c) { return a.last_levels[std::size_t(c)]; }};
        const flood::LabelledRow first{d.first_labels.data(), d.first_valid.data(), [&d](int c) { return d.first_levels[std::size_t(c)]; }};
        // the east pairs of the last row are the band's own: only the pairs across are new, and
        // noting them again changes no least spill
        flood::row_pair_spills(bands.cols, last, first, true, out);
    }
    out.flush();
    return flood::water_levels(spills, flood::band_label_count(n, bands.cols));
}

std::size_t finish_fill_band(const FillBands& bands, int b, const FillRowReader& read, const std::vector<float>& water,
                             std::vector<float>& filled, std::vector<std::uint8_t>& valid) {
    if (water.size() != flood::band_label_count(bands.count(), bands.cols))
        throw std::invalid_argument("tiled fill: water levels of another grid");
    const BandWindow w = flood_band(bands, b, read);
    const int cols = bands.cols;
    const std::size_t a = w.at(w.r0, 0, cols), e = w.at(w.r1, 0, cols);
    filled.resize(e - a), valid.assign(w.valid.begin() + std::ptrdiff_t(a), w.valid.begin() + std::ptrdiff_t(e));
    std::size_t raised = 0;
    for (std::size_t i = a; i < e; ++i) {
        float h = w.local(i);
        const bool by_water = flood::raise_to(h, w.labels[i], water, h);
        raised += by_water || (w.flags[i] & fill_raised);
        filled[i - a] = h;
    }
    return raised;
}

namespace {

using bands::Reader;
using bands::Writer;

// Rows of a band sent to the rank that writes: band, raised, filled heights and valid flags.
struct FinishedBand {
    int band = 0;
    std::size_t raised = 0;
    std::vector<float> filled;
    std::vector<std::uint8_t> valid;
};

std::vector<std::uint8_t> encode_finished(const FinishedBand& f) {
    Writer w;
    w.put(std::int32_t(f.band)), w.put(std::uint64_t(f.raised)), w.put_all(f.filled), w.put_all(f.valid);
    return std::move(w.out);
}

FinishedBand decode_finished(const FillBands& bands, int band, std::span<const std::uint8_t> bytes) {
    Reader r{bytes};
    FinishedBand f;
    f.band = r.get<std::int32_t>();
    if (f.band != band) throw std::runtime_error("tiled fill: a band out of order");
    f.raised = std::size_t(r.get<std::uint64_t>());
    const std::size_t cells = std::size_t(bands.end_row(band) - bands.first_row(band)) * std::size_t(bands.cols);
    f.filled = r.get_all<float>(cells), f.valid = r.get_all<std::uint8_t>(cells);
    r.end();
    return f;
}

// Surveys of the bands `which` on up to `threads` threads, the reads one at a time; tell() after each.
std::vector<BandSurvey> survey_bands(const FillBands& bands, const std::vector<int>& which, const FillRowReader& read,
                                     int threads, const std::function<void()>& tell) {
    return bands::survey_list<BandSurvey>(
        which, read, threads, [&](int b, const FillRowReader& r) { return survey_fill_band(bands, b, r); }, tell);
}

// Finishes the bands `which` on up to `threads` threads (reads one at a time), handing each to
// use() in the order of `which`.
void finish_bands(const FillBands& bands, const std::vector<int>& which, const FillRowReader& read,
                  const std::vector<float>& water, int threads, const std::function<void(const FinishedBand&)>& use) {
    bands::finish_in_order<FinishedBand>(
        which, read, threads,
        [&](int b, const FillRowReader& r, FinishedBand& out) {
            out.raised = finish_fill_band(bands, b, r, water, out.filled, out.valid);
        },
        use);
}

}  // namespace

std::vector<std::uint8_t> encode_band_survey(const BandSurvey& s) {
    Writer w;
    w.put(std::int32_t(s.band));
    w.put(std::uint64_t(s.stats.raised)), w.put(std::uint64_t(s.stats.queued)), w.put(std::uint64_t(s.stats.labels));
    std::vector<std::uint64_t> keys(s.spills.size());
    std::vector<float> levels(s.spills.size());
    for (std::size_t k = 0; k < s.spills.size(); ++k) keys[k] = s.spills[k].first, levels[k] = s.spills[k].second;
    w.put_all(keys), w.put_all(levels);
    w.put_all(s.first_labels), w.put_all(s.last_labels), w.put_all(s.first_levels), w.put_all(s.last_levels);
    w.put_all(s.first_valid), w.put_all(s.last_valid);
    return std::move(w.out);
}

BandSurvey decode_band_survey(const FillBands& bands, std::span<const std::uint8_t> bytes) {
    Reader r{bytes};
    BandSurvey s;
    s.band = r.get<std::int32_t>();
    if (s.band < 0 || s.band >= bands.count()) throw std::runtime_error("tiled fill: a survey of another grid");
    s.stats.raised = std::size_t(r.get<std::uint64_t>()), s.stats.queued = std::size_t(r.get<std::uint64_t>());
    s.stats.labels = std::size_t(r.get<std::uint64_t>());
    const auto keys = r.get_all<std::uint64_t>();
    const auto levels = r.get_all<float>(keys.size());
    const std::uint64_t labels = flood::band_label_count(bands.count(), bands.cols);
    s.spills.resize(keys.size());
    for (std::size_t k = 0; k < keys.size(); ++k) {
        if ((keys[k] >> 32) >= labels || (keys[k] & 0xffffffffu) >= labels)
            throw std::runtime_error("tiled fill: a survey of another grid");
        s.spills[k] = {keys[k], levels[k]};
    }
    const std::size_t cols = std::size_t(bands.cols);
    s.first_labels = r.get_all<std::uint32_t>(cols), s.last_labels = r.get_all<std::uint32_t>(cols);
    s.first_levels = r.get_all<float>(cols), s.last_levels = r.get_all<float>(cols);
    s.first_valid = r.get_all<std::uint8_t>(cols), s.last_valid = r.get_all<std::uint8_t>(cols);
    for (const auto* l : {&s.first_labels, &s.last_labels})
        for (const std::uint32_t v : *l)
            if (v >= labels) throw std::runtime_error("tiled fill: a survey of another grid");
    r.end();
    return s;
}

TiledFillStats tiled_priority_flood(const FillBands& bands, const FillRowReader& read, const FillRowWriter& write,
                                    int threads, const std::function<void(int, int)>& progress) {
    if (bands.cols < 1 || bands.rows < 1 || bands.band_rows < 1) throw std::invalid_argument("tiled fill: empty grid");
    const int n = bands.count();
    if (threads <= 0) threads = rank_threads(nullptr);
    threads = std::min(threads, n);
    std::atomic<int> done{0};
    std::mutex told;
    auto tell = [&] {
        const int d = ++done;
        if (!progress) return;
        const std::lock_guard<std::mutex> lock(told);
        progress(d, 2 * n);
    };
    std::vector<int> all(static_cast<std::size_t>(n));
    for (int b = 0; b < n; ++b) all[std::size_t(b)] = b;
    std::vector<BandSurvey> surveys = survey_bands(bands, all, read, threads, tell);
    TiledFillStats st;
    st.bands = n, st.band_bytes = fill_band_bytes(bands.cols, bands.band_rows);
    for (const BandSurvey& s : surveys) st.spills += s.spills.size(), st.labels += s.stats.labels;
    const std::vector<float> water = fill_water_levels(bands, surveys);
    surveys.clear(), surveys.shrink_to_fit();
    finish_bands(bands, all, read, water, threads, [&](const FinishedBand& f) {
        write(bands.first_row(f.band), bands.end_row(f.band), f.filled.data(), f.valid.data());
        st.raised += f.raised;
        tell();
    });
    return st;
}

TiledFillStats distributed_priority_flood(const FillBands& bands, const FillRowReader& read, const FillRowWriter& write,
                                          Ranks& ranks, int threads, const std::function<void(int, int)>& progress) {
    if (bands.cols < 1 || bands.rows < 1 || bands.band_rows < 1) throw std::invalid_argument("tiled fill: empty grid");
    const int n = bands.count();
    const bool root = ranks.rank() == 0;
    threads = std::max(threads, 1);
    int done = 0;
    std::mutex told;
    auto tell = [&] {
        const std::lock_guard<std::mutex> lock(told);
        ++done;
        if (root && progress) progress(done, 2 * n);
    };
    TiledFillStats st;
    st.bands = n, st.band_bytes = fill_band_bytes(bands.cols, bands.band_rows);
    const std::size_t labels = flood::band_label_count(n, bands.cols);
    bands::over_ranks<BandSurvey>(
        ranks, n, [&](const std::vector<int>& mine) { return survey_bands(bands, mine, read, threads, tell); },
        encode_band_survey,
        [&](std::span<const std::uint8_t> m) {
            BandSurvey s = decode_band_survey(bands, m);
            tell();
            return s;
        },
        [&](const std::vector<BandSurvey>& surveys) {
            for (const BandSurvey& s : surveys) st.spills += s.spills.size(), st.labels += s.stats.labels;
            bands::Writer w;
            w.put_all(fill_water_levels(bands, surveys));
            return std::move(w.out);
        },
        [&](const std::vector<int>& mine, std::vector<std::uint8_t> solved, const auto& use) {
            bands::Reader r{solved};
            const std::vector<float> water = r.get_all<float>(labels);
            r.end();
            solved = {};
            finish_bands(bands, mine, read, water, threads, use);
        },
        encode_finished, [&](int band, std::span<const std::uint8_t> m) { return decode_finished(bands, band, m); },
        [&](const FinishedBand& f) {
            write(bands.first_row(f.band), bands.end_row(f.band), f.filled.data(), f.valid.data());
            st.raised += f.raised;
            tell();
        });
    return st;
}

}  // namespace penink
