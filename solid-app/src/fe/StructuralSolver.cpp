// SPDX-License-Identifier: GPL-3.0-or-later
#include "fe/StructuralSolver.hpp"

#include "fe/ElementKernel.hpp"
#include "fe/Quadrature.hpp"
#include "linalg/CsrPattern.hpp"
#include "linalg/Partition.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace fsi::fe
{
using material::Kinematics;
using material::Vector6;

struct StructuralSolver::Pattern
{
    linalg::CsrPattern csr;
};

namespace
{

Eigen::Matrix3Xd cellCoordinates(const Eigen::Matrix3Xd& nodes, const int* conn, int n)
{
    Eigen::Matrix3Xd X(3, n);
    for (int a = 0; a < n; ++a)
        X.col(a) = nodes.col(conn[a]);
    return X;
}

// Consistent nodal weights int N_a dA of the faces of a group [m^2] (added into w per node).
void faceWeights(const mesh::Mesh& mesh, const mesh::SurfaceGroup& group, std::vector<double>& w)
{
    Eigen::VectorXd N;
    Eigen::MatrixXd dN;
    for (int f = 0; f < group.faces.size(); ++f)
    {
        const auto type = group.faces.types[f];
        const auto& ref = mesh::ReferenceElement::get(type);
        const int n = ref.numNodes();
        const int* conn = group.faces.nodes(f);
        const Eigen::Matrix3Xd X = cellCoordinates(mesh.nodes, conn, n);
        for (const auto& qp : quadrature(type))
        {
            ref.evaluate(qp.xi, N, dN);
            const Eigen::Matrix<double, 3, 2> T = X * dN;
            const double dA = T.col(0).cross(T.col(1)).norm() * qp.weight;
            for (int a = 0; a < n; ++a)
                w[conn[a]] += N[a] * dA;
        }
    }
}

// One line on stderr naming the cell types that lock volumetrically for this law.
void warnIfLocking(const mesh::Mesh& mesh, const material::Material& law, Formulation formulation)
{
    const double nu = effectivePoissonRatio(law);
    const auto locking = lockingCellTypes(mesh.cells.types, formulation, nu);
    if (locking.empty())
        return;
    std::string names;
    for (const auto& name : locking)
        names += (names.empty() ? "" : "/") + name;
    std::fprintf(stderr,
                 "warning: %s: %s cells lock volumetrically at nu = %.4g (>= 0.45) with the %s "
                 "element formulation: displacements come out too small; use Hex8/Hex20/Hex27 with "
                 "solid.element.type: projected-dilatation (or Tet10)\n",
                 mesh.source.c_str(), names.c_str(), nu, formulationName(formulation));
}

// A law whose tangent is a given matrix D (stress = D strain, no history): the element kernel
// assembles the parts of an isotropic linear tangent with it.
class FixedTangentLaw final : public material::Material
{
public:
    explicit FixedTangentLaw(const material::Matrix6& D) : D_(D) {}
    std::string name() const override { return "fixed-tangent"; }
    std::size_t historySize() const override { return 0; }
    bool isLinearInStrain() const override { return true; }
    void evaluate(const Vector6& strain, const material::TimeStep&, const double*, Vector6& stress,
                  material::Matrix6& tangent) const override
    {
        stress = D_ * strain;
        tangent = D_;
    }
    void updateHistory(const Vector6&, const material::TimeStep&, const double*,
                       double*) const override
    {
    }

private:
    material::Matrix6 D_;
};

// A law affine in the strain, stress = D strain + offset, the offset of each integration point
// passed as its 6-double "history": a linear law's stress without evaluating it.
class AffineLaw final : public material::Material
{
public:
    explicit AffineLaw(const material::Matrix6& D) : D_(D) {}
    std::string name() const override { return "affine"; }
    std::size_t historySize() const override { return 6; }
    bool isLinearInStrain() const override { return true; }
    void evaluate(const Vector6& strain, const material::TimeStep&, const double* offset,
                  Vector6& stress, material::Matrix6& tangent) const override
    {
        stress = D_ * strain + Eigen::Map<const Vector6>(offset);
        tangent = D_;
    }
    void updateHistory(const Vector6&, const material::TimeStep&, const double*,
                       double*) const override
    {
    }

private:
    material::Matrix6 D_;
};

// The Voigt tangent lambda m m^T + mu diag(2, 2, 2, 1, 1, 1) (engineering shear) of the moduli.
material::Matrix6 isotropicVoigt(double lambda, double mu)
{
    material::Matrix6 D = material::Matrix6::Zero();
    D.topLeftCorner<3, 3>().setConstant(lambda);
    for (int i = 0; i < 3; ++i)
        D(i, i) += 2.0 * mu;
    for (int i = 3; i < 6; ++i)
        D(i, i) = mu;
    return D;
}

// (lambda, mu) of an isotropic tangent D; nullopt when D differs from isotropicVoigt(lambda, mu)
// by more than 1e-13 of its largest entry.
std::optional<std::pair<double, double>> isotropicModuli(const material::Matrix6& D)
{
    const double lambda = D(0, 1), mu = D(3, 3);
    const double scale = D.cwiseAbs().maxCoeff();
    if (!D.allFinite() || !(scale > 0.0) ||
        (D - isotropicVoigt(lambda, mu)).cwiseAbs().maxCoeff() > 1e-13 * scale)
        return std::nullopt;
    return std::make_pair(lambda, mu);
}

// The law's tangent at `step` for a law linear in the strain (independent of the strain, and
// of the history but for the committed level's step length, the same at every point: the
// quadratic Prony rule): evaluated at zero strain with `committed` (one point's committed
// history; null: a virgin history).
material::Matrix6 linearLawTangent(const material::Material& law, const material::TimeStep& step,
                                   const double* committed)
{
    Vector6 stress;
    material::Matrix6 D;
    if (law.historySize() == 0 || committed)
    {
        law.evaluate(Vector6::Zero(), step, committed, stress, D);
        return D;
    }
    std::vector<double> virgin(law.historySize());
    law.initialiseHistory(virgin.data());
    law.evaluate(Vector6::Zero(), step, virgin.data(), stress, D);
    return D;
}

} // namespace

StructuralSolver::StructuralSolver(MPI_Comm comm, const mesh::Mesh& mesh,
                                   const material::Material& law, ProblemDefinition problem)
    : comm_(comm), mesh_(mesh), law_(law), problem_(std::move(problem))
{
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &size_);
    const int nDofs = numDofs();

    // --- constraints: clamped surfaces, then prescribed components
    std::vector<char> fixed(nDofs, 0);
    std::vector<double> value(nDofs, 0.0);
    for (const auto& name : problem_.clamped)
        for (int node : mesh_.surface(name).nodes)
            for (int c = 0; c < 3; ++c)
                fixed[3 * node + c] = 1;
    std::vector<int> fieldOf(mesh_.numNodes(), -1);
    for (std::size_t k = 0; k < problem_.displacements.size(); ++k)
    {
        const auto& d = problem_.displacements[k];
        for (int node : mesh_.surface(d.surface).nodes)
        {
            if (d.field)
            {
                fieldOf[node] = static_cast<int>(k);
                for (int c = 0; c < 3; ++c)
                    fixed[3 * node + c] = 1;
                continue;
            }
            for (int c = 0; c < 3; ++c)
                if (d.value[c])
                {
                    if (!fixed[3 * node + c] || value[3 * node + c] == 0.0)
                        value[3 * node + c] = *d.value[c];
                    fixed[3 * node + c] = 1;
                }
        }
    }
    for (int node = 0; node < mesh_.numNodes(); ++node)
        if (fieldOf[node] >= 0)
            fieldNodes_.emplace_back(node, fieldOf[node]);
    equation_.assign(nDofs, -1);
    for (int dof = 0; dof < nDofs; ++dof)
    {
        if (fixed[dof])
        {
            prescribedDofs_.push_back(dof);
            prescribedValues_.push_back(value[dof]);
        }
        else
            equation_[dof] = numFree_++;
    }
    if (numFree_ == 0)
        throw std::runtime_error(mesh_.source + ": every degree of freedom is constrained");
    for (const auto& t : problem_.tractions)
        mesh_.surface(t.surface);
    for (const auto& f : problem_.forces)
        mesh_.surface(f.surface);
    if (!problem_.wetted.empty())
        wettedNodes_ = mesh_.surface(problem_.wetted).nodes;

    // --- element partition (METIS) and this rank's cells
    const auto& cells = mesh_.cells;
    std::vector<int> part = size_ > 1 ? linalg::partitionElements(cells.size(), cells.offsets,
                                                                  cells.connectivity, size_)
                                      : std::vector<int>(cells.size(), 0);
    for (int c = 0; c < cells.size(); ++c)
        if (part[c] == rank_)
            ownCells_.push_back(c);

    // --- quadrature data, history, dof lists of own cells
    std::vector<int> dofOffsets{0}, dofs;
    int points = 0;
    for (int c : ownCells_)
    {
        const int n = cells.numNodes(c);
        quadOffset_.push_back(quad_.size());
        pointOffset_.push_back(points);
        const double det =
            appendCellQuadrature(cells.types[c], cellCoordinates(mesh_.nodes, cells.nodes(c), n),
                                 quad_, dilatationModeCount(cells.types[c], problem_.formulation));
        if (!(det > 0.0))
            throw std::runtime_error(mesh_.source + ": inverted cell " + std::to_string(c) +
                                     " (negative Jacobian at an integration point)");
        points += static_cast<int>(quadrature(cells.types[c]).size());
        for (int a = 0; a < n; ++a)
            for (int i = 0; i < 3; ++i)
                dofs.push_back(equation_[3 * cells.nodes(c)[a] + i]);
        dofOffsets.push_back(static_cast<int>(dofs.size()));
    }
    pointOffset_.push_back(points);
    if (rank_ == 0)
        warnIfLocking(mesh_, law_, problem_.formulation);
    committedHistory_.assign(static_cast<std::size_t>(points) * law_.historySize(), 0.0);
    for (int p = 0; p < points && law_.historySize(); ++p)
        law_.initialiseHistory(committedHistory_.data() + p * law_.historySize());

    pattern_ = std::make_unique<Pattern>();
    pattern_->csr = linalg::CsrPattern::fromElements(numFree_, dofOffsets, dofs, true);
    linalg::DirectSolverOptions options = problem_.linearSolver;
    options.symmetric = true;
    // A linear problem's tangent changes with dt only (and little): CG on the last
    // factorization instead of a new one (SparseDirectSolver::reuseFactorization).
    options.reuseFactorization =
        problem_.kinematics == material::Kinematics::SmallStrain && law.isLinearInStrain();
    linear_ = std::make_unique<linalg::SparseDirectSolver>(comm_, options);
    linear_->setPattern(numFree_, pattern_->csr.tripletRows(), pattern_->csr.tripletColumns());
    values_.assign(pattern_->csr.nonZeros(), 0.0);

    u_.assign(nDofs, 0.0);
    uCommitted_ = u_;
    fextCommitted_.assign(nDofs, 0.0);
    linearProblem_ =
        problem_.kinematics == material::Kinematics::SmallStrain && law_.isLinearInStrain();
    fintAtU_ = fextAtU_ = fintCommitted_ = fextCommitted_;
}

