// SPDX-License-Identifier: GPL-3.0-or-later
//
// Interface mapping between non-matching point clouds (solid wetted nodes <-> fluid patch
// points / face centres). This layer knows point clouds, value arrays and, for the strategies
// that project onto it, the source's surface faces (mesh::CellList, reference elements): no MPI,
// no FE assembly, no YAML. The config layer fills MappingParameters; buildMapping() returns a ready
// operator.
//
// A mapping is the linear operator H (N_t x N_s) from source-point values to target-point values:
//   consistent   (displacements): targetValues = H sourceValues        (per component)
//   conservative (forces):        sourceValues = H^T targetValues      (per component)
// For forces, build the mapping with source = solid wetted nodes and target = fluid face centres
// and call applyConservative: total force is conserved exactly (H reproduces constants), total
// moment too when H reproduces linear fields (all RBF kinds; not nearest-neighbour; for
// nearest-projection up to the forces' lever arm off the source surface; moving-least-squares
// where its stencils span three directions).
#pragma once

#include "config/Strategy.hpp"
#include "mesh/Mesh.hpp"

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

namespace fsi::mapping
{

// One row per point, coordinates x y z in metres.
using PointCloud = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
// One row per point, one column per component (3 for displacement or force); any unit.
using Values = Eigen::MatrixXd;

// The source points' surface: its faces (Tri3, Tri6, Quad4, Quad8, Quad9 in Gmsh node order),
// node indices into the source cloud. nearest-projection maps through it; the point-cloud
// strategies ignore it.
struct SourceSurface
{
    mesh::CellList faces;
};

// Base of all mapping strategies (after preCICE mapping::Mapping). Not thread-safe: apply*()
// use internal workspace, so one object serves one thread.
class Mapping
{
public:
    static constexpr const char* kConfigKey = "mapping"; // for config::Strategy messages
    virtual ~Mapping() = default;

    // Keyword of the strategy ("nearest-neighbour", "rbf-thin-plate", "rbf-wendland-c2",
    // "rbf-pu", "nearest-projection", "moving-least-squares").
    virtual std::string name() const = 0;

    // The source's surface faces, before compute(); ignored by the point-cloud strategies
    // (nearest-projection's compute() refuses to run without them).
    virtual void setSourceSurface(const SourceSurface& /*surface*/) {}

    // Set-up (search trees, factorisations); the expensive part, done once per pair of meshes.
    // Pre: source and target non-empty; coordinates in metres. Throws std::runtime_error on
    // degenerate input (duplicate source points for RBF, support radius too small, ...).
    virtual void compute(const PointCloud& source, const PointCloud& target) = 0;

    // targetValues = H sourceValues. Pre: compute() done; sourceValues.rows() == sourceSize(),
    // targetValues is sized targetSize() x sourceValues.cols() by the caller. No factorisation,
    // and no heap allocation after the first call with a given column count (checked by
    // tests/mapping/test_no_allocation.cpp; except rbf-wendland-c2 with the iterative solver).
    virtual void applyConsistent(const Eigen::Ref<const Values>& sourceValues,
                                 Eigen::Ref<Values> targetValues) const = 0;

    // sourceValues = H^T targetValues (forces: target = fluid faces, source = solid nodes).
    // Pre: targetValues.rows() == targetSize(); sourceValues sized sourceSize() x cols by caller.
    virtual void applyConservative(const Eigen::Ref<const Values>& targetValues,
                                   Eigen::Ref<Values> sourceValues) const = 0;

    // A mapping from this one's source to `target` that shares this one's source-side set-up
    // (e.g. the factorised source matrix), or nullptr where the strategy has nothing to share
    // (the default; buildMappings() then computes it from scratch). Mappings that share a
    // source serve one thread together. Pre: compute() done; throws as compute() does for a
    // bad target.
    virtual std::unique_ptr<Mapping> withSameSource(const PointCloud& /*target*/) const
    {
        return nullptr;
    }
    Eigen::Index sourceSize() const { return sourceSize_; }
    Eigen::Index targetSize() const { return targetSize_; }

protected:
    Eigen::Index sourceSize_ = 0;
    Eigen::Index targetSize_ = 0;
};

// The chosen strategy with its coefficients (config/Strategy.hpp says what a strategy's
// parameter struct provides; Registry.hpp lists them), and what every mapping shares.
struct MappingParameters
{
    MappingParameters(); // nearest-neighbour
    template <class P>
    MappingParameters(const P& strategyParameters) // NOLINT: implicit
        : strategy(strategyParameters)
    {
    }
    config::Strategy<Mapping> strategy;
    // checkOverlap(): max distance from a target point to the nearest source point, relative to
    // the source interface size (bounding-box diagonal); larger means the meshes do not match.
    double overlapTolerance = 0.1;
    // > 0: the consistent direction's values are smoothed on the target cloud by moving least
    // squares within this radius [m] (H -> S H, forces H^T S^T; TargetSmoothing.hpp). 0 = off.
    double smoothingRadius = 0.0;

    const std::string& type() const { return strategy.type(); }
    // Throws std::runtime_error, one line naming the key (mapping.<key>) and the fix: the
    // strategy's coefficients, then the two checks below (a config parser calls those two on
    // their own, to name the key it read).
    void validate() const;
    void validateOverlapTolerance() const;
    void validateSmoothingRadius() const;
};

// Strategy object for params.type (validated), not yet computed.
std::unique_ptr<Mapping> makeMapping(const MappingParameters& params);

// validate + checkOverlap(source, target, params.overlapTolerance) + makeMapping + compute
// (+ the target-side smoothing when params.smoothingRadius > 0).
// surface: the source's faces, given to every strategy (setSourceSurface); nearest-projection
// needs them (compute() throws one line without), the others ignore them.
std::unique_ptr<Mapping> buildMapping(const MappingParameters& params, const PointCloud& source,
                                      const PointCloud& target,
                                      const SourceSurface* surface = nullptr);
// buildMapping() from one source to each of `targets` (e.g. the fluid's points and its face
// centres; non-null, at least one), the source-side set-up done once where the strategy shares
// it (withSameSource()). Each target's overlap is checked.
std::vector<std::unique_ptr<Mapping>> buildMappings(const MappingParameters& params,
                                                    const PointCloud& source,
                                                    const std::vector<const PointCloud*>& targets,
                                                    const SourceSurface* surface = nullptr);

} // namespace fsi::mapping
