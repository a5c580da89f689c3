#include "drainage/tiled_fill.hpp"

#include <algorithm>
#include <atomic>
#include <bit>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "core/parallel_chunks.hpp"

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

TiledFillStats tiled_priority_flood(const FillBands& bands, const FillRowReader& read, const FillRowWriter& write,
                                    int threads, const std::function<void(int, int)>& progress) {
    if (bands.cols < 1 || bands.rows < 1 || bands.band_rows < 1) throw std::invalid_argument("tiled fill: empty grid");
    const int n = bands.count();
    if (threads <= 0) threads = int(std::clamp<unsigned>(std::thread::hardware_concurrency(), 1, 16));
    threads = std::min(threads, n);
    std::mutex reading;  // the reader is called one band at a time
    const FillRowReader serial = [&](int y0, int y1, float* z, std::uint8_t* valid) {
        const std::lock_guard<std::mutex> lock(reading);
        read(y0, y1, z, valid);
    };
    std::atomic<int> done{0};
    std::mutex told;
    auto tell = [&] {
        const int d = ++done;
        if (!progress) return;
        const std::lock_guard<std::mutex> lock(told);
        progress(d, 2 * n);
    };
    std::vector<BandSurvey> surveys(static_cast<std::size_t>(n));
    {
        std::atomic<int> next{0};
        std::vector<std::future<void>> others;
        std::exception_ptr first;
        auto work = [&] {
            for (int b; (b = next++) < n;) surveys[std::size_t(b)] = survey_fill_band(bands, b, serial), tell();
        };
        for (int t = 1; t < threads; ++t) others.push_back(std::async(std::launch::async, work));
        try {
            work();
        } catch (...) {
            first = std::current_exception(), next = n;
        }
        for (auto& o : others) try {
                o.get();
            } catch (...) {
                if (!first) first = std::current_exception();
            }
        if (first) std::rethrow_exception(first);
    }
    TiledFillStats st;
    st.bands = n, st.band_bytes = fill_band_bytes(bands.cols, bands.band_rows);
    for (const BandSurvey& s : surveys) st.spills += s.spills.size(), st.labels += s.stats.labels;
    const std::vector<float> water = fill_water_levels(bands, surveys);
    surveys.clear(), surveys.shrink_to_fit();
    struct Finished {
        int band = 0;
        std::size_t raised = 0;
        std::vector<float> filled;
        std::vector<std::uint8_t> valid;
    };
    ordered_parts<Finished>(
        std::size_t(n), std::size_t(threads),
        [&](std::size_t b, Finished& out) {
            out.band = int(b);
            out.raised = finish_fill_band(bands, int(b), serial, water, out.filled, out.valid);
        },
        [&](const Finished& f) {
            write(bands.first_row(f.band), bands.end_row(f.band), f.filled.data(), f.valid.data());
            st.raised += f.raised;
            tell();
        });
    return st;
}

}  // namespace penink
