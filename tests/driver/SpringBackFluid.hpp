// SPDX-License-Identifier: GPL-3.0-or-later
// Test double of the fluid for the driver layer's unit tests (the real fluid-app is used by the
// integration tests). Its interface points and faces are the solid's wetted nodes; the force on
// every face is (F0 / faces) (1 - kappa * mean(u_y)) in y. For a linear structure whose mean
// wetted y-displacement under the load pattern alone is U1, the coupled fixed point is
//   mean(u_y)* = U1 / (1 + kappa U1),
// and plain fixed-point iteration (omega = 1) has the contraction factor -kappa U1.
#pragma once

#include "driver/FluidPeer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace fsi::testing
{

class SpringBackFluid : public driver::FluidPeer
{
public:
    SpringBackFluid(const std::vector<double>& wettedXyz, double totalForce, double kappa)
        : totalForce_(totalForce), kappa_(kappa)
    {
        const Eigen::Index n = static_cast<Eigen::Index>(wettedXyz.size() / 3);
        interface_.points.resize(n, 3);
        for (Eigen::Index i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k)
                interface_.points(i, k) = wettedXyz[3 * i + k];
        interface_.faceCentres = interface_.points;
        interface_.faceAreas = mapping::PointCloud::Zero(n, 3);
    }
    const driver::FluidInterface& interface() const override { return interface_; }
    // Moves the fluid's interface away (a case whose fluid and solid meshes do not overlap).
    void shiftInterface(double dx, double dy, double dz)
    {
        for (mapping::PointCloud* c : {&interface_.points, &interface_.faceCentres})
            c->rowwise() += Eigen::RowVector3d(dx, dy, dz);
    }
    // Moves the face centres alone (forces then come from other places than the points).
    void shiftFaceCentres(double dx, double dy, double dz)
    {
        interface_.faceCentres.rowwise() += Eigen::RowVector3d(dx, dy, dz);
    }
    driver::FluidResponse solve(int level, int iteration, double time,
                                const mapping::Values& pointDisplacement,
                                const driver::FluidAccuracy& accuracy) override
    {
        ++solves;
        asked.push_back(accuracy);
        if (pointDisplacement.rows() == 0) // not the solid's rank 0: nothing significant
            return {};
        const double meanUy = pointDisplacement.col(1).mean();
        driver::FluidResponse r;
        const Eigen::Index n = interface_.faceCentres.rows();
        r.faceForces = mapping::Values::Zero(n, 3);
        r.faceForces.col(1).setConstant(totalForce_ / n * (1.0 - kappa_ * meanUy));
        const double lastTime = accepted.empty() ? 0.0 : accepted.back();
        if (unstableStep > 0 && time - lastTime > unstableStep)
            r.faceForces.setConstant(std::nan(""));
        // An inexact flow (driver-controlled accuracy eta): like SIMPLE warm-started from its
        // last solution, the double moves from its last forces F_last towards the exact F and
        // stops once within eta |F| of it (error left: min(gap, eta |F|), never overshooting);
        // "iterations" = those of a contraction 0.5 per iteration from gap to eta |F|.
        if (accuracy.driverControlled && inexactness > 0)
        {
            if (lastForces_.rows() != n)
                lastForces_ = mapping::Values::Zero(n, 3); // from rest
            const double gap = (lastForces_ - r.faceForces).norm();
            const double allowed = inexactness * accuracy.forceTolerance * r.faceForces.norm();
            if (gap > allowed)
            {
                r.faceForces += (lastForces_ - r.faceForces) * (allowed / gap);
                r.iterations = static_cast<int>(std::ceil(std::log2(gap / allowed)));
            }
            r.iterations = std::max(r.iterations, accuracy.minIterations);
        }
        else
            r.iterations = 1;
        lastForces_ = r.faceForces;
        if (meanBand > 0) // a flow without a steady state, accepted in the mean
        {
            r.faceForces *= 1.0 + (solves % 2 ? meanBand : -meanBand);
            r.band = meanBand;
        }
        r.converged = true;
        return r;
    }
    void accept(int level, double time) override { accepted.push_back(time); }
    void finish() override { finished = true; }
    void abort(const std::string& reason) noexcept override { abortReason = reason; }

    double unstableStep = 0; // > 0: NaN forces when time - last accepted time exceeds it
    std::vector<driver::FluidAccuracy> asked; // the accuracy of every solve
    double inexactness = 0; // > 0: inexact solves, error inexactness x eta |F| at most
    // > 0: a flow without a steady state: every answer is the exact force times
    // 1 +- meanBand (the sign alternating from solve to solve: a mean known only to its band),
    // reported as converged in the mean with band meanBand.
    double meanBand = 0;
    int solves = 0;
    std::vector<double> accepted;
    bool finished = false;
    std::string abortReason;

private:
    driver::FluidInterface interface_;
    double totalForce_, kappa_;
    mapping::Values lastForces_; // the last answer (the warm start of the next solve)
};

} // namespace fsi::testing
