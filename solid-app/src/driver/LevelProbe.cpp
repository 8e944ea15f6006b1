// SPDX-License-Identifier: GPL-3.0-or-later
#include "driver/LevelProbe.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace fsi::driver
{

namespace
{
Eigen::Vector3d nodeDisplacement(const fe::StructuralSolver& solid, int node)
{
    const auto& u = solid.displacement();
    return {u[3 * node], u[3 * node + 1], u[3 * node + 2]};
}
} // namespace

std::vector<std::string> WatchedNodeProbe::columns() const
{
    return {name_ + "_ux", name_ + "_uy", name_ + "_uz"};
}

std::vector<double> WatchedNodeProbe::values(const fe::StructuralSolver& solid) const
{
    const Eigen::Vector3d u = nodeDisplacement(solid, node_);
    return {u.x(), u.y(), u.z()};
}

std::string WatchedNodeProbe::describe(const std::vector<double>& v) const
{
    std::ostringstream s;
    s.precision(4);
    s << name_ << " u = (" << v[0] << ", " << v[1] << ", " << v[2] << ") m";
    return s.str();
}

SectionAngleProbe::SectionAngleProbe(const SectionAngleParameters& params, const mesh::Mesh& mesh)
    : params_(params)
{
    leading_ =
        mesh.nearestNode({params.leadingEdge[0], params.leadingEdge[1], params.leadingEdge[2]});
    trailing_ =
        mesh.nearestNode({params.trailingEdge[0], params.trailingEdge[1], params.trailingEdge[2]});
    if (leading_ == trailing_)
        throw std::runtime_error(
            "coupling.section_angle: leading and trailing edge map to the same node");
}

// The chord from trailing to leading edge, deformed, in the plane (reference chord direction,
// lift direction); positive when the leading edge moves towards the lift direction.
std::vector<double> SectionAngleProbe::values(const fe::StructuralSolver& solid) const
{
    const auto& x = solid.mesh().nodes;
    const Eigen::Vector3d xl = x.col(leading_), xt = x.col(trailing_);
    const Eigen::Vector3d lift(params_.liftDirection[0], params_.liftDirection[1],
                               params_.liftDirection[2]);
    Eigen::Vector3d chord = xl - xt;
    chord -= chord.dot(lift) * lift;
    chord.normalize();
    const Eigen::Vector3d d =
        (xl + nodeDisplacement(solid, leading_)) - (xt + nodeDisplacement(solid, trailing_));
    return {std::atan2(d.dot(lift), d.dot(chord)) * 180.0 / M_PI};
}

std::string SectionAngleProbe::describe(const std::vector<double>& v) const
{
    std::ostringstream s;
    s.precision(4);
    s << params_.name << " " << v[0] << " deg";
    return s.str();
}

namespace
{
const char* const voigt[6] = {"xx", "yy", "zz", "xy", "yz", "xz"};
} // namespace

std::vector<std::string> NodeStressProbe::columns() const
{
    std::vector<std::string> c;
    for (const char* quantity : {"_sigma_", "_eps_"})
        for (const char* component : voigt)
            c.push_back(name_ + quantity + component);
    return c;
}

std::vector<double> NodeStressProbe::values(const fe::StructuralSolver& solid) const
{
    const auto at = solid.stressAndStrainAt({node_}).front();
    std::vector<double> v(at.stress.data(), at.stress.data() + 6);
    v.insert(v.end(), at.strain.data(), at.strain.data() + 6);
    return v;
}

std::vector<std::string> ReactionProbe::columns() const
{
    return {"reaction_" + surface_ + "_x", "reaction_" + surface_ + "_y",
            "reaction_" + surface_ + "_z"};
}

std::vector<double> ReactionProbe::values(const fe::StructuralSolver& solid) const
{
    const Eigen::Vector3d r = solid.reactionForce(surface_);
    return {r.x(), r.y(), r.z()};
}

} // namespace fsi::driver
