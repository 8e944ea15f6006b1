// SPDX-License-Identifier: GPL-3.0-or-later
#include "driver/CoupledDriver.hpp"

#include "acceleration/Convergence.hpp"
#include "driver/TimeSchedule.hpp"
#include "mapping/Quality.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace fsi::driver
{

namespace
{
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0)
{
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

mapping::PointCloud toCloud(const std::vector<double>& xyz)
{
    mapping::PointCloud c(static_cast<Eigen::Index>(xyz.size() / 3), 3);
    for (Eigen::Index i = 0; i < c.rows(); ++i)
        for (int k = 0; k < 3; ++k)
            c(i, k) = xyz[3 * i + k];
    return c;
}

Eigen::VectorXd toVector(const std::vector<double>& v)
{
    return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

enum Decision : int
{
    Continue = 0,
    Converged = 1,
    Diverged = 2
};
} // namespace

struct CoupledDriver::Impl
{
    MPI_Comm comm;
    int rank = 0;
    fe::StructuralSolver& solid;
    FluidPeer* fluid;
    CouplingParameters params;
    std::string outputFolder;
    std::vector<double> relaxationTimes;
    std::vector<WatchedNode> watched;
    std::function<void(const LevelRecord&)> callback;

    std::unique_ptr<mapping::Mapping> displacementMap; // solid nodes -> fluid points (rank 0)
    std::unique_ptr<mapping::Mapping> forceMap;        // solid nodes -> fluid faces (rank 0)
    std::unique_ptr<acceleration::Accelerator> accelerator;
    std::ofstream couplingLog, historyLog;
    int angleLeading = -1, angleTrailing = -1;

    Impl(MPI_Comm c, fe::StructuralSolver& s, FluidPeer* f, CouplingParameters p, std::string out,
         std::vector<double> tau, std::vector<WatchedNode> w)
        : comm(c), solid(s), fluid(f), params(std::move(p)), outputFolder(std::move(out)),
          relaxationTimes(std::move(tau)), watched(std::move(w))
    {
        MPI_Comm_rank(comm, &rank);
    }

    // Collective: every rank calls it with the same reason.
    [[noreturn]] void fail(const std::string& reason)
    {
        fluid->abort(reason);
        throw std::runtime_error(reason);
    }

    // Broadcasts rank 0's error text; fails on every rank if it is not empty.
    void failIfRootFailed(std::string error)
    {
        int len = static_cast<int>(error.size());
        MPI_Bcast(&len, 1, MPI_INT, 0, comm);
        if (len == 0)
            return;
        error.resize(len);
        MPI_Bcast(error.data(), len, MPI_CHAR, 0, comm);
        fail(error);
    }

    void say(const std::string& line) const
    {
        if (rank == 0)
        {
            std::printf("%s\n", line.c_str());
            std::fflush(stdout);
        }
    }

    void setUp();
    void writeHeaders();
    void writeLevel(const LevelRecord& r, const Eigen::VectorXd& u, const Eigen::VectorXd& f);
    double sectionAngle() const;
};

CoupledDriver::CoupledDriver(MPI_Comm comm, fe::StructuralSolver& solid, FluidPeer* fluid,
                             CouplingParameters params, std::string outputFolder,
                             std::vector<double> relaxationTimes, std::vector<WatchedNode> watched)
    : impl_(std::make_unique<Impl>(comm, solid, fluid, std::move(params), std::move(outputFolder),
                                   std::move(relaxationTimes), std::move(watched)))
{
    if (!fluid)
        throw std::logic_error("CoupledDriver: every rank needs the fluid peer");
}

CoupledDriver::~CoupledDriver() = default;

void CoupledDriver::onLevelAccepted(std::function<void(const LevelRecord&)> callback)
{
    impl_->callback = std::move(callback);
}

void CoupledDriver::Impl::setUp()
{
    accelerator = acceleration::makeAccelerator(params.acceleration);
    if (params.sectionAngle)
    {
        const auto& mesh = solid.mesh();
        const auto& a = *params.sectionAngle;
        angleLeading = mesh.nearestNode({a.leadingEdge[0], a.leadingEdge[1], a.leadingEdge[2]});
        angleTrailing = mesh.nearestNode({a.trailingEdge[0], a.trailingEdge[1], a.trailingEdge[2]});
        if (angleLeading == angleTrailing)
            throw std::runtime_error("coupling.section_angle: leading and trailing edge map to the same node");
    }
    const auto solidNodes = toCloud(solid.wettedNodeCoordinates());
    if (solidNodes.rows() == 0)
        fail("solid mesh: the wetted surface has no nodes (check mesh.wetted)");
    std::string error;
    const auto t0 = Clock::now();
    if (rank == 0)
    {
        try
        {
            const auto& fi = fluid->interface();
            displacementMap = mapping::buildMapping(params.mapping, solidNodes, fi.points);
            forceMap = mapping::buildMapping(params.mapping, solidNodes, fi.faceCentres);
            std::filesystem::create_directories(outputFolder + "/interface");
            writeHeaders();
        }
        catch (const std::exception& e)
        {
            error = std::string("interface set-up: ") + e.what();
        }
    }
    failIfRootFailed(error);
    if (rank != 0)
        return;
    const auto& fi = fluid->interface();
    say("[mapping] " + params.mapping.type + ": " + std::to_string(solidNodes.rows()) +
        " solid wetted nodes, " + std::to_string(fi.points.rows()) + " fluid points, " +
        std::to_string(fi.faceCentres.rows()) + " fluid faces; set-up " +
        std::to_string(secondsSince(t0)) + " s");
    say("[mapping] points: " + mapping::assessQuality(*displacementMap, solidNodes, fi.points).toString());
    say("[mapping] faces:  " + mapping::assessQuality(*forceMap, solidNodes, fi.faceCentres).toString());
}

void CoupledDriver::Impl::writeHeaders()
{
    couplingLog.open(outputFolder + "/coupling.csv");
    couplingLog << "level,time,iteration,relaxation,rms_residual,relative_residual,fluid_iterations,"
                   "fluid_residual,fluid_converged,newton_iterations,wall_fluid_s,wall_solid_s,"
                   "wall_mapping_s,note\n";
    historyLog.open(outputFolder + "/history.csv");
    historyLog << "level,time,dt,coupling_iterations,fluid_iterations,newton_iterations,residual,"
                  "converged,Fx,Fy,Fz";
    for (const auto& w : watched)
        historyLog << "," << w.name << "_ux," << w.name << "_uy," << w.name << "_uz";
    if (params.sectionAngle)
        historyLog << "," << params.sectionAngle->name << "_deg";
    historyLog << ",relative_change,wall_s\n";
    if (!couplingLog || !historyLog)
        throw std::runtime_error("cannot write the coupling logs in " + outputFolder);
}

double CoupledDriver::Impl::sectionAngle() const
{
    const auto& a = *params.sectionAngle;
    const auto& x = solid.mesh().nodes;
    const auto& u = solid.displacement();
    Eigen::Vector3d xl = x.col(angleLeading), xt = x.col(angleTrailing);
    Eigen::Vector3d ul(u[3 * angleLeading], u[3 * angleLeading + 1], u[3 * angleLeading + 2]);
    Eigen::Vector3d ut(u[3 * angleTrailing], u[3 * angleTrailing + 1], u[3 * angleTrailing + 2]);
    const Eigen::Vector3d lift(a.liftDirection[0], a.liftDirection[1], a.liftDirection[2]);
    Eigen::Vector3d chord = xl - xt;
    chord -= chord.dot(lift) * lift;
    chord.normalize();
    const Eigen::Vector3d d = (xl + ul) - (xt + ut);
    return std::atan2(d.dot(lift), d.dot(chord)) * 180.0 / M_PI;
}

void CoupledDriver::Impl::writeLevel(const LevelRecord& r, const Eigen::VectorXd& u,
                                     const Eigen::VectorXd& f)
{
    historyLog << std::setprecision(10) << r.level << ',' << r.time << ',' << r.dt << ','
               << r.couplingIterations << ',' << r.fluidIterations << ',' << r.newtonIterations
               << ',' << r.residual << ',' << (r.converged ? 1 : 0) << ',' << r.force.x() << ','
               << r.force.y() << ',' << r.force.z();
    for (const auto& w : r.watched)
        historyLog << ',' << w.x() << ',' << w.y() << ',' << w.z();
    if (params.sectionAngle)
        historyLog << ',' << r.sectionAngle;
    historyLog << ',' << r.relativeChange << ',' << r.wallSeconds << '\n';
    historyLog.flush();

    // Interface state of the level: wetted node positions, displacement, nodal force.
    char name[64];
    std::snprintf(name, sizeof name, "/interface/level_%04d.csv", r.level);
    const std::string file = outputFolder + name;
    const auto x = solid.wettedNodeCoordinates();
    std::ofstream out(file + ".tmp");
    out << "# level " << r.level << " time " << r.time << " s\nx,y,z,ux,uy,uz,fx,fy,fz\n"
        << std::setprecision(10);
    for (std::size_t i = 0; i < x.size() / 3; ++i)
        out << x[3 * i] << ',' << x[3 * i + 1] << ',' << x[3 * i + 2] << ',' << u[3 * i] << ','
            << u[3 * i + 1] << ',' << u[3 * i + 2] << ',' << f[3 * i] << ',' << f[3 * i + 1] << ','
            << f[3 * i + 2] << '\n';
    out.close();
    std::filesystem::rename(file + ".tmp", file);
}

RunSummary CoupledDriver::run()
{
    auto& m = *impl_;
    const auto runStart = Clock::now();
    m.setUp();
    TimeSchedule schedule(m.params.time, m.relaxationTimes);
    m.say("[driver] " + schedule.describe() + "; acceleration " + m.accelerator->name() +
          ", max " + std::to_string(m.params.maxIterations) + " iterations per level");

    const int n = 3 * static_cast<int>(m.solid.wettedNodes().size());
    Eigen::VectorXd uLast = Eigen::VectorXd::Zero(n), uBeforeLast = uLast;
    Eigen::VectorXd iterate = uLast, solverOutput = uLast, nodalForce = uLast;
    double dtLast = 0.0;
    RunSummary summary;
    // Mapping buffers, sized once (rank 0): the per-iteration applies then allocate nothing.
    using NodeRows = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>;
    mapping::Values nodalDisplacement, pointDisplacement, nodalForceRows;
    if (m.rank == 0)
    {
        nodalDisplacement.resize(n / 3, 3);
        pointDisplacement.resize(m.displacementMap->targetSize(), 3);
        nodalForceRows.resize(n / 3, 3);
    }

    while (true)
    {
        const int level = schedule.level();
        const double time = schedule.time();
        const double dt = level == 0 ? 0.0 : schedule.lastStep();
        const auto levelStart = Clock::now();

        // Predictor for the first iterate of the level.
        iterate = uLast;
        if (m.params.predictor == "linear" && level >= 2 && dtLast > 0.0)
            iterate = uLast + (uLast - uBeforeLast) * (dt / dtLast);
        m.accelerator->beginLevel();

        LevelRecord record;
        record.level = level;
        record.time = time;
        record.dt = dt;
        double firstResidual = -1.0;
        int decision = Continue;
        std::string failure;
        for (int it = 1; it <= m.params.maxIterations; ++it)
        {
            double wallFluid = 0, wallMapping = 0;
            auto t0 = Clock::now();
            if (m.rank == 0)
            {
                nodalDisplacement = NodeRows(iterate.data(), n / 3, 3);
                m.displacementMap->applyConsistent(nodalDisplacement, pointDisplacement);
                wallMapping += secondsSince(t0);
            }
            t0 = Clock::now();
            const FluidResponse response = m.fluid->solve(level, it, time, pointDisplacement);
            wallFluid = secondsSince(t0);
            if (m.rank == 0)
            {
                t0 = Clock::now();
                m.forceMap->applyConservative(response.faceForces, nodalForceRows);
                for (int i = 0; i < n / 3; ++i)
                    for (int k = 0; k < 3; ++k)
                        nodalForce[3 * i + k] = nodalForceRows(i, k);
                record.force = response.faceForces.colwise().sum().transpose();
                wallMapping += secondsSince(t0);
                record.fluidIterations += response.iterations;
            }
            MPI_Bcast(nodalForce.data(), n, MPI_DOUBLE, 0, m.comm);

            t0 = Clock::now();
            fe::InterfaceLoads loads{std::vector<double>(nodalForce.data(), nodalForce.data() + n)};
            const auto report = m.solid.solve({time, dt}, loads);
            const double wallSolid = secondsSince(t0);
            record.newtonIterations += report.newtonIterations;
            if (!report.converged)
                m.fail("level " + std::to_string(level) + " (t = " + std::to_string(time) +
                       " s), coupling iteration " + std::to_string(it) +
                       ": the structural Newton solve failed: " + report.message);
            solverOutput = toVector(m.solid.wettedNodeDisplacements());
            record.couplingIterations = it;

            std::string note;
            double relaxation = std::nan("");
            if (m.rank == 0)
            {
                const auto measure = acceleration::measureConvergence(iterate, solverOutput, m.params.convergence);
                record.residual = measure.rmsResidual;
                if (firstResidual < 0)
                    firstResidual = measure.rmsResidual;
                if (!measure.finite)
                {
                    decision = Diverged;
                    failure = "the interface residual is not finite (NaN/inf)";
                }
                else if (measure.converged)
                    decision = Converged;
                else if (it > 2 && measure.rmsResidual > m.params.divergenceFactor * firstResidual)
                {
                    decision = Diverged;
                    std::ostringstream s;
                    s << "the interface residual grew from " << firstResidual << " to "
                      << measure.rmsResidual << " m (x" << m.params.divergenceFactor
                      << "): lower the initial relaxation or use iqn-ils";
                    failure = s.str();
                }
                else
                {
                    iterate = m.accelerator->update(iterate, solverOutput);
                    relaxation = m.accelerator->lastRelaxation();
                    note = m.accelerator->lastNote();
                }
                m.couplingLog << std::setprecision(8) << level << ',' << time << ',' << it << ','
                              << relaxation << ',' << measure.rmsResidual << ','
                              << measure.relativeResidual << ',' << response.iterations << ','
                              << response.finalResidual << ',' << (response.converged ? 1 : 0) << ','
                              << report.newtonIterations << ',' << wallFluid << ',' << wallSolid
                              << ',' << wallMapping << ',' << note << '\n';
                m.couplingLog.flush();
                if (verbose_)
                {
                    char line[256];
                    std::snprintf(line, sizeof line,
                                  "  [level %d it %2d] |r|/sqrt(n) %.3e  omega %s  fluid %d it (res %.1e)  "
                                  "newton %d  wall fluid %.2f s solid %.2f s%s%s",
                                  level, it, measure.rmsResidual,
                                  std::isnan(relaxation) ? "  -  " : std::to_string(relaxation).substr(0, 6).c_str(),
                                  response.iterations, response.finalResidual, report.newtonIterations,
                                  wallFluid, wallSolid, note.empty() ? "" : "  ", note.c_str());
                    m.say(line);
                }
                summary.fluidSeconds += wallFluid;
                summary.mappingSeconds += wallMapping;
            }
            summary.solidSeconds += wallSolid;
            MPI_Bcast(&decision, 1, MPI_INT, 0, m.comm);
            if (decision != Continue)
                break;
        }
        if (decision == Diverged)
            m.failIfRootFailed("level " + std::to_string(level) + " (t = " + std::to_string(time) +
                               " s) diverged: " + failure);
        record.converged = decision == Converged;
        if (!record.converged)
        {
            std::ostringstream s;
            s << "level " << level << " (t = " << time << " s) did not converge in "
              << m.params.maxIterations << " coupling iterations (|r|/sqrt(n) = " << record.residual
              << " m)";
            if (!m.params.continueOnMaxIterations)
                m.fail(s.str() + ": raise coupling.max_iterations, loosen the tolerance, or set "
                                 "on_max_iterations: continue");
            m.say("WARNING: " + s.str() + "; accepted anyway (on_max_iterations: continue)");
        }

        m.accelerator->endLevel();
        m.solid.acceptLevel();
        m.fluid->accept(level, time);

        const double norm = solverOutput.norm();
        record.relativeChange = norm > 0 ? (solverOutput - uLast).norm() / norm : 0.0;
        for (const auto& w : m.watched)
        {
            const auto& u = m.solid.displacement();
            record.watched.emplace_back(u[3 * w.node], u[3 * w.node + 1], u[3 * w.node + 2]);
        }
        if (m.params.sectionAngle)
            record.sectionAngle = m.sectionAngle();
        record.wallSeconds = secondsSince(runStart);
        if (m.rank == 0)
            m.writeLevel(record, solverOutput, nodalForce);
        if (m.callback)
            m.callback(record);

        summary.history.push_back(record);
        summary.levels += 1;
        summary.couplingIterations += record.couplingIterations;
        summary.fluidIterations += record.fluidIterations;
        {
            std::ostringstream s;
            s << std::setprecision(4) << "[level " << level << "] t = " << time << " s (dt " << dt
              << " s): " << record.couplingIterations << " coupling it, " << record.fluidIterations
              << " fluid it; F = (" << record.force.x() << ", " << record.force.y() << ", "
              << record.force.z() << ") N";
            for (std::size_t i = 0; i < m.watched.size(); ++i)
                s << "; " << m.watched[i].name << " u = (" << record.watched[i].x() << ", "
                  << record.watched[i].y() << ", " << record.watched[i].z() << ") m";
            if (m.params.sectionAngle)
                s << "; " << m.params.sectionAngle->name << " " << record.sectionAngle << " deg";
            s << "; level " << secondsSince(levelStart) << " s";
            const double done = schedule.progress();
            if (done > 0 && done < 1)
                s << ", ETA " << std::setprecision(3) << record.wallSeconds * (1 - done) / done << " s";
            m.say(s.str());
        }

        uBeforeLast = uLast;
        uLast = solverOutput;
        if (!schedule.hasNext())
            break;
        dtLast = dt;
        schedule.advance(record.relativeChange);
    }
    m.fluid->finish();
    summary.factorizations = m.solid.factorizationCount();
    summary.wallSeconds = secondsSince(runStart);
    return summary;
}

} // namespace fsi::driver
