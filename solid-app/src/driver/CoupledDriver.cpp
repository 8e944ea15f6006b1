// SPDX-License-Identifier: GPL-3.0-or-later
#include "driver/CoupledDriver.hpp"

#include "acceleration/Convergence.hpp"
#include "driver/Checkpoint.hpp"
#include "driver/TimeSchedule.hpp"
#include "mapping/Quality.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <optional>
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

    // Interface vectors (3 per wetted node, all ranks): the accepted u_n, u_{n-1}, the current
    // iterate, the solid's output and the nodal fluid force.
    int n = 0;
    Eigen::VectorXd uLast, uBeforeLast, iterate, solverOutput, nodalForce;
    double dtLast = 0.0;
    mapping::Values nodalDisplacement, pointDisplacement, nodalForceRows; // rank 0 buffers
    std::vector<double> acceptedTimes;
    double relaxationScale = 1.0; // product of the relaxation cures so far

    enum class Outcome
    {
        Converged,
        Capped,      // max_iterations reached
        Diverged,    // residual growth or NaN
        SolidFailed  // structural Newton failed (after its own load sub-stepping)
    };
    struct Attempt
    {
        Outcome outcome = Outcome::Converged;
        std::string diagnosis; // same on every rank
        int iteration = 0;     // the coupling iteration it ended in
    };

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

    // Collective: fails on every rank (fluid told) when any rank's localError is not empty.
    void failIfAnyRankFailed(const std::string& localError)
    {
        try
        {
            throwIfAnyRankFailed(comm, localError);
        }
        catch (const std::exception& e)
        {
            fail(e.what());
        }
    }

    void say(const std::string& line) const
    {
        if (rank == 0)
        {
            std::printf("%s\n", line.c_str());
            std::fflush(stdout);
        }
    }

    void setUp(int restartLevel);
    void writeHeaders();
    void keepLogRowsUpTo(int level);
    Attempt attemptLevel(int level, double time, double dt, bool usePredictor, LevelRecord& record,
                         RunSummary& summary, bool verbose);
    std::string cure(const Attempt& attempt, TimeSchedule& schedule);
    void makeScaledAccelerator();
    DriverState state(const LevelRecord& r, double wallSeconds, const RunSummary& summary) const;
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

const std::vector<double>& CoupledDriver::acceptedTimes() const
{
    return impl_->acceptedTimes;
}

void CoupledDriver::Impl::setUp(int restartLevel)
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
            if (restartLevel >= 0)
                keepLogRowsUpTo(restartLevel);
            else
                writeHeaders();
        }
        catch (const std::exception& e)
        {
            error = std::string("interface set-up: ") + e.what();
        }
    }
    failIfAnyRankFailed(error);
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
    historyLog << ",relative_change,wall_s,retries\n";
    if (!couplingLog || !historyLog)
        throw std::runtime_error("cannot write the coupling logs in " + outputFolder);
}

