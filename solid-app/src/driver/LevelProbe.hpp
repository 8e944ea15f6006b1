// SPDX-License-Identifier: GPL-3.0-or-later
//
// Post-processing hook of the coupled driver: quantities evaluated on the solid after every
// accepted level and written as extra columns of history.csv and the console's level line.
// The driver knows nothing of what they mean (a tip angle, a watched point): each probe names
// its columns and computes its values. Probes are built from the config by the application
// (RunCoupled) and handed to the driver.
#pragma once

#include "driver/CouplingParameters.hpp"
#include "fe/StructuralSolver.hpp"

#include <memory>
#include <string>
#include <vector>

namespace fsi::driver
{

class LevelProbe
{
public:
    virtual ~LevelProbe() = default;
    // Column names of history.csv (fixed for the run).
    virtual std::vector<std::string> columns() const = 0;
    // One value per column at the solid's current (just accepted) state. Called on every rank;
    // the solid's displacement is replicated, so the values are the same on every rank.
    virtual std::vector<double> values(const fe::StructuralSolver& solid) const = 0;
    // Short text for the console's level line, e.g. "tip_le u = (1e-3, 2e-3, 0) m"; empty:
    // nothing on the console (history.csv only).
    virtual std::string describe(const std::vector<double>& values) const = 0;
};

// Displacement [m] of a named mesh node (the node nearest to a requested point):
// columns NAME_ux, NAME_uy, NAME_uz.
class WatchedNodeProbe final : public LevelProbe
{
public:
    WatchedNodeProbe(std::string name, int node) : name_(std::move(name)), node_(node) {}
    std::vector<std::string> columns() const override;
    std::vector<double> values(const fe::StructuralSolver& solid) const override;
    std::string describe(const std::vector<double>& values) const override;

private:
    std::string name_;
    int node_;
};

// Angle of a section chord in the deformed state [deg] (e.g. the hydrofoil's tip AOA), see
// SectionAngleParameters: column NAME_deg. Throws std::runtime_error when the leading and
// trailing edge points map to the same mesh node.
class SectionAngleProbe final : public LevelProbe
{
public:
    SectionAngleProbe(const SectionAngleParameters& params, const mesh::Mesh& mesh);
    std::vector<std::string> columns() const override { return {params_.name + "_deg"}; }
    std::vector<double> values(const fe::StructuralSolver& solid) const override;
    std::string describe(const std::vector<double>& values) const override;

private:
    SectionAngleParameters params_;
    int leading_ = -1, trailing_ = -1;
};

// Cauchy stress [Pa] and strain [-] (tensor shear; Green-Lagrange under total Lagrangian) at a
// named node, volume-averaged over its cells: columns NAME_sigma_xx..xz, NAME_eps_xx..xz
// (Voigt order xx, yy, zz, xy, yz, xz). Collective (every rank calls values()).
class NodeStressProbe final : public LevelProbe
{
public:
    NodeStressProbe(std::string name, int node) : name_(std::move(name)), node_(node) {}
    std::vector<std::string> columns() const override;
    std::vector<double> values(const fe::StructuralSolver& solid) const override;
    std::string describe(const std::vector<double>&) const override { return {}; }

private:
    std::string name_;
    int node_;
};

// Reaction force [N] of the supports on a surface group (a clamped group): columns
// reaction_GROUP_x/y/z.
class ReactionProbe final : public LevelProbe
{
public:
    explicit ReactionProbe(std::string surface) : surface_(std::move(surface)) {}
    std::vector<std::string> columns() const override;
    std::vector<double> values(const fe::StructuralSolver& solid) const override;
    std::string describe(const std::vector<double>&) const override { return {}; }

private:
    std::string surface_;
};

using LevelProbes = std::vector<std::unique_ptr<LevelProbe>>;

} // namespace fsi::driver
