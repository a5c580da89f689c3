#include "drainage/stored_creases.hpp"

#include "core/error.hpp"
#include "core/hash64.hpp"
#include "drainage/crease_source.hpp"
#include "drainage/drainage_db.hpp"

namespace penink {

struct StoredCreases::Decoded {
    DrainageGrid g;
    std::vector<std::uint8_t> dir;
    FlowNetwork net;
    std::unique_ptr<CreaseTiles> tiles;
};

StoredCreases::StoredCreases(std::vector<std::uint8_t> source, std::string folder)
    : source_(std::move(source)), folder_(std::move(folder)) {}

StoredCreases::~StoredCreases() = default;

CreaseTiles& StoredCreases::tiles() {
    if (!decoded_) {
        auto d = std::make_unique<Decoded>();
        CreaseTileIndex index;
        // the index now; the grid, directions and network only when a tile is built here
        if (!decode_crease_source(source_.data(), source_.size(), d->g, d->dir, index, false))
            throw Error("drainage", "", "stored crease source does not decode", ExitCode::internal);
        TileStore store;
        if (!folder_.empty()) {
            const std::uint64_t fields[2] = {std::uint64_t(drainage_db_version), hash64(source_.data(), source_.size())};
            store.folder = folder_, store.key = hash64(fields, sizeof fields);
        }
        d->tiles = std::make_unique<CreaseTiles>(d->g, d->dir, d->net, std::move(index), std::move(store));
        d->tiles->before_first_build([this, d = d.get()] {
            CreaseTileIndex again;
            if (!decode_crease_source(source_.data(), source_.size(), d->g, d->dir, again))
                throw Error("drainage", "", "stored crease source does not decode", ExitCode::internal);
            d->net = network_of_directions(d->g, d->dir);
        });
        decoded_ = std::move(d);
    }
    return *decoded_->tiles;
}

DrapedLineSet StoredCreases::lines_for_box(glm::vec2 lo, glm::vec2 hi) {
    const std::lock_guard<std::mutex> lock(mutex_);
    return tiles().lines_for_box(lo, hi);
}

CreaseTiles::LineRefs StoredCreases::line_refs_for_box(glm::vec2 lo, glm::vec2 hi) {
    const std::lock_guard<std::mutex> lock(mutex_);
    return tiles().line_refs_for_box(lo, hi);
}

std::size_t StoredCreases::tile_count() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return decoded_ ? decoded_->tiles->tile_count() : 0;
}

std::size_t StoredCreases::tiles_built() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return decoded_ ? decoded_->tiles->tiles_built() - decoded_->tiles->tiles_read() : 0;
}

std::size_t StoredCreases::tiles_read() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return decoded_ ? decoded_->tiles->tiles_read() : 0;
}

std::string crease_tile_folder(const std::string& dv_path) { return dv_path + ".tiles"; }

}  // namespace penink
