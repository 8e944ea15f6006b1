// SPDX-License-Identifier: GPL-3.0-or-later
// VTK unstructured-grid output of the solid (reference configuration + displacement field,
// use ParaView's "Warp By Vector"). Quadratic cells are written as VTK quadratic types
// (Tet10 -> VTK_QUADRATIC_TETRA 24, Hex20 -> VTK_QUADRATIC_HEXAHEDRON 25, Hex27 ->
// VTK_TRIQUADRATIC_HEXAHEDRON 29, Prism6/15/18 -> VTK_WEDGE 13 / VTK_QUADRATIC_WEDGE 26 /
// VTK_BIQUADRATIC_QUADRATIC_WEDGE 32) with the node order converted from Gmsh's.
#pragma once
#include "mesh/Mesh.hpp"

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace fsi::io
{

using Vector6 = Eigen::Matrix<double, 6, 1>;

struct SolidFields
{
    const std::vector<double>* displacement = nullptr; // 3 per node [m]
    const std::vector<Vector6>* nodalStress = nullptr; // Cauchy, Voigt tensor shear [Pa]
    const std::vector<Vector6>* cellStress = nullptr;  // Cauchy, per cell [Pa]
};

// Writes one .vtu (atomically). binary: inline base64 raw data, else ASCII.
// Point data: displacement, cauchy_stress (xx yy zz xy yz xz), von_mises; cell data likewise.
// The file names its fields, units and the stress measure in an XML comment (kFieldNote).
void writeVtu(const std::string& path, const mesh::Mesh& mesh, const SolidFields& fields,
              bool binary);

// A ParaView .pvd series: add() a (time, file name relative to the .pvd) then write() it
// again atomically each level, so the series on disk is always complete.
class PvdSeries
{
public:
    explicit PvdSeries(std::string path) : path_(std::move(path)) {}
    void add(double time, const std::string& file);
    void write() const;

private:
    std::string path_;
    std::vector<std::pair<double, std::string>> entries_;
};

// The comment at the top of every .vtu: fields, units, stress measure (Cauchy).
extern const char* const kFieldNote;

// Von Mises equivalent of a Voigt stress (tensor shear) [Pa].
double vonMisesStress(const Vector6& s);

} // namespace fsi::io
