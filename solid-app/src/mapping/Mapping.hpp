// SPDX-License-Identifier: GPL-3.0-or-later
//
// Interface mapping between non-matching point clouds (solid wetted nodes <-> fluid patch
// points / face centres). This layer knows point clouds and value arrays only: no MPI, no FE,
// no YAML. The config layer fills MappingParameters; buildMapping() returns a ready operator.
//
// A mapping is the linear operator H (N_t x N_s) from source-point values to target-point values:
//   consistent   (displacements): targetValues = H sourceValues        (per component)
//   conservative (forces):        sourceValues = H^T targetValues      (per component)
// For forces, build the mapping with source = solid wetted nodes and target = fluid face centres
// and call applyConservative: total force is conserved exactly (H reproduces constants), total
// moment too when H reproduces linear fields (all RBF kinds; not nearest-neighbour).
#pragma once

#include <Eigen/Core>

#include <memory>
#include <string>

namespace fsi::mapping
{

// One row per point, coordinates x y z in metres.
using PointCloud = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
// One row per point, one column per component (3 for displacement or force); any unit.
using Values = Eigen::MatrixXd;

// Base of all mapping strategies (after preCICE mapping::Mapping). Not thread-safe: apply*()
// use internal workspace, so one object serves one thread.
class Mapping
{
public:
    virtual ~Mapping() = default;

    // Keyword of the strategy ("nearest-neighbour", "rbf-thin-plate", "rbf-wendland-c2",
    // "rbf-pu").
    virtual std::string name() const = 0;

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

    Eigen::Index sourceSize() const { return sourceSize_; }
    Eigen::Index targetSize() const { return targetSize_; }

protected:
    Eigen::Index sourceSize_ = 0;
    Eigen::Index targetSize_ = 0;
};

// Coefficients of rbf-wendland-c2: phi(r) = (1 - r/rho)^4_+ (4 r/rho + 1).
struct WendlandParameters
{
    double supportRadius = 0.0; // rho [m]; a few source-node spacings (3..6 is typical)
    // "direct" (sparse LDLT, fast apply, fill grows fast with N) | "iterative" (CG with
    // incomplete Cholesky, to iterative_tolerance) | "auto" (direct up to direct_max_points)
    std::string solver = "auto";
    long directMaxPoints = 20000;
    double iterativeTolerance = 1e-10; // relative residual of each CG solve
    void validate() const;             // throws: support_radius must be > 0, ...
};

// Coefficients of rbf-thin-plate: phi(r) = r^2 log r, global and dense (O(N^3) set-up).
struct ThinPlateParameters
{
    long maxSourcePoints = 10000; // refuse larger interfaces (memory ~ 16 N^2 bytes)
    void validate() const;
};

// Coefficients of rbf-pu, partition of unity: local cubic RBF + linear polynomial on
// overlapping patches of k nearest source points, blended by smooth weights
// (RbfPartitionOfUnity.hpp). Set-up and apply O(N), for any interface size.
struct PartitionOfUnityParameters
{
    long pointsPerPatch = 20;    // k: source points of each local problem, in [4, 200]; more =
                                 // a little more accurate, cost ~ k^2
    double centreSpacing = 0.85; // in (0, 1): every target lies within this fraction of a patch
                                 // radius from a patch centre; smaller = more overlap, slower
    void validate() const;       // throws one line naming mapping.rbf-pu.<key>
};

struct MappingParameters
{
    // "nearest-neighbour" | "rbf-thin-plate" | "rbf-wendland-c2" | "rbf-pu"
    std::string type = "nearest-neighbour";
    // checkOverlap(): max distance from a target point to the nearest source point, relative to
    // the source interface size (bounding-box diagonal); larger means the meshes do not match.
    double overlapTolerance = 0.1;
    WendlandParameters wendland;
    ThinPlateParameters thinPlate;
    PartitionOfUnityParameters partitionOfUnity;

    // Throws std::runtime_error, one line naming the key (mapping.<key>) and the fix.
    void validate() const;
};

// Strategy object for params.type (validated), not yet computed.
std::unique_ptr<Mapping> makeMapping(const MappingParameters& params);

// validate + checkOverlap(source, target, params.overlapTolerance) + makeMapping + compute.
std::unique_ptr<Mapping> buildMapping(const MappingParameters& params, const PointCloud& source,
                                      const PointCloud& target);

} // namespace fsi::mapping
