// SPDX-License-Identifier: GPL-3.0-or-later
//
// What a coupled run tells its user, in one place (rank 0 writes, other ranks do nothing):
//   OUT/coupling.csv          one row per coupling iteration
//   OUT/history.csv           one row per accepted level (+ the probes' columns)
//   OUT/interface/level_NNNN.csv   wetted node positions, displacement and nodal force [m, N]
//   the console               "[level L it I] ..." per iteration, "[level L] ..." per level
// On restart the rows of levels after the checkpointed one are dropped and the files appended.
#pragma once

#include "acceleration/Convergence.hpp"

#include <Eigen/Core>

#include <fstream>
#include <string>
#include <vector>

namespace fsi::driver
{

struct LevelRecord;

// One coupling iteration as logged.
struct IterationLine
{
    int level = 0;
    double time = 0.0; // [s]
    int iteration = 0;
    double relaxation = 0.0; // NaN: no relaxation step (converged, diverged, quasi-Newton)
    acceleration::ConvergenceMeasure measure;
    int fluidIterations = 0;
    double fluidResidual = 0.0;
    bool fluidConverged = false;
    double fluidTolerance = 0.0; // force tolerance asked of the fluid (0: its own controls)
    int newtonIterations = 0;
    double wallFluid = 0.0, wallSolid = 0.0, wallMapping = 0.0; // [s]
    std::string note;
};

// A CSV field (RFC 4180): as is, or in double quotes (quotes doubled) when it holds a comma, a
// quote or a line break. The notes of coupling.csv are free text.
std::string csvField(const std::string& text);

// Remaining wall time of a run: the levels still needed to reach the end time if the step keeps
// growing as it did over the last `window` levels (at most to maxStep), times the recent wall
// time per level. With a constant step this is the simulated time to go times the recent cost
// per simulated second; with geometrically growing steps it counts the (few) large levels left
// instead of extrapolating the cost of the small early ones.
class ProgressClock
{
public:
    explicit ProgressClock(int window = 3) : window_(window) {}
    // A level of step dt [s] reached simulated time `time` [s] after `wallSeconds` in all.
    void levelDone(double time, double dt, double wallSeconds);
    // Estimated wall seconds until `endTime`; maxStep [s] caps the step (0: none); negative
    // when unknown (fewer than two levels).
    double remaining(double endTime, double maxStep) const;

private:
    int window_;
    std::vector<double> times_, steps_, walls_;
};

class CouplingLog
{
public:
    // probeColumns: extra history.csv columns (LevelProbe::columns of every probe, in order).
    CouplingLog(std::string folder, int rank, std::vector<std::string> probeColumns);

    // Rank 0: new files with headers (restartLevel < 0) or keep the rows of levels <=
    // restartLevel and append. Throws std::runtime_error naming the file.
    void open(int restartLevel);
    void setVerbose(bool verbose) { verbose_ = verbose; }

    // Rank 0 prints the line (and flushes).
    void say(const std::string& line) const;
    void iteration(const IterationLine& line);
    // probeValues: in probeColumns order; probeText: what the console line says of them.
    void level(const LevelRecord& record, const std::vector<double>& probeValues,
               const std::string& probeText, double levelSeconds, double etaSeconds);
    // Interface state of an accepted level (flat xyz per wetted node).
    void interfaceState(const LevelRecord& record, const std::vector<double>& nodes,
                        const Eigen::VectorXd& displacement, const Eigen::VectorXd& force) const;

private:
    void writeHeaders();
    void keepRowsUpTo(int level);
    std::string folder_;
    int rank_;
    std::vector<std::string> probeColumns_;
    bool verbose_ = true;
    std::ofstream coupling_, history_;
};

} // namespace fsi::driver