StructuralSolver::~StructuralSolver() = default;

int StructuralSolver::factorizationCount() const
{
    return linear_->factorizationCount();
}
int StructuralSolver::analysisCount() const
{
    return linear_->analysisCount();
}

double StructuralSolver::freeNorm(const std::vector<double>& v) const
{
    double s = 0.0;
    for (std::size_t dof = 0; dof < v.size(); ++dof)
        if (equation_[dof] >= 0)
            s += v[dof] * v[dof];
    return std::sqrt(s);
}

void StructuralSolver::applyPrescribed(double factor, std::vector<double>& u) const
{
    for (std::size_t k = 0; k < prescribedDofs_.size(); ++k)
        u[prescribedDofs_[k]] = factor * prescribedValues_[k];
    for (const auto& [node, k] : fieldNodes_)
    {
        const Eigen::Vector3d v = problem_.displacements[k].field(mesh_.nodes.col(node), factor);
        for (int c = 0; c < 3; ++c)
            u[3 * node + c] = v[c];
    }
}

void StructuralSolver::buildExternalLoads(double factor, const InterfaceLoads& interface,
                                          std::vector<double>& f) const
{
    f.assign(numDofs(), 0.0);
    const auto& cells = mesh_.cells;
    // gravity over all cells (replicated: cheap against assembly)
    if (problem_.density > 0.0 && problem_.gravity.squaredNorm() > 0.0)
    {
        std::vector<double> w(mesh_.numNodes(), 0.0);
        Eigen::VectorXd N;
        Eigen::MatrixXd dN;
        for (int c = 0; c < cells.size(); ++c)
        {
            const auto& ref = mesh::ReferenceElement::get(cells.types[c]);
            const int n = ref.numNodes();
            const Eigen::Matrix3Xd X = cellCoordinates(mesh_.nodes, cells.nodes(c), n);
            for (const auto& qp : quadrature(cells.types[c]))
            {
                ref.evaluate(qp.xi, N, dN);
                const double dV = (X * dN).determinant() * qp.weight;
                for (int a = 0; a < n; ++a)
                    w[cells.nodes(c)[a]] += N[a] * dV;
            }
        }
        for (int node = 0; node < mesh_.numNodes(); ++node)
            for (int i = 0; i < 3; ++i)
                f[3 * node + i] += factor * problem_.density * problem_.gravity[i] * w[node];
    }
    auto spread = [&](const std::string& surface, const Eigen::Vector3d& traction)
    {
        std::vector<double> w(mesh_.numNodes(), 0.0);
        faceWeights(mesh_, mesh_.surface(surface), w);
        for (int node : mesh_.surface(surface).nodes)
            for (int i = 0; i < 3; ++i)
                f[3 * node + i] += factor * traction[i] * w[node];
        return std::accumulate(w.begin(), w.end(), 0.0);
    };
    for (const auto& t : problem_.tractions)
        spread(t.surface, t.traction);
    for (const auto& force : problem_.forces)
    {
        std::vector<double> w(mesh_.numNodes(), 0.0);
        faceWeights(mesh_, mesh_.surface(force.surface), w);
        const double area = std::accumulate(w.begin(), w.end(), 0.0);
        spread(force.surface, force.total / area);
    }
    if (!interface.forces.empty())
    {
        if (interface.forces.size() != 3 * wettedNodes_.size())
            throw std::runtime_error("StructuralSolver::solve: interface forces have " +
                                     std::to_string(interface.forces.size()) +
                                     " values, expected 3 x " +
                                     std::to_string(wettedNodes_.size()) + " wetted nodes");
        for (std::size_t k = 0; k < wettedNodes_.size(); ++k)
            for (int i = 0; i < 3; ++i)
                f[3 * wettedNodes_[k] + i] += interface.forces[3 * k + i];
    }
}

const double* StructuralSolver::firstCommittedHistory() const
{
    return law_.historySize() > 0 && !committedHistory_.empty() ? committedHistory_.data()
                                                                : nullptr;
}

