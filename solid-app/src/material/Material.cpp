// SPDX-License-Identifier: GPL-3.0-or-later
#include "material/Material.hpp"

#include "material/MaterialParameters.hpp"
#include "material/Registry.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace fsi::material
{

void Material::initialiseHistory(double* history) const
{
    for (std::size_t i = 0; i < historySize(); ++i)
        history[i] = 0.0;
}

Vector6 Material::acceptedStress(const Vector6& strain, const double* newHistory) const
{
    if (historySize() != 0)
        throw std::logic_error(name() + ": a law with history must override acceptedStress()");
    Vector6 stress;
    Matrix6 tangent;
    evaluate(strain, TimeStep{0.0, 0.0}, newHistory, stress, tangent);
    return stress;
}

Matrix6 Material::initialTangent() const
{
    std::vector<double> history(historySize());
    initialiseHistory(history.data());
    Vector6 stress;
    Matrix6 tangent;
    evaluate(Vector6::Zero(), TimeStep{0.0, 0.0}, history.empty() ? nullptr : history.data(),
             stress, tangent);
    return tangent;
}

Matrix6 deviatoricProjector()
{
    Matrix6 p = Matrix6::Zero();
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            p(i, j) = (i == j ? 1.0 : 0.0) - 1.0 / 3.0;
    for (int i = 3; i < 6; ++i)
        p(i, i) = 0.5; // engineering shear in, tensor shear out
    return p;
}

Matrix6 isotropicTangent(double bulkModulus, double shearModulus)
{
    Matrix6 c = 2.0 * shearModulus * deviatoricProjector();
    c.topLeftCorner<3, 3>().array() += bulkModulus;
    return c;
}

double vonMises(const Vector6& s)
{
    const double d01 = s(0) - s(1), d12 = s(1) - s(2), d20 = s(2) - s(0);
    return std::sqrt(0.5 * (d01 * d01 + d12 * d12 + d20 * d20) +
                     3.0 * (s(3) * s(3) + s(4) * s(4) + s(5) * s(5)));
}

std::unique_ptr<Material> makeMaterial(const MaterialParameters& p, Kinematics kinematics)
{
    p.validate();
    const MaterialType& law = *findMaterialType(p.type); // validate() checked it is registered
    if (law.needsTotalLagrangian && kinematics != Kinematics::TotalLagrangian)
        p.fail("type", "= " + p.type +
                           " needs total-Lagrangian kinematics; set kinematics to "
                           "total-lagrangian or use linear-elastic");
    return law.make(p);
}

} // namespace fsi::material
