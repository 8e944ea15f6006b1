// SPDX-License-Identifier: GPL-3.0-or-later
#include "setup/SolidSetup.hpp"

#include "config/SolidConfig.hpp"
#include "mesh/Mesh.hpp"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace fsi::setup
{
namespace fs = std::filesystem;

fe::ProblemDefinition problemFromConfig(const config::SolidConfig& c)
{
    fe::ProblemDefinition p;
    p.kinematics = c.kinematics;
    p.formulation = fe::formulationFromName(c.elementType);
    p.density = c.density;
    if (c.loads.hasGravity)
        p.gravity = Eigen::Vector3d(c.loads.gravity[0], c.loads.gravity[1], c.loads.gravity[2]);
    p.clamped = c.mesh.clamped;
    p.wetted = c.mesh.wetted;
    p.displacements = c.loads.displacements;
    for (const auto& t : c.loads.tractions)
        p.tractions.push_back(
            {t.surface, Eigen::Vector3d(t.traction[0], t.traction[1], t.traction[2])});
    for (const auto& f : c.loads.forces)
        p.forces.push_back({f.surface, Eigen::Vector3d(f.total[0], f.total[1], f.total[2])});
    p.newton = c.newton;
    p.linearSolver = c.linearSolver;
    p.refactorShearDrift = c.refactorShearDrift;
    return p;
}

std::vector<std::string> surfaceGroups(const config::SolidConfig& c)
{
    std::vector<std::string> s = c.mesh.clamped;
    if (!c.mesh.wetted.empty())
        s.push_back(c.mesh.wetted);
    for (const auto& d : c.loads.displacements)
        s.push_back(d.surface);
    for (const auto& t : c.loads.tractions)
        s.push_back(t.surface);
    for (const auto& f : c.loads.forces)
        s.push_back(f.surface);
    return s;
}

void prepareOutputFolder(const std::string& folder, bool restart)
{
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec)
        throw std::runtime_error(folder + ": cannot create the output folder (" + ec.message() +
                                 ")");
    if (restart)
        return;
    auto remove = [&](const fs::path& path)
    {
        fs::remove_all(path, ec);
        if (ec)
            throw std::runtime_error(path.string() +
                                     ": cannot remove this file of an earlier run (" +
                                     ec.message() + "); remove it or choose another output folder");
    };
    for (const char* name : {"config.echo.yaml", "solid.pvd", "history.csv", "levels.csv",
                             "summary.csv", "coupling.csv", "interface", "checkpoint"})
        if (fs::exists(fs::path(folder) / name))
            remove(fs::path(folder) / name);
    for (const auto& entry : fs::directory_iterator(folder))
    {
        const std::string name = entry.path().filename().string();
        const bool series = name.size() == 15 && name.rfind("solid_", 0) == 0 &&
                            name.compare(11, 4, ".vtu") == 0 &&
                            name.find_first_not_of("0123456789", 6) == 11;
        if (series)
            remove(entry.path());
    }
}

void checkWatchPoints(const config::SolidConfig& c, const mesh::Mesh& mesh)
{
    if (c.output.watch.empty() || mesh.numNodes() == 0)
        return;
    const double diagonal =
        (mesh.nodes.rowwise().maxCoeff() - mesh.nodes.rowwise().minCoeff()).norm();
    for (std::size_t k = 0; k < c.output.watch.size(); ++k)
    {
        const auto& w = c.output.watch[k];
        const Eigen::Vector3d x(w.point[0], w.point[1], w.point[2]);
        const double distance = (mesh.nodes.col(mesh.nearestNode(x)) - x).norm();
        if (distance > 0.1 * diagonal)
        {
            char text[512];
            std::snprintf(text, sizeof text,
                          "%s: 'solid.output.watch[%zu]' (%s) point [%g, %g, %g] is %g m from "
                          "the nearest node of %s (mesh size %g m); give a point on the structure "
                          "in the mesh's units",
                          fs::path(c.file).filename().c_str(), k, w.name.c_str(), x[0], x[1], x[2],
                          distance, mesh.source.c_str(), diagonal);
            throw std::runtime_error(text);
        }
    }
}

} // namespace fsi::setup