bool StructuralSolver::linearTangentFromParts()
{
    if (!linearProblem_)
        return false;
    const auto moduli = isotropicModuli(linearLawTangent(law_, step_, firstCommittedHistory()));
    if (!moduli)
        return false;
    if (!isotropicPartsTried_)
    {
        isotropicPartsTried_ = true;
        const auto& cells = mesh_.cells;
        const FixedTangentLaw lambdaLaw(isotropicVoigt(1.0, 0.0)), muLaw(isotropicVoigt(0.0, 1.0));
        lambdaPart_.assign(values_.size(), 0.0);
        muPart_.assign(values_.size(), 0.0);
        Eigen::VectorXd fe;
        Eigen::MatrixXd Ke;
        std::vector<int> dofs;
        for (std::size_t k = 0; k < ownCells_.size(); ++k)
        {
            const int c = ownCells_[k];
            const int n = cells.numNodes(c);
            CellQuadrature cq{n, pointOffset_[k + 1] - pointOffset_[k],
                              quad_.data() + quadOffset_[k],
                              dilatationModeCount(cells.types[c], problem_.formulation)};
            const Eigen::Matrix3Xd zero = Eigen::Matrix3Xd::Zero(3, n);
            dofs.resize(3 * n);
            for (int a = 0; a < n; ++a)
                for (int i = 0; i < 3; ++i)
                    dofs[3 * a + i] = equation_[3 * cells.nodes(c)[a] + i];
            for (auto [law, part] :
                 {std::make_pair(&lambdaLaw, &lambdaPart_), std::make_pair(&muLaw, &muPart_)})
            {
                cellResponse(cq, zero, *law, Kinematics::SmallStrain, step_, nullptr, fe, &Ke);
                for (int r = 0; r < 3 * n; ++r)
                {
                    if (dofs[r] < 0)
                        continue;
                    for (int s = 0; s < 3 * n; ++s)
                        if (dofs[s] >= 0 && dofs[s] <= dofs[r])
                            (*part)[pattern_->csr.find(dofs[r], dofs[s])] += Ke(r, s);
                }
            }
        }
        elementTangentAssemblies_ += 2;
    }
    if (lambdaPart_.empty())
        return false;
    const auto [lambda, mu] = *moduli;
    if (linear_->factorizationCount() != factorizationsSeen_) // factorized since: at muValues_
    {
        factorizationsSeen_ = linear_->factorizationCount();
        muFactorized_ = muValues_;
    }
    std::vector<double> values(lambdaPart_.size()); // values_ stays the element loop's buffer
    for (std::size_t k = 0; k < values.size(); ++k)
        values[k] = lambda * lambdaPart_[k] + mu * muPart_[k];
    linear_->setValues(std::move(values));
    muValues_ = mu;
    lambdaValues_ = lambda;
    const double drift = problem_.refactorShearDrift;
    if (factorizationsSeen_ > 0 && drift > 0.0 && std::abs(mu - muFactorized_) > drift * mu)
        linear_->factorizeAtNextSolve();
    return true;
}

double StructuralSolver::linearSolveAllowance(double ref) const
{
    if (!linearProblem_)
        return 0.0;
    const auto& nw = problem_.newton;
    return 0.1 * (nw.residualTolerance * ref + nw.absoluteTolerance);
}

bool StructuralSolver::affineStressFor(const material::TimeStep& step)
{
    if (!linearProblem_)
        return false;
    if (offsetsVersion_ == historyVersion_ && offsetsStep_.time == step.time &&
        offsetsStep_.dt == step.dt)
        return true;
    const std::size_t hs = law_.historySize();
    const std::size_t points = static_cast<std::size_t>(pointOffset_.back());
    stressOffsets_.resize(6 * points);
    Vector6 stress;
    affineTangent_ = linearLawTangent(law_, step, firstCommittedHistory());
    material::Matrix6 D;
    for (std::size_t p = 0; p < points; ++p)
    {
        law_.evaluate(Vector6::Zero(), step, hs ? committedHistory_.data() + p * hs : nullptr,
                      stress, D);
        Eigen::Map<Vector6>(stressOffsets_.data() + 6 * p) = stress;
    }
    offsetsStep_ = step;
    offsetsVersion_ = historyVersion_;
    return true;
}

bool StructuralSolver::assemble(const std::vector<double>& u, bool withMatrix,
                                std::vector<double>& fint)
{
    const double start = MPI_Wtime();
    struct Timer
    {
        double start;
        double& total;
        ~Timer() { total += MPI_Wtime() - start; }
    } timer{start, assemblySeconds_};
    const auto& cells = mesh_.cells;
    fint.assign(numDofs(), 0.0);
    // a linear problem's tangent from its parts; the element loop then computes forces only
    if (withMatrix && linearTangentFromParts())
        withMatrix = false;
    if (withMatrix)
    {
        std::fill(values_.begin(), values_.end(), 0.0);
        ++elementTangentAssemblies_;
    }
    // forces only, linear problem: stress = D strain + offset, no law evaluation
    const bool affine = !withMatrix && affineStressFor(step_);
    const AffineLaw affineLaw(affineTangent_);
    const material::Material& law =
        affine ? static_cast<const material::Material&>(affineLaw) : law_;
    const std::size_t hs = affine ? 6 : law_.historySize();
    const double* history = affine ? stressOffsets_.data() : committedHistory_.data();
    Eigen::VectorXd fe;
    Eigen::MatrixXd Ke;
    int ok = 1;
    std::vector<int> dofs;
    for (std::size_t k = 0; k < ownCells_.size() && ok; ++k)
    {
        const int c = ownCells_[k];
        const int n = cells.numNodes(c);
        const int* conn = cells.nodes(c);
        CellQuadrature cq{n, pointOffset_[k + 1] - pointOffset_[k], quad_.data() + quadOffset_[k],
                          dilatationModeCount(cells.types[c], problem_.formulation)};
        Eigen::Matrix3Xd ue(3, n);
        for (int a = 0; a < n; ++a)
            for (int i = 0; i < 3; ++i)
                ue(i, a) = u[3 * conn[a] + i];
        try
        {
            cellResponse(cq, ue, law, problem_.kinematics, step_,
                         hs ? history + pointOffset_[k] * hs : nullptr, fe,
                         withMatrix ? &Ke : nullptr);
        }
        catch (const material::InadmissibleDeformation&)
        {
            ok = 0;
            break;
        }
        if (!fe.allFinite())
        {
            ok = 0;
            break;
        }
        dofs.resize(3 * n);
        for (int a = 0; a < n; ++a)
            for (int i = 0; i < 3; ++i)
            {
                dofs[3 * a + i] = equation_[3 * conn[a] + i];
                fint[3 * conn[a] + i] += fe[3 * a + i];
            }
        if (withMatrix)
            for (int r = 0; r < 3 * n; ++r)
            {
                if (dofs[r] < 0)
                    continue;
                for (int s = 0; s < 3 * n; ++s)
                    if (dofs[s] >= 0 && dofs[s] <= dofs[r])
                        values_[pattern_->csr.find(dofs[r], dofs[s])] += Ke(r, s);
            }
    }
    MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_MIN, comm_);
    if (!ok)
        return false;
    if (size_ > 1)
        MPI_Allreduce(MPI_IN_PLACE, fint.data(), static_cast<int>(fint.size()), MPI_DOUBLE, MPI_SUM,
                      comm_);
    if (withMatrix)
        linear_->setValues(values_);
    return true;
}

bool StructuralSolver::admissible(const std::vector<double>& u) const
{
    if (problem_.kinematics != Kinematics::TotalLagrangian)
        return true;
    const auto& cells = mesh_.cells;
    int ok = 1;
    for (std::size_t k = 0; k < ownCells_.size() && ok; ++k)
    {
        const int c = ownCells_[k];
        const int n = cells.numNodes(c);
        CellQuadrature cq{n, pointOffset_[k + 1] - pointOffset_[k], quad_.data() + quadOffset_[k]};
        Eigen::Matrix3Xd ue(3, n);
        for (int a = 0; a < n; ++a)
            for (int i = 0; i < 3; ++i)
                ue(i, a) = u[3 * cells.nodes(c)[a] + i];
        for (int q = 0; q < cq.numPoints && ok; ++q)
            ok =
                (Eigen::Matrix3d::Identity() + displacementGradient(cq, q, ue)).determinant() > 0.0;
    }
    MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_MIN, comm_);
    return ok != 0;
}

