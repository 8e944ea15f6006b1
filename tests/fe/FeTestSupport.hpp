// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include "fe/StructuralSolver.hpp"
#include "material/Material.hpp"
#include "material/MaterialParameters.hpp"
#include "mesh/GmshTestMeshes.hpp"
#include "mesh/Mesh.hpp"

#include <filesystem>
#include <string>
#include <vector>
#include <unistd.h>

namespace fsi::testing
{

inline std::string tempFile(const std::string& name)
{
    auto dir =
        std::filesystem::temp_directory_path() / ("fsi_test_fe_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

inline material::MaterialParameters elastic(double E, double nu)
{
    material::MaterialParameters p;
    p.type = "linear-elastic";
    p.youngsModulus = E;
    p.poissonRatio = nu;
    return p;
}

// Prony solid with bulk modulus K and long-term shear modulus G [Pa], gamma_i relative to G
// (the paper's convention), tau_i [s].
inline material::MaterialParameters viscoelasticKG(double K, double G, std::vector<double> gammas,
                                                   std::vector<double> taus)
{
    material::MaterialParameters p;
    p.type = "viscoelastic";
    p.bulkModulus = K;
    p.shearModulus = G;
    p.modulusBasis = "long-term";
    p.pronyConvention = "long-term-gamma";
    p.pronyCoefficients = std::move(gammas);
    p.pronyTimes = std::move(taus);
    return p;
}

} // namespace fsi::testing
