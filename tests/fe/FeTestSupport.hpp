// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
#include "fe/StructuralSolver.hpp"
#include "material/Material.hpp"
#include "material/MaterialParameters.hpp"
#include "mesh/GmshTestMeshes.hpp"
#include "mesh/Mesh.hpp"

#include <filesystem>
#include <string>
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

} // namespace fsi::testing
