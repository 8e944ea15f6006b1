// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh/Mesh.hpp"

#include <gmsh.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <unordered_map>

namespace fsi::mesh
{
namespace
{

// Gmsh keeps global state: initialise once per read and always finalise.
struct GmshSession
{
    GmshSession()
    {
        gmsh::initialize(0, nullptr, false);
        gmsh::option::setNumber("General.Terminal", 0);
        gmsh::option::setNumber("General.Verbosity", 0);
    }
    ~GmshSession() { gmsh::finalize(); }
};

// Tag of the physical group named `name` of dimension `dim`; -1 if absent.
int findPhysical(int dim, const std::string& name)
{
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups, dim);
    for (const auto& g : groups)
    {
        std::string n;
        gmsh::model::getPhysicalName(g.first, g.second, n);
        if (n == name)
            return g.second;
    }
    return -1;
}

std::string availableGroups(int dim)
{
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups, dim);
    std::string list;
    for (const auto& g : groups)
    {
        std::string n;
        gmsh::model::getPhysicalName(g.first, g.second, n);
        list += (list.empty() ? "" : ", ") + (n.empty() ? std::to_string(g.second) : "'" + n + "'");
    }
    return list.empty() ? "none" : list;
}

void readCells(int dim, int physical, const std::string& file, const std::string& group,
               std::unordered_map<std::size_t, int>& nodeIndex, std::vector<std::size_t>& nodeTags,
               CellList& out, bool createNodes)
{
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(dim, physical, entities);
    std::vector<int> conn;
    for (int entity : entities)
    {
        std::vector<int> types;
        std::vector<std::vector<std::size_t>> tags, nodes;
        gmsh::model::mesh::getElements(types, tags, nodes, dim, entity);
        for (std::size_t t = 0; t < types.size(); ++t)
        {
            CellType type;
            if (!cellTypeFromGmsh(types[t], type))
            {
                std::string name;
                int d, o, nn, np;
                std::vector<double> c;
                gmsh::model::mesh::getElementProperties(types[t], name, d, o, nn, c, np);
                throw std::runtime_error(
                    file + ": physical group '" + group + "' has " + name +
                    " elements, which are not supported (use Tet10, "
                    "Hex20/Hex27, Prism15/18, Tet4, Hex8 or Prism6; pyramids are not supported)");
            }
            const int n = ReferenceElement::get(type).numNodes();
            const std::size_t count = tags[t].size();
            for (std::size_t e = 0; e < count; ++e)
            {
                conn.assign(n, -1);
                for (int a = 0; a < n; ++a)
                {
                    const std::size_t tag = nodes[t][e * n + a];
                    auto it = nodeIndex.find(tag);
                    if (it == nodeIndex.end())
                    {
                        if (!createNodes)
                            throw std::runtime_error(file + ": surface group '" + group +
                                                     "' has nodes that are not on the volume");
                        it = nodeIndex.emplace(tag, static_cast<int>(nodeTags.size())).first;
                        nodeTags.push_back(tag);
                    }
                    conn[a] = it->second;
                }
                out.add(type, conn.data(), n);
            }
        }
    }
}

} // namespace

Mesh readGmsh(const std::string& file, const MeshSelection& selection, bool /*quiet*/)
{
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec))
        throw std::runtime_error(file + ": is a directory, not a mesh file; give the .msh file");
    if (!std::ifstream(file).good())
        throw std::runtime_error(file + ": cannot open mesh file");
    if (std::filesystem::file_size(file, ec) == 0 && !ec)
        throw std::runtime_error(file + ": the mesh file is empty; write the mesh again (e.g. "
                                        "gmsh -3 part.geo -o part.msh)");
    GmshSession session;
    try
    {
        gmsh::open(file);
    }
    catch (const std::exception& e)
    {
        throw std::runtime_error(file + ": Gmsh cannot read the mesh (" + e.what() + ")");
    }
    catch (...)
    {
        throw std::runtime_error(file + ": Gmsh cannot read the mesh");
    }
    {
        std::vector<std::size_t> tags;
        std::vector<double> coordinates, parametric;
        gmsh::model::mesh::getNodes(tags, coordinates, parametric, -1, -1, false, false);
        if (tags.empty())
            throw std::runtime_error(file + ": holds no mesh nodes (empty, truncated or not a "
                                            "Gmsh mesh); write the mesh again (e.g. gmsh -3 "
                                            "part.geo -o part.msh)");
    }
    Mesh mesh;
    mesh.source = file;
    const int volumeTag = findPhysical(3, selection.volume);
    if (volumeTag < 0)
        throw std::runtime_error(file + ": no volume physical group '" + selection.volume +
                                 "' (volume groups: " + availableGroups(3) + ")");
    std::unordered_map<std::size_t, int> nodeIndex;
    std::vector<std::size_t> nodeTags;
    readCells(3, volumeTag, file, selection.volume, nodeIndex, nodeTags, mesh.cells, true);
    if (mesh.cells.size() == 0)
        throw std::runtime_error(file + ": volume group '" + selection.volume + "' has no cells");

    // coordinates of the used nodes
    std::vector<std::size_t> allTags;
    std::vector<double> coords, parametric;
    gmsh::model::mesh::getNodes(allTags, coords, parametric, -1, -1, false, false);
    mesh.nodes.resize(3, static_cast<Eigen::Index>(nodeTags.size()));
    std::vector<char> seen(nodeTags.size(), 0);
    for (std::size_t i = 0; i < allTags.size(); ++i)
    {
        auto it = nodeIndex.find(allTags[i]);
        if (it != nodeIndex.end())
        {
            mesh.nodes.col(it->second) =
                Eigen::Vector3d(coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]);
            seen[it->second] = 1;
        }
    }
    if (std::find(seen.begin(), seen.end(), 0) != seen.end())
        throw std::runtime_error(file + ": some cell nodes have no coordinates");

    for (const std::string& name : selection.surfaces)
    {
        if (mesh.surfaces.count(name))
            continue;
        const int tag = findPhysical(2, name);
        if (tag < 0)
            throw std::runtime_error(file + ": no surface physical group '" + name +
                                     "' (surface groups: " + availableGroups(2) + ")");
        SurfaceGroup group;
        group.name = name;
        readCells(2, tag, file, name, nodeIndex, nodeTags, group.faces, false);
        group.nodes = group.faces.connectivity;
        std::sort(group.nodes.begin(), group.nodes.end());
        group.nodes.erase(std::unique(group.nodes.begin(), group.nodes.end()), group.nodes.end());
        if (group.nodes.empty())
            throw std::runtime_error(file + ": surface group '" + name + "' has no faces");
        mesh.surfaces.emplace(name, std::move(group));
    }
    mesh.checkJacobians();
    return mesh;
}

} // namespace fsi::mesh