bool StructuralSolver::newtonWithPolicy(const std::vector<double>& fext, double factor,
                                        std::vector<double>& u, SolveReport& report)
{
    const LineSearch policy = problem_.newton.lineSearch;
    if (policy != LineSearch::Fallback)
        return newton(fext, factor, u, report, policy == LineSearch::Always);
    const std::vector<double> start = u;
    if (newton(fext, factor, u, report, false))
        return true;
    const int plainIterations = report.newtonIterations;
    if (problem_.printIterations && rank_ == 0)
        std::printf("    %s -> retrying with the line search\n", report.message.c_str());
    u = start;
    report.newtonIterations = 0;
    const bool ok = newton(fext, factor, u, report, true);
    report.newtonIterations += plainIterations;
    return ok;
}

bool StructuralSolver::newton(const std::vector<double>& fext, double factor,
                              std::vector<double>& u, SolveReport& report, bool lineSearch)
{
    const auto& nw = problem_.newton;
    applyPrescribed(factor, u);
    std::vector<double> fint, R(numDofs()), du(numFree_), trial;
    auto residual = [&](const std::vector<double>& state, bool matrix, double& norm, double& ref)
    {
        if (!assemble(state, matrix, fint))
            return false;
        double fe2 = 0.0, fi2 = 0.0;
        for (int dof = 0; dof < numDofs(); ++dof)
        {
            R[dof] = fext[dof] - fint[dof];
            fe2 += fext[dof] * fext[dof];
            fi2 += fint[dof] * fint[dof];
        }
        norm = freeNorm(R);
        // the largest force seen in this solve: a zero-force solution (rigid motion) has
        // f_int -> 0, which must not turn the relative tolerance into round-off
        ref = std::max({ref, std::sqrt(fe2), std::sqrt(fi2)});
        return std::isfinite(norm);
    };
    report.residuals.clear();
    double norm = 0.0, ref = 0.0;
    if (!residual(u, true, norm, ref))
    {
        report.message = "inadmissible deformation (det F <= 0) at the start state";
        return false;
    }
    report.initialResidual = norm;
    report.residuals.push_back(norm);
    for (int it = 0;; ++it)
    {
        report.referenceForce = ref;
        report.finalResidual = norm;
        if (norm <= nw.residualTolerance * ref + nw.absoluteTolerance)
        {
            if (!admissible(u))
            {
                report.message = "Newton converged to an inverted configuration (det F <= 0)";
                return false;
            }
            fintConverged_ = fint; // the last assembly was at u
            return true;
        }
        if (it >= nw.maxIterations)
        {
            char text[160];
            std::snprintf(
                text, sizeof text,
                "Newton stalled: %d iterations, residual %.3e N above the tolerance %.3e N", it,
                norm, nw.residualTolerance * ref + nw.absoluteTolerance);
            report.message = text;
            return false;
        }
        // solve K du = R on the free dofs (rhs on rank 0, solution on all ranks)
        std::fill(du.begin(), du.end(), 0.0);
        if (rank_ == 0)
            for (int dof = 0; dof < numDofs(); ++dof)
                if (equation_[dof] >= 0)
                    du[equation_[dof]] = R[dof];
        const double linearStart = MPI_Wtime();
        // a linear problem on a stale factor: the part of R in the span of earlier solutions
        // by projection (R is replicated), CG on the rest from rank 0's rhs
        const bool recycle = linearProblem_ && linear_->cgOnStaleFactor();
        std::vector<double> fromKept;
        if (recycle)
        {
            std::vector<double> rhs(numFree_, 0.0);
            for (int dof = 0; dof < numDofs(); ++dof)
                if (equation_[dof] >= 0)
                    rhs[equation_[dof]] = R[dof];
            fromKept.assign(numFree_, 0.0);
            projectOnSolves(rhs, fromKept);
            if (rank_ == 0)
                du = rhs;
        }
        if (pendingResponse_ && !pendingResponse_->answered && linearProblem_)
            solveStepWithResponse(du, linearSolveAllowance(ref)); // the columns ride along
        else
            linear_->solveSummedRhs(du, linearSolveAllowance(ref));
        if (recycle)
        {
            for (int eq = 0; eq < numFree_; ++eq)
                du[eq] += fromKept[eq];
            rememberSolve(du);
        }
        linearSeconds_ += MPI_Wtime() - linearStart;
        // line search (energy form, Crisfield): find alpha with s(alpha) = du . R(u + alpha du)
        // small against s(0) = du . R(u) > 0; the residual NORM may grow on a good Newton step
        // (e.g. membrane forces of a bending predictor), so it is not the acceptance test.
        auto directional = [&]()
        {
            double s = 0.0;
            for (int dof = 0; dof < numDofs(); ++dof)
                if (equation_[dof] >= 0)
                    s += du[equation_[dof]] * R[dof];
            return s;
        };
        const double s0 = directional();
        double alpha = 1.0, trialNorm = 0.0, trialRef = ref;
        auto tryStep = [&](double a)
        {
            trial = u;
            for (int dof = 0; dof < numDofs(); ++dof)
                if (equation_[dof] >= 0)
                    trial[dof] += a * du[equation_[dof]];
            trialRef = ref;
            return residual(trial, false, trialNorm, trialRef);
        };
        bool admissible = tryStep(alpha);
        for (int cut = 0; !admissible && cut < 8; ++cut) // inadmissible (det F <= 0, NaN): halve
            admissible = tryStep(alpha *= 0.5);
        if (!admissible)
        {
            report.message =
                "Newton stalled: every step along the Newton direction is inadmissible";
            return false;
        }
        if (lineSearch && s0 > 0.0)
        {
            double sAlpha = directional();
            for (int k = 0; k < 5 && std::abs(sAlpha) > 0.5 * s0; ++k)
            {
                // secant for the zero of s(alpha) through (0, s0) and (alpha, s(alpha))
                double next = s0 - sAlpha > 0.0 ? alpha * s0 / (s0 - sAlpha) : 1.0;
                next = std::clamp(next, 0.1 * alpha, 1.0);
                if (std::abs(next - alpha) < 1e-3)
                    break;
                alpha = next;
                if (!tryStep(alpha))
                    break;
                sAlpha = directional();
            }
            if (!std::isfinite(trialNorm) && !tryStep(alpha = 0.1))
            {
                report.message = "Newton stalled: no admissible line-search step";
                return false;
            }
        }
        // divergence guard: a residual exploding by orders of magnitude is not progress
        if (trialNorm > 1e8 * std::max(norm, nw.absoluteTolerance) && trialNorm > ref)
        {
            char text[96];
            std::snprintf(text, sizeof text, "Newton diverged: residual %.3e N", trialNorm);
            report.message = text;
            return false;
        }
        u.swap(trial);
        ++report.newtonIterations;
        if (problem_.printIterations && rank_ == 0)
            std::printf("    newton %2d  |R| = %.3e N  (ref %.3e N)%s\n", it + 1, trialNorm,
                        trialRef,
                        alpha < 1.0 ? ("  line search " + std::to_string(alpha)).c_str() : "");
        norm = trialNorm;
        ref = trialRef;
        report.residuals.push_back(norm);
        if (norm <= nw.residualTolerance * ref + nw.absoluteTolerance || it + 1 >= nw.maxIterations)
            continue; // converged (or out of iterations): no new matrix needed
        if (!residual(u, true, norm, ref))
        {
            report.message = "inadmissible deformation after a Newton step";
            return false;
        }
    }
}

SolveReport StructuralSolver::solve(const material::TimeStep& step, const InterfaceLoads& interface,
                                    double loadFactor)
{
    SolveReport report = solveLevel(step, interface, loadFactor);
    report.assemblySeconds = assemblySeconds_;
    report.linearSolveSeconds = linearSeconds_;
    return report;
}

