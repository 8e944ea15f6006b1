// SPDX-License-Identifier: GPL-3.0-or-later
// The structural mesh: nodes, volume cells and named boundary face groups.
// Units: whatever the mesh file uses (the solver assumes SI: metres).
#pragma once
#include "mesh/ReferenceElement.hpp"

#include <Eigen/Dense>
#include <map>
#include <string>
#include <vector>

namespace fsi::mesh
{

// A list of cells of mixed types with a flat connectivity (0-based node indices).
struct CellList
{
    std::vector<CellType> types;
    std::vector<int> offsets{0}; // cell c uses connectivity[offsets[c] .. offsets[c+1])
    std::vector<int> connectivity;

    int size() const { return static_cast<int>(types.size()); }
    int numNodes(int c) const { return offsets[c + 1] - offsets[c]; }
    const int* nodes(int c) const { return connectivity.data() + offsets[c]; }
    void add(CellType type, const int* nodes, int n);
};

// A named boundary surface (a Gmsh physical group of dimension 2).
struct SurfaceGroup
{
    std::string name;
    CellList faces;
    std::vector<int> nodes; // sorted, unique node indices of the faces
};

struct Mesh
{
    std::string source;     // file name, for messages
    Eigen::Matrix3Xd nodes; // reference coordinates, one column per node
    CellList cells;         // volume cells
    std::map<std::string, SurfaceGroup> surfaces;

    int numNodes() const { return static_cast<int>(nodes.cols()); }
    // Throws (one line naming source and group) if the group does not exist.
    const SurfaceGroup& surface(const std::string& name) const;
    // Counts of cells per type name, e.g. {"Tet10": 1200}.
    std::map<std::string, int> cellTypeCounts() const;
    // Smallest Jacobian determinant over the nodes and centroid of cell c (reference config).
    double minJacobian(int c) const;
    // Throws if any cell has a non-positive Jacobian (inverted / degenerate), naming the cell.
    void checkJacobians() const;
    // Nearest node to a point (linear search).
    int nearestNode(const Eigen::Vector3d& x) const;
};

// What to read: the volume group and the surface groups needed by the case.
struct MeshSelection
{
    std::string volume;                // physical group (dim 3) holding the cells
    std::vector<std::string> surfaces; // physical groups (dim 2) that must exist
};

// Reads a Gmsh .msh (v2 or v4) file through the Gmsh API. Throws std::runtime_error with a
// one-line message naming the file and the group for missing groups, unsupported cell types,
// inverted cells. quiet: no longer used (the volumetric-locking warning, which needs the
// material and the element formulation, is printed by fe::StructuralSolver).
Mesh readGmsh(const std::string& file, const MeshSelection& selection, bool quiet = false);

} // namespace fsi::mesh
