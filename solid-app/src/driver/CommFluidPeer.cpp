// SPDX-License-Identifier: GPL-3.0-or-later
#include "driver/CommFluidPeer.hpp"

#include <algorithm>
#include <stdexcept>

namespace fsi::driver
{

namespace
{
mapping::PointCloud rows(const std::vector<double>& v, std::size_t offset, Eigen::Index count)
{
    mapping::PointCloud c(count, 3);
    for (Eigen::Index i = 0; i < count; ++i)
        for (int k = 0; k < 3; ++k)
            c(i, k) = v[offset + 3 * i + k];
    return c;
}
} // namespace

CommFluidPeer::CommFluidPeer(comm::Channel& channel) : channel_(channel)
{
    const auto& sizes = channel_.peer().interfaceSizes;
    if (sizes.size() != 2 || sizes[0] <= 0 || sizes[1] <= 0)
        throw std::runtime_error("fluid-app announced interface sizes that are not {points > 0, faces > 0}: "
                                 "check the interface patch of the fluid case");
    const Eigen::Index points = sizes[0], faces = sizes[1];
    auto m = channel_.receive(comm::MessageKind::InterfaceGeometry);
    if (m.valueCount != 3 * points + 6 * faces)
        throw std::runtime_error("fluid-app sent " + std::to_string(m.valueCount) +
                                 " interface geometry values, expected " +
                                 std::to_string(3 * points + 6 * faces) + " (3 points + 6 faces)");
    if (channel_.isRoot())
    {
        interface_.points = rows(m.values, 0, points);
        interface_.faceCentres = rows(m.values, 3 * points, faces);
        interface_.faceAreas = rows(m.values, 3 * (points + faces), faces);
    }
}

FluidResponse CommFluidPeer::solve(int level, int iteration, double time,
                                   const mapping::Values& pointDisplacement,
                                   const FluidAccuracy& accuracy)
{
    comm::Message command;
    command.kind = comm::MessageKind::Solve;
    command.timeStep = level;
    command.iteration = iteration;
    command.scalars = {time};
    if (accuracy.driverControlled)
    {
        command.scalars.push_back(accuracy.forceTolerance);
        command.scalars.push_back(accuracy.residualDrop);
        command.integers = {accuracy.minIterations};
    }
    if (channel_.isRoot())
    {
        command.values.resize(3 * pointDisplacement.rows());
        for (Eigen::Index i = 0; i < pointDisplacement.rows(); ++i)
            for (int k = 0; k < 3; ++k)
                command.values[3 * i + k] = pointDisplacement(i, k);
    }
    channel_.send(command);
    auto answer = channel_.receive(comm::MessageKind::Forces);
    if (answer.timeStep != level || answer.iteration != iteration)
        throw std::runtime_error("fluid-app answered level " + std::to_string(answer.timeStep) +
                                 " iteration " + std::to_string(answer.iteration) + " to level " +
                                 std::to_string(level) + " iteration " + std::to_string(iteration));
    const Eigen::Index faces = channel_.peer().interfaceSizes[1];
    if (answer.valueCount != 3 * faces)
        throw std::runtime_error("fluid-app sent " + std::to_string(answer.valueCount) +
                                 " force values, expected " + std::to_string(3 * faces));
    FluidResponse r;
    if (channel_.isRoot())
        r.faceForces = rows(answer.values, 0, faces);
    r.iterations = answer.integers.empty() ? 0 : static_cast<int>(answer.integers[0]);
    r.converged = answer.integers.size() < 2 || answer.integers[1] != 0;
    if (!answer.scalars.empty())
        r.finalResidual = *std::max_element(answer.scalars.begin(), answer.scalars.end());
    return r;
}

void CommFluidPeer::accept(int level, double time)
{
    comm::Message m;
    m.kind = comm::MessageKind::Accept;
    m.timeStep = level;
    m.scalars = {time};
    channel_.send(m);
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
