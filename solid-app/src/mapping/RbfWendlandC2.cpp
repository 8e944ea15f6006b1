// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/RbfWendlandC2.hpp"
#include "config/YamlReader.hpp"
#include <sstream>

#include "linalg/SparseDirectSolver.hpp"
#include "mapping/KdTree.hpp"
#include "mapping/RbfSupport.hpp"

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
} // namespace

RbfWendlandC2::RbfWendlandC2(const WendlandParameters& params) : params_(params) {}

RbfWendlandC2::~RbfWendlandC2() = default;

std::string RbfWendlandC2::solverInUse() const
{
    switch (backend_)
    {
    case Backend::Mumps:
        return "mumps";
    case Backend::Iterative:
        return "iterative";
    default:
        return "direct";
    }
}

namespace
{
bool mpiRunning()
{
    int initialised = 0, finalised = 0;
    MPI_Initialized(&initialised);
    MPI_Finalized(&finalised);
    return initialised && !finalised;
}
} // namespace

void RbfWendlandC2::compute(const PointCloud& source, const PointCloud& target)
{
    params_.validate();
    const bool withMpi = mpiRunning();
    if (params_.solver == "mumps" && !withMpi)
        throw std::runtime_error("mapping rbf-wendland-c2: solver mumps needs MPI (solid-app "
                                 "initialises it); use solver direct or iterative here");
    if (params_.solver == "mumps" || (params_.solver == "auto" && withMpi))
        backend_ = Backend::Mumps;
    else if (params_.solver == "iterative" ||
             (params_.solver == "auto" && source.rows() > params_.directMaxPoints))
        backend_ = Backend::Iterative;
    else
        backend_ = Backend::Direct;
    detail::checkDistinctPoints(source, "rbf-wendland-c2");
    const detail::Normalisation normalisation(source);
    const PointCloud s = normalisation.apply(source), t = normalisation.apply(target);
    const double rho = params_.supportRadius / normalisation.scale;
    const KdTree tree(s);

    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(static_cast<size_t>(s.rows()) * 32);
    kernelTriplets(tree, s, rho, triplets);
    system_.resize(s.rows(), s.rows());
    system_.setFromTriplets(triplets.begin(), triplets.end());
    systemNonZeros_ = system_.nonZeros();
    mumps_.reset();
    if (backend_ == Backend::Mumps)
        factoriseWithMumps(triplets);
    else if (backend_ == Backend::Iterative)
    {
        cg_.setTolerance(params_.iterativeTolerance);
        cg_.setMaxIterations(std::max<Eigen::Index>(1000, s.rows()));
        cg_.compute(system_);
    }
    else
    {
        ldlt_.compute(system_);
        diagonal_ = ldlt_.vectorD(); // vectorD() returns a copy: keep it
    }
    const Eigen::ComputationInfo info = backend_ == Backend::Iterative ? cg_.info()
                                        : backend_ == Backend::Direct  ? ldlt_.info()
                                                                       : Eigen::Success;
    if (info != Eigen::Success)
        throw std::runtime_error("mapping rbf-wendland-c2: factorisation of the RBF matrix "
                                 "failed; check for near-duplicate source points or change "
                                 "mapping.support_radius");

    triplets.clear();
    const Eigen::Index lonely = kernelTriplets(tree, t, rho, triplets);
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
    evaluation_.resize(t.rows(), s.rows());
    evaluation_.setFromTriplets(triplets.begin(), triplets.end());

    const detail::LinearPolynomial polynomial(s, t);
    sourceBasis_ = polynomial.sourceBasis;
    targetBasis_ = polynomial.targetBasis;
    sourceSize_ = s.rows();
    targetSize_ = t.rows();
}

void RbfWendlandC2::factoriseWithMumps(const std::vector<Eigen::Triplet<double>>& triplets)
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
        mumps_ = std::make_unique<linalg::SparseDirectSolver>(MPI_COMM_SELF, options);
        mumps_->setPattern(static_cast<int>(system_.rows()), std::move(rows), std::move(cols));
        mumps_->setValues(std::move(values));
        mumps_->factorize();
    }
    catch (const std::exception& e)
    {
        mumps_.reset();
        throw std::runtime_error(std::string("mapping rbf-wendland-c2: MUMPS factorisation of "
                                             "the RBF matrix failed (") +
                                 e.what() +
                                 "); check for near-duplicate source points or change "
                                 "mapping.support_radius");
    }
}

void RbfWendlandC2::solve(const Eigen::MatrixXd& rhs, Eigen::MatrixXd& solution) const
{
    if (backend_ == Backend::Mumps)
    {
        // All columns in one solve phase: the factor is read once, not once per column.
        mumpsColumns_.resize(static_cast<std::size_t>(rhs.size())); // sized at the first apply
        mumpsAllowances_.assign(static_cast<std::size_t>(rhs.cols()), 0.0);
        Eigen::MatrixXd::Map(mumpsColumns_.data(), rhs.rows(), rhs.cols()) = rhs;
        mumps_->solveMany(mumpsColumns_, static_cast<int>(rhs.cols()), mumpsAllowances_);
        solution = Eigen::MatrixXd::Map(mumpsColumns_.data(), rhs.rows(), rhs.cols());
        return;
    }
    if (backend_ == Backend::Direct)
    {
        // ldlt_.solve() spelled out: its last step permutes in place, which allocates a mask.
        resizeWorkspace(permuted_, rhs.rows(), rhs.cols());
        permuted_ = ldlt_.permutationP() * rhs;
        ldlt_.matrixL().solveInPlace(permuted_);
        permuted_.array().colwise() /= diagonal_.array();
        ldlt_.matrixU().solveInPlace(permuted_);
        solution = ldlt_.permutationPinv() * permuted_;
        return;
    }
    lastIterations_ = 0;
    for (Eigen::Index j = 0; j < rhs.cols(); ++j)
    {
        solution.col(j) = cg_.solve(rhs.col(j));
        lastIterations_ = std::max(lastIterations_, cg_.iterations());
        if (cg_.info() != Eigen::Success)
            throw std::runtime_error(
                "mapping rbf-wendland-c2: conjugate gradients did not converge in " +
                std::to_string(cg_.iterations()) +
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
