// SPDX-License-Identifier: GPL-3.0-or-later
#include "driver/CoupledDriver.hpp"

#include "acceleration/Convergence.hpp"
#include "driver/Checkpoint.hpp"
#include "driver/CouplingLog.hpp"
#include "driver/FluidAccuracy.hpp"
#include "driver/RecoveryPolicy.hpp"
#include "driver/SecantFluidModel.hpp"
#include "mapping/Quality.hpp"
#include "schedule/Registry.hpp"

#include <chrono>
#include <cmath>
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

// Adds the wall seconds of its scope to `total` (also when the scope is left by an exception).
struct ScopedSeconds
{
    double& total;
    Clock::time_point start = Clock::now();
    ~ScopedSeconds() { total += secondsSince(start); }
};

// Wall seconds of one solveSecantModel() (the predictor's note in coupling.csv).
struct SecantCost
{
    double solveSeconds = 0.0;    // solid solves (the base, columns without a response)
    double assemblySeconds = 0.0; // of them, element loops
    double responseSeconds = 0.0; // response columns (StructuralSolver::interfaceResponse)
};

// The interface representation: n x 3, row-major (x, y, z per node or face). The solid's flat
// vectors, the accelerator's 3n vectors, the wire's arrays and mapping::PointCloud share that
// layout, so these are views, not conversions.
using NodeRows = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>;
using MutableNodeRows = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>;

mapping::PointCloud toCloud(const std::vector<double>& xyz)
{
    return NodeRows(xyz.data(), static_cast<Eigen::Index>(xyz.size() / 3), 3);
}

