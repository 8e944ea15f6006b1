// SPDX-License-Identifier: GPL-3.0-or-later
#include "fe/ElementKernel.hpp"

#include "fe/Quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace fsi::fe
{
using material::Kinematics;
using material::Matrix6;
using material::Vector6;
using mesh::CellType;

Formulation formulationFromName(const std::string& name)
{
    if (name == "displacement")
        return Formulation::Displacement;
    if (name == "projected-dilatation")
        return Formulation::ProjectedDilatation;
    throw std::invalid_argument("unknown element formulation '" + name +
                                "' (displacement | projected-dilatation)");
}

const char* formulationName(Formulation formulation)
{
    return formulation == Formulation::Displacement ? "displacement" : "projected-dilatation";
}

int dilatationModeCount(CellType type, Formulation formulation)
{
    if (formulation == Formulation::Displacement)
        return 0;
    if (type == CellType::Hex8)
        return 1;
    if (type == CellType::Hex20 || type == CellType::Hex27)
        return 4;
    return 0;
}

std::vector<std::string> lockingCellTypes(const std::vector<CellType>& types,
                                          Formulation formulation, double nu)
{
    std::vector<std::string> names;
    if (nu < 0.45)
        return names;
    for (CellType t : types)
    {
        const bool locks = t == CellType::Tet4 || t == CellType::Prism6 ||
                           ((t == CellType::Hex8 || t == CellType::Hex20 || t == CellType::Hex27) &&
                            dilatationModeCount(t, formulation) == 0);
        const std::string& name = mesh::ReferenceElement::get(t).name();
        if (locks && std::find(names.begin(), names.end(), name) == names.end())
            names.push_back(name);
    }
    return names;
}

double effectivePoissonRatio(const material::Material& law)
{
    std::vector<double> history(law.historySize());
    law.initialiseHistory(history.data());
    double nu = -1.0;
    for (double dt : {0.0, 1e300})
    {
        Vector6 stress;
        Matrix6 D;
        law.evaluate(Vector6::Zero(), {dt, dt}, history.empty() ? nullptr : history.data(), stress,
                     D);
        // isotropic: D00 = K + 4G/3, D01 = K - 2G/3 -> nu = D01 / (D00 + D01)
        nu = std::max(nu, D(0, 1) / (D(0, 0) + D(0, 1)));
    }
    return nu;
}

double appendCellQuadrature(CellType type, const Eigen::Matrix3Xd& X, std::vector<double>& out,
                            int numModes)
{
    const auto& ref = mesh::ReferenceElement::get(type);
    const int n = ref.numNodes();
    Eigen::VectorXd N;
    Eigen::MatrixXd dN;
    double minDet = std::numeric_limits<double>::max();
    const auto& rule = quadrature(type);
    Eigen::Matrix3Xd points(3, rule.size());
    Eigen::VectorXd weights(rule.size());
    for (std::size_t q = 0; q < rule.size(); ++q)
    {
        ref.evaluate(rule[q].xi, N, dN);
        const Eigen::Matrix3d J = X * dN; // dX/dxi
        const double det = J.determinant();
        minDet = std::min(minDet, det);
        const Eigen::MatrixXd dNdX = dN * J.inverse();
        out.push_back(rule[q].weight * det);
        out.insert(out.end(), N.data(), N.data() + n);
        out.insert(out.end(), dNdX.data(), dNdX.data() + 3 * n);
        points.col(q) = X * N;
        weights[q] = rule[q].weight * det;
    }
    if (numModes != 0 && numModes != 1 && numModes != 4)
        throw std::invalid_argument("appendCellQuadrature: numModes must be 0, 1 or 4");
    // P1 modes in physical coordinates about the centroid, scaled by the cell size
    const double volume = weights.sum();
    const Eigen::Vector3d centroid = points * weights / volume;
    const double size = std::cbrt(std::abs(volume));
    for (std::size_t q = 0; q < rule.size() && numModes > 0; ++q)
    {
        out.push_back(1.0);
        if (numModes == 4)
            for (int k = 0; k < 3; ++k)
                out.push_back((points(k, q) - centroid[k]) / size);
    }
    return minDet;
}

Eigen::Matrix3d displacementGradient(const CellQuadrature& cq, int q, const Eigen::Matrix3Xd& u)
{
    return u * cq.dNdX(q);
}

Eigen::Matrix3d deformationGradient(const CellQuadrature& cq, int q, const Eigen::Matrix3Xd& u)
{
    return Eigen::Matrix3d::Identity() + displacementGradient(cq, q, u);
}

Vector6 strainFromH(const Eigen::Matrix3d& H, Kinematics kinematics)
{
    Eigen::Matrix3d e = 0.5 * (H + H.transpose());
    if (kinematics != Kinematics::SmallStrain)
        e += 0.5 * H.transpose() * H;
    Vector6 v;
    v << e(0, 0), e(1, 1), e(2, 2), 2 * e(0, 1), 2 * e(1, 2), 2 * e(0, 2);
    return v;
}

namespace
{
Eigen::Matrix3d tensorFromVoigt(const Vector6& s)
{
    Eigen::Matrix3d t;
    t << s(0), s(3), s(5), s(3), s(1), s(4), s(5), s(4), s(2);
    return t;
}

// Voigt vector with engineering shear of a symmetric tensor.
Vector6 engineeringVoigt(const Eigen::Matrix3d& e)
{
    Vector6 v;
    v << e(0, 0), e(1, 1), e(2, 2), 2 * e(0, 1), 2 * e(1, 2), 2 * e(0, 2);
    return v;
}

const Vector6 unitVoigt = (Vector6() << 1, 1, 1, 0, 0, 0).finished();

// L2 projection onto the dilatation modes as a point-to-point operator: for values v_p at the
// points, the projected values are P v, P(q, p) = phi_q^T M^-1 phi_p w_p, M = sum w phi phi^T.
Eigen::MatrixXd projectionOperator(const CellQuadrature& cq)
{
    const int np = cq.numPoints, m = cq.numModes;
    Eigen::MatrixXd phi(np, m);
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(m, m);
    for (int q = 0; q < np; ++q)
    {
        phi.row(q) = cq.modes(q).transpose();
        M += cq.weight(q) * cq.modes(q) * cq.modes(q).transpose();
    }
    Eigen::MatrixXd P = phi * M.ldlt().solve(phi.transpose());
    for (int p = 0; p < np; ++p)
        P.col(p) *= cq.weight(p);
    return P;
}

// Kinematics of the projected-dilatation element at every point of a cell.
struct ProjectedKinematics
{
    Eigen::MatrixXd P;                 // projection operator (points x points)
    std::vector<Eigen::Matrix3d> F;    // deformation gradient (TL) / identity (small strain)
    Eigen::VectorXd volume, volumeBar; // J, J_bar (TL) or tr eps, its projection (small strain)
    std::vector<Vector6> strain;       // eps_bar / E_bar
    std::vector<double> beta;          // (J_bar / J)^(2/3) (TL), 1 (small strain)
};

ProjectedKinematics projectedKinematics(const CellQuadrature& cq, const Eigen::Matrix3Xd& u,
                                        Kinematics kinematics)
{
    const int np = cq.numPoints;
    ProjectedKinematics k;
    k.P = projectionOperator(cq);
    k.F.resize(np);
    k.volume.resize(np);
    k.strain.resize(np);
    k.beta.assign(np, 1.0);
    std::vector<Eigen::Matrix3d> H(np);
    for (int q = 0; q < np; ++q)
    {
        H[q] = displacementGradient(cq, q, u);
        if (kinematics == Kinematics::SmallStrain)
        {
            k.F[q].setIdentity();
            k.volume[q] = H[q].trace();
        }
        else
        {
            k.F[q] = Eigen::Matrix3d::Identity() + H[q];
            k.volume[q] = k.F[q].determinant();
            if (!(k.volume[q] > 0.0))
                throw material::InadmissibleDeformation(
                    "projected dilatation: det F <= 0 (inverted element); reduce the load step");
        }
    }
    k.volumeBar = k.P * k.volume;
    for (int q = 0; q < np; ++q)
    {
        if (kinematics == Kinematics::SmallStrain)
        {
            k.strain[q] =
                strainFromH(H[q], kinematics) + (k.volumeBar[q] - k.volume[q]) / 3.0 * unitVoigt;
            continue;
        }
        if (!(k.volumeBar[q] > 0.0))
            throw material::InadmissibleDeformation(
                "projected dilatation: projected J <= 0; reduce the load step");
        k.beta[q] = std::pow(k.volumeBar[q] / k.volume[q], 2.0 / 3.0);
        // E_bar = (beta C - I)/2 = beta E + (beta - 1)/2 I, from H (keeps small-strain digits)
        k.strain[q] =
            k.beta[q] * strainFromH(H[q], kinematics) + 0.5 * (k.beta[q] - 1.0) * unitVoigt;
    }
    return k;
}

// Standard B (6 x 3n): delta strain = B delta u for the kinematics (F = I: small strain).
void strainDisplacementMatrix(const Eigen::Ref<const Eigen::MatrixXd>& g, const Eigen::Matrix3d& F,
                              Eigen::Matrix<double, 6, Eigen::Dynamic>& B)
{
    const int n = static_cast<int>(g.rows());
    for (int a = 0; a < n; ++a)
        for (int i = 0; i < 3; ++i)
        {
            const int col = 3 * a + i;
            B(0, col) = F(i, 0) * g(a, 0);
            B(1, col) = F(i, 1) * g(a, 1);
            B(2, col) = F(i, 2) * g(a, 2);
            B(3, col) = F(i, 0) * g(a, 1) + F(i, 1) * g(a, 0);
            B(4, col) = F(i, 1) * g(a, 2) + F(i, 2) * g(a, 1);
            B(5, col) = F(i, 0) * g(a, 2) + F(i, 2) * g(a, 0);
        }
}

// Adds w (Grad N_a . S Grad N_b) delta_ij: the geometric stiffness of Green-Lagrange strain.
void addGeometricStiffness(const Eigen::Ref<const Eigen::MatrixXd>& g, const Vector6& stress,
                           double w, Eigen::MatrixXd& K)
{
    const int n = static_cast<int>(g.rows());
    const Eigen::MatrixXd G = g * tensorFromVoigt(stress) * g.transpose(); // n x n
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
            for (int i = 0; i < 3; ++i)
                K(3 * a + i, 3 * b + i) += w * G(a, b);
}

// Projected-dilatation cell response (see the header): B-bar in small strain, F-bar with the
// consistent (symmetric) tangent of int W(E_bar) dV in total Lagrangian kinematics.
void projectedCellResponse(const CellQuadrature& cq, const Eigen::Matrix3Xd& u,
                           const material::Material& law, Kinematics kinematics,
                           const material::TimeStep& step, const double* history,
                           Eigen::VectorXd& fint, Eigen::MatrixXd* K)
{
    const int n = cq.numNodes, np = cq.numPoints, nd = 3 * n;
    const std::size_t hs = law.historySize();
    const ProjectedKinematics k = projectedKinematics(cq, u, kinematics);
    const bool small = kinematics == Kinematics::SmallStrain;
    // a_p: delta(tr eps) (small) or delta(ln J) (TL) = a_p . delta u; rows of A
    Eigen::MatrixXd A(np, nd);
    // n x 3 (fixed 3 columns: the 3 x 3 blocks below need no heap): row a = (F^-T Grad N_a)^T
    std::vector<Eigen::Matrix<double, Eigen::Dynamic, 3>> gFinv(np);
    for (int q = 0; q < np; ++q)
    {
        gFinv[q] =
            small ? Eigen::MatrixXd(cq.dNdX(q)) : Eigen::MatrixXd(cq.dNdX(q) * k.F[q].inverse());
        for (int a = 0; a < n; ++a)
            for (int i = 0; i < 3; ++i)
                A(q, 3 * a + i) = gFinv[q](a, i);
    }
    // delta(volumeBar_q) = Abar.row(q) . delta u; small: P A; TL: P diag(J) A
    const Eigen::MatrixXd Abar =
        small ? Eigen::MatrixXd(k.P * A) : Eigen::MatrixXd(k.P * (k.volume.asDiagonal() * A));
    fint.setZero(nd);
    if (K)
        K->setZero(nd, nd);
    // TL second-variation terms of ln J_bar, collected per point and added after the loop:
    //   sum_p curvature_p tr(F_p^-1 dH F_p^-1 DH)
    //   + A^T diag(rankOne) A + Abar^T diag(rankOneBar) Abar
    Eigen::VectorXd curvature = Eigen::VectorXd::Zero(np), rankOne = Eigen::VectorXd::Zero(np),
                    rankOneBar = Eigen::VectorXd::Zero(np);
    Eigen::Matrix<double, 6, Eigen::Dynamic> B(6, nd), Bbar(6, nd);
    Vector6 stress;
    Matrix6 D;
    for (int q = 0; q < np; ++q)
    {
        const auto g = cq.dNdX(q);
        const double w = cq.weight(q);
        law.evaluate(k.strain[q], step, hs ? history + q * hs : nullptr, stress, D);
        strainDisplacementMatrix(g, k.F[q], B);
        if (small)
        {
            Bbar = B + unitVoigt * (Abar.row(q) - A.row(q)) / 3.0;
            fint.noalias() += w * (Bbar.transpose() * stress);
            if (K)
                K->noalias() += w * (Bbar.transpose() * (D * Bbar));
            continue;
        }
        const double beta = k.beta[q], Jbar = k.volumeBar[q];
        const Eigen::Matrix3d C = k.F[q].transpose() * k.F[q];
        // delta g = delta ln beta = (2/3)(delta J_bar / J_bar - delta ln J)
        const Eigen::RowVectorXd dg = (2.0 / 3.0) * (Abar.row(q) / Jbar - A.row(q));
        Bbar = beta * (B + 0.5 * engineeringVoigt(C) * dg);
        fint.noalias() += w * (Bbar.transpose() * stress);
        if (!K)
            continue;
        const double SC = tensorFromVoigt(stress).cwiseProduct(C).sum(); // S_bar : C
        const Eigen::VectorXd s = B.transpose() * stress;                // S_bar : delta E
        K->noalias() += w * (Bbar.transpose() * (D * Bbar));
        addGeometricStiffness(g, stress, w * beta, *K);
        K->noalias() += (0.5 * w * beta * SC) * dg.transpose() * dg; // outer products, in place
        K->noalias() += (w * beta) * dg.transpose() * s.transpose();
        K->noalias() += (w * beta) * s * dg;
        // kappa [Delta delta J_bar / J_bar - dJ_bar dJ_bar^T / J_bar^2 - Delta delta ln J] with
        // kappa = w beta S:C / 3, Delta delta ln J = -tr(F^-1 dH F^-1 DH) and
        // Delta delta J_bar_q = sum_p P(q, p) J_p (a_p a_p^T - tr(F_p^-1 dH F_p^-1 DH))
        const double kappa = w * beta * SC / 3.0;
        rankOneBar[q] -= kappa / (Jbar * Jbar);
        curvature[q] += kappa;
        for (int p = 0; p < np; ++p)
        {
            const double c = kappa / Jbar * k.P(q, p) * k.volume[p];
            rankOne[p] += c;
            curvature[p] -= c;
        }
    }
    if (!K || small)
        return;
    K->noalias() += A.transpose() * rankOne.asDiagonal() * A;
    K->noalias() += Abar.transpose() * rankOneBar.asDiagonal() * Abar;
    for (int p = 0; p < np; ++p)
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b) // block (a, b), entry (l, j): gFinv(a, j) gFinv(b, l)
                K->block<3, 3>(3 * a, 3 * b).noalias() +=
                    curvature[p] * gFinv[p].row(b).transpose() * gFinv[p].row(a);
}

} // namespace