// A linear level (small strain, a law linear in the strain) whose last solve converged at the
// same step and load factor: R(u + du) = f_new - f_int(u) - K du exactly, so du = K^-1 (f_new -
// f_int(u)) -- the load change plus the residual the last solve left -- with the level's tangent
// as it is (no assembly; CG on the last factorization if dt changed since) to a tenth of Newton's
// tolerance. One residual assembly (no matrix) checks it and gives f_int for the reactions.
// Declined (false, nothing changed) for non-finite loads or a residual above the tolerance:
// Newton then runs.
bool StructuralSolver::linearUpdate(const std::vector<double>& fTarget, SolveReport& report)
{
    std::vector<double> rhs(numFree_, 0.0); // replicated: fTarget and fintConverged_ are
    double change2 = 0.0, fe0 = 0.0, fi0 = 0.0;
    for (int dof = 0; dof < numDofs(); ++dof)
    {
        fe0 += fTarget[dof] * fTarget[dof];
        fi0 += fintConverged_[dof] * fintConverged_[dof];
        const int eq = equation_[dof];
        if (eq < 0)
            continue;
        const double d = fTarget[dof] - fintConverged_[dof];
        change2 += d * d;
        rhs[eq] = d;
    }
    if (!std::isfinite(change2) || !std::isfinite(fi0))
        return false; // Newton diagnoses non-finite loads
    const double linearStart = MPI_Wtime();
    // on a stale factor: the part of the rhs in the span of the kept earlier solves is solved
    // by projection, CG gets the rest (a current factor solves exactly in one phase)
    const bool stale = linear_->cgOnStaleFactor();
    std::vector<double> du(numFree_, 0.0), remainder = rhs;
    if (stale)
        projectOnSolves(remainder, du);
    std::vector<double> correction(numFree_, 0.0);
    if (rank_ == 0)
        correction = remainder;
    linear_->solveSummedRhs(correction,
                            linearSolveAllowance(std::max(std::sqrt(fe0), std::sqrt(fi0))));
    for (int eq = 0; eq < numFree_; ++eq)
        du[eq] += correction[eq];
    if (stale)
        rememberSolve(du);
    linearSeconds_ += MPI_Wtime() - linearStart;
    std::vector<double> u = u_, fint;
    for (int dof = 0; dof < numDofs(); ++dof)
        if (equation_[dof] >= 0)
            u[dof] += du[equation_[dof]];
    if (!assemble(u, false, fint))
        return false;
    std::vector<double> R(numDofs());
    double fe2 = 0.0, fi2 = 0.0;
    for (int dof = 0; dof < numDofs(); ++dof)
    {
        R[dof] = fTarget[dof] - fint[dof];
        fe2 += fTarget[dof] * fTarget[dof];
        fi2 += fint[dof] * fint[dof];
    }
    const double norm = freeNorm(R), ref = std::max(std::sqrt(fe2), std::sqrt(fi2));
    const auto& nw = problem_.newton;
    if (!(norm <= nw.residualTolerance * ref + nw.absoluteTolerance))
        return false;
    u_.swap(u);
    fextLast_ = fTarget;
    fintConverged_ = fintAtU_ = fint;
    fextAtU_ = fTarget;
    atAcceptedState_ = false;
    report.converged = true;
    report.newtonIterations = 1;
    report.initialResidual = std::sqrt(change2);
    report.finalResidual = norm;
    report.referenceForce = ref;
    report.residuals = {norm};
    report.message = "linear update of the last converged solve (same tangent, new loads)";
    return true;
}

void StructuralSolver::partProduct(const std::vector<double>& part, const std::vector<double>& x,
                                   std::vector<double>& y) const
{
    const auto& offsets = pattern_->csr.rowOffsets();
    const auto& columns = pattern_->csr.columns();
    y.assign(static_cast<std::size_t>(numFree_), 0.0);
    for (int i = 0; i < numFree_; ++i)
        for (int k = offsets[i]; k < offsets[i + 1]; ++k) // lower triangle: columns[k] <= i
        {
            const int j = columns[k];
            y[i] += part[k] * x[j];
            if (j != i)
                y[j] += part[k] * x[i];
        }
    MPI_Allreduce(MPI_IN_PLACE, y.data(), numFree_, MPI_DOUBLE, MPI_SUM, comm_);
}

void StructuralSolver::rememberSolve(std::vector<double> x)
{
    const bool parts = problem_.recycleSolutions && !lambdaPart_.empty();
    if (parts != kept_.withParts || (!parts && kept_.valuesVersion != linear_->valuesVersion()))
    {
        kept_ = KeptSolves{};
        kept_.valuesVersion = linear_->valuesVersion();
        kept_.withParts = parts;
    }
    const auto dot = [](const std::vector<double>& a, const std::vector<double>& c)
    { return std::inner_product(a.begin(), a.end(), c.begin(), 0.0); };
    const double start = std::sqrt(dot(x, x));
    if (!(start > 0.0) || !std::isfinite(start))
        return;
    for (int pass = 0; pass < 2; ++pass) // Gram-Schmidt twice: orthogonal to rounding
        for (const auto& q : kept_.x)
        {
            const double c = dot(q, x);
            for (std::size_t i = 0; i < x.size(); ++i)
                x[i] -= c * q[i];
        }
    const double rest = std::sqrt(dot(x, x));
    if (!(rest > 1e-6 * start)) // nothing new
        return;
    for (double& v : x)
        v /= rest;
    std::vector<double> first, second;
    if (parts)
    {
        partProduct(lambdaPart_, x, first);
        partProduct(muPart_, x, second);
    }
    else
    {
        std::vector<double> copy = x; // multiplyAll takes rank 0's x
        linear_->multiplyAll(copy, first);
    }
    if (static_cast<int>(kept_.x.size()) >= kSolvesKept) // drop the oldest
    {
        kept_.x.erase(kept_.x.begin());
        kept_.firstProduct.erase(kept_.firstProduct.begin());
        if (!kept_.secondProduct.empty())
            kept_.secondProduct.erase(kept_.secondProduct.begin());
        const Eigen::Index m = kept_.firstGram.rows() - 1;
        kept_.firstGram = Eigen::MatrixXd(kept_.firstGram.bottomRightCorner(m, m));
        if (parts)
            kept_.secondGram = Eigen::MatrixXd(kept_.secondGram.bottomRightCorner(m, m));
    }
    const Eigen::Index m = static_cast<Eigen::Index>(kept_.x.size());
    const auto grow = [&](Eigen::MatrixXd& gram, const std::vector<std::vector<double>>& products,
                          const std::vector<double>& product)
    {
        gram.conservativeResize(m + 1, m + 1);
        for (Eigen::Index j = 0; j < m; ++j) // symmetric part of X^T P X
            gram(m, j) = gram(j, m) = 0.5 * (dot(x, products[static_cast<std::size_t>(j)]) +
                                             dot(kept_.x[static_cast<std::size_t>(j)], product));
        gram(m, m) = dot(x, product);
    };
    grow(kept_.firstGram, kept_.firstProduct, first);
    kept_.firstProduct.push_back(std::move(first));
    if (parts)
    {
        grow(kept_.secondGram, kept_.secondProduct, second);
        kept_.secondProduct.push_back(std::move(second));
    }
    kept_.x.push_back(std::move(x));
}

