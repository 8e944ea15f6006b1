// SPDX-License-Identifier: GPL-3.0-or-later
#include "material/LinearElastic.hpp"

#include "material/MaterialParameters.hpp"

namespace fsi::material
{

MaterialType LinearElastic::entry()
{
    MaterialType t;
    t.name = "linear-elastic";
    t.keys = {"E", "nu", "K", "G"};
    t.parse = readElasticModuli;
    t.validate = [](const MaterialParameters& p) { p.requireNoViscoelasticData(); };
    t.make = [](const MaterialParameters& p) -> std::unique_ptr<Material>
    { return std::make_unique<LinearElastic>(p.bulkModulusValue(), p.longTermShearModulus()); };
    return t;
}

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
