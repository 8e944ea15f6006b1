// SPDX-License-Identifier: GPL-3.0-or-later
#include "material/LinearElastic.hpp"

namespace fsi::material
{

LinearElastic::LinearElastic(double bulkModulus, double shearModulus)
    : stiffness_(isotropicTangent(bulkModulus, shearModulus))
{
}

void LinearElastic::evaluate(const Vector6& strain, const TimeStep&, const double*, Vector6& stress,
                             Matrix6& tangent) const
{
    tangent = stiffness_;
    stress.noalias() = stiffness_ * strain;
}

} // namespace fsi::material
