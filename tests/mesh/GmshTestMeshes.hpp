// SPDX-License-Identifier: GPL-3.0-or-later
// Test meshes made with the Gmsh API: a (possibly skewed) hexahedral block with physical
// groups "solid" (volume), "x0","x1","y0","y1","z0","z1" (faces) and "boundary" (all faces).
#pragma once
#include <gmsh.h>

#include <array>
#include <string>
#include <vector>

namespace fsi::testing
{

enum class TestCell
{
    Tet4,
    Tet10,
    Hex8,
    Hex20,
    Hex27
};

struct BlockSpec
{
    std::array<double, 3> size{1.0, 1.0, 1.0};
    std::array<int, 3> cells{2, 2, 2};
    bool skew = false;           // move corners: non-affine hexes, irregular tets
    bool structuredTets = false; // tets: transfinite (else unstructured, size from cells[0])
    double mshVersion = 4.1;
};

inline std::string makeBlockMesh(const std::string& path, TestCell cell, const BlockSpec& spec = {})
{
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::model::add("block");
    const double L = spec.size[0], H = spec.size[1], W = spec.size[2];
    std::array<std::array<double, 3>, 8> x = {
        {{0, 0, 0}, {L, 0, 0}, {L, H, 0}, {0, H, 0}, {0, 0, W}, {L, 0, W}, {L, H, W}, {0, H, W}}};
    if (spec.skew)
    {
        x[2] = {1.2 * L, 1.1 * H, 0.0};
        x[5] = {0.9 * L, 0.1 * H, 1.15 * W};
        x[7] = {0.1 * L, 0.95 * H, 0.9 * W};
        x[6] = {1.05 * L, 1.05 * H, 1.1 * W};
    }
    std::vector<int> p;
    for (const auto& v : x)
        p.push_back(gmsh::model::geo::addPoint(v[0], v[1], v[2]));
    // edges: bottom 0-1,1-2,2-3,3-0; top 4-5,5-6,6-7,7-4; vertical 0-4,1-5,2-6,3-7
    const int e[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                          {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    const int dir[12] = {0, 1, 0, 1, 0, 1, 0, 1, 2, 2, 2, 2};
    std::vector<int> l;
    for (int i = 0; i < 12; ++i)
        l.push_back(gmsh::model::geo::addLine(p[e[i][0]], p[e[i][1]]));
    auto face = [&](std::vector<int> loop)
    { return gmsh::model::geo::addSurfaceFilling({gmsh::model::geo::addCurveLoop(loop)}); };
    const int z0 = face({l[0], l[1], l[2], l[3]});
    const int z1 = face({l[4], l[5], l[6], l[7]});
    const int y0 = face({l[0], l[9], -l[4], -l[8]});
    const int x1 = face({l[1], l[10], -l[5], -l[9]});
    const int y1 = face({l[2], l[11], -l[6], -l[10]});
    const int x0 = face({l[3], l[8], -l[7], -l[11]});
    const std::vector<int> faces = {x0, x1, y0, y1, z0, z1};
    const int vol = gmsh::model::geo::addVolume({gmsh::model::geo::addSurfaceLoop(faces)});
    const bool hex = cell == TestCell::Hex8 || cell == TestCell::Hex20 || cell == TestCell::Hex27;
    if (hex || spec.structuredTets)
    {
        for (int i = 0; i < 12; ++i)
            gmsh::model::geo::mesh::setTransfiniteCurve(l[i], spec.cells[dir[i]] + 1);
        for (int f : faces)
        {
            gmsh::model::geo::mesh::setTransfiniteSurface(f);
            if (hex)
                gmsh::model::geo::mesh::setRecombine(2, f);
        }
        gmsh::model::geo::mesh::setTransfiniteVolume(vol);
    }
    else
    {
        const double h = L / spec.cells[0];
        for (int id : p)
            gmsh::model::geo::mesh::setSize({{0, id}}, h);
    }
    gmsh::model::geo::synchronize();
    gmsh::model::addPhysicalGroup(3, {vol}, 1);
    gmsh::model::setPhysicalName(3, 1, "solid");
    const char* names[6] = {"x0", "x1", "y0", "y1", "z0", "z1"};
    for (int i = 0; i < 6; ++i)
    {
        gmsh::model::addPhysicalGroup(2, {faces[i]}, 10 + i);
        gmsh::model::setPhysicalName(2, 10 + i, names[i]);
    }
    gmsh::model::addPhysicalGroup(2, faces, 20);
    gmsh::model::setPhysicalName(2, 20, "boundary");
    gmsh::option::setNumber("Mesh.SecondOrderIncomplete", cell == TestCell::Hex20 ? 1 : 0);
    gmsh::model::mesh::generate(3);
    if (cell == TestCell::Tet10 || cell == TestCell::Hex20 || cell == TestCell::Hex27)
        gmsh::model::mesh::setOrder(2);
    gmsh::option::setNumber("Mesh.MshFileVersion", spec.mshVersion);
    gmsh::write(path);
    gmsh::finalize();
    return path;
}

// Unit cube of prisms: the triangulated bottom face extruded in n layers. Groups as above.
// quadratic: 0 (Prism6), 15 (Prism15) or 18 (Prism18).
inline std::string makePrismBlock(const std::string& path, int quadratic, int n = 2)
{
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::model::add("prisms");
    const int p0 = gmsh::model::geo::addPoint(0, 0, 0), p1 = gmsh::model::geo::addPoint(1, 0, 0),
              p2 = gmsh::model::geo::addPoint(1, 1, 0), p3 = gmsh::model::geo::addPoint(0, 1, 0);
    const std::vector<int> l = {
        gmsh::model::geo::addLine(p0, p1), gmsh::model::geo::addLine(p1, p2),
        gmsh::model::geo::addLine(p2, p3), gmsh::model::geo::addLine(p3, p0)};
    const int s = gmsh::model::geo::addPlaneSurface({gmsh::model::geo::addCurveLoop(l)});
    gmsh::model::geo::mesh::setSize({{0, p0}, {0, p1}, {0, p2}, {0, p3}}, 1.0 / n);
    gmsh::vectorpair out;
    gmsh::model::geo::extrude({{2, s}}, 0, 0, 1, out, {n}, {}, true);
    gmsh::model::geo::synchronize();
    // out: top, volume, sides of l[0..3] (y0, x1, y1, x0)
    gmsh::model::addPhysicalGroup(3, {out[1].second}, 1);
    gmsh::model::setPhysicalName(3, 1, "solid");
    const std::vector<std::pair<std::string, int>> faces = {{"z0", s},
                                                            {"z1", out[0].second},
                                                            {"y0", out[2].second},
                                                            {"x1", out[3].second},
                                                            {"y1", out[4].second},
                                                            {"x0", out[5].second}};
    std::vector<int> all;
    int tag = 10;
    for (const auto& [name, id] : faces)
    {
        gmsh::model::addPhysicalGroup(2, {id}, tag);
        gmsh::model::setPhysicalName(2, tag++, name);
        all.push_back(id);
    }
    gmsh::model::addPhysicalGroup(2, all, 20);
    gmsh::model::setPhysicalName(2, 20, "boundary");
    gmsh::option::setNumber("Mesh.SecondOrderIncomplete", quadratic == 15 ? 1 : 0);
    gmsh::model::mesh::generate(3);
    if (quadratic)
        gmsh::model::mesh::setOrder(2);
    gmsh::write(path);
    gmsh::finalize();
    return path;
}

inline const char* testCellName(TestCell c)
{
    static const char* n[] = {"Tet4", "Tet10", "Hex8", "Hex20", "Hex27"};
    return n[static_cast<int>(c)];
}

} // namespace fsi::testing
