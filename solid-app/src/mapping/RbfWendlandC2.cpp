// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/RbfWendlandC2.hpp"
#include "config/YamlReader.hpp"
#include <sstream>

#include "linalg/SparseDirectSolver.hpp"
#include "mapping/KdTree.hpp"
#include "mapping/RbfSupport.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace fsi::mapping
{

const std::vector<std::string>& WendlandParameters::keys()
{
    static const std::vector<std::string> k{"support_radius", "solver", "direct_max_points",
                                            "iterative_tolerance"};
    return k;
}

WendlandParameters WendlandParameters::parse(const config::Block& layer)
{
    const config::Block b = layer.block(keyword);
    b.allowOnly(keys());
    WendlandParameters p;
    p.supportRadius = b.number("support_radius");
    p.solver = b.choice("solver", {"auto", "mumps", "direct", "iterative"}, p.solver);
    p.directMaxPoints = b.integer("direct_max_points", static_cast<int>(p.directMaxPoints));
    p.iterativeTolerance = b.number("iterative_tolerance", p.iterativeTolerance);
    return p;
}

void WendlandParameters::validate() const
{
    if (!(supportRadius > 0.0) || !std::isfinite(supportRadius))
        throw std::runtime_error("rbf-wendland-c2.support_radius must be > 0 m for type "
                                 "rbf-wendland-c2 (got " +
                                 config::formatNumber(supportRadius) +
                                 "); set it to a few solid node spacings");
    if (solver != "auto" && solver != "mumps" && solver != "direct" && solver != "iterative")
        throw std::runtime_error("rbf-wendland-c2.solver '" + solver +
                                 "' is unknown; use auto, mumps, direct or iterative");
    if (directMaxPoints < 0)
        throw std::runtime_error("rbf-wendland-c2.direct_max_points must be >= 0 (got " +
                                 std::to_string(directMaxPoints) + "); e.g. 20000");
    if (!(iterativeTolerance > 0.0 && iterativeTolerance < 1.0))
        throw std::runtime_error("rbf-wendland-c2.iterative_tolerance must be in (0, 1) (got " +
                                 config::formatNumber(iterativeTolerance) + "); e.g. 1e-10");
}

std::string WendlandParameters::echo() const
{
    std::ostringstream s;
    s << "{support_radius: " << supportRadius << ", solver: " << solver
      << ", direct_max_points: " << directMaxPoints
      << ", iterative_tolerance: " << iterativeTolerance << "}";
    return s.str();
}

namespace
{
// %g keeps small values readable in messages (1e-05, not 0.000000).
std::string number(double value)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

inline double wendlandC2(double rOverRho)
{
    const double a = 1.0 - rOverRho;
    return a > 0.0 ? a * a * a * a * (4.0 * rOverRho + 1.0) : 0.0;
}

void resizeWorkspace(Eigen::MatrixXd& m, Eigen::Index rows, Eigen::Index cols)
{
    if (m.rows() != rows || m.cols() != cols)
        m.resize(rows, cols);
}

// Triplets phi(|q_i - s_j| / rho) for all s_j within rho of q_i.
// Returns the index of a query with no neighbour, or -1.
Eigen::Index kernelTriplets(const KdTree& tree, const PointCloud& queries, double rho,
                            std::vector<Eigen::Triplet<double>>& triplets)
{
    std::vector<std::pair<Eigen::Index, double>> found;
    for (Eigen::Index i = 0; i < queries.rows(); ++i)
    {
        tree.withinRadius(queries.row(i).data(), rho, found);
        if (found.empty())
            return i;
        for (const auto& [j, d2] : found)
            triplets.emplace_back(i, j, wendlandC2(std::sqrt(d2) / rho));
    }
    return -1;
}

bool mpiRunning()
{
    int initialised = 0, finalised = 0;
    MPI_Initialized(&initialised);
    MPI_Finalized(&finalised);
    return initialised && !finalised;
}
} // namespace

struct RbfWendlandC2::SourceSystem
{
    // Normalises the source, builds Phi and factorises it with the backend `solver` chooses.
    SourceSystem(const PointCloud& source, const WendlandParameters& params);
    // params.solver resolved: "auto" is mumps with MPI running, else direct up to
    // direct_max_points source points and iterative above.
    static Backend chooseBackend(const WendlandParameters& params, Eigen::Index sourcePoints);

    Backend backend = Backend::Direct;
    detail::Normalisation normalisation;
    PointCloud points;                  // normalised source
    double rho = 0.0;                   // normalised support radius
    KdTree tree;                        // over points
    Eigen::SparseMatrix<double> system; // Phi, both triangles (the CG solver refers to it)
    // MUMPS on MPI_COMM_SELF (the mapping runs on solid rank 0)
    std::unique_ptr<linalg::SparseDirectSolver> mumps;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt;
    Eigen::VectorXd diagonal; // D of the LDLT
    Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper,
                             Eigen::IncompleteCholesky<double>>
        cg;

private:
    // Factorises system (given as its triplets, both triangles) with MUMPS into mumps.
    void factoriseWithMumps(const std::vector<Eigen::Triplet<double>>& triplets);
};

RbfWendlandC2::RbfWendlandC2(const WendlandParameters& params) : params_(params) {}

RbfWendlandC2::~RbfWendlandC2() = default;

std::string RbfWendlandC2::solverInUse() const
{
    switch (source_ ? source_->backend : Backend::Direct)
    {
    case Backend::Mumps:
        return "mumps";
    case Backend::Iterative:
        return "iterative";
    default:
        return "direct";
    }
}

Eigen::Index RbfWendlandC2::systemNonZeros() const
{
    return source_ ? source_->system.nonZeros() : 0;
}

bool RbfWendlandC2::iterative() const
{
    return source_ && source_->backend == Backend::Iterative;
}

RbfWendlandC2::Backend RbfWendlandC2::SourceSystem::chooseBackend(const WendlandParameters& params,
                                                                  Eigen::Index sourcePoints)
{
    const bool withMpi = mpiRunning();
    if (params.solver == "mumps" && !withMpi)
        throw std::runtime_error("mapping rbf-wendland-c2: solver mumps needs MPI (solid-app "
                                 "initialises it); use solver direct or iterative here");
    if (params.solver == "mumps" || (params.solver == "auto" && withMpi))
        return Backend::Mumps;
    if (params.solver == "iterative" ||
        (params.solver == "auto" && sourcePoints > params.directMaxPoints))
        return Backend::Iterative;
    return Backend::Direct;
}

RbfWendlandC2::SourceSystem::SourceSystem(const PointCloud& source,
                                          const WendlandParameters& params)
    : backend(chooseBackend(params, source.rows())), normalisation(source),
      points(normalisation.apply(source)), rho(params.supportRadius / normalisation.scale),
      tree(points)
{
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(static_cast<size_t>(points.rows()) * 32);
    kernelTriplets(tree, points, rho, triplets);
    system.resize(points.rows(), points.rows());
    system.setFromTriplets(triplets.begin(), triplets.end());
    if (backend == Backend::Mumps)
        factoriseWithMumps(triplets);
    else if (backend == Backend::Iterative)
    {
        cg.setTolerance(params.iterativeTolerance);
        cg.setMaxIterations(std::max<Eigen::Index>(1000, points.rows()));
        cg.compute(system);
    }
    else
    {
        ldlt.compute(system);
        diagonal = ldlt.vectorD(); // vectorD() returns a copy: keep it
    }
    const Eigen::ComputationInfo info = backend == Backend::Iterative ? cg.info()
                                        : backend == Backend::Direct  ? ldlt.info()
                                                                      : Eigen::Success;
    if (info != Eigen::Success)
        throw std::runtime_error("mapping rbf-wendland-c2: factorisation of the RBF matrix "
                                 "failed; check for near-duplicate source points or change "
                                 "mapping.support_radius");
}

void RbfWendlandC2::compute(const PointCloud& source, const PointCloud& target)
{
    params_.validate();
    detail::checkDistinctPoints(source, "rbf-wendland-c2");
    source_.reset(); // a recompute frees the old factor first (unless another mapping shares it)
    source_ = std::make_shared<SourceSystem>(source, params_);
    computeTarget(target);
}

std::unique_ptr<Mapping> RbfWendlandC2::withSameSource(const PointCloud& target) const
{
    if (!source_)
        throw std::logic_error("RbfWendlandC2::withSameSource: compute() first");
    auto mapping = std::make_unique<RbfWendlandC2>(params_);
    mapping->source_ = source_;
    mapping->computeTarget(target);
    return mapping;
}

void RbfWendlandC2::computeTarget(const PointCloud& target)
{
    const SourceSystem& source = *source_;
    const PointCloud t = source.normalisation.apply(target);
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(static_cast<size_t>(t.rows()) * 32);
    const Eigen::Index lonely = kernelTriplets(source.tree, t, source.rho, triplets);
    if (lonely >= 0)
    {
        char where[160];
        const auto p = target.row(lonely);
        std::snprintf(where, sizeof where, "target point %ld (%.4g %.4g %.4g) m",
                      static_cast<long>(lonely), p(0), p(1), p(2));
        throw std::runtime_error(std::string("mapping rbf-wendland-c2: ") + where +
                                 " has no source point within mapping.support_radius " +
                                 number(params_.supportRadius) +
                                 " m; raise support_radius to a few solid node spacings");
    }
    evaluation_.resize(t.rows(), source.points.rows());
    evaluation_.setFromTriplets(triplets.begin(), triplets.end());

    const detail::LinearPolynomial polynomial(source.points, t);
    sourceBasis_ = polynomial.sourceBasis;
    targetBasis_ = polynomial.targetBasis;
    sourceSize_ = source.points.rows();
    targetSize_ = t.rows();
}

void RbfWendlandC2::SourceSystem::factoriseWithMumps(
    const std::vector<Eigen::Triplet<double>>& triplets)
{
    // Phi is symmetric positive definite (Wendland C2 in 3-D, distinct points): LDL^T without
    // pivoting. Both triangles are passed: the wrapper keeps the lower one.
    linalg::DirectSolverOptions options;
    options.symmetric = true;
    options.positiveDefinite = true;
    std::vector<int> rows(triplets.size()), cols(triplets.size());
    std::vector<double> values(triplets.size());
    for (std::size_t k = 0; k < triplets.size(); ++k)
    {
        rows[k] = static_cast<int>(triplets[k].row());
        cols[k] = static_cast<int>(triplets[k].col());
        values[k] = triplets[k].value();
    }
    try
    {
        mumps = std::make_unique<linalg::SparseDirectSolver>(MPI_COMM_SELF, options);
        mumps->setPattern(static_cast<int>(system.rows()), std::move(rows), std::move(cols));
        mumps->setValues(std::move(values));
        mumps->factorize();
    }
    catch (const std::exception& e)
    {
        mumps.reset();
        throw std::runtime_error(std::string("mapping rbf-wendland-c2: MUMPS factorisation of "
                                             "the RBF matrix failed (") +
                                 e.what() +
                                 "); check for near-duplicate source points or change "
                                 "mapping.support_radius");
    }
}

void RbfWendlandC2::solve(const Eigen::MatrixXd& rhs, Eigen::MatrixXd& solution) const
{
    SourceSystem& source = *source_;
    if (source.backend == Backend::Mumps)
    {
        // All columns in one solve phase: the factor is read once, not once per column.
        mumpsColumns_.resize(static_cast<std::size_t>(rhs.size())); // sized at the first apply
        mumpsAllowances_.assign(static_cast<std::size_t>(rhs.cols()), 0.0);
        Eigen::MatrixXd::Map(mumpsColumns_.data(), rhs.rows(), rhs.cols()) = rhs;
        source.mumps->solveMany(mumpsColumns_, static_cast<int>(rhs.cols()), mumpsAllowances_);
        solution = Eigen::MatrixXd::Map(mumpsColumns_.data(), rhs.rows(), rhs.cols());
        return;
    }
    if (source.backend == Backend::Direct)
    {
        // ldlt.solve() spelled out: its last step permutes in place, which allocates a mask.
        resizeWorkspace(permuted_, rhs.rows(), rhs.cols());
        permuted_ = source.ldlt.permutationP() * rhs;
        source.ldlt.matrixL().solveInPlace(permuted_);
        permuted_.array().colwise() /= source.diagonal.array();
        source.ldlt.matrixU().solveInPlace(permuted_);
        solution = source.ldlt.permutationPinv() * permuted_;
        return;
    }
    lastIterations_ = 0;
    for (Eigen::Index j = 0; j < rhs.cols(); ++j)
    {
        solution.col(j) = source.cg.solve(rhs.col(j));
        lastIterations_ = std::max(lastIterations_, source.cg.iterations());
        if (source.cg.info() != Eigen::Success)
            throw std::runtime_error(
                "mapping rbf-wendland-c2: conjugate gradients did not converge in " +
                std::to_string(source.cg.iterations()) +
                " iterations; use mapping.solver direct or a smaller support_radius");
    }
}

void RbfWendlandC2::applyConsistent(const Eigen::Ref<const Values>& sourceValues,
                                    Eigen::Ref<Values> targetValues) const
{
    // Dense products column by column (matrix-vector products need no heap workspace).
    const Eigen::Index k = sourceValues.cols();
    resizeWorkspace(polynomial_, sourceBasis_.cols(), k);
    resizeWorkspace(residual_, sourceSize_, k);
    resizeWorkspace(coefficients_, sourceSize_, k);
    residual_ = sourceValues;
    for (Eigen::Index j = 0; j < k; ++j)
    {
        polynomial_.col(j).noalias() = sourceBasis_.transpose() * sourceValues.col(j);
        residual_.col(j).noalias() -= sourceBasis_ * polynomial_.col(j);
    }
    solve(residual_, coefficients_);
    targetValues.noalias() = evaluation_ * coefficients_;
    for (Eigen::Index j = 0; j < k; ++j)
        targetValues.col(j).noalias() += targetBasis_ * polynomial_.col(j);
}

void RbfWendlandC2::applyConservative(const Eigen::Ref<const Values>& targetValues,
                                      Eigen::Ref<Values> sourceValues) const
{
    const Eigen::Index k = targetValues.cols();
    resizeWorkspace(polynomial_, sourceBasis_.cols(), k);
    resizeWorkspace(projected_, sourceBasis_.cols(), k);
    resizeWorkspace(residual_, sourceSize_, k);
    resizeWorkspace(coefficients_, sourceSize_, k);
    residual_.noalias() = evaluation_.transpose() * targetValues;
    solve(residual_, coefficients_);
    sourceValues = coefficients_;
    for (Eigen::Index j = 0; j < k; ++j)
    {
        projected_.col(j).noalias() = sourceBasis_.transpose() * coefficients_.col(j);
        polynomial_.col(j).noalias() = targetBasis_.transpose() * targetValues.col(j);
        projected_.col(j) -= polynomial_.col(j);
        sourceValues.col(j).noalias() -= sourceBasis_ * projected_.col(j);
    }
}

} // namespace fsi::mapping