Eigen::VectorXd toVector(const std::vector<double>& v)
{
    return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

// last + ratio (last - beforeLast): the value at t_n + ratio (t_n - t_{n-1}) on the line through
// the last two levels.
Eigen::VectorXd linearExtrapolation(const Eigen::VectorXd& last, const Eigen::VectorXd& beforeLast,
                                    double ratio)
{
    return last + (last - beforeLast) * ratio;
}

// The log line of coupling iteration `iteration` of the level `record`, measures still empty.
IterationLine iterationLine(const LevelRecord& record, int iteration)
{
    IterationLine line;
    line.level = record.level;
    line.time = record.time;
    line.iteration = iteration;
    return line;
}

double rms(const Eigen::VectorXd& v)
{
    return v.size() ? v.norm() / std::sqrt(static_cast<double>(v.size())) : 0.0;
}

// Rank 0's outcome (and its diagnosis) on every rank of comm.
void broadcastOutcome(MPI_Comm comm, std::optional<LevelAttempt>& attempt)
{
    int code = attempt ? static_cast<int>(attempt->outcome) : -1;
    MPI_Bcast(&code, 1, MPI_INT, 0, comm);
    if (code < 0)
    {
        attempt.reset();
        return;
    }
    if (!attempt)
        attempt.emplace();
    attempt->outcome = static_cast<Outcome>(code);
    int length = static_cast<int>(attempt->diagnosis.size());
    MPI_Bcast(&length, 1, MPI_INT, 0, comm);
    attempt->diagnosis.resize(length);
    MPI_Bcast(attempt->diagnosis.data(), length, MPI_CHAR, 0, comm);
}
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
    LevelProbes probes;
    std::function<void(const LevelRecord&)> callback;
    RecoveryPolicy recovery;
    ForcingTerm forcing;
    CouplingLog log;
    ProgressClock progress;
    bool verbose = true;

    std::unique_ptr<mapping::Mapping> displacementMap; // solid nodes -> fluid points (rank 0)
    std::unique_ptr<mapping::Mapping> forceMap;        // solid nodes -> fluid faces (rank 0)
    std::unique_ptr<acceleration::Accelerator> accelerator;

    // Interface vectors (3 per wetted node, all ranks): the accepted u_n, u_{n-1}, the current
    // iterate, the solid's output and the nodal fluid force.
    int n = 0;
    Eigen::VectorXd uLast, uBeforeLast, iterate, solverOutput, nodalForce;
    // The nodal fluid force of the accepted levels n and n-1 (the structural predictors); empty
    // when unknown (before the level, after a restart from an older checkpoint).
    Eigen::VectorXd forceLast, forceBeforeLast;
    // The fluid's loads against its interface input over the last accepted levels (only with
    // coupling.predictor secant or coupling.secant.coupling_iterations; rank 0's column choice
    // is broadcast).
    SecantFluidModel secant{params.secant.maxColumns, params.secant.levels};
    bool secantSamples = params.predictor == "secant" || params.secant.couplingIterations;
    std::string predictorNote; // what the level's predictor did (iteration 1's note)
    double dtLast = 0.0;
    double lastFirstResidual = 0.0; // of the last accepted level [m] (0: none yet)
    mapping::Values nodalDisplacement, pointDisplacement, nodalForceRows; // rank 0 buffers
    std::vector<double> wettedCoordinates; // reference positions of the wetted nodes (set-up)
    std::vector<double> acceptedTimes;
    RunSummary summary;
    Clock::time_point runStart = Clock::now();
    double wallOffset = 0.0; // wall seconds of the run before a restart

    Impl(MPI_Comm c, fe::StructuralSolver& s, FluidPeer* f, CouplingParameters p, std::string out,
         std::vector<double> tau, LevelProbes pr)
        : comm(c), solid(s), fluid(f), params(std::move(p)), outputFolder(std::move(out)),
          relaxationTimes(std::move(tau)), probes(std::move(pr)),
          recovery(params.recovery, params.acceleration),
          forcing(params.fluidAccuracy ? &*params.fluidAccuracy : nullptr),
          log(outputFolder, (MPI_Comm_rank(c, &rank), rank), probeColumns())
    {
    }

    std::vector<std::string> probeColumns() const
    {
        std::vector<std::string> columns;
        for (const auto& p : probes)
            for (auto& c : p->columns())
                columns.push_back(c);
        return columns;
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

    std::optional<CheckpointStore::Loaded> loadCheckpoint(const CheckpointStore& store,
                                                          bool restart);
    void setUp(int restartLevel);
    bool restore(const CheckpointStore::Loaded& saved, schedule::Schedule& schedule);
    LevelRecord solveLevel(schedule::Schedule& schedule);
    LevelAttempt attemptLevel(LevelRecord& record, bool usePredictor);
    std::optional<LevelAttempt> predictFirstIterate(LevelRecord& record, bool usePredictor);
    std::optional<LevelAttempt> predictSecant(LevelRecord& record, bool twoLevels);
    std::optional<SecantFluidModel::Prediction>
    solveSecantModel(LevelRecord& record, SecantFluidModel::Base base, SecantCost* cost = nullptr);
    // The secant model's noise floor [m] (|v|/sqrt(n)): interface differences below the coupling
    // tolerance are the fluid's scatter, not directions (columns and kept perturbations).
    double secantNoiseFloor() const { return params.convergence.absoluteTolerance; }
    std::optional<LevelAttempt> secantStep(LevelRecord& record, IterationLine& line);
    // coupling.secant.min_feedback_margin: whether the model's answer may be used, as rank 0
    // judges it (every rank takes its choice). Collective.
    bool secantTrusted(const std::optional<SecantFluidModel::Prediction>& answer) const;
    FluidAccuracy accuracyFor(int level, int iteration, double lastResidual,
                              bool interfaceConverged) const;
    FluidResponse solveFluid(const LevelRecord& record, int iteration,
                             const FluidAccuracy& accuracy, IterationLine& line);
    std::optional<LevelAttempt> judge(LevelRecord& record, const FluidResponse& response,
                                      const FluidAccuracy& accuracy, double firstResidual,
                                      IterationLine& line);
    void acceptLevel(LevelRecord& record, double levelSeconds, const schedule::Schedule& schedule);
    void checkpoint(const CheckpointStore& store, const LevelRecord& record, bool last);
    DriverState state(const LevelRecord& r) const;
};

CoupledDriver::CoupledDriver(MPI_Comm comm, fe::StructuralSolver& solid, FluidPeer* fluid,
                             CouplingParameters params, std::string outputFolder,
                             std::vector<double> relaxationTimes, LevelProbes probes)
{
    if (!fluid)
        throw std::logic_error("CoupledDriver: every rank needs the fluid peer");
    impl_ = std::make_unique<Impl>(comm, solid, fluid, std::move(params), std::move(outputFolder),
                                   std::move(relaxationTimes), std::move(probes));
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

std::optional<CheckpointStore::Loaded>
CoupledDriver::Impl::loadCheckpoint(const CheckpointStore& store, bool restart)
{
    if (!restart)
        return std::nullopt;
    try
    {
        return store.loadLatest();
    }
    catch (const std::exception& e)
    {
        fail(e.what());
    }
}

void CoupledDriver::Impl::setUp(int restartLevel)
{
    accelerator = recovery.makeAccelerator();
    wettedCoordinates = solid.wettedNodeCoordinates();
    const auto solidNodes = toCloud(wettedCoordinates);
    if (solidNodes.rows() == 0)
        fail("solid mesh: the wetted surface has no nodes (check mesh.wetted)");
    std::string error;
    const auto t0 = Clock::now();
    if (rank == 0)
    {
        try
        {
            const auto& fi = fluid->interface();
            // one source (the wetted nodes, with their faces for nearest-projection) for both:
            // its set-up is shared where it can be, unless the forces have their own strategy
            const mapping::SourceSurface surface{solid.wettedFaces()};
            if (params.forceMapping)
            {
                displacementMap =
                    mapping::buildMapping(params.mapping, solidNodes, fi.points, &surface);
                forceMap = mapping::buildMapping(*params.forceMapping, solidNodes, fi.faceCentres,
                                                 &surface);
            }
            else
            {
                auto maps = mapping::buildMappings(params.mapping, solidNodes,
                                                   {&fi.points, &fi.faceCentres}, &surface);
                displacementMap = std::move(maps[0]);
                forceMap = std::move(maps[1]);
            }
            log.open(restartLevel);
        }
        catch (const std::exception& e)
        {
            error = std::string("interface set-up: ") + e.what();
        }
    }
    failIfAnyRankFailed(error);

    n = 3 * static_cast<int>(solid.wettedNodes().size());
    uLast = Eigen::VectorXd::Zero(n);
    uBeforeLast = iterate = solverOutput = nodalForce = uLast;
    if (rank != 0)
        return;
    // Mapping buffers, sized once: the per-iteration applies then allocate nothing.
    nodalDisplacement.resize(n / 3, 3);
    pointDisplacement.resize(displacementMap->targetSize(), 3);
    nodalForceRows.resize(n / 3, 3);
    const auto& fi = fluid->interface();
    std::ostringstream s;
    s << "[mapping] " << params.mapping.type()
      << (params.forceMapping ? " (forces: " + params.forceMapping->type() + ")" : "") << ": "
      << solidNodes.rows() << " solid wetted nodes, " << fi.points.rows() << " fluid points, "
      << fi.faceCentres.rows() << " fluid faces; set-up " << secondsSince(t0) << " s";
    log.say(s.str());
    log.say("[mapping] points: " +
            mapping::assessQuality(*displacementMap, solidNodes, fi.points).toString());
    log.say("[mapping] faces:  " +
            mapping::assessQuality(*forceMap, solidNodes, fi.faceCentres).toString());
}

// Restart: the solid, the accelerator, the schedule and the run totals from the checkpoint.
// Returns false when the checkpointed run had already reached its last level.
bool CoupledDriver::Impl::restore(const CheckpointStore::Loaded& saved,
                                  schedule::Schedule& schedule)
{
    const DriverState& d = saved.driver;
    std::string error;
    try
    {
        if (static_cast<int>(d.interfaceDisplacement.size()) != n)
            throw std::runtime_error("the checkpoint has " +
                                     std::to_string(d.interfaceDisplacement.size() / 3) +
                                     " wetted nodes, this mesh " + std::to_string(n / 3) +
                                     " (same mesh as the checkpointed run?)");
        solid.restoreCommittedState(saved.solid);
        recovery.restore(d.relaxationScale);
        accelerator = recovery.makeAccelerator();
        if (rank == 0)
            accelerator->loadState(d.accelerator);
        schedule.resume(d.level, d.time, d.lastStep);
        secant.clear();
        if (!d.secantMeta.empty())
            secant.load({d.secantMeta, d.secantValues}, n);
    }
    catch (const std::exception& e)
    {
        error = saved.folder + ": " + e.what();
    }
    failIfAnyRankFailed(error); // a rank-local failure must stop every rank
    uLast = toVector(d.interfaceDisplacement);
    uBeforeLast = toVector(d.previousInterfaceDisplacement);
    forceLast = toVector(d.interfaceForce);
    forceBeforeLast = toVector(d.previousInterfaceForce);
    if (secantSamples && d.secantMeta.empty()) // an older checkpoint: the two levels it holds
        for (const auto& [u, force] :
             {std::pair{&uBeforeLast, &forceBeforeLast}, std::pair{&uLast, &forceLast}})
            if (force->size() == n)
            {
                secant.addSample(*u, *force);
                secant.acceptLevel(secantNoiseFloor());
            }
    dtLast = d.lastStep;
    lastFirstResidual = d.firstResidual;
    acceptedTimes = d.acceptedTimes;
    summary.levels = static_cast<int>(d.acceptedTimes.size());
    summary.couplingIterations = d.couplingIterations;
    summary.fluidIterations = d.fluidIterations;
    summary.factorizations = d.factorizations;
    summary.fluidSeconds = d.fluidSeconds;
    summary.solidSeconds = d.solidSeconds;
    summary.mappingSeconds = d.mappingSeconds;
    wallOffset = d.wallSeconds;
    std::ostringstream s;
    s << "[restart] from " << saved.folder << ": level " << d.level << ", t = " << d.time << " s, "
      << d.acceptedTimes.size() << " levels and " << d.wallSeconds << " s of wall time done";
    log.say(s.str());
    if (!schedule.hasNext())
    {
        log.say("[restart] the checkpointed run had already reached its last level; nothing to do");
        return false;
    }
    const double norm = uLast.norm();
    schedule.advance(norm > 0 ? (uLast - uBeforeLast).norm() / norm : 0.0, d.pathError);
    return true;
}

// The level at the schedule's current time: attempts, and the recovery cures between them.
LevelRecord CoupledDriver::Impl::solveLevel(schedule::Schedule& schedule)
{
    for (int retries = 0;; ++retries)
    {
        LevelRecord record;
        record.level = schedule.level();
        record.time = schedule.time();
        record.dt = record.level == 0 ? 0.0 : schedule.lastStep();
        record.retries = retries;
        const LevelAttempt attempt = attemptLevel(record, retries == 0);
        if (attempt.outcome == Outcome::Converged)
        {
            record.converged = true;
            return record;
        }
        std::ostringstream where;
        where << "level " << record.level << " (t = " << record.time << " s) ";
        if (attempt.outcome == Outcome::Capped && params.continueOnMaxIterations)
        {
            log.say("WARNING: " + where.str() + attempt.diagnosis +
                    "; accepted anyway (on_max_iterations: continue)");
            return record;
        }
        std::string cure;
        if (retries < recovery.maxRetries())
        {
            solid.rejectLevel();
            cure = recovery.cure(attempt, schedule, accelerator);
            if (cure.empty())
                log.say("[cure] " + where.str() +
                        "no automatic cure applies to: " + attempt.diagnosis);
        }
        if (cure.empty())
            fail(where.str() + attempt.diagnosis +
                 (retries ? " (after " + std::to_string(retries) + " automatic retries)"
                          : std::string()) +
                 RecoveryPolicy::fixFor(attempt.outcome));
        log.say("[cure " + std::to_string(retries + 1) + "/" +
                std::to_string(recovery.maxRetries()) + "] " + where.str() + attempt.diagnosis +
                " -> " + cure);
    }
}

// The accuracy asked of the fluid for coupling iteration `iteration` of level `level` (rank 0
// decides). lastResidual: |r|/sqrt(n) of the previous iteration (or, at a level's first, of the
// previous level's first iteration: what a good predictor leaves); interfaceConverged: the
// interface met its tolerance on a loose flow, so this solve must be final. The run's first
// solve (from rest, nothing known) is the loosest; the first solve of level 1 is final, since
// level 0's first residual measured the distance from the undeformed interface, not a
// predictor's miss.
FluidAccuracy CoupledDriver::Impl::accuracyFor(int level, int iteration, double lastResidual,
                                               bool interfaceConverged) const
{
    if (interfaceConverged || (iteration == 1 && level == 1))
        return forcing.finalAccuracy();
    const double expected = iteration == 1 && lastFirstResidual <= 0.0 ? -1.0 : lastResidual;
    return forcing.forIterate(expected, rms(iterate));
}

// One try at a level: coupling iterations until convergence, the cap, divergence or a failed
// structural solve. Leaves the solid with the level's last solve (accepted by the caller).
LevelAttempt CoupledDriver::Impl::attemptLevel(LevelRecord& record, bool usePredictor)
{
    secant.clearResponses(); // the solid's operator of this attempt (dt) is a new one
    // A retried level (a recovery cure) iterates with the accelerator alone.
    const bool secantIterations = params.secant.couplingIterations && usePredictor;
    predictorNote.clear();
    if (auto failed = predictFirstIterate(record, usePredictor))
        return *failed;
    accelerator->beginLevel();
    double lastResidual = lastFirstResidual;
    bool interfaceConverged = false;
    for (int it = 1; it <= params.maxIterations; ++it)
    {
        IterationLine line = iterationLine(record, it);
        if (it == 1)
            line.note = predictorNote;
        const FluidAccuracy accuracy =
            accuracyFor(record.level, it, lastResidual, interfaceConverged);
        const FluidResponse response = solveFluid(record, it, accuracy, line);

        const auto t0 = Clock::now();
        const auto report =
            solid.solve({record.time, record.dt},
                        {std::vector<double>(nodalForce.data(), nodalForce.data() + n)});
        line.wallSolid = secondsSince(t0);
        line.newtonIterations = report.newtonIterations;
        record.newtonIterations += report.newtonIterations;
        record.couplingIterations = it;
        summary.couplingIterations += 1;
        summary.solidSeconds += line.wallSolid;
        if (!report.converged)
            return {Outcome::SolidFailed,
                    "coupling iteration " + std::to_string(it) +
                        ": the structural Newton solve failed: " + report.message,
                    it};
        solverOutput = toVector(solid.wettedNodeDisplacements());
        if (params.secant.couplingIterations)
            secant.setNewestResponse(solverOutput);
        if (report.loadCuts > 0)
            line.note = "[cure] solid load sub-stepping x" + std::to_string(1 << report.loadCuts) +
                        (line.note.empty() ? "" : "; " + line.note);

        auto outcome =
            judge(record, response, accuracy, it == 1 ? -1.0 : record.firstResidual, line);
        broadcastOutcome(comm, outcome);
        if (!outcome && secantIterations)
            outcome = secantStep(record, line);
        log.iteration(line);
        if (outcome)
            return {outcome->outcome, outcome->diagnosis, it};
        lastResidual = line.measure.rmsResidual;
        interfaceConverged = line.measure.converged;
    }
    MPI_Bcast(&record.residual, 1, MPI_DOUBLE, 0, comm);
    std::ostringstream s;
    s << "did not converge in " << params.maxIterations
      << " coupling iterations (|r|/sqrt(n) = " << record.residual << " m)";
    return {Outcome::Capped, s.str(), params.maxIterations};
}

// The level's first iterate (coupling.predictor): the last accepted interface (constant, and
// whenever too few levels are known), its linear extrapolation in time (linear), or the solid at
// the new time under the last level's interface loads (structural: the creep increment under
// frozen loads) or under loads extrapolated linearly from the last two levels
// (structural-linear). A failed structural solve ends the attempt (then the recovery cures).
std::optional<LevelAttempt> CoupledDriver::Impl::predictFirstIterate(LevelRecord& record,
                                                                     bool usePredictor)
{
    iterate = uLast;
    const bool twoLevels = record.level >= 2 && dtLast > 0.0;
    const std::string& kind = params.predictor;
    if (!usePredictor || record.level == 0 || kind == "constant")
        return std::nullopt;
    if (kind == "linear")
    {
        if (twoLevels)
            iterate = linearExtrapolation(uLast, uBeforeLast, record.dt / dtLast);
        return std::nullopt;
    }
    if (kind == "secant")
        return predictSecant(record, twoLevels);
    if (forceLast.size() != n)
        return std::nullopt; // restarted from a checkpoint without interface forces
    Eigen::VectorXd load = forceLast;
    if (kind == "structural-linear" && twoLevels && forceBeforeLast.size() == n)
        load = linearExtrapolation(forceLast, forceBeforeLast, record.dt / dtLast);
    const auto t0 = Clock::now();
    const auto report =
        solid.solve({record.time, record.dt}, {std::vector<double>(load.data(), load.data() + n)});
    summary.solidSeconds += secondsSince(t0);
    record.newtonIterations += report.newtonIterations;
    if (!report.converged)
        return LevelAttempt{Outcome::SolidFailed,
                            "the structural predictor's solve failed: " + report.message, 0};
    iterate = toVector(solid.wettedNodeDisplacements());
    return std::nullopt;
}

// The solid at the level's time coupled to the secant model of the fluid expanded about `base`
// (collective: rank 0's column choice is broadcast). nullopt when the model has no column or is
// degenerate; columns below secantNoiseFloor() are not used. Throws std::runtime_error when a
// solid solve fails.
std::optional<SecantFluidModel::Prediction>
CoupledDriver::Impl::solveSecantModel(LevelRecord& record, SecantFluidModel::Base base,
                                      SecantCost* cost)
{
    std::vector<int> columns = secant.selectColumns(base, secantNoiseFloor());
    int count = static_cast<int>(columns.size());
    MPI_Bcast(&count, 1, MPI_INT, 0, comm);
    columns.resize(count);
    MPI_Bcast(columns.data(), count, MPI_INT, 0, comm);
    SecantCost spent;
    const auto solveSolid = [&](const Eigen::VectorXd& load)
    {
        ScopedSeconds timer{spent.solveSeconds};
        const auto report = solid.solve({record.time, record.dt},
                                        {std::vector<double>(load.data(), load.data() + n)});
        record.newtonIterations += report.newtonIterations;
        spent.assemblySeconds += report.assemblySeconds;
        if (!report.converged)
            throw std::runtime_error(report.message);
        return toVector(solid.wettedNodeDisplacements());
    };
    // The predictor's columns need predictor accuracy only: linear solves without residual
    // assembly (coupling.secant.response_tolerance) where the solid is linear in its loads.
    SecantFluidModel::SolidResponse respond;
    SecantFluidModel::SolidSolveWithResponse solveAndRespond;
    if (base == SecantFluidModel::Base::Accepted && params.secant.responseTolerance > 0.0 &&
        solid.linearInLoads())
    {
        respond = [&](const Eigen::MatrixXd& loadChanges)
        {
            ScopedSeconds timer{spent.responseSeconds};
            return Eigen::MatrixXd(
                solid.interfaceResponse(loadChanges, params.secant.responseTolerance));
        };
        // the base solve with the columns riding along (one set of MUMPS solve phases)
        solveAndRespond = [&](const Eigen::VectorXd& load, const Eigen::MatrixXd& loadChanges)
        {
            ScopedSeconds timer{spent.solveSeconds};
            Eigen::MatrixXd responses;
            const auto report = solid.solveWithResponse(
                {record.time, record.dt}, {std::vector<double>(load.data(), load.data() + n)},
                loadChanges, params.secant.responseTolerance, responses);
            record.newtonIterations += report.newtonIterations;
            spent.assemblySeconds += report.assemblySeconds;
            if (!report.converged)
                throw std::runtime_error(report.message);
            return std::make_pair(toVector(solid.wettedNodeDisplacements()), responses);
        };
    }
    ScopedSeconds solidTime{summary.solidSeconds};
    auto prediction = secant.predict(columns, solveSolid, base, respond, solveAndRespond);
    if (cost)
        *cost = spent;
    return prediction;
}

// coupling.predictor secant: the solid at the new time coupled to the secant model of the fluid
// (SecantFluidModel.hpp); the linear extrapolation while the model has no column or is degenerate.
std::optional<LevelAttempt> CoupledDriver::Impl::predictSecant(LevelRecord& record, bool twoLevels)
{
    std::optional<SecantFluidModel::Prediction> prediction;
    SecantCost cost;
    try
    {
        prediction = solveSecantModel(record, SecantFluidModel::Base::Accepted, &cost);
    }
    catch (const std::runtime_error& e)
    {
        return LevelAttempt{Outcome::SolidFailed,
                            std::string("the secant predictor's solid solve failed: ") + e.what(),
                            0};
    }
    const bool trusted = secantTrusted(prediction);
    if (prediction)
    {
        std::ostringstream note;
        note << std::setprecision(3) << "secant predictor (" << prediction->columns << " columns; "
             << prediction->solidSolves << " solid solves " << cost.solveSeconds << " s (assembly "
             << cost.assemblySeconds << " s), " << prediction->responseColumns
             << " response columns " << cost.responseSeconds << " s"
             << (prediction->responseColumns > 0 && cost.responseSeconds == 0.0
                     ? " apart: solved with the base solve"
                     : "")
             << "; feedback margin " << prediction->feedbackMargin << ")";
        if (!trusted)
            note << " not trusted (margin < secant.min_feedback_margin "
                 << params.secant.minFeedbackMargin
                 << "): " << (twoLevels ? "linear extrapolation" : "the last level's interface");
        predictorNote = note.str();
    }
    if (trusted)
        iterate = prediction->displacement;
    else if (twoLevels)
        iterate = linearExtrapolation(uLast, uBeforeLast, record.dt / dtLast);
    return std::nullopt;
}

bool CoupledDriver::Impl::secantTrusted(
    const std::optional<SecantFluidModel::Prediction>& answer) const
{
    int trusted = answer && answer->feedbackMargin >= params.secant.minFeedbackMargin;
    MPI_Bcast(&trusted, 1, MPI_INT, 0, comm);
    return trusted != 0;
}

// coupling.secant.coupling_iterations: the next iterate is the solid coupled to the secant model
// expanded about this iteration's fluid solve (collective). Columns closer to the newest solve
// than the convergence tolerance are noise of the fluid's accuracy and are not used. Without a
// usable model the accelerator's iterate (judge()) stands.
std::optional<LevelAttempt> CoupledDriver::Impl::secantStep(LevelRecord& record,
                                                            IterationLine& line)
{
    std::optional<SecantFluidModel::Prediction> step;
    try
    {
        step = solveSecantModel(record, SecantFluidModel::Base::Newest);
    }
    catch (const std::runtime_error& e)
    {
        return LevelAttempt{Outcome::SolidFailed,
                            std::string("the secant step's solid solve failed: ") + e.what()};
    }
    if (!step)
        return std::nullopt;
    if (!secantTrusted(step))
    {
        std::ostringstream note;
        note << std::setprecision(3) << "secant step not trusted (feedback margin "
             << step->feedbackMargin << " < secant.min_feedback_margin): the accelerator's iterate";
        line.note = note.str() + (line.note.empty() ? "" : "; " + line.note);
        return std::nullopt;
    }
    iterate = step->displacement;
    line.relaxation = std::nan("");
    std::ostringstream note;
    note << "secant step (" << step->columns << " columns, " << step->solidSolves
         << " solid solves)";
    line.note = note.str() + (line.note.empty() ? "" : "; " + line.note);
    return std::nullopt;
}

// Maps the iterate to the fluid, solves the flow to `accuracy`, maps the forces back to
// nodalForce (broadcast to every rank).
FluidResponse CoupledDriver::Impl::solveFluid(const LevelRecord& record, int iteration,
                                              const FluidAccuracy& accuracy, IterationLine& line)
{
    auto t0 = Clock::now();
    if (rank == 0)
    {
        nodalDisplacement = NodeRows(iterate.data(), n / 3, 3);
        displacementMap->applyConsistent(nodalDisplacement, pointDisplacement);
        line.wallMapping += secondsSince(t0);
    }
    t0 = Clock::now();
    FluidResponse response =
        fluid->solve(record.level, iteration, record.time, pointDisplacement, accuracy);
    line.wallFluid = secondsSince(t0);
    if (rank == 0)
    {
        t0 = Clock::now();
        forceMap->applyConservative(response.faceForces, nodalForceRows);
        MutableNodeRows(nodalForce.data(), n / 3, 3) = nodalForceRows;
        line.wallMapping += secondsSince(t0);
        line.fluidIterations = response.iterations;
        line.fluidResidual = response.finalResidual;
        line.fluidConverged = response.converged;
        line.fluidTolerance = accuracy.driverControlled ? accuracy.forceTolerance : 0.0;
        if (response.band > 0)
        {
            std::ostringstream note;
            note << std::setprecision(2) << "fluid converged in the mean (no steady state; band +-"
                 << 100 * response.band << " %)";
            line.note += (line.note.empty() ? "" : "; ") + note.str();
        }
        summary.fluidIterations += response.iterations;
        summary.fluidSeconds += line.wallFluid;
        summary.mappingSeconds += line.wallMapping;
    }
    MPI_Bcast(nodalForce.data(), n, MPI_DOUBLE, 0, comm);
    if (secantSamples)
    {
        // The accelerator updates the iterate on rank 0 only; the secant model needs it on every
        // rank (its predictions call the distributed solid).
        MPI_Bcast(iterate.data(), n, MPI_DOUBLE, 0, comm);
        secant.addSample(iterate, nodalForce);
    }
    return response;
}

// Rank 0: the convergence test of one coupling iteration and, unless the level ends here, the
// accelerator's next iterate. Returns the level's outcome when it ends (other ranks: nullopt).
// firstResidual: the level's first |r|/sqrt(n) (< 0 in its first iteration).
std::optional<LevelAttempt> CoupledDriver::Impl::judge(LevelRecord& record,
                                                       const FluidResponse& response,
                                                       const FluidAccuracy& accuracy,
                                                       double firstResidual, IterationLine& line)
{
    line.relaxation = std::nan("");
    if (rank != 0)
        return std::nullopt;
    record.force = response.faceForces.colwise().sum().transpose();
    record.fluidIterations += response.iterations;
    // A flow accepted in the mean answers only to its band: the tolerance follows it.
    const auto tolerances = params.convergence.widenedForBand(response.band, rms(solverOutput));
    line.measure = acceleration::measureConvergence(iterate, solverOutput, tolerances);
    if (tolerances.absoluteTolerance != params.convergence.absoluteTolerance ||
        tolerances.relativeTolerance != params.convergence.relativeTolerance)
        line.note += (line.note.empty() ? "" : "; ") +
                     ("tolerance widened to the band: " + tolerances.describe());
    const double r = line.measure.rmsResidual;
    record.residual = r;
    if (firstResidual < 0)
        record.firstResidual = r;
    if (!line.measure.finite)
        return LevelAttempt{Outcome::Diverged,
                            "diverged: the interface residual is not finite (NaN/inf)"};
    const bool flowFinal = accuracy.isFinal && response.converged;
    if (line.measure.converged && flowFinal)
        return LevelAttempt{Outcome::Converged, ""};
    if (firstResidual >= 0 && r > params.divergenceFactor * firstResidual && line.iteration > 2)
    {
        std::ostringstream s;
        s << "diverged: the interface residual grew from " << firstResidual << " to " << r
          << " m (x" << params.divergenceFactor << ")";
        return LevelAttempt{Outcome::Diverged, s.str()};
    }
    iterate = accelerator->update(iterate, solverOutput);
    line.relaxation = accelerator->lastRelaxation();
    std::string note = accelerator->lastNote();
    if (line.measure.converged)
        note += std::string(note.empty() ? "" : "; ") + "interface converged on a " +
                (response.converged ? "loose" : "capped") +
                " flow: once more at the final accuracy";
    if (!note.empty())
        line.note += (line.note.empty() ? "" : "; ") + note;
    return std::nullopt;
}

void CoupledDriver::Impl::acceptLevel(LevelRecord& record, double levelSeconds,
                                      const schedule::Schedule& schedule)
{
    accelerator->endLevel();
    solid.acceptLevel();
    fluid->accept(record.level, record.time);
    secant.acceptLevel(secantNoiseFloor());

    const double norm = solverOutput.norm();
    record.relativeChange = norm > 0 ? (solverOutput - uLast).norm() / norm : 0.0;
    if (record.level >= 2 && dtLast > 0.0 && norm > 0)
        record.pathError =
            (solverOutput - linearExtrapolation(uLast, uBeforeLast, record.dt / dtLast)).norm() /
            norm;
    MPI_Bcast(&record.firstResidual, 1, MPI_DOUBLE, 0, comm);
    std::string probeText;
    for (const auto& p : probes)
    {
        const auto values = p->values(solid);
        record.probes.insert(record.probes.end(), values.begin(), values.end());
        const std::string text = p->describe(values);
        if (!text.empty())
            probeText += "; " + text;
    }
    record.wallSeconds = wallOffset + secondsSince(runStart);
    log.interfaceState(record, wettedCoordinates, solverOutput, nodalForce);
    acceptedTimes.push_back(record.time);
    if (callback)
        callback(record);
    summary.history.push_back(record);
    summary.levels += 1;
    progress.levelDone(record.time, record.dt, record.wallSeconds);
    const double eta =
        schedule.hasNext() ? progress.remaining(schedule.endTime(), schedule.maxStep()) : -1.0;
    log.level(record, record.probes, probeText, levelSeconds, eta);

    uBeforeLast = uLast;
    uLast = solverOutput;
    forceBeforeLast = forceLast;
    forceLast = nodalForce;
    dtLast = record.dt;
    lastFirstResidual = record.firstResidual;
}

void CoupledDriver::Impl::checkpoint(const CheckpointStore& store, const LevelRecord& record,
                                     bool last)
{
    const int every = params.checkpoint.every;
    if (every <= 0 || (record.level % every != 0 && !last))
        return;
    try
    {
        store.write(state(record), solid.committedState());
    }
    catch (const std::exception& e)
    {
        fail(e.what());
    }
}

DriverState CoupledDriver::Impl::state(const LevelRecord& r) const
{
    DriverState d;
    d.level = r.level;
    d.time = r.time;
    d.lastStep = r.dt;
    d.interfaceDisplacement.assign(uLast.data(), uLast.data() + n);
    d.previousInterfaceDisplacement.assign(uBeforeLast.data(), uBeforeLast.data() + n);
    d.interfaceForce.assign(forceLast.data(), forceLast.data() + forceLast.size());
    d.previousInterfaceForce.assign(forceBeforeLast.data(),
                                    forceBeforeLast.data() + forceBeforeLast.size());
    if (secantSamples)
    {
        auto samples = secant.save();
        d.secantMeta = std::move(samples.meta);
        d.secantValues = std::move(samples.values);
    }
    if (rank == 0)
        d.accelerator = accelerator->saveState();
    d.relaxationScale = recovery.relaxationScale();
    d.firstResidual = r.firstResidual;
    d.pathError = r.pathError;
    d.acceptedTimes = acceptedTimes;
    d.couplingIterations = summary.couplingIterations;
    d.fluidIterations = summary.fluidIterations;
    d.factorizations = summary.factorizations + solid.factorizationCount();
    d.wallSeconds = r.wallSeconds;
    d.fluidSeconds = summary.fluidSeconds;
    d.solidSeconds = summary.solidSeconds;
    d.mappingSeconds = summary.mappingSeconds;
    return d;
}

RunSummary CoupledDriver::run()
{
    auto& m = *impl_;
    m.runStart = Clock::now();
    m.log.setVerbose(verbose_);
    const CheckpointStore store(m.comm, m.outputFolder + "/checkpoint", m.params.checkpoint.keep);
    const auto saved = m.loadCheckpoint(store, restart_);
    m.setUp(saved ? saved->driver.level : -1);
    const auto timeLevels = schedule::makeSchedule(m.params.time, m.relaxationTimes);
    schedule::Schedule& schedule = *timeLevels;
    m.log.say("[driver] " + schedule.describe() + "; acceleration " + m.accelerator->name() +
              ", max " + std::to_string(m.params.maxIterations) + " iterations per level");
    m.log.say("[driver] " + m.forcing.describe());
    bool levelsLeft = true;
    if (saved)
        levelsLeft = m.restore(*saved, schedule);
    while (levelsLeft)
    {
        const auto levelStart = Clock::now();
        LevelRecord record = m.solveLevel(schedule);
        m.acceptLevel(record, secondsSince(levelStart), schedule);
        levelsLeft = schedule.hasNext();
        m.checkpoint(store, record, !levelsLeft);
        if (levelsLeft)
            schedule.advance(record.relativeChange, record.pathError);
    }
    m.fluid->finish();
    m.summary.factorizations += m.solid.factorizationCount();
    m.summary.wallSeconds = m.wallOffset + secondsSince(m.runStart);
    return m.summary;
}

} // namespace fsi::driver
