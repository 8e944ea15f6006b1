// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app: a transport that prescribes the interface motion (tests only).
#include "couplingTransport.H"

#include <cmath>
#include <sstream>

namespace fsi
{
namespace fluid
{

std::vector<double> prescribedDisplacement
(
    const PrescribedMotion& m,
    const std::vector<double>& points,
    double fraction
)
{
    const std::size_t n = points.size()/3;
    std::vector<double> d(points.size(), 0.0);
    if (m.type == "rotation")
    {
        const double pi = std::acos(-1.0);
        const double theta = fraction*m.angleDeg*pi/180.0;
        const double c = std::cos(theta), s = std::sin(theta);
        const double* k = m.axis;
        for (std::size_t i = 0; i < n; ++i)
        {
            const double r[3] =
            {
                points[3*i] - m.origin[0],
                points[3*i + 1] - m.origin[1],
                points[3*i + 2] - m.origin[2]
            };
            const double kr = k[0]*r[0] + k[1]*r[1] + k[2]*r[2];
            const double kxr[3] =
            {
                k[1]*r[2] - k[2]*r[1],
                k[2]*r[0] - k[0]*r[2],
                k[0]*r[1] - k[1]*r[0]
            };
            // Rodrigues: R r = r c + (k x r) s + k (k.r)(1 - c)
            for (int j = 0; j < 3; ++j)
            {
                d[3*i + j] = r[j]*c + kxr[j]*s + k[j]*kr*(1.0 - c) - r[j];
            }
        }
    }
    else if (m.type == "bending")
    {
        for (std::size_t i = 0; i < n; ++i)
        {
            double x = 0;
            for (int j = 0; j < 3; ++j)
            {
                x += (points[3*i + j] - m.origin[j])*m.beamAxis[j];
            }
            const double xi = (x - m.start)/m.length;
            if (xi > 0)
            {
                for (int j = 0; j < 3; ++j)
                {
                    d[3*i + j] = fraction*m.amplitude*xi*xi*m.direction[j];
                }
            }
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
