// Drainage lines and divides as vertex lists (Mower, "Concurrent Drainage Network Rendering" sec. 3): every drainage point belongs to
// one branch — a run from a source (ridge point, no inflow) or a junction (inflow > 1) down
// through single-inflow points to the next junction (repeated as the branch's last vertex) or
// an outlet; all flow paths are kept (thresholding happens at render time by the score).
// Divides: the boundary between 4-adjacent valid points of different basins, i.e. the dual-grid
// edges between them, chained at dual corners into polylines (corner = mean x, y of its valid
// surrounding points, z = their highest elevation; flow 0).
#pragma once
#include <memory>

#include "drainage/drainage_db.hpp"
#include "drainage/drainage_grid.hpp"
#include "drainage/flow_network.hpp"

namespace penink {

// Fills db.vertices, db.branches and db.upstream (branches in row-major order of their head).
// z comes from g.z (pass the original, unfilled elevations).
void build_branches(const DrainageGrid& g, const std::vector<std::uint8_t>& dir,
                    const FlowNetwork& net, DrainageDb& db);

// The branches of a drainage network as the DV encoder asks for them (DvBranchSource), without
// holding their vertices: heads ranked in cell order (= branch ids) up front, each branch walked
// when its range is encoded (from any thread). Gives the bytes build_branches' DrainageDb encodes
// to, or, on an affine grid at factor 1 (grid_nodes), a smaller file of cells that reads back to
// that DrainageDb. g, dir and net must outlive it; net needs indeg (accumulate_flow) or it is
// counted here.
class NetworkBranches : public DvBranchSource {
public:
    NetworkBranches(const DrainageGrid& g, const std::vector<std::uint8_t>& dir, const FlowNetwork& net);
    ~NetworkBranches() override;
    std::size_t branch_count() const override;
    std::size_t vertex_count() const override;
    std::size_t link_count() const override;
    // Grid positions when the grid is the Terrain's own (factor 1) on an affine grid.
    const AffineNodes* grid_nodes() const override;
    void encode(std::size_t b0, std::size_t b1, DvBytes& out) const override;

private:
    struct Walks;
    std::unique_ptr<Walks> w_;
};

// Fills db.divide_vertices and db.divides.
void build_divides(const DrainageGrid& g, const FlowNetwork& net, DrainageDb& db);

}  // namespace penink
