// SPDX-License-Identifier: GPL-3.0-or-later
// CSV histories of watched points: the node nearest to each requested coordinate.
// Columns: time, then <name>_ux, <name>_uy, <name>_uz per point [s, m], then the caller's extra
// columns (e.g. stresses, reactions; their names carry the meaning). Rewritten atomically after
// each level (small files), so it is always complete.
#pragma once
#include "mesh/Mesh.hpp"

#include <array>
#include <string>
#include <vector>

namespace fsi::io
{

class CsvHistory
{
public:
    CsvHistory(std::string path, const mesh::Mesh& mesh, const std::vector<std::string>& names,
               const std::vector<std::array<double, 3>>& points,
               const std::vector<std::string>& extraColumns = {});
    // Records the displacement (3 per node) and the extra columns' values at time t and rewrites
    // the file. Throws std::invalid_argument if extra does not have one value per extra column.
    void record(double time, const std::vector<double>& displacement,
                const std::vector<double>& extra = {});
    int node(std::size_t k) const { return nodes_[k]; }
    // Distance from the requested point to its node [m].
    double distance(std::size_t k) const { return distances_[k]; }

private:
    std::string path_;
    std::string header_;
    std::vector<int> nodes_;
    std::vector<double> distances_;
    std::string rows_;
    std::size_t extraColumns_ = 0;
};

} // namespace fsi::io
