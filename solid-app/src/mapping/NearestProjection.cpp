// SPDX-License-Identifier: GPL-3.0-or-later
#include "mapping/NearestProjection.hpp"

#include "config/YamlReader.hpp"
#include "mapping/KdTree.hpp"
#include "mesh/ReferenceElement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace fsi::mapping
{

const std::vector<std::string>& NearestProjectionParameters::keys()
{
    static const std::vector<std::string> k{"candidate_faces", "blend"};
    return k;
}

NearestProjectionParameters NearestProjectionParameters::parse(const config::Block& layer)
{
    NearestProjectionParameters p;
    if (const auto b = layer.optionalBlock(keyword))
    {
        b->allowOnly(keys());
        p.candidateFaces = b->integer("candidate_faces", p.candidateFaces);
        p.blend = b->number("blend", p.blend);
    }
    return p;
}

void NearestProjectionParameters::validate() const
{
    if (candidateFaces < 1 || candidateFaces > 200)
        throw std::runtime_error("nearest-projection.candidate_faces must be in [1, 200] (got " +
                                 std::to_string(candidateFaces) + "); e.g. 24");
    if (!(blend >= 0.0 && blend <= 10.0))
    {
        std::ostringstream message;
        message << "nearest-projection.blend must be in [0, 10] (got " << blend
                << "); 0 = the closest face only, 1 = blend faces up to twice as far";
        throw std::runtime_error(message.str());
    }
}

std::string NearestProjectionParameters::echo() const
{
    std::ostringstream out;
    out << "{candidate_faces: " << candidateFaces << ", blend: " << blend << "}";
    return out.str();
}

namespace
{

using Vec3 = Eigen::Vector3d;

bool isSurfaceType(mesh::CellType t)
{
    using mesh::CellType;
    return t == CellType::Tri3 || t == CellType::Tri6 || t == CellType::Quad4 ||
           t == CellType::Quad8 || t == CellType::Quad9;
}

// The reference face's domain: triangle xi, eta >= 0, xi + eta <= 1; quad [-1, 1]^2.
Vec3 clampToFace(Vec3 xi, bool simplex)
{
    xi(2) = 0.0;
    if (!simplex)
    {
        xi(0) = std::clamp(xi(0), -1.0, 1.0);
        xi(1) = std::clamp(xi(1), -1.0, 1.0);
        return xi;
    }
    xi(0) = std::max(xi(0), 0.0);
    xi(1) = std::max(xi(1), 0.0);
    const double sum = xi(0) + xi(1);
    if (sum > 1.0)
    {
        xi(0) /= sum;
        xi(1) /= sum;
    }
    return xi;
}

// The closest point of one (possibly curved) face to x: Gauss-Newton on |X(xi) - x|^2 from
// the face's centre, each step clamped to the face. Returns xi; N the shape functions there and
// *distance |X(xi) - x|.
Vec3 projectOntoFace(const mesh::ReferenceElement& ref, const Eigen::Matrix3Xd& nodes,
                     const Vec3& x, Eigen::VectorXd& N, Eigen::MatrixXd& dN, double* distance)
{
    Vec3 xi = ref.isSimplex() ? Vec3(1.0 / 3.0, 1.0 / 3.0, 0.0) : Vec3::Zero();
    for (int iteration = 0; iteration < 12; ++iteration)
    {
        ref.evaluate(xi, N, dN);
        const Vec3 r = nodes * N - x;
        const Eigen::Matrix<double, 3, 2> J = nodes * dN.leftCols<2>();
        const Eigen::Matrix2d JtJ = J.transpose() * J;
        const Eigen::Vector2d step = JtJ.ldlt().solve(-J.transpose() * r);
        if (!step.allFinite())
            break; // a degenerate (zero-area) face: keep the last point
        const Vec3 next = clampToFace(xi + Vec3(step(0), step(1), 0.0), ref.isSimplex());
        const double moved = (next - xi).norm();
        xi = next;
        if (moved < 1e-12)
            break;
    }
    ref.evaluate(xi, N, dN);
    *distance = (nodes * N - x).norm();
    return xi;
}

} // namespace

NearestProjection::NearestProjection(const NearestProjectionParameters& params) : params_(params)
{
    params_.validate();
}

void NearestProjection::setSourceSurface(const SourceSurface& surface)
{
    surface_ = surface;
}

void NearestProjection::compute(const PointCloud& source, const PointCloud& target)
{
    if (surface_.faces.size() == 0)
        throw std::runtime_error("mapping nearest-projection needs the source's surface faces (the "
                                 "solid's wetted faces), and none were given; use another "
                                 "mapping.type");
    const mesh::CellList& faces = surface_.faces;
    const int nFaces = faces.size();
    PointCloud centroids(nFaces, 3);
    for (int f = 0; f < nFaces; ++f)
    {
        if (!isSurfaceType(faces.types[static_cast<size_t>(f)]))
            throw std::runtime_error(
                "mapping nearest-projection: source face " + std::to_string(f) + " is a " +
                mesh::ReferenceElement::get(faces.types[static_cast<size_t>(f)]).name() +
                ", not a Tri3/Tri6/Quad4/Quad8/Quad9 surface face");
        Vec3 c = Vec3::Zero();
        for (int a = 0; a < faces.numNodes(f); ++a)
        {
            const int node = faces.nodes(f)[a];
            if (node < 0 || node >= source.rows())
                throw std::runtime_error("mapping nearest-projection: source face " +
                                         std::to_string(f) + " names point " +
                                         std::to_string(node) + " of a cloud of " +
                                         std::to_string(source.rows()));
            c += source.row(node).transpose();
        }
        centroids.row(f) = (c / faces.numNodes(f)).transpose();
    }
    const KdTree tree(centroids);
    const int k = std::min(params_.candidateFaces, nFaces);

    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(static_cast<size_t>(target.rows()) * 9);
    std::vector<Eigen::Index> candidates;
    std::vector<double> centroidDistances;
    // each candidate's projection: its distance and shape-function values there
    std::vector<double> distances, blendWeights;
    std::vector<Eigen::VectorXd> shapes;
    Eigen::VectorXd N;
    Eigen::MatrixXd dN;
    Eigen::Matrix3Xd nodes;
    double extent = 0.0; // the source's bounding-box diagonal: scale of "on the surface"
    if (source.rows() > 0)
        extent = (source.colwise().maxCoeff() - source.colwise().minCoeff()).norm();
    const double onSurface = 1e-12 * extent;
    double sumSquares = 0.0;
    maxDistance_ = 0.0;
    for (Eigen::Index t = 0; t < target.rows(); ++t)
    {
        const Vec3 x = target.row(t).transpose();
        tree.nearest(x.data(), k, candidates, centroidDistances);
        distances.assign(candidates.size(), std::numeric_limits<double>::infinity());
        shapes.resize(candidates.size());
        double best = std::numeric_limits<double>::infinity();
        int bestCandidate = -1;
        for (size_t c = 0; c < candidates.size(); ++c)
        {
            const int face = static_cast<int>(candidates[c]);
            const auto& ref = mesh::ReferenceElement::get(faces.types[static_cast<size_t>(face)]);
            nodes.resize(3, faces.numNodes(face));
            for (int a = 0; a < faces.numNodes(face); ++a)
                nodes.col(a) = source.row(faces.nodes(face)[a]).transpose();
            projectOntoFace(ref, nodes, x, N, dN, &distances[c]);
            shapes[c] = N;
            if (distances[c] < best)
            {
                best = distances[c];
                bestCandidate = static_cast<int>(c);
            }
        }
        if (bestCandidate < 0)
            throw std::runtime_error("mapping nearest-projection: target point " +
                                     std::to_string(t) +
                                     " has no finite distance to any candidate face (degenerate "
                                     "wetted faces?)");
        const auto addFace = [&](size_t c, double weight)
        {
            const int face = static_cast<int>(candidates[c]);
            for (int a = 0; a < faces.numNodes(face); ++a)
                triplets.emplace_back(t, faces.nodes(face)[a], weight * shapes[c](a));
        };
        if (params_.blend > 0.0 && best > onSurface)
        {
            // weights (1 - s)^2, s = (d_f - d_min) / (blend d_min), normalised
            const double band = params_.blend * best;
            blendWeights.assign(candidates.size(), 0.0);
            double sum = 0.0;
            for (size_t c = 0; c < candidates.size(); ++c)
            {
                const double s = (distances[c] - best) / band;
                blendWeights[c] = s < 1.0 ? (1.0 - s) * (1.0 - s) : 0.0;
                sum += blendWeights[c];
            }
            for (size_t c = 0; c < candidates.size(); ++c)
                if (blendWeights[c] > 0.0)
                    addFace(c, blendWeights[c] / sum);
        }
        else
            addFace(static_cast<size_t>(bestCandidate), 1.0);
        maxDistance_ = std::max(maxDistance_, best);
        sumSquares += best * best;
    }
    rmsDistance_ = target.rows() > 0 ? std::sqrt(sumSquares / double(target.rows())) : 0.0;
    setWeights(target.rows(), source.rows(), triplets); // duplicates summed
}

} // namespace fsi::mapping
