// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/VtuWriter.hpp"

#include "io/AtomicFile.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace fsi::io
{
namespace
{

using mesh::CellType;

// VTK wedges: corners (c0, c1, c2) with the right-hand normal pointing AWAY from (c3, c4, c5),
// i.e. Gmsh's (0, 2, 1, 3, 5, 4); then mid-edges and quad-face centres defined by VTK corners.
// Each VTK node is found in the Gmsh table by its reference position (mean of its corners).
std::vector<int> prismOrder(CellType t)
{
    const int corner[6] = {0, 2, 1, 3, 5, 4};
    const std::vector<std::vector<int>> vtk = {
        {0},    {1},    {2},    {3},    {4},    {5},    {0, 1},       {1, 2},       {2, 0},
        {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}, {0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};
    const auto& ref = mesh::ReferenceElement::get(t);
    std::vector<int> order;
    for (int k = 0; k < ref.numNodes(); ++k)
    {
        Eigen::Vector3d x = Eigen::Vector3d::Zero();
        for (int c : vtk[k])
            x += ref.node(corner[c]) / static_cast<double>(vtk[k].size());
        int found = -1;
        for (int a = 0; a < ref.numNodes(); ++a)
            if ((ref.node(a) - x).norm() < 1e-12)
                found = a;
        if (found < 0)
            throw std::logic_error("writeVtu: no wedge node at a VTK position");
        order.push_back(found);
    }
    return order;
}

// VTK cell type and the Gmsh node index for each VTK node position.
int vtkType(CellType t, std::vector<int>& order)
{
    switch (t)
    {
    case CellType::Tet4:
        order = {0, 1, 2, 3};
        return 10;
    case CellType::Tet10:
        order = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};
        return 24;
    case CellType::Hex8:
        order = {0, 1, 2, 3, 4, 5, 6, 7};
        return 12;
    case CellType::Hex20:
        order = {0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15};
        return 25;
    case CellType::Hex27:
        order = {0,  1,  2,  3,  4,  5,  6,  7,  8,  11, 13, 9,  16, 18,
                 19, 17, 10, 12, 14, 15, 22, 23, 21, 24, 20, 25, 26};
        return 29;
    case CellType::Prism6:
    case CellType::Prism15:
    case CellType::Prism18:
        order = prismOrder(t);
        return t == CellType::Prism6 ? 13 : t == CellType::Prism15 ? 26 : 32;
    default:
        throw std::logic_error("writeVtu: not a volume cell");
    }
}

std::string base64(const std::vector<unsigned char>& in)
{
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((in.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 2 < in.size(); i += 3)
    {
        const unsigned v = (in[i] << 16) | (in[i + 1] << 8) | in[i + 2];
        out += table[(v >> 18) & 63];
        out += table[(v >> 12) & 63];
        out += table[(v >> 6) & 63];
        out += table[v & 63];
    }
    if (i < in.size())
    {
        unsigned v = in[i] << 16;
        if (i + 1 < in.size())
            v |= in[i + 1] << 8;
        out += table[(v >> 18) & 63];
        out += table[(v >> 12) & 63];
        out += i + 1 < in.size() ? table[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

class ArrayWriter
{
public:
    ArrayWriter(std::ostringstream& out, bool binary) : out_(out), binary_(binary) {}

    template <typename T>
    void write(const std::string& name, const char* vtkTypeName, int components,
               const std::vector<T>& data)
    {
        out_ << "        <DataArray type=\"" << vtkTypeName << "\" Name=\"" << name << "\"";
        if (components > 1)
            out_ << " NumberOfComponents=\"" << components << "\"";
        out_ << " format=\"" << (binary_ ? "binary" : "ascii") << "\">\n";
        if (binary_)
        {
            const std::uint64_t bytes = data.size() * sizeof(T);
            std::vector<unsigned char> raw(sizeof(bytes) + bytes);
            std::memcpy(raw.data(), &bytes, sizeof(bytes));
            if (bytes)
                std::memcpy(raw.data() + sizeof(bytes), data.data(), bytes);
            out_ << base64(raw) << "\n";
        }
        else
        {
            out_ << std::setprecision(12);
            for (std::size_t i = 0; i < data.size(); ++i)
                out_ << (i % 9 == 0 ? "" : " ") << +data[i]
                     << ((i % 9 == 8 || i + 1 == data.size()) ? "\n" : "");
        }
        out_ << "        </DataArray>\n";
    }

private:
    std::ostringstream& out_;
    bool binary_;
};

void stressArrays(ArrayWriter& w, const std::vector<Vector6>& s)
{
    std::vector<double> flat, vm;
    for (const auto& v : s)
    {
        flat.insert(flat.end(), v.data(), v.data() + 6);
        vm.push_back(vonMisesStress(v));
    }
    w.write("cauchy_stress", "Float64", 6, flat);
    w.write("von_mises", "Float64", 1, vm);
}

} // namespace

const char* const kFieldNote =
    "<!-- solid-app fields (reference configuration; warp by displacement): displacement [m]; "
    "cauchy_stress = Cauchy (true) stress sigma [Pa], components xx yy zz xy yz xz (tensor "
    "shear), small strain: the stress of the law, total Lagrangian: sigma = J^-1 F S F^T; "
    "von_mises = von Mises equivalent of sigma [Pa]; point data: volume-weighted averages of "
    "the cells around each node, cell data: cell averages -->";

double vonMisesStress(const Vector6& s)
{
    const double a = s[0] - s[1], b = s[1] - s[2], c = s[2] - s[0];
    return std::sqrt(0.5 * (a * a + b * b + c * c) +
                     3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

void writeVtu(const std::string& path, const mesh::Mesh& mesh, const SolidFields& fields,
              bool binary)
{
    const auto& cells = mesh.cells;
    std::vector<double> points(mesh.nodes.data(), mesh.nodes.data() + 3 * mesh.numNodes());
    std::vector<std::int64_t> connectivity, offsets;
    std::vector<std::uint8_t> types;
    std::vector<int> order;
    for (int c = 0; c < cells.size(); ++c)
    {
        types.push_back(static_cast<std::uint8_t>(vtkType(cells.types[c], order)));
        for (int k : order)
            connectivity.push_back(cells.nodes(c)[k]);
        offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    }
    std::ostringstream out;
    out << "<?xml version=\"1.0\"?>\n"
        << kFieldNote << "\n"
        << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
           "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n"
        << "    <Piece NumberOfPoints=\"" << mesh.numNodes() << "\" NumberOfCells=\""
        << cells.size() << "\">\n";
    ArrayWriter w(out, binary);
    out << "      <Points>\n";
    w.write("Points", "Float64", 3, points);
    out << "      </Points>\n      <Cells>\n";
    w.write("connectivity", "Int64", 1, connectivity);
    w.write("offsets", "Int64", 1, offsets);
    w.write("types", "UInt8", 1, types);
    out << "      </Cells>\n      <PointData Vectors=\"displacement\">\n";
    if (fields.displacement)
        w.write("displacement", "Float64", 3, *fields.displacement);
    if (fields.nodalStress)
        stressArrays(w, *fields.nodalStress);
    out << "      </PointData>\n      <CellData>\n";
    if (fields.cellStress)
        stressArrays(w, *fields.cellStress);
    out << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
    writeFileAtomically(path, out.str());
}

void PvdSeries::add(double time, const std::string& file)
{
    entries_.emplace_back(time, file);
}

void PvdSeries::write() const
{
    std::ostringstream out;
    out << std::setprecision(12)
        << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n  "
           "<Collection>\n";
    for (const auto& e : entries_)
        out << "    <DataSet timestep=\"" << e.first << "\" part=\"0\" file=\"" << e.second
            << "\"/>\n";
    out << "  </Collection>\n</VTKFile>\n";
    writeFileAtomically(path_, out.str());
}

} // namespace fsi::io
