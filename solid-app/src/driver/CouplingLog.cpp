// SPDX-License-Identifier: GPL-3.0-or-later
#include "driver/CouplingLog.hpp"

#include "driver/CoupledDriver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace fsi::driver
{

void ProgressClock::levelDone(double time, double dt, double wallSeconds)
{
    times_.push_back(time);
    steps_.push_back(dt);
    walls_.push_back(wallSeconds);
}

double ProgressClock::remaining(double endTime, double maxStep) const
{
    const int n = static_cast<int>(times_.size());
    if (n < 2)
        return -1.0;
    const int first = std::max(1, n - 1 - window_); // level 0 (dt = 0) does not count
    const int levels = n - 1 - first;
    if (levels < 1 || !(steps_[first] > 0.0))
        return -1.0;
    const double costPerLevel = (walls_.back() - walls_[first]) / levels;
    const double growth =
        std::clamp(std::pow(steps_.back() / steps_[first], 1.0 / levels), 1.0, 10.0);
    double t = times_.back(), dt = steps_.back();
    int left = 0;
    while (t < endTime * (1 - 1e-12) && left < 100000)
    {
        dt *= growth;
        if (maxStep > 0.0)
            dt = std::min(dt, maxStep);
        t += dt;
        ++left;
    }
    return left * costPerLevel;
}

CouplingLog::CouplingLog(std::string folder, int rank, std::vector<std::string> probeColumns)
    : folder_(std::move(folder)), rank_(rank), probeColumns_(std::move(probeColumns))
{
}

void CouplingLog::open(int restartLevel)
{
    if (rank_ != 0)
        return;
    std::filesystem::create_directories(folder_ + "/interface");
    if (restartLevel >= 0)
        keepRowsUpTo(restartLevel);
    else
        writeHeaders();
}

void CouplingLog::say(const std::string& line) const
{
    if (rank_ != 0)
        return;
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
}

void CouplingLog::writeHeaders()
{
    coupling_.open(folder_ + "/coupling.csv");
    coupling_ << "level,time,iteration,relaxation,rms_residual,relative_residual,fluid_iterations,"
                 "fluid_residual,fluid_converged,fluid_tolerance,newton_iterations,wall_fluid_s,"
                 "wall_solid_s,wall_mapping_s,note\n";
    history_.open(folder_ + "/history.csv");
    history_ << "level,time,dt,coupling_iterations,fluid_iterations,newton_iterations,residual,"
                "converged,Fx,Fy,Fz";
    for (const auto& c : probeColumns_)
        history_ << "," << c;
    history_ << ",relative_change,path_error,wall_s,retries\n";
    if (!coupling_ || !history_)
        throw std::runtime_error("cannot write the coupling logs in " + folder_);
}

// Keeps the header and the rows of levels <= level (first column) of both logs, then appends.
void CouplingLog::keepRowsUpTo(int level)
{
    for (const char* name : {"/coupling.csv", "/history.csv"})
    {
        const std::string file = folder_ + name;
        std::ifstream in(file);
        if (!in)
            throw std::runtime_error(file +
                                     ": missing; a restart needs the logs of the checkpointed "
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
    coupling_.open(folder_ + "/coupling.csv", std::ios::app);
    history_.open(folder_ + "/history.csv", std::ios::app);
    if (!coupling_ || !history_)
        throw std::runtime_error("cannot append to the coupling logs in " + folder_);
}

std::string csvField(const std::string& text)
{
    if (text.find_first_of(",\"\n\r") == std::string::npos)
        return text;
    std::string quoted = "\"";
    for (const char c : text)
        quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + '"';
}

void CouplingLog::iteration(const IterationLine& l)
{
    if (rank_ != 0)
        return;
    coupling_ << std::setprecision(8) << l.level << ',' << l.time << ',' << l.iteration << ','
              << l.relaxation << ',' << l.measure.rmsResidual << ',' << l.measure.relativeResidual
              << ',' << l.fluidIterations << ',' << l.fluidResidual << ','
              << (l.fluidConverged ? 1 : 0) << ',' << l.fluidTolerance << ',' << l.newtonIterations
              << ',' << l.wallFluid << ',' << l.wallSolid << ',' << l.wallMapping << ','
              << csvField(l.note) << '\n';
    coupling_.flush();
    if (!verbose_)
        return;
    char omega[16] = "  -  ";
    if (!std::isnan(l.relaxation))
        std::snprintf(omega, sizeof omega, "%.4f", l.relaxation);
    char tolerance[32] = "";
    if (l.fluidTolerance > 0)
        std::snprintf(tolerance, sizeof tolerance, ", tol %.1e", l.fluidTolerance);
    char line[400];
    std::snprintf(line, sizeof line,
                  "  [level %d it %2d] |r|/sqrt(n) %.3e  omega %s  fluid %d it (res %.1e%s)  "
                  "newton %d  wall fluid %.2f s solid %.2f s%s%s",
                  l.level, l.iteration, l.measure.rmsResidual, omega, l.fluidIterations,
                  l.fluidResidual, tolerance, l.newtonIterations, l.wallFluid, l.wallSolid,
                  l.note.empty() ? "" : "  ", l.note.c_str());
    say(line);
}

void CouplingLog::level(const LevelRecord& r, const std::vector<double>& probeValues,
                        const std::string& probeText, double levelSeconds, double etaSeconds)
{
    if (rank_ != 0)
        return;
    history_ << std::setprecision(10) << r.level << ',' << r.time << ',' << r.dt << ','
             << r.couplingIterations << ',' << r.fluidIterations << ',' << r.newtonIterations << ','
             << r.residual << ',' << (r.converged ? 1 : 0) << ',' << r.force.x() << ','
             << r.force.y() << ',' << r.force.z();
    for (double v : probeValues)
        history_ << ',' << v;
    history_ << ',' << r.relativeChange << ',';
    if (std::isfinite(r.pathError))
        history_ << r.pathError; // empty: unknown (the first two levels)
    history_ << ',' << r.wallSeconds << ',' << r.retries << '\n';
    history_.flush();

    std::ostringstream s;
    s << std::setprecision(4) << "[level " << r.level << "] t = " << r.time << " s (dt " << r.dt
      << " s): " << r.couplingIterations << " coupling it, " << r.fluidIterations
      << " fluid it; F = (" << r.force.x() << ", " << r.force.y() << ", " << r.force.z() << ") N"
      << probeText;
    if (r.retries)
        s << "; " << r.retries << " automatic retries";
    s << "; level " << levelSeconds << " s";
    if (etaSeconds >= 0)
        s << ", ETA " << std::setprecision(3) << etaSeconds << " s";
    say(s.str());
}

void CouplingLog::interfaceState(const LevelRecord& r, const std::vector<double>& x,
                                 const Eigen::VectorXd& u, const Eigen::VectorXd& f) const
{
    if (rank_ != 0)
        return;
    char name[64];
    std::snprintf(name, sizeof name, "/interface/level_%04d.csv", r.level);
    const std::string file = folder_ + name;
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

} // namespace fsi::driver
