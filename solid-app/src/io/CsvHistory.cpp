// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/CsvHistory.hpp"

#include "io/AtomicFile.hpp"

#include <cstdio>
#include <stdexcept>
#include <string>

namespace fsi::io
{

CsvHistory::CsvHistory(std::string path, const mesh::Mesh& mesh,
                       const std::vector<std::string>& names,
                       const std::vector<std::array<double, 3>>& points,
                       const std::vector<std::string>& extraColumns)
    : path_(std::move(path)), extraColumns_(extraColumns.size())
{
    header_ = "time";
    for (std::size_t k = 0; k < names.size(); ++k)
    {
        const Eigen::Vector3d x(points[k][0], points[k][1], points[k][2]);
        const int node = mesh.nearestNode(x);
        nodes_.push_back(node);
        distances_.push_back((mesh.nodes.col(node) - x).norm());
        header_ += "," + names[k] + "_ux," + names[k] + "_uy," + names[k] + "_uz";
    }
    for (const auto& column : extraColumns)
        header_ += "," + column;
    header_ += "\n";
}

void CsvHistory::record(double time, const std::vector<double>& u, const std::vector<double>& extra)
{
    if (extra.size() != extraColumns_)
        throw std::invalid_argument("CsvHistory::record: " + std::to_string(extra.size()) +
                                    " extra values for " + std::to_string(extraColumns_) +
                                    " extra columns");
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.10g", time);
    rows_ += buf;
    for (int node : nodes_)
        for (int i = 0; i < 3; ++i)
        {
            std::snprintf(buf, sizeof buf, ",%.12e", u[3 * node + i]);
            rows_ += buf;
        }
    for (double v : extra)
    {
        std::snprintf(buf, sizeof buf, ",%.12e", v);
        rows_ += buf;
    }
    rows_ += "\n";
    writeFileAtomically(path_, header_ + rows_);
}

} // namespace fsi::io
