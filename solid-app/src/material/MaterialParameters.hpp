// SPDX-License-Identifier: GPL-3.0-or-later
// Plain material data shared by the laws, filled by each law's parse() (Registry.hpp) from the
// material block, checked by validate().
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace fsi::config
{
class Block;
}

namespace fsi::material
{

// Keys (as named in error messages, relative to keyPrefix):
//   type                 a registered law (Registry.hpp): linear-elastic | neo-hookean |
//                        viscoelastic
//   E, nu                Young's modulus [Pa] and Poisson's ratio, or
//   K, G                 bulk and shear modulus [Pa]   (exactly one of the two pairs)
//   modulus_basis        long-term | instantaneous     (viscoelastic only, required:
//                        which modulus E/G refers to; K is elastic, the same at all times)
//   prony.convention     long-term-gamma | abaqus-g    (viscoelastic only, required)
//   prony.coefficients   gamma_i (relative to long-term G) or Abaqus g_i (relative to
//                        instantaneous G), >= 0; for abaqus-g sum(g) < 1
//   prony.times          tau_i [s] > 0, same length as prony.coefficients
struct MaterialParameters
{
    std::string type;

    std::optional<double> youngsModulus; // E  [Pa]
    std::optional<double> poissonRatio;  // nu [-], in (-1, 0.5)
    std::optional<double> bulkModulus;   // K  [Pa]
    std::optional<double> shearModulus;  // G  [Pa]

    std::string modulusBasis;    // "long-term" | "instantaneous"
    std::string pronyConvention; // "long-term-gamma" | "abaqus-g"
    std::vector<double> pronyCoefficients;
    std::vector<double> pronyTimes; // [s]
    // How the Prony recursion interpolates the strain over a step: "linear" (exact for strain
    // linear in time) | "quadratic" (through the last two accepted levels too: second order in
    // the step for curved histories; config/solid.example.yaml). Empty: linear.
    std::string pronyIntegration;

    // Used only to build error messages: "<file>: <keyPrefix>.<key> ...".
    std::string file = "config";
    std::string keyPrefix = "material";

    // Throws std::runtime_error, one line naming file, key and the fix, on the first
    // problem found: the type is registered, the moduli, then the law's own checks.
    // Every accessor below assumes a validated struct.
    void validate() const;
    // Throws std::runtime_error "<file>: <keyPrefix>.<key> <what>".
    [[noreturn]] void fail(const std::string& key, const std::string& what) const;
    // For the elastic laws' validate(): fails when Prony data or modulus_basis are set.
    void requireNoViscoelasticData() const;

    // Prony series in the paper's long-term convention (empty for elastic laws).
    std::vector<double> longTermGamma() const;
    const std::vector<double>& relaxationTimes() const { return pronyTimes; }

    // Moduli [Pa]. Elastic laws: long-term == instantaneous. Viscoelastic: K elastic,
    // G_inst = G_inf (1 + sum gamma_i); E and nu follow from (K, G) at each limit.
    double bulkModulusValue() const;
    double longTermShearModulus() const;
    double instantaneousShearModulus() const;
    double longTermYoungsModulus() const;
    double instantaneousYoungsModulus() const;
    double longTermPoissonRatio() const;
    double instantaneousPoissonRatio() const;

    // Multi-line echo for the start-up log: law, long-term gamma, tau,
    // long-term and instantaneous E / G / K / nu.
    std::string describe() const;
};

// Reads E, nu, K, G (those present) of a material block into p; the laws' parse() use it.
void readElasticModuli(const config::Block& block, MaterialParameters& p);

} // namespace fsi::material
