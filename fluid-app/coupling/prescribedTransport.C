// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app: a transport that prescribes the interface motion (tests only).
#include "couplingTransport.H"

#include <cmath>
#include <sstream>

namespace fsi
{
namespace fluid
{

namespace
{

// Displacement R r - r of the point r (relative to a point on the axis) rotated by theta
// [rad] about the unit axis k (Rodrigues: R r = r c + (k x r) s + k (k.r)(1 - c)).
void addRotation(const double r[3], const double k[3], double theta, double* d)
{
    const double c = std::cos(theta), s = std::sin(theta);
    const double kr = k[0]*r[0] + k[1]*r[1] + k[2]*r[2];
    const double kxr[3] =
    {
        k[1]*r[2] - k[2]*r[1],
        k[2]*r[0] - k[0]*r[2],
        k[0]*r[1] - k[1]*r[0]
    };
    for (int j = 0; j < 3; ++j)
    {
        d[j] += r[j]*c + kxr[j]*s + k[j]*kr*(1.0 - c) - r[j];
    }
}

} // namespace

std::vector<double> prescribedDisplacement
(
    const PrescribedMotion& m,
    const std::vector<double>& points,
    double fraction
)
{
    const double degree = std::acos(-1.0)/180.0;
    const std::size_t n = points.size()/3;
    std::vector<double> d(points.size(), 0.0);
    for (std::size_t i = 0; i < n; ++i)
    {
        const double r[3] =
        {
            points[3*i] - m.origin[0],
            points[3*i + 1] - m.origin[1],
            points[3*i + 2] - m.origin[2]
        };
        double* di = &d[3*i];
        if (m.type == "rotation")
        {
            addRotation(r, m.axis, fraction*m.angleDeg*degree, di);
            continue;
        }
        // bending and twist: xi, the position along beamAxis from `start`, per `length`
        const double x = r[0]*m.beamAxis[0] + r[1]*m.beamAxis[1] + r[2]*m.beamAxis[2];
        const double xi = (x - m.start)/m.length;
        if (xi <= 0)
        {
            continue;
        }
        if (m.type == "twist")
        {
            addRotation(r, m.beamAxis, fraction*m.angleDeg*xi*degree, di);
        }
        for (int j = 0; j < 3; ++j)
        {
            di[j] += fraction*m.amplitude*xi*xi*m.direction[j];
        }
    }
    return d;
}

namespace
{

class PrescribedTransport : public CouplingTransport
{
public:
    explicit PrescribedTransport(const PrescribedMotion& motion) : motion_(motion) {}

    void handshake(const InterfaceGeometry&, long, long, const LocalInterface& local) override
    {
        points_ = local.pointCoordinates; // every rank moves its own points
    }

    Command receive() override
    {
        Command c;
        if (step_ >= motion_.steps && !pendingAccept_)
        {
            c.kind = CommandKind::finish;
            return c;
        }
        if (pendingAccept_)
        {
            pendingAccept_ = false;
            c.kind = CommandKind::accept;
            c.step = step_;
            c.time = step_;
            return c;
        }
        ++step_;
        c.kind = CommandKind::solve;
        c.step = step_;
        c.iteration = 1;
        c.time = step_;
        c.displacements =
            prescribedDisplacement(motion_, points_, double(step_)/motion_.steps);
        pendingAccept_ = true;
        return c;
    }

    void sendForces(const Command&, const ForceReport&) override {}
    void abortRun(const std::string&) override {}

    std::string describe() const override
    {
        std::ostringstream os;
        os << "prescribed " << motion_.type << " motion in " << motion_.steps << " steps";
        return os.str();
    }

private:
    PrescribedMotion motion_;
    std::vector<double> points_;
    int step_ = 0;
    bool pendingAccept_ = false;
};

} // namespace

std::unique_ptr<CouplingTransport> makePrescribedTransport(const PrescribedMotion& motion)
{
    return std::unique_ptr<CouplingTransport>(new PrescribedTransport(motion));
}

} // namespace fluid
} // namespace fsi