void StructuralSolver::projectOnSolves(std::vector<double>& rhs, std::vector<double>& x) const
{
    const bool parts = problem_.recycleSolutions && !lambdaPart_.empty();
    const Eigen::Index m = static_cast<Eigen::Index>(kept_.x.size());
    if (m == 0 || parts != kept_.withParts ||
        (!parts && kept_.valuesVersion != linear_->valuesVersion()))
        return; // nothing kept, or the matrix changed since they were kept
    // K X = a (first products) + b (second products) for the current tangent
    const double a = parts ? lambdaValues_ : 1.0, b = parts ? muValues_ : 0.0;
    Eigen::MatrixXd gram = a * kept_.firstGram;
    if (parts)
        gram += b * kept_.secondGram;
    Eigen::VectorXd g(m);
    for (Eigen::Index j = 0; j < m; ++j)
        g(j) = std::inner_product(kept_.x[static_cast<std::size_t>(j)].begin(),
                                  kept_.x[static_cast<std::size_t>(j)].end(), rhs.begin(), 0.0);
    // c = gram^+ g: directions whose energy is rounding (below 1e-12 of the largest) are dropped
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram);
    if (eigen.info() != Eigen::Success)
        return;
    const Eigen::VectorXd& lambdas = eigen.eigenvalues();
    const double cut = 1e-12 * lambdas.cwiseAbs().maxCoeff();
    Eigen::VectorXd projected = eigen.eigenvectors().transpose() * g;
    for (Eigen::Index k = 0; k < m; ++k)
        projected(k) = lambdas(k) > cut ? projected(k) / lambdas(k) : 0.0;
    const Eigen::VectorXd c = eigen.eigenvectors() * projected;
    if (!c.allFinite())
        return;
    for (Eigen::Index j = 0; j < m; ++j)
    {
        const auto J = static_cast<std::size_t>(j);
        const double cj = c(j);
        for (std::size_t i = 0; i < rhs.size(); ++i)
        {
            x[i] += cj * kept_.x[J][i];
            rhs[i] -= cj * (parts ? a * kept_.firstProduct[J][i] + b * kept_.secondProduct[J][i]
                                  : kept_.firstProduct[J][i]);
        }
    }
}

StructuralSolver::ResponseColumns
StructuralSolver::responseColumns(const Eigen::MatrixXd& loadChanges,
                                  double relativeTolerance) const
{
    const auto wetted = static_cast<Eigen::Index>(wettedNodes_.size());
    if (loadChanges.rows() != 3 * wetted)
        throw std::invalid_argument(
            "StructuralSolver::interfaceResponse: " + std::to_string(loadChanges.rows()) +
            " rows, expected 3 x " + std::to_string(wetted) + " wetted nodes");
    if (!(relativeTolerance > 0.0 && relativeTolerance < 1.0))
        throw std::invalid_argument(
            "StructuralSolver::interfaceResponse: relativeTolerance must be in (0, 1)");
    // rank 0 holds the right-hand sides: the others' part of a summed one would be zero
    ResponseColumns c;
    c.count = static_cast<int>(loadChanges.cols());
    const std::size_t free = static_cast<std::size_t>(numFree_);
    c.rhs.assign(rank_ == 0 ? free * c.count : 0, 0.0);
    c.allowances.assign(c.count, 0.0);
    for (int j = 0; j < c.count; ++j)
    {
        double norm2 = 0.0;
        for (Eigen::Index r = 0; r < loadChanges.rows(); ++r)
        {
            const int eq = wettedEquation(r);
            if (eq < 0)
                continue;
            const double f = loadChanges(r, j);
            norm2 += f * f;
            if (rank_ == 0)
                c.rhs[free * j + eq] = f;
        }
        if (!std::isfinite(norm2))
            throw std::runtime_error("StructuralSolver::interfaceResponse: non-finite loads");
        c.allowances[j] = relativeTolerance * std::sqrt(norm2);
    }
    return c;
}

Eigen::MatrixXd StructuralSolver::solveResponseColumns(std::vector<double>& rhs,
                                                       std::vector<double> allowances, int leading,
                                                       int count)
{
    const std::size_t free = static_cast<std::size_t>(numFree_);
    const bool stale = linear_->cgOnStaleFactor();
    // on a stale factor each response column first takes its part in the span of the kept
    // solutions (rank 0 holds the columns; the kept ones are replicated, so no communication):
    // CG gets the rest, often already within the column's loose allowance (no iteration), and
    // the lockstep solve then runs with fewer columns
    std::vector<double> fromKept;
    if (stale && rank_ == 0)
    {
        fromKept.assign(free * static_cast<std::size_t>(count), 0.0);
        std::vector<double> column(free), part(free);
        for (int j = 0; j < count; ++j)
        {
            const auto first = rhs.begin() + static_cast<std::ptrdiff_t>(free * (leading + j));
            std::copy(first, first + static_cast<std::ptrdiff_t>(free), column.begin());
            std::fill(part.begin(), part.end(), 0.0);
            projectOnSolves(column, part);
            std::copy(column.begin(), column.end(), first);
            std::copy(part.begin(), part.end(),
                      fromKept.begin() + static_cast<std::ptrdiff_t>(free * j));
        }
    }
    linear_->solveMany(rhs, leading + count, allowances);
    for (std::size_t k = 0; k < fromKept.size(); ++k) // rank 0, before the broadcast
        rhs[free * static_cast<std::size_t>(leading) + k] += fromKept[k];
    linear_->broadcastFromRoot(rhs);
    responseColumns_ += count;
    // on a stale factor the columns' answers serve the later solves (projectOnSolves)
    for (int j = leading; stale && j < leading + count; ++j)
        rememberSolve(
            std::vector<double>(rhs.begin() + static_cast<std::ptrdiff_t>(free * j),
                                rhs.begin() + static_cast<std::ptrdiff_t>(free * (j + 1))));
    return wettedRowsOf(rhs, leading, count);
}

Eigen::MatrixXd StructuralSolver::wettedRowsOf(const std::vector<double>& solutions, int first,
                                               int columns) const
{
    const std::size_t free = static_cast<std::size_t>(numFree_);
    const auto rows = static_cast<Eigen::Index>(3 * wettedNodes_.size());
    Eigen::MatrixXd response = Eigen::MatrixXd::Zero(rows, columns);
    for (int j = 0; j < columns; ++j)
        for (Eigen::Index r = 0; r < rows; ++r)
            if (const int eq = wettedEquation(r); eq >= 0)
                response(r, j) = solutions[free * (first + j) + eq];
    return response;
}

Eigen::MatrixXd StructuralSolver::interfaceResponse(const Eigen::MatrixXd& loadChanges,
                                                    double relativeTolerance)
{
    if (!linearProblem_ || !lastConverged_ || !linearUpdateReady_)
        throw std::logic_error("StructuralSolver::interfaceResponse needs a linear problem and a "
                               "converged solve at the level");
    ResponseColumns c = responseColumns(loadChanges, relativeTolerance);
    const double start = MPI_Wtime();
    Eigen::MatrixXd response = solveResponseColumns(c.rhs, std::move(c.allowances), 0, c.count);
    linearSeconds_ += MPI_Wtime() - start;
    return response;
}

SolveReport StructuralSolver::solveWithResponse(const material::TimeStep& step,
                                                const InterfaceLoads& interface,
                                                const Eigen::MatrixXd& loadChanges,
                                                double relativeTolerance,
                                                Eigen::MatrixXd& responses)
{
    if (!linearProblem_)
        throw std::logic_error("StructuralSolver::solveWithResponse needs a linear problem");
    const ResponseColumns columns = responseColumns(loadChanges, relativeTolerance); // checked
    responses.resize(0, 0);
    PendingResponse pending{&columns, &responses, false};
    pendingResponse_ = &pending;
    struct Clear // the pending request ends with this call, also when solve() throws
    {
        PendingResponse*& pending;
        ~Clear() { pending = nullptr; }
    } clear{pendingResponse_};
    const SolveReport report = solve(step, interface);
    if (report.converged && !pending.answered) // no Newton step of its own: the columns alone
    {
        std::vector<double> rhs = columns.rhs;
        responses = solveResponseColumns(rhs, columns.allowances, 0, columns.count);
    }
    else if (!report.converged)
        responses.resize(0, 0);
    return report;
}

void StructuralSolver::solveStepWithResponse(std::vector<double>& du, double allowance)
{
    PendingResponse& pending = *pendingResponse_;
    const ResponseColumns& columns = *pending.columns;
    std::vector<double> rhs;
    if (rank_ == 0) // the step first, then the columns
    {
        rhs.reserve(du.size() + columns.rhs.size());
        rhs.insert(rhs.end(), du.begin(), du.end());
        rhs.insert(rhs.end(), columns.rhs.begin(), columns.rhs.end());
    }
    std::vector<double> allowances{allowance};
    allowances.insert(allowances.end(), columns.allowances.begin(), columns.allowances.end());
    *pending.responses = solveResponseColumns(rhs, std::move(allowances), 1, columns.count);
    std::copy(rhs.begin(), rhs.begin() + static_cast<std::ptrdiff_t>(du.size()), du.begin());
    pending.answered = true;
}