Vector6 cauchyFromMaterialStress(const Vector6& stress, const Eigen::Matrix3d& F,
                                 Kinematics kinematics)
{
    if (kinematics == Kinematics::SmallStrain)
        return stress;
    const Eigen::Matrix3d sigma = F * tensorFromVoigt(stress) * F.transpose() / F.determinant();
    Vector6 v;
    v << sigma(0, 0), sigma(1, 1), sigma(2, 2), sigma(0, 1), sigma(1, 2), sigma(0, 2);
    return v;
}

std::vector<PointStrain> materialStrains(const CellQuadrature& cq, const Eigen::Matrix3Xd& u,
                                         Kinematics kinematics)
{
    std::vector<PointStrain> points(cq.numPoints);
    if (cq.numModes > 0)
    {
        const ProjectedKinematics k = projectedKinematics(cq, u, kinematics);
        for (int q = 0; q < cq.numPoints; ++q)
            points[q] = {k.strain[q], std::sqrt(k.beta[q]) * k.F[q]};
        return points;
    }
    for (int q = 0; q < cq.numPoints; ++q)
    {
        const Eigen::Matrix3d H = displacementGradient(cq, q, u);
        points[q].strain = strainFromH(H, kinematics);
        points[q].F = kinematics == Kinematics::SmallStrain
                          ? Eigen::Matrix3d::Identity()
                          : Eigen::Matrix3d(Eigen::Matrix3d::Identity() + H);
    }
    return points;
}

