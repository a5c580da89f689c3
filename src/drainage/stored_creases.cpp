#include "drainage/stored_creases.hpp"

#include <filesystem>

#include "core/error.hpp"
#include "core/hash64.hpp"
#include "drainage/crease_source.hpp"
#include "drainage/drainage_db.hpp"

namespace penink {

struct StoredCreases::Decoded {
    DrainageGrid g;
    std::vector<std::uint8_t> dir;
    FlowNetwork net;
    std::vector<SourceUnitBlock> blocks;  // where each unit's stems lie in the source
    std::unique_ptr<CreaseTiles> tiles;
};


std::string crease_tile_folder(const std::string& dv_path) { return dv_path + ".tiles"; }

void remove_crease_tiles(const std::string& dv_path) {
    namespace fs = std::filesystem;
    const fs::path folder = crease_tile_folder(dv_path);
    std::error_code ec;
    if (!fs::is_directory(fs::symlink_status(folder, ec))) return;  // never follow a link out of it
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
        if (it->path().extension() == ".pnlt" && it->is_regular_file(ec)) fs::remove(it->path(), ec);
    fs::remove(folder, ec);  // only when empty
}

StoredCreases::StoredCreases(std::vector<std::uint8_t> source, std::string folder)
    : source_(std::move(source)), size_(source_.size()), folder_(std::move(folder)) {}

StoredCreases::StoredCreases(std::shared_ptr<const CheckedBlocks> pages, std::uint64_t size,
                             std::vector<std::uint64_t> sums, std::string folder)
    : pages_(std::move(pages)), size_(size), sums_(std::move(sums)), folder_(std::move(folder)) {}

std::shared_ptr<StoredCreases> StoredCreases::of(const DrainageDb& db, std::string folder) {
    std::shared_ptr<StoredCreases> out =
        db.crease_source_pages ? std::make_shared<StoredCreases>(db.crease_source_pages, db.crease_source_size,
                                                                  db.crease_source_sums, std::move(folder))
                               : std::make_shared<StoredCreases>(db.crease_source, std::move(folder));
    out->dem_ = db.crease_source_dem;
    return out;
}

std::shared_ptr<StoredCreases> StoredCreases::take(DrainageDb& db, std::string folder) {
    std::shared_ptr<StoredCreases> out = db.crease_source_pages
                                             ? of(db, std::move(folder))
                                             : std::make_shared<StoredCreases>(std::move(db.crease_source), std::move(folder));
    out->dem_ = db.crease_source_dem;
    out->built_ = std::move(db.built_network.arrays);
    db.crease_source = {}, db.crease_source_pages = nullptr;
    return out;
}

CreaseSourceBytes StoredCreases::bytes() const { return crease_source_bytes(source_, pages_.get(), size_, dem_); }

StoredCreases::~StoredCreases() = default;

CreaseTiles& StoredCreases::tiles() {
    if (!decoded_) {
        auto d = std::make_unique<Decoded>();
        const auto decoded = [this](DrainageGrid& g, std::vector<std::uint8_t>& dir, CreaseTileIndex& index, SourcePart part,
                                    std::vector<SourceUnitBlock>* blocks = nullptr, FlowNetwork* net = nullptr) {
            if (!decode_crease_source(bytes(), g, dir, index, part, blocks, net, &heights_))
                throw Error("drainage", "", "stored crease source does not decode", ExitCode::internal);
        };
        // the units now (with a folder: a frame whose tiles are all in files needs no more), a
        // unit's stems where its file fails, the stems' sources when a stem is built, with the
        // grid, directions and network (the whole index: only when asked for)
        CreaseTileIndex index;
        const bool lazy = !folder_.empty();
        decoded(d->g, d->dir, index, lazy ? SourcePart::units : SourcePart::index, &d->blocks);
        TileStore store;
        if (!folder_.empty()) {
            // identified by its pages' checksums (not a pass over its bytes)
            if (sums_.empty()) sums_ = crease_source_page_sums(source_.data(), source_.size());
            const std::uint64_t fields[2] = {std::uint64_t(drainage_db_version), hash64(sums_.data(), sums_.size() * 8)};
            store.folder = folder_, store.key = hash64(fields, sizeof fields);
        }
        CreaseIndexReader reader;
        if (lazy) {
            reader.unit = [this, d = d.get()](std::size_t u, std::vector<std::uint32_t>& ids, std::vector<StemBound>& bounds) {
                if (u >= d->blocks.size() || !decode_crease_unit(bytes(), d->blocks[u], ids, bounds))
                    throw Error("drainage", "", "stored crease source does not decode", ExitCode::internal);
            };
            reader.whole = [decoded] {
                DrainageGrid g;
                std::vector<std::uint8_t> dir;
                CreaseTileIndex whole;
                decoded(g, dir, whole, SourcePart::index);
                return whole;
            };
            reader.sources = [decoded] {
                DrainageGrid g;
                std::vector<std::uint8_t> dir;
                CreaseTileIndex unit_table;
                decoded(g, dir, unit_table, SourcePart::sources);
                return std::move(unit_table.parts.sources);
            };
        }
        if (built_ && built_->g.cols == d->g.cols && built_->g.rows == d->g.rows) {  // as the build made them
            d->g = std::move(built_->g), d->dir = std::move(built_->dir), d->net = std::move(built_->net);
            built_.reset();
            keep_normalised_flow(d->net);  // (done where the build kept it)
        }
        d->tiles = std::make_unique<CreaseTiles>(d->g, d->dir, d->net, std::move(index), std::move(store), std::move(reader));
        if (build_progress_) d->tiles->on_build_progress(build_progress_);
        if (d->dir.empty())
            d->tiles->before_first_build([this, decoded, d = d.get()] {
                if (before_decode_) before_decode_(d->g.cols, d->g.rows);
                CreaseTileIndex again;
                // the index: the tiles hold it; the network made as the DEM is read again
                decoded(d->g, d->dir, again, SourcePart::grid, nullptr, &d->net);
                keep_normalised_flow(d->net);  // what the stems' walks read
            });
        else if (d->g.node_xy)  // the build's grid, its node x, y let go (drainage_grid.hpp): read
                                // from its rows' samples (1 B a node; the drapers keep those they
                                // make: DemSurface::NodeXYCache), not made whole again (8 B a node:
                                // a cold render of jacksboro x29 peaks at 3.17 GB, not 3.48)
            d->tiles->before_first_build([d = d.get()] { readable_node_xy(d->g); });
        decoded_ = std::move(d);
    }
    return *decoded_->tiles;
}

namespace {

// f(), a damaged page of a source left in its file (DamagedBlockError) thrown as the database's
// damage (DvCorrupt: a render then reads the database whole, or rebuilds it).
template <class F> auto pages_checked(F&& f) {
    try {
        return f();
    } catch (const DamagedBlockError& e) {
        throw DvCorrupt("drainage", e.file(), "drainage database checksum mismatch (file corrupt)");
    }
}

}  // namespace

DrapedLineSet StoredCreases::lines_for_box(glm::vec2 lo, glm::vec2 hi, const CreaseTiles::LineTest& may_show,
                                           const CreaseTiles::LineDetail& detail) {
    const std::lock_guard<std::mutex> lock(mutex_);
    return pages_checked([&] { return tiles().lines_for_box(lo, hi, nullptr, may_show, detail); });
}

void StoredCreases::line_refs_by_row(glm::vec2 lo, glm::vec2 hi, const CreaseTiles::LineTest& may_show,
                                     const CreaseTiles::LineDetail& detail,
                                     const std::function<void(CreaseTiles::LineRefs)>& f) {
    const std::lock_guard<std::mutex> lock(mutex_);
    pages_checked([&] { tiles().line_refs_by_row(lo, hi, may_show, detail, f); });
}

std::size_t StoredCreases::count(std::size_t (CreaseTiles::*which)() const) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return decoded_ ? (*decoded_->tiles.*which)() : 0;
}

std::size_t StoredCreases::stem_count() const { return count(&CreaseTiles::stem_count); }
std::size_t StoredCreases::stems_built() const { return count(&CreaseTiles::stems_built); }
std::size_t StoredCreases::vertices_built() const { return count(&CreaseTiles::vertices_built); }
std::size_t StoredCreases::builds() const { return count(&CreaseTiles::builds); }
std::size_t StoredCreases::tiles_read() const { return count(&CreaseTiles::tiles_read); }
std::size_t StoredCreases::tiles_written() const { return count(&CreaseTiles::tiles_written); }

}  // namespace penink