// Restart: keeps the header and the rows of levels <= level (first column) of both logs and
// reopens them for appending.
void CoupledDriver::Impl::keepLogRowsUpTo(int level)
{
    for (const char* name : {"/coupling.csv", "/history.csv"})
    {
        const std::string file = outputFolder + name;
        std::ifstream in(file);
        if (!in)
            throw std::runtime_error(file + ": missing; a restart needs the logs of the checkpointed "
                                            "run in the same --out folder");
        std::string line, kept;
        std::getline(in, line);
        kept = line + "\n";
        while (std::getline(in, line))
        {
            const std::string first = line.substr(0, line.find(','));
            if (!first.empty() && first.find_first_not_of("0123456789") == std::string::npos &&
                std::stoi(first) <= level)
                kept += line + "\n";
        }
        in.close();
        std::ofstream(file + ".tmp") << kept;
        std::filesystem::rename(file + ".tmp", file);
    }
    couplingLog.open(outputFolder + "/coupling.csv", std::ios::app);
    historyLog.open(outputFolder + "/history.csv", std::ios::app);
    if (!couplingLog || !historyLog)
        throw std::runtime_error("cannot append to the coupling logs in " + outputFolder);
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
    historyLog << ',' << r.relativeChange << ',' << r.wallSeconds << ',' << r.retries << '\n';
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


// One try at a level: coupling iterations until convergence, the cap, divergence or a failed
// structural solve. Leaves the solid with the level's last solve (accepted by the caller).
CoupledDriver::Impl::Attempt CoupledDriver::Impl::attemptLevel(int level, double time, double dt,
                                                               bool usePredictor, LevelRecord& record,
                                                               RunSummary& summary, bool verbose)
{
    using NodeRows = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>;
    iterate = uLast;
    if (usePredictor && params.predictor == "linear" && level >= 2 && dtLast > 0.0)
        iterate = uLast + (uLast - uBeforeLast) * (dt / dtLast);
    accelerator->beginLevel();

    double firstResidual = -1.0;
    int decision = Continue;
    std::string failure;
    for (int it = 1; it <= params.maxIterations; ++it)
    {
        double wallFluid = 0, wallMapping = 0;
        auto t0 = Clock::now();
        if (rank == 0)
        {
            nodalDisplacement = NodeRows(iterate.data(), n / 3, 3);
            displacementMap->applyConsistent(nodalDisplacement, pointDisplacement);
            wallMapping += secondsSince(t0);
        }
        t0 = Clock::now();
        const FluidResponse response = fluid->solve(level, it, time, pointDisplacement);
        wallFluid = secondsSince(t0);
        if (rank == 0)
        {
            t0 = Clock::now();
            forceMap->applyConservative(response.faceForces, nodalForceRows);
            for (int i = 0; i < n / 3; ++i)
                for (int k = 0; k < 3; ++k)
                    nodalForce[3 * i + k] = nodalForceRows(i, k);
            record.force = response.faceForces.colwise().sum().transpose();
            wallMapping += secondsSince(t0);
            record.fluidIterations += response.iterations;
            summary.fluidIterations += response.iterations;
        }
        MPI_Bcast(nodalForce.data(), n, MPI_DOUBLE, 0, comm);

        t0 = Clock::now();
        fe::InterfaceLoads loads{std::vector<double>(nodalForce.data(), nodalForce.data() + n)};
        const auto report = solid.solve({time, dt}, loads);
        const double wallSolid = secondsSince(t0);
        record.newtonIterations += report.newtonIterations;
        record.couplingIterations = it;
        summary.couplingIterations += 1;
        summary.solidSeconds += wallSolid;
        if (!report.converged)
            return {Outcome::SolidFailed, "coupling iteration " + std::to_string(it) +
                                              ": the structural Newton solve failed: " + report.message, it};
        solverOutput = toVector(solid.wettedNodeDisplacements());

        std::string note = report.loadCuts > 0 ? "[cure] solid load sub-stepping x" +
                                                     std::to_string(1 << report.loadCuts)
                                               : std::string();
        double relaxation = std::nan("");
        if (rank == 0)
        {
            const auto measure = acceleration::measureConvergence(iterate, solverOutput, params.convergence);
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
            else if (it > 2 && measure.rmsResidual > params.divergenceFactor * firstResidual)
            {
                decision = Diverged;
                std::ostringstream s;
                s << "the interface residual grew from " << firstResidual << " to "
                  << measure.rmsResidual << " m (x" << params.divergenceFactor << ")";
                failure = s.str();
            }
            else
            {
                iterate = accelerator->update(iterate, solverOutput);
                relaxation = accelerator->lastRelaxation();
                if (!accelerator->lastNote().empty())
                    note += (note.empty() ? "" : "; ") + accelerator->lastNote();
            }
            couplingLog << std::setprecision(8) << level << ',' << time << ',' << it << ','
                        << relaxation << ',' << measure.rmsResidual << ',' << measure.relativeResidual
                        << ',' << response.iterations << ',' << response.finalResidual << ','
                        << (response.converged ? 1 : 0) << ',' << report.newtonIterations << ','
                        << wallFluid << ',' << wallSolid << ',' << wallMapping << ',' << note << '\n';
            couplingLog.flush();
            if (verbose)
            {
                char line[320];
                std::snprintf(line, sizeof line,
                              "  [level %d it %2d] |r|/sqrt(n) %.3e  omega %s  fluid %d it (res %.1e)  "
                              "newton %d  wall fluid %.2f s solid %.2f s%s%s",
                              level, it, measure.rmsResidual,
                              std::isnan(relaxation) ? "  -  " : std::to_string(relaxation).substr(0, 6).c_str(),
                              response.iterations, response.finalResidual, report.newtonIterations,
                              wallFluid, wallSolid, note.empty() ? "" : "  ", note.c_str());
                say(line);
            }
            summary.fluidSeconds += wallFluid;
            summary.mappingSeconds += wallMapping;
        }
        MPI_Bcast(&decision, 1, MPI_INT, 0, comm);
        if (decision == Converged)
            return {Outcome::Converged, "", it};
        if (decision == Diverged)
        {
            int length = static_cast<int>(failure.size());
            MPI_Bcast(&length, 1, MPI_INT, 0, comm);
            failure.resize(length);
            MPI_Bcast(failure.data(), length, MPI_CHAR, 0, comm);
            return {Outcome::Diverged, "diverged: " + failure, it};
        }
    }
    MPI_Bcast(&record.residual, 1, MPI_DOUBLE, 0, comm);
    std::ostringstream s;
    s << "did not converge in " << params.maxIterations << " coupling iterations (|r|/sqrt(n) = "
      << record.residual << " m)";
    return {Outcome::Capped, s.str(), params.maxIterations};
}

// A fresh accelerator of the configured type with its relaxation scaled by relaxationScale.
void CoupledDriver::Impl::makeScaledAccelerator()
{
    auto a = params.acceleration;
    a.constant.relaxation *= relaxationScale;
    a.aitken.initialRelaxation *= relaxationScale;
    a.aitken.maxRelaxation = std::max(a.aitken.minRelaxation, a.aitken.maxRelaxation * relaxationScale);
    a.iqnIls.initialRelaxation *= relaxationScale;
    accelerator = acceleration::makeAccelerator(a);
}

// Applies the cure for a failed attempt and says what it did; empty when none applies (then
// nothing was changed).
std::string CoupledDriver::Impl::cure(const Attempt& attempt, TimeSchedule& schedule)
{
    const Outcome outcome = attempt.outcome;
    if (outcome == Outcome::SolidFailed)
    {
        const double before = schedule.lastStep();
        if (schedule.cutStep(params.recovery.stepFactor))
        {
            std::ostringstream s;
            s << "redoing the level with dt = " << schedule.lastStep() << " s (was " << before
              << " s), t = " << schedule.time() << " s";
            return s.str();
        }
        // Level 0 (or no step left to cut): a wild iterate may have caused it; relax harder.
        // Not in the first iteration, whose displacement no relaxation has touched yet.
        if (attempt.iteration <= 1)
            return {};
    }
    relaxationScale *= params.recovery.relaxationFactor;
    makeScaledAccelerator();
    std::ostringstream s;
    s << "redoing the level from its start value with a fresh " << accelerator->name()
      << " accelerator, initial relaxation x" << relaxationScale << " (kept for the rest of the run)";
    return s.str();
}

DriverState CoupledDriver::Impl::state(const LevelRecord& r, double wallSeconds, const RunSummary& summary) const
{
    DriverState d;
    d.level = r.level;
    d.time = r.time;
    d.lastStep = r.dt;
    d.interfaceDisplacement.assign(uLast.data(), uLast.data() + n);
    d.previousInterfaceDisplacement.assign(uBeforeLast.data(), uBeforeLast.data() + n);
    if (rank == 0)
        d.accelerator = accelerator->saveState();
    d.relaxationScale = relaxationScale;
    d.acceptedTimes = acceptedTimes;
    d.couplingIterations = summary.couplingIterations;
    d.fluidIterations = summary.fluidIterations;
    d.factorizations = summary.factorizations + solid.factorizationCount();
    d.wallSeconds = wallSeconds;
    d.fluidSeconds = summary.fluidSeconds;
    d.solidSeconds = summary.solidSeconds;
    d.mappingSeconds = summary.mappingSeconds;
    return d;
}

RunSummary CoupledDriver::run()
{
    auto& m = *impl_;
    const auto runStart = Clock::now();
    RunSummary summary;
    double wallOffset = 0.0;
    const CheckpointStore store(m.comm, m.outputFolder + "/checkpoint", m.params.checkpoint.keep);
    std::optional<CheckpointStore::Loaded> saved;
    if (restart_)
    {
        try
        {
            saved = store.loadLatest();
        }
        catch (const std::exception& e)
        {
            m.fail(e.what());
        }
    }
    m.setUp(saved ? saved->driver.level : -1);
    TimeSchedule schedule(m.params.time, m.relaxationTimes);
    m.say("[driver] " + schedule.describe() + "; acceleration " + m.accelerator->name() +
          ", max " + std::to_string(m.params.maxIterations) + " iterations per level");

    m.n = 3 * static_cast<int>(m.solid.wettedNodes().size());
    const int n = m.n;
    m.uLast = Eigen::VectorXd::Zero(n);
    m.uBeforeLast = m.iterate = m.solverOutput = m.nodalForce = m.uLast;
    // Mapping buffers, sized once (rank 0): the per-iteration applies then allocate nothing.
    if (m.rank == 0)
    {
        m.nodalDisplacement.resize(n / 3, 3);
        m.pointDisplacement.resize(m.displacementMap->targetSize(), 3);
        m.nodalForceRows.resize(n / 3, 3);
    }

    if (saved)
    {
        const DriverState& d = saved->driver;
        std::string error;
        try
        {
            if (static_cast<int>(d.interfaceDisplacement.size()) != n)
                throw std::runtime_error("the checkpoint has " + std::to_string(d.interfaceDisplacement.size() / 3) +
                                         " wetted nodes, this mesh " + std::to_string(n / 3) +
                                         " (same mesh as the checkpointed run?)");
            m.solid.restoreCommittedState(saved->solid);
            m.relaxationScale = d.relaxationScale;
            if (m.relaxationScale != 1.0)
                m.makeScaledAccelerator();
            if (m.rank == 0)
                m.accelerator->loadState(d.accelerator);
            schedule.resume(d.level, d.time, d.lastStep);
        }
        catch (const std::exception& e)
        {
            error = saved->folder + ": " + e.what();
        }
        m.failIfAnyRankFailed(error); // a rank-local failure must stop every rank
        m.uLast = toVector(d.interfaceDisplacement);
        m.uBeforeLast = toVector(d.previousInterfaceDisplacement);
        m.dtLast = d.lastStep;
        m.acceptedTimes = d.acceptedTimes;
        summary.levels = static_cast<int>(d.acceptedTimes.size());
        summary.couplingIterations = d.couplingIterations;
        summary.fluidIterations = d.fluidIterations;
        summary.factorizations = d.factorizations;
        summary.fluidSeconds = d.fluidSeconds;
        summary.solidSeconds = d.solidSeconds;
        summary.mappingSeconds = d.mappingSeconds;
        wallOffset = d.wallSeconds;
        std::ostringstream s;
        s << "[restart] from " << saved->folder << ": level " << d.level << ", t = " << d.time
          << " s, " << d.acceptedTimes.size() << " levels and " << d.wallSeconds << " s of wall time done";
        m.say(s.str());
        if (!schedule.hasNext())
        {
            m.say("[restart] the checkpointed run had already reached its last level; nothing to do");
            m.fluid->finish();
            summary.wallSeconds = wallOffset;
            return summary;
        }
        const double norm = m.uLast.norm();
        schedule.advance(norm > 0 ? (m.uLast - m.uBeforeLast).norm() / norm : 0.0);
    }

    while (true)
    {
        const auto levelStart = Clock::now();
        LevelRecord record;
        int retries = 0;
        while (true)
        {
            record = LevelRecord{};
            record.level = schedule.level();
            record.time = schedule.time();
            record.dt = record.level == 0 ? 0.0 : schedule.lastStep();
            record.retries = retries;
            const auto attempt = m.attemptLevel(record.level, record.time, record.dt, retries == 0,
                                                record, summary, verbose_);
            if (attempt.outcome == Impl::Outcome::Converged)
            {
                record.converged = true;
                break;
            }
            std::ostringstream where;
            where << "level " << record.level << " (t = " << record.time << " s) ";
            if (attempt.outcome == Impl::Outcome::Capped && m.params.continueOnMaxIterations)
            {
                m.say("WARNING: " + where.str() + attempt.diagnosis + "; accepted anyway (on_max_iterations: continue)");
                break;
            }
            if (retries < m.params.recovery.maxRetries)
            {
                m.solid.rejectLevel();
                const std::string cure = m.cure(attempt, schedule);
                if (!cure.empty())
                {
                    ++retries;
                    m.say("[cure " + std::to_string(retries) + "/" + std::to_string(m.params.recovery.maxRetries) +
                          "] " + where.str() + attempt.diagnosis + " -> " + cure);
                    continue;
                }
                m.say("[cure] " + where.str() + "no automatic cure applies to: " + attempt.diagnosis);
            }
            std::string fix;
            switch (attempt.outcome)
            {
            case Impl::Outcome::Capped:
                fix = ": raise coupling.max_iterations, loosen the tolerance, or set on_max_iterations: continue";
                break;
            case Impl::Outcome::Diverged:
                fix = ": lower the initial relaxation or use iqn-ils";
                break;
            default:
                fix = ": smaller time steps (coupling.time) or a softer load; check the material";
            }
            m.fail(where.str() + attempt.diagnosis +
                   (retries ? " (after " + std::to_string(retries) + " automatic retries)" : std::string()) + fix);
        }

        m.accelerator->endLevel();
        m.solid.acceptLevel();
        m.fluid->accept(record.level, record.time);

        const double norm = m.solverOutput.norm();
        record.relativeChange = norm > 0 ? (m.solverOutput - m.uLast).norm() / norm : 0.0;
        for (const auto& w : m.watched)
        {
            const auto& u = m.solid.displacement();
            record.watched.emplace_back(u[3 * w.node], u[3 * w.node + 1], u[3 * w.node + 2]);
        }
        if (m.params.sectionAngle)
            record.sectionAngle = m.sectionAngle();
        record.wallSeconds = wallOffset + secondsSince(runStart);
        if (m.rank == 0)
            m.writeLevel(record, m.solverOutput, m.nodalForce);
        m.acceptedTimes.push_back(record.time);
        if (m.callback)
            m.callback(record);

        summary.history.push_back(record);
        summary.levels += 1;
        {
            std::ostringstream s;
            s << std::setprecision(4) << "[level " << record.level << "] t = " << record.time << " s (dt "
              << record.dt << " s): " << record.couplingIterations << " coupling it, "
              << record.fluidIterations << " fluid it; F = (" << record.force.x() << ", "
              << record.force.y() << ", " << record.force.z() << ") N";
            for (std::size_t i = 0; i < m.watched.size(); ++i)
                s << "; " << m.watched[i].name << " u = (" << record.watched[i].x() << ", "
                  << record.watched[i].y() << ", " << record.watched[i].z() << ") m";
            if (m.params.sectionAngle)
                s << "; " << m.params.sectionAngle->name << " " << record.sectionAngle << " deg";
            if (record.retries)
                s << "; " << record.retries << " automatic retries";
            s << "; level " << secondsSince(levelStart) << " s";
            const double done = schedule.progress();
            if (done > 0 && done < 1)
                s << ", ETA " << std::setprecision(3) << record.wallSeconds * (1 - done) / done << " s";
            m.say(s.str());
        }

        m.uBeforeLast = m.uLast;
        m.uLast = m.solverOutput;
        m.dtLast = record.dt;
        const bool last = !schedule.hasNext();
        const int every = m.params.checkpoint.every;
        if (every > 0 && (record.level % every == 0 || last))
        {
            try
            {
                store.write(m.state(record, record.wallSeconds, summary), m.solid.committedState());
            }
            catch (const std::exception& e)
            {
                m.fail(e.what());
            }
        }
        if (last)
            break;
        schedule.advance(record.relativeChange);
    }
    m.fluid->finish();
    summary.factorizations += m.solid.factorizationCount();
    summary.wallSeconds = wallOffset + secondsSince(runStart);
    return summary;
}

} // namespace fsi::driver