SolveReport StructuralSolver::solveLevel(const material::TimeStep& step,
                                         const InterfaceLoads& interface, double loadFactor)
{
    if (!(step.dt >= 0.0))
        throw std::runtime_error("StructuralSolver::solve: dt must be >= 0");
    const bool sameLinearSystem = linearUpdateReady_ && lastConverged_ && step.time == step_.time &&
                                  step.dt == step_.dt && loadFactor == factorLast_;
    step_ = step;
    assemblySeconds_ = linearSeconds_ = 0.0;
    std::vector<double> fTarget;
    buildExternalLoads(loadFactor, interface, fTarget);
    SolveReport report;
    if (sameLinearSystem && linearUpdate(fTarget, report))
        return report;
    linearUpdateReady_ = false;
    // attempt 0: the full step from the last converged state (warm start)
    std::vector<double> u = lastConverged_ ? u_ : uCommitted_;
    fextLast_ = fTarget;
    factorLast_ = loadFactor;
    const auto converged = [&](std::vector<double>& solution)
    {
        u_.swap(solution);
        fintAtU_ = fintConverged_;
        fextAtU_ = fTarget;
        solvedStep_ = step;
        atAcceptedState_ = false;
        lastConverged_ = true;
    };
    if (newtonWithPolicy(fTarget, loadFactor, u, report))
    {
        converged(u);
        report.converged = true;
        linearUpdateReady_ = linearProblem_;
        return report;
    }
    // sub-stepping from the committed state: loads ramped from the committed ones
    std::string firstFailure = report.message;
    int iterations = report.newtonIterations;
    for (int cuts = 1; cuts <= problem_.newton.maxLoadCuts; ++cuts)
    {
        const int steps = 1 << cuts;
        if (problem_.printIterations && rank_ == 0)
            std::printf("    %s -> retrying in %d load sub-steps\n", report.message.c_str(), steps);
        u = uCommitted_;
        bool ok = true;
        std::vector<double> f(numDofs());
        for (int s = 1; s <= steps && ok; ++s)
        {
            const double lambda = static_cast<double>(s) / steps;
            for (int dof = 0; dof < numDofs(); ++dof)
                f[dof] = fextCommitted_[dof] + lambda * (fTarget[dof] - fextCommitted_[dof]);
            SolveReport sub;
            ok = newtonWithPolicy(f, factorCommitted_ + lambda * (loadFactor - factorCommitted_), u,
                                  sub);
            iterations += sub.newtonIterations;
            report.residuals = sub.residuals;
            report.finalResidual = sub.finalResidual;
            report.referenceForce = sub.referenceForce;
            report.message = sub.message;
        }
        if (ok)
        {
            converged(u);
            report.converged = true;
            linearUpdateReady_ = linearProblem_;
            report.loadCuts = cuts;
            report.newtonIterations = iterations;
            report.message = "converged after load sub-stepping (" + firstFailure + ")";
            return report;
        }
    }
    report.newtonIterations = iterations;
    report.loadCuts = problem_.newton.maxLoadCuts;
    report.converged = false;
    lastConverged_ = false;
    if (report.message.empty())
        report.message = firstFailure;
    return report;
}

void StructuralSolver::acceptLevel()
{
    if (!lastConverged_)
        throw std::runtime_error("StructuralSolver::acceptLevel: the last solve did not converge");
    const std::size_t hs = law_.historySize();
    if (hs)
    {
        std::vector<double> next(committedHistory_.size());
        const auto& cells = mesh_.cells;
        for (std::size_t k = 0; k < ownCells_.size(); ++k)
        {
            const int c = ownCells_[k];
            const int n = cells.numNodes(c);
            CellQuadrature cq{n, pointOffset_[k + 1] - pointOffset_[k],
                              quad_.data() + quadOffset_[k],
                              dilatationModeCount(cells.types[c], problem_.formulation)};
            Eigen::Matrix3Xd ue(3, n);
            for (int a = 0; a < n; ++a)
                for (int i = 0; i < 3; ++i)
                    ue(i, a) = u_[3 * cells.nodes(c)[a] + i];
            const auto points = materialStrains(cq, ue, problem_.kinematics);
            for (int q = 0; q < cq.numPoints; ++q)
            {
                const std::size_t p = static_cast<std::size_t>(pointOffset_[k] + q) * hs;
                law_.updateHistory(points[q].strain, step_, committedHistory_.data() + p,
                                   next.data() + p);
            }
        }
        committedHistory_.swap(next);
        ++historyVersion_;
    }
    uCommitted_ = u_;
    fextCommitted_ = fextLast_;
    factorCommitted_ = factorLast_;
    linearUpdateReady_ = false; // the history changed: the residual must be assembled anew
    fintCommitted_ = fintAtU_;
    atAcceptedState_ = true;
}

void StructuralSolver::rejectLevel()
{
    linearUpdateReady_ = false;
    u_ = uCommitted_;
    fextLast_ = fextCommitted_;
    factorLast_ = factorCommitted_;
    fintAtU_ = fintCommitted_;
    fextAtU_ = fextCommitted_;
    atAcceptedState_ = true;
    lastConverged_ = true;
}

CommittedState StructuralSolver::committedState() const
{
    CommittedState state;
    state.displacement = uCommitted_;
    state.externalForces = fextCommitted_;
    state.loadFactor = factorCommitted_;
    state.cells = ownCells_;
    state.history = committedHistory_;
    return state;
}

void StructuralSolver::restoreCommittedState(const std::vector<CommittedState>& parts)
{
    const auto fail = [](const std::string& why)
    {
        throw std::runtime_error("restart: the saved solid state does not fit: " + why +
                                 " (same mesh and material as the checkpointed run?)");
    };
    if (parts.empty())
        fail("no parts");
    const std::size_t nDofs = static_cast<std::size_t>(numDofs());
    const std::size_t hs = law_.historySize();
    // Where each cell's history sits in the saved parts.
    std::vector<std::pair<int, std::size_t>> where(mesh_.cells.size(), {-1, 0});
    for (std::size_t r = 0; r < parts.size(); ++r)
    {
        const auto& p = parts[r];
        if (p.displacement.size() != nDofs || p.externalForces.size() != nDofs)
            fail("displacement of " + std::to_string(p.displacement.size() / 3) +
                 " nodes, mesh has " + std::to_string(nDofs / 3));
        std::size_t offset = 0;
        for (int c : p.cells)
        {
            if (c < 0 || c >= mesh_.cells.size())
                fail("cell id " + std::to_string(c) + " out of range");
            where[c] = {static_cast<int>(r), offset};
            offset += quadrature(mesh_.cells.types[c]).size() * hs;
        }
        if (offset != p.history.size())
            fail("material history of " + std::to_string(p.history.size()) + " values, expected " +
                 std::to_string(offset) +
                 "; a viscoelastic checkpoint restarts only with the prony.integration it was "
                 "written with");
    }
    for (std::size_t k = 0; k < ownCells_.size(); ++k)
    {
        const int c = ownCells_[k];
        if (where[c].first < 0)
            fail("cell " + std::to_string(c) + " missing");
        const std::size_t count =
            static_cast<std::size_t>(pointOffset_[k + 1] - pointOffset_[k]) * hs;
        const double* from = parts[where[c].first].history.data() + where[c].second;
        std::copy(from, from + count,
                  committedHistory_.begin() + static_cast<std::ptrdiff_t>(pointOffset_[k] * hs));
    }
    ++historyVersion_;
    linearUpdateReady_ = false;
    uCommitted_ = u_ = parts[0].displacement;
    fextCommitted_ = fextLast_ = parts[0].externalForces;
    factorCommitted_ = factorLast_ = parts[0].loadFactor;
    fextAtU_ = fextCommitted_;
    fintAtU_.assign(nDofs, std::nan("")); // not checkpointed: known after the next solve
    fintCommitted_ = fintAtU_;
    atAcceptedState_ = true;
    lastConverged_ = true;
}

