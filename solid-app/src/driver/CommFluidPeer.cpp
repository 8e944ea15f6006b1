// SPDX-License-Identifier: GPL-3.0-or-later
#include "driver/CommFluidPeer.hpp"

#include "fsi/comm/Protocol.hpp"

#include <algorithm>
#include <stdexcept>

namespace fsi::driver
{

namespace
{
// An n x 3 row-major array of the wire as the driver's n x 3 matrix (same layout).
template <class Matrix> Matrix rows(const std::vector<double>& xyz)
{
    return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
        xyz.data(), static_cast<Eigen::Index>(xyz.size() / 3), 3);
}
} // namespace

CommFluidPeer::CommFluidPeer(comm::Channel& channel) : channel_(channel)
{
    const auto& sizes = channel_.peer().interfaceSizes;
    if (sizes.size() != 2 || sizes[0] <= 0 || sizes[1] <= 0)
        throw std::runtime_error(
            "fluid-app announced interface sizes that are not {points > 0, faces > 0}: "
            "check the interface patch of the fluid case");
    const auto geometry = comm::protocol::decodeGeometry(
        channel_.receive(comm::MessageKind::InterfaceGeometry), sizes[0], sizes[1]);
    if (channel_.isRoot())
    {
        interface_.points = rows<mapping::PointCloud>(geometry.points);
        interface_.faceCentres = rows<mapping::PointCloud>(geometry.faceCentres);
        interface_.faceAreas = rows<mapping::PointCloud>(geometry.faceAreas);
    }
    using namespace comm::protocol;
    std::vector<comm::RowShape> shapes(2);
    shapes[kPointRows] = {sizes[0], kRowWidth, false};
    shapes[kFaceRows] = {sizes[1], kRowWidth, true};
    auto maps = channel_.receiveRowMaps(shapes);
    pointRows_ = std::move(maps[kPointRows]);
    faceRows_ = std::move(maps[kFaceRows]);
}

FluidResponse CommFluidPeer::solve(int level, int iteration, double time,
                                   const mapping::Values& pointDisplacement,
                                   const FluidAccuracy& accuracy)
{
    comm::protocol::Solve command;
    command.level = level;
    command.iteration = iteration;
    command.time = time;
    command.accuracyGiven = accuracy.driverControlled;
    command.forceTolerance = accuracy.forceTolerance;
    command.residualDrop = accuracy.residualDrop;
    command.minIterations = accuracy.minIterations;
    std::vector<double> displacements;
    if (channel_.isRoot())
    {
        displacements.resize(3 * static_cast<std::size_t>(pointDisplacement.rows()));
        Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
            displacements.data(), pointDisplacement.rows(), 3) = pointDisplacement;
    }
    channel_.send(comm::protocol::encode(command));
    channel_.scatterRows(pointRows_, displacements);
    const auto answer =
        comm::protocol::decodeForces(channel_.receive(comm::MessageKind::Forces), level, iteration);
    const std::vector<double> faceForces = channel_.gatherRows(faceRows_);
    FluidResponse r;
    if (channel_.isRoot())
        r.faceForces = rows<mapping::Values>(faceForces);
    r.iterations = static_cast<int>(answer.iterations);
    r.converged = answer.converged;
    r.band = answer.band;
    if (!answer.residuals.empty())
        r.finalResidual = *std::max_element(answer.residuals.begin(), answer.residuals.end());
    return r;
}

void CommFluidPeer::accept(int level, double time)
{
    channel_.send(comm::protocol::encode(comm::protocol::Accept{level, time}));
}

void CommFluidPeer::finish()
{
    channel_.send(comm::MessageKind::Finish, 0, 0);
    finished_ = true;
}

void CommFluidPeer::abort(const std::string& reason) noexcept
{
    if (!finished_)
        channel_.sendAbort(reason);
}

} // namespace fsi::driver
