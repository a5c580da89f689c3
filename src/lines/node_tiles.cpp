// A grid's nodes in memory or read on demand in tiles through a bounded cache (node_tiles.hpp).
#include "lines/node_tiles.hpp"

#include <algorithm>
#include <utility>

namespace penink {

NodeTiles::NodeTiles(int cols, int rows, const glm::vec3* pos, const std::uint8_t* valid)
    : cols_(cols), rows_(rows), tile_cols_(cols), tile_rows_(rows), cur_{0, 0, cols, rows}, cur_pos_(pos),
      cur_valid_(valid) {}

NodeTiles::NodeTiles(int cols, int rows, NodeReader read, std::size_t budget, int tile_cols, int tile_rows)
    : cols_(cols), rows_(rows), tile_cols_(std::max(tile_cols, 1)), tile_rows_(std::max(tile_rows, 1)),
      read_(std::move(read)) {
    tiles_across_ = std::max(1, (cols_ + tile_cols_ - 1) / tile_cols_);
    const int tiles_down = std::max(1, (rows_ + tile_rows_ - 1) / tile_rows_);
    slot_of_.assign(std::size_t(tiles_across_) * std::size_t(tiles_down), -1);
    seen_.assign(slot_of_.size(), 0);
    const std::size_t tile_bytes = std::size_t(tile_cols_) * std::size_t(tile_rows_) * node_bytes;
    max_slots_ = std::max<std::size_t>(2, budget / tile_bytes);
    slots_.reserve(max_slots_);
}

GridWindow NodeTiles::tile_part(int index) const {
    const int tc = index % tiles_across_, tr = index / tiles_across_;
    GridWindow w{tc * tile_cols_, tr * tile_rows_, (tc + 1) * tile_cols_, (tr + 1) * tile_rows_};
    return w.clamped(cols_, rows_);
}

void NodeTiles::enter(int c, int r) {
    const int index = tile_index(c, r);
    int s = slot_of_[std::size_t(index)];
    if (s < 0) {
        cur_ = {}, cur_pos_ = nullptr, cur_valid_ = nullptr;
        const std::size_t full = std::size_t(tile_cols_) * std::size_t(tile_rows_);
        if (slots_.size() < max_slots_) {  // a free slot: its buffers a whole tile, once
            s = int(slots_.size());
            slots_.emplace_back();
            slots_.back().pos.reserve(full), slots_.back().valid.reserve(full);
            held_bytes_ += full * node_bytes;
            counts_.most_bytes = std::max(counts_.most_bytes, held_bytes_);
        } else {
            s = dropped_slot();
            slot_of_[std::size_t(slots_[std::size_t(s)].index)] = -1;
        }
        Tile& tile = slots_[std::size_t(s)];
        tile.index = -1, tile.part = tile_part(index);
        const std::size_t n = std::size_t(tile.part.cols()) * std::size_t(tile.part.rows());
        tile.pos.resize(n), tile.valid.resize(n);  // within the capacity reserved: no allocation
        read_(tile.part, tile.pos.data(), tile.valid.data());
        tile.index = index, slot_of_[std::size_t(index)] = s;
        ++counts_.reads;
        if (!seen_[std::size_t(index)]) seen_[std::size_t(index)] = 1, ++counts_.distinct;
    }
    Tile& tile = slots_[std::size_t(s)];
    tile.used = ++clock_;
    cur_ = tile.part, cur_pos_ = tile.pos.data(), cur_valid_ = tile.valid.data();
}

int NodeTiles::dropped_slot() const {
    // (0 north of the sweep, 1 elsewhere; when last used), least first
    const auto key = [&](const Tile& t) { return std::pair(t.index / tiles_across_ < sweep_ ? 0 : 1, t.used); };
    return int(std::min_element(slots_.begin(), slots_.end(), [&](const Tile& a, const Tile& b) { return key(a) < key(b); }) -
               slots_.begin());
}

glm::vec3 NodeTiles::probe_pos(int c, int r) {
    if (!read_ || slot_of_[std::size_t(tile_index(c, r))] >= 0) return pos(c, r);
    if (c < probe_.c0 || c >= probe_.c1 || r < probe_.r0 || r >= probe_.r1) {
        probe_ = GridWindow{c, r, c + 2, r + 2}.clamped(cols_, rows_);
        read_(probe_, probe_pos_, probe_valid_);
        ++counts_.probes;
    }
    return probe_pos_[(r - probe_.r0) * probe_.cols() + (c - probe_.c0)];
}

}  // namespace penink