std::vector<double> StructuralSolver::wettedNodeCoordinates() const
{
    std::vector<double> x;
    for (int node : wettedNodes_)
        for (int i = 0; i < 3; ++i)
            x.push_back(mesh_.nodes(i, node));
    return x;
}

mesh::CellList StructuralSolver::wettedFaces() const
{
    mesh::CellList local;
    if (problem_.wetted.empty())
        return local;
    const mesh::CellList& faces = mesh_.surface(problem_.wetted).faces;
    std::vector<int> nodes;
    for (int f = 0; f < faces.size(); ++f)
    {
        nodes.clear();
        for (int a = 0; a < faces.numNodes(f); ++a)
        {
            // wettedNodes_ is sorted and holds every node of these faces
            const auto it =
                std::lower_bound(wettedNodes_.begin(), wettedNodes_.end(), faces.nodes(f)[a]);
            nodes.push_back(static_cast<int>(it - wettedNodes_.begin()));
        }
        local.add(faces.types[static_cast<std::size_t>(f)], nodes.data(),
                  static_cast<int>(nodes.size()));
    }
    return local;
}

std::vector<double> StructuralSolver::wettedNodeDisplacements() const
{
    std::vector<double> d;
    for (int node : wettedNodes_)
        for (int i = 0; i < 3; ++i)
            d.push_back(u_[3 * node + i]);
    return d;
}

Vector6 StructuralSolver::pointStress(std::size_t k, int q, const Vector6& strain) const
{
    const std::size_t hs = law_.historySize();
    const double* history =
        hs ? committedHistory_.data() + static_cast<std::size_t>(pointOffset_[k] + q) * hs
           : nullptr;
    if (atAcceptedState_) // committedHistory_ already holds this level's increment
        return law_.acceptedStress(strain, history);
    Vector6 stress;
    material::Matrix6 D;
    law_.evaluate(strain, solvedStep_, history, stress, D);
    return stress;
}

void StructuralSolver::accumulateFields(const std::vector<char>& cellFilter,
                                        std::vector<double>& nodeSum,
                                        std::vector<double>* cellSum) const
{
    const auto& cells = mesh_.cells;
    nodeSum.assign(13 * static_cast<std::size_t>(mesh_.numNodes()), 0.0);
    if (cellSum)
        cellSum->assign(6 * static_cast<std::size_t>(cells.size()), 0.0);
    for (std::size_t k = 0; k < ownCells_.size(); ++k)
    {
        const int c = ownCells_[k];
        if (!cellFilter.empty() && !cellFilter[c])
            continue;
        const int n = cells.numNodes(c);
        CellQuadrature cq{n, pointOffset_[k + 1] - pointOffset_[k], quad_.data() + quadOffset_[k],
                          dilatationModeCount(cells.types[c], problem_.formulation)};
        Eigen::Matrix3Xd ue(3, n);
        for (int a = 0; a < n; ++a)
            for (int i = 0; i < 3; ++i)
                ue(i, a) = u_[3 * cells.nodes(c)[a] + i];
        Vector6 meanStress = Vector6::Zero(), meanStrain = Vector6::Zero();
        double volume = 0.0;
        std::vector<PointStrain> points;
        try
        {
            points = materialStrains(cq, ue, problem_.kinematics);
        }
        catch (const material::InadmissibleDeformation&)
        {
            points.assign(cq.numPoints,
                          {Vector6::Constant(std::nan("")), Eigen::Matrix3d::Identity()});
        }
        for (int q = 0; q < cq.numPoints; ++q)
        {
            Vector6 strain = points[q].strain;
            Vector6 stress;
            try
            {
                stress = pointStress(k, q, strain);
            }
            catch (const material::InadmissibleDeformation&)
            {
                stress.setConstant(std::nan(""));
            }
            strain.tail<3>() *= 0.5; // engineering -> tensor shear
            meanStress +=
                cq.weight(q) * cauchyFromMaterialStress(stress, points[q].F, problem_.kinematics);
            meanStrain += cq.weight(q) * strain;
            volume += cq.weight(q);
        }
        if (cellSum)
            for (int i = 0; i < 6; ++i)
                (*cellSum)[6 * c + i] = meanStress[i] / volume;
        for (int a = 0; a < n; ++a)
        {
            double* sum = nodeSum.data() + 13 * static_cast<std::size_t>(cells.nodes(c)[a]);
            for (int i = 0; i < 6; ++i)
            {
                sum[i] += meanStress[i];
                sum[6 + i] += meanStrain[i];
            }
            sum[12] += volume;
        }
    }
    if (size_ > 1)
    {
        MPI_Allreduce(MPI_IN_PLACE, nodeSum.data(), static_cast<int>(nodeSum.size()), MPI_DOUBLE,
                      MPI_SUM, comm_);
        if (cellSum)
            MPI_Allreduce(MPI_IN_PLACE, cellSum->data(), static_cast<int>(cellSum->size()),
                          MPI_DOUBLE, MPI_SUM, comm_);
    }
}

void StructuralSolver::cauchyStress(std::vector<Vector6>& nodal,
                                    std::vector<Vector6>& cellStress) const
{
    std::vector<double> nodeSum, cellSum;
    accumulateFields({}, nodeSum, &cellSum);
    nodal.assign(mesh_.numNodes(), Vector6::Zero());
    cellStress.assign(mesh_.cells.size(), Vector6::Zero());
    for (int node = 0; node < mesh_.numNodes(); ++node)
        if (nodeSum[13 * node + 12] > 0.0)
            for (int i = 0; i < 6; ++i)
                nodal[node][i] = nodeSum[13 * node + i] / nodeSum[13 * node + 12];
    for (int c = 0; c < mesh_.cells.size(); ++c)
        for (int i = 0; i < 6; ++i)
            cellStress[c][i] = cellSum[6 * c + i];
}

std::vector<StructuralSolver::NodalStressStrain>
StructuralSolver::stressAndStrainAt(const std::vector<int>& nodes) const
{
    const auto& cells = mesh_.cells;
    std::vector<char> wanted(mesh_.numNodes(), 0), cellFilter(cells.size(), 0);
    for (int node : nodes)
    {
        if (node < 0 || node >= mesh_.numNodes())
            throw std::out_of_range("StructuralSolver::stressAndStrainAt: node " +
                                    std::to_string(node) + " is not a node of the mesh");
        wanted[node] = 1;
    }
    for (int c = 0; c < cells.size(); ++c)
        for (int a = 0; a < cells.numNodes(c) && !cellFilter[c]; ++a)
            cellFilter[c] = wanted[cells.nodes(c)[a]];
    std::vector<double> nodeSum;
    accumulateFields(cellFilter, nodeSum, nullptr);
    std::vector<NodalStressStrain> out(nodes.size());
    for (std::size_t k = 0; k < nodes.size(); ++k)
    {
        const double* sum = nodeSum.data() + 13 * static_cast<std::size_t>(nodes[k]);
        for (int i = 0; i < 6; ++i)
        {
            out[k].stress[i] = sum[12] > 0.0 ? sum[i] / sum[12] : 0.0;
            out[k].strain[i] = sum[12] > 0.0 ? sum[6 + i] / sum[12] : 0.0;
        }
    }
    return out;
}

Eigen::Vector3d StructuralSolver::reactionForce(const std::string& surface) const
{
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    for (int node : mesh_.surface(surface).nodes)
        for (int i = 0; i < 3; ++i)
            r[i] += fintAtU_[3 * node + i] - fextAtU_[3 * node + i];
    return r;
}

} // namespace fsi::fe
