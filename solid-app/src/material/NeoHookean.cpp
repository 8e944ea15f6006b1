// SPDX-License-Identifier: GPL-3.0-or-later
#include "material/NeoHookean.hpp"

#include "material/MaterialParameters.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <string>

namespace fsi::material
{
namespace
{
constexpr int voigtI[6] = {0, 1, 2, 0, 1, 0};
constexpr int voigtJ[6] = {0, 1, 2, 1, 2, 2};
} // namespace

MaterialType NeoHookean::entry()
{
    MaterialType t;
    t.name = "neo-hookean";
    t.keys = {"E", "nu", "K", "G"};
    t.needsTotalLagrangian = true;
    t.parse = readElasticModuli;
    t.validate = [](const MaterialParameters& p) { p.requireNoViscoelasticData(); };
    t.make = [](const MaterialParameters& p) -> std::unique_ptr<Material>
    { return std::make_unique<NeoHookean>(p.bulkModulusValue(), p.longTermShearModulus()); };
    return t;
}

NeoHookean::NeoHookean(double bulkModulus, double shearModulus)
    : lambda_(bulkModulus - 2.0 * shearModulus / 3.0), mu_(shearModulus)
{
}

void NeoHookean::evaluate(const Vector6& e, const TimeStep&, const double*, Vector6& stress,
                          Matrix6& tangent) const
{
    Eigen::Matrix3d c;
    c << 1 + 2 * e(0), e(3), e(5), //
        e(3), 1 + 2 * e(1), e(4),  //
        e(5), e(4), 1 + 2 * e(2);
    const double detC = c.determinant();
    if (!(detC > 0.0))
        throw InadmissibleDeformation("neo-hookean: det C = " + std::to_string(detC) +
                                      " <= 0 (inverted element); reduce the load step");
    const double lnJ = 0.5 * std::log(detC);
    const Eigen::Matrix3d ci = c.inverse();
    const Eigen::Matrix3d s = mu_ * (Eigen::Matrix3d::Identity() - ci) + lambda_ * lnJ * ci;
    const double factor = mu_ - lambda_ * lnJ;
    for (int a = 0; a < 6; ++a)
    {
        const int i = voigtI[a], j = voigtJ[a];
        stress(a) = s(i, j);
        for (int b = 0; b < 6; ++b)
        {
            const int k = voigtI[b], l = voigtJ[b];
            tangent(a, b) = lambda_ * ci(i, j) * ci(k, l) +
                            factor * (ci(i, k) * ci(j, l) + ci(i, l) * ci(j, k));
        }
    }
}

} // namespace fsi::material
