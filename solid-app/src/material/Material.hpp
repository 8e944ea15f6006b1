// SPDX-License-Identifier: GPL-3.0-or-later
// Integration-point constitutive laws: the abstract base and the factory.
//
// Voigt order (xx, yy, zz, xy, yz, xz). Strain vectors carry ENGINEERING shear
// (gamma_xy = 2 eps_xy); stress vectors carry tensor components (sigma_xy).
// With this pair, stress . strain is the work density and the Voigt tangent
// D(a, b) = C_ijkl (minor-symmetric 4th-order tensor) is symmetric.
// Units: strain [-], stress and tangent [Pa], time [s].
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>

namespace fsi::material
{

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

struct MaterialParameters; // MaterialParameters.hpp

enum class Kinematics
{
    SmallStrain,    // strain = infinitesimal eps, stress = Cauchy sigma
    TotalLagrangian // strain = Green-Lagrange E, stress = 2nd Piola-Kirchhoff S
};

// One time level n -> n+1.
struct TimeStep
{
    double time = 0.0; // t^{n+1} [s]
    double dt = 0.0;   // t^{n+1} - t^n [s], >= 0; dt == 0: instantaneous (t = 0) level
};

// Thrown by evaluate() when the deformation is not admissible (det F <= 0 for
// finite-strain laws). Newton can catch it to cut the load step / line search.
class InadmissibleDeformation : public std::runtime_error
{
public:
    using std::runtime_error::runtime_error;
};

// One instance shared by all integration points (and threads): stateless itself,
// every history lives in caller-owned arrays of historySize() doubles per point.
class Material
{
public:
    virtual ~Material() = default;

    // Keyword of the law: "linear-elastic", "neo-hookean", "viscoelastic".
    virtual std::string name() const = 0;

    // Doubles of history per integration point (0 for elastic laws: no storage, no cost).
    virtual std::size_t historySize() const = 0;

    // Stress and consistent tangent dStress/dStrain at the trial strain of level n+1.
    // committedHistory: historySize() doubles of level n (read-only; nullptr if historySize()==0).
    // Pre: step.dt >= 0. Throws InadmissibleDeformation for det F <= 0 (finite strain).
    virtual void evaluate(const Vector6& strain, const TimeStep& step,
                          const double* committedHistory, Vector6& stress,
                          Matrix6& tangent) const = 0;

    // Writes the history of level n+1 for the converged strain (call when a level is
    // accepted). newHistory may not alias committedHistory. No-op if historySize()==0.
    virtual void updateHistory(const Vector6& strain, const TimeStep& step,
                               const double* committedHistory, double* newHistory) const = 0;

    // True when the stress is affine in the strain for a fixed step and committed history (the
    // tangent then depends on the step and on what every point's committed history shares, e.g.
    // the previous step's length of Viscoelastic's quadratic rule, not on the strain): with
    // small-strain kinematics the structural problem of a level is linear. Default false.
    virtual bool isLinearInStrain() const { return false; }

    // Stress of an ACCEPTED level from its own history: newHistory is what updateHistory()
    // wrote for this strain, so the result equals evaluate(strain, step, committedHistory) of
    // that level, without the level's step or the history before it (output after the commit,
    // after a restart). Default: laws with historySize() == 0 (evaluate at any step); laws with
    // history must override it (the default throws std::logic_error for them).
    virtual Vector6 acceptedStress(const Vector6& strain, const double* newHistory) const;

    // Virgin (t = 0, unstrained) history; zeros by default.
    virtual void initialiseHistory(double* history) const;

    // Small-strain tangent at zero strain and dt = 0 (instantaneous), e.g. for a
    // predictor or a stiffness estimate.
    virtual Matrix6 initialTangent() const;
};

// Builds the law named by params.type; calls params.validate() first (throws
// std::runtime_error naming the key). neo-hookean needs Kinematics::TotalLagrangian.
std::unique_ptr<Material> makeMaterial(const MaterialParameters& params, Kinematics kinematics);

// --- small Voigt helpers (exact, used by the laws and handy in tests / output) ---

// Isotropic elastic Voigt matrix (engineering shear): K II + 2G (I - II/3).
Matrix6 isotropicTangent(double bulkModulus, double shearModulus);
// Deviatoric projector from an engineering-shear strain vector to dev(eps) in tensor
// components (shear entries gamma/2), so 2G * deviatoricProjector() * strain = 2G dev(eps)
// as a stress vector; also the (I - II/3) of eq. 9 in this Voigt pair.
Matrix6 deviatoricProjector();
// Trace of a Voigt tensor (strain or stress): v0 + v1 + v2.
inline double trace(const Vector6& v)
{
    return v(0) + v(1) + v(2);
}
// Von Mises equivalent of a stress vector (tensor shear components) [Pa].
double vonMises(const Vector6& stress);

} // namespace fsi::material
