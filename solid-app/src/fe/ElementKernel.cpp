// SPDX-License-Identifier: GPL-3.0-or-later
#include "fe/ElementKernel.hpp"

#include "fe/Quadrature.hpp"

#include <limits>

namespace fsi::fe
{
using material::Kinematics;
using material::Matrix6;
using material::Vector6;

double appendCellQuadrature(mesh::CellType type, const Eigen::Matrix3Xd& X,
                            std::vector<double>& out)
{
    const auto& ref = mesh::ReferenceElement::get(type);
    const int n = ref.numNodes();
    Eigen::VectorXd N;
    Eigen::MatrixXd dN;
    double minDet = std::numeric_limits<double>::max();
    for (const auto& qp : quadrature(type))
    {
        ref.evaluate(qp.xi, N, dN);
        const Eigen::Matrix3d J = X * dN; // dX/dxi
        const double det = J.determinant();
        minDet = std::min(minDet, det);
        const Eigen::MatrixXd dNdX = dN * J.inverse();
        out.push_back(qp.weight * det);
        out.insert(out.end(), N.data(), N.data() + n);
        out.insert(out.end(), dNdX.data(), dNdX.data() + 3 * n);
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

void cellResponse(const CellQuadrature& cq, const Eigen::Matrix3Xd& u,
                  const material::Material& law, Kinematics kinematics,
                  const material::TimeStep& step, const double* history, Eigen::VectorXd& fint,
                  Eigen::MatrixXd* K)
{
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
        const double w = cq.weight(q);
        fint.noalias() += w * (B.transpose() * stress);
        if (K)
        {
            K->noalias() += w * (B.transpose() * (D * B));
            if (kinematics == Kinematics::TotalLagrangian)
            {
                const Eigen::Matrix3d S = tensorFromVoigt(stress);
                const Eigen::MatrixXd G = g * S * g.transpose(); // n x n
                for (int a = 0; a < n; ++a)
                    for (int b = 0; b < n; ++b)
                        for (int i = 0; i < 3; ++i)
                            (*K)(3 * a + i, 3 * b + i) += w * G(a, b);
            }
        }
    }
}

} // namespace fsi::fe