void cellResponse(const CellQuadrature& cq, const Eigen::Matrix3Xd& u,
                  const material::Material& law, Kinematics kinematics,
                  const material::TimeStep& step, const double* history, Eigen::VectorXd& fint,
                  Eigen::MatrixXd* K)
{
    if (cq.numModes > 0)
    {
        projectedCellResponse(cq, u, law, kinematics, step, history, fint, K);
        return;
    }
    const int n = cq.numNodes;
    const std::size_t hs = law.historySize();
    fint.setZero(3 * n);
    if (K)
        K->setZero(3 * n, 3 * n);
    Eigen::Matrix<double, 6, Eigen::Dynamic> B(6, 3 * n);
    Vector6 stress;
    Matrix6 D;
    for (int q = 0; q < cq.numPoints; ++q)
    {
        const auto g = cq.dNdX(q);
        const Eigen::Matrix3d H = displacementGradient(cq, q, u);
        const Eigen::Matrix3d F = kinematics == Kinematics::SmallStrain
                                      ? Eigen::Matrix3d::Identity()
                                      : Eigen::Matrix3d(Eigen::Matrix3d::Identity() + H);
        const Vector6 strain = strainFromH(H, kinematics);
        law.evaluate(strain, step, hs ? history + q * hs : nullptr, stress, D);
        strainDisplacementMatrix(g, F, B);
        const double w = cq.weight(q);
        fint.noalias() += w * (B.transpose() * stress);
        if (K)
        {
            K->noalias() += w * (B.transpose() * (D * B));
            if (kinematics == Kinematics::TotalLagrangian)
                addGeometricStiffness(g, stress, w, *K);
        }
    }
}

} // namespace fsi::fe
