// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app: logging: postProcessing/fsi CSV files and the level fields (see fluidSolidCoupling.H).
#include "fluidSolidCoupling.H"

#include "OFstream.H"

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

Foam::fileName Foam::fluidSolidCoupling::logDir() const
{
    return mesh_.time().globalPath()/"postProcessing"/"fsi";
}


void Foam::fluidSolidCoupling::openCouplingLogs(const bool restart)
{
    if (!Pstream::master())
    {
        return;
    }
    mkDir(logDir());
    const bool append = restart && isFile(logDir()/"coupling.csv");
    logFile_.reset
    (
        new OFstream
        (
            logDir()/"coupling.csv",
            IOstream::ASCII,
            IOstream::currentVersion,
            IOstream::UNCOMPRESSED,
            append
        )
    );
    if (!append)
    {
        logFile_()
            << "step,iteration,simpleIterations,converged,residualU,residualP,"
            << "Fx,Fy,Fz,maxDisplacement,wall_s,exchange_s" << endl;
    }
    if (!restart || !isFile(logDir()/"accepted.csv"))
    {
        OFstream(logDir()/"accepted.csv")() << "step,time,timeName" << endl;
    }
    if (writeSolveIterations_)
    {
        const bool appendIterations = restart && isFile(logDir()/"solveIterations.csv");
        solveIterationLog_.reset
        (
            new OFstream
            (
                logDir()/"solveIterations.csv",
                IOstream::ASCII,
                IOstream::currentVersion,
                IOstream::UNCOMPRESSED,
                appendIterations
            )
        );
        solveIterationLog_().precision(12);
        if (!appendIterations)
        {
            solveIterationLog_()
                << "step,iteration,simpleIteration,Fx,Fy,Fz,residualU,residualP" << nl;
        }
    }
}


void Foam::fluidSolidCoupling::logSolve
(
    const fsi::fluid::Command& solve,
    const SolveResult& r,
    const vector& total,
    const scalar maxDisplacement,
    const scalar wallSeconds,
    const scalar exchangeSeconds
)
{
    if (Pstream::master())
    {
        logFile_()
            << solve.step << ',' << solve.iteration << ',' << r.iterations << ','
            << int(r.converged) << ',' << r.residualU << ',' << r.residualP << ','
            << total.x() << ',' << total.y() << ',' << total.z() << ','
            << maxDisplacement << ',' << wallSeconds << ',' << exchangeSeconds << endl;
    }
}


void Foam::fluidSolidCoupling::logAccepted(const fsi::fluid::Command& accept) const
{
    if (Pstream::master())
    {
        OFstream os
        (
            logDir()/"accepted.csv",
            IOstream::ASCII,
            IOstream::currentVersion,
            IOstream::UNCOMPRESSED,
            true
        );
        os.precision(17);   // the solid checkpoint's time, matched by scripts/fsi-restart-fluid
        os << accept.step << ',' << accept.time << ',' << Time::timeName(accept.time) << endl;
    }
}


namespace
{

// The iteration of one rigidIterations.csv row, or -1 unless the row is whole: an integer and
// the five numbers of the header "iteration,Fx,Fy,Fz,residualU,residualP".
Foam::label rigidLogRowIteration(const std::string& row)
{
    std::istringstream fields(row);
    std::string field;
    std::vector<std::string> parts;
    while (std::getline(fields, field, ','))
    {
        parts.push_back(field);
    }
    if (parts.size() != 6)
    {
        return -1;
    }
    char* end = nullptr;
    const long iteration = std::strtol(parts[0].c_str(), &end, 10);
    if (parts[0].empty() || *end != '\0')
    {
        return -1;
    }
    for (std::size_t i = 1; i < parts.size(); ++i)
    {
        std::strtod(parts[i].c_str(), &end);
        if (parts[i].empty() || *end != '\0')
        {
            return -1;
        }
    }
    return Foam::label(iteration);
}

} // namespace


void Foam::fluidSolidCoupling::openIterationLog()
{
    recordIterations_ = true;
    if (!Pstream::master())
    {
        return;
    }
    mkDir(logDir());
    const fileName csv(logDir()/"rigidIterations.csv");
    const bool resume = rigidStartIteration_ > 0 && isFile(csv);
    if (resume)
    {
        // keep the header and the whole rows up to the restart point: the iterations after it
        // are done again from the written fields; a row torn by the kill is dropped
        std::vector<std::string> kept;
        label dropped = 0;
        std::ifstream in(csv);
        for (std::string line; std::getline(in, line);)
        {
            if (kept.empty())
            {
                kept.push_back(line);   // the header
                continue;
            }
            const label row = rigidLogRowIteration(line);
            if (row > 0 && row <= rigidStartIteration_)
            {
                kept.push_back(line);
            }
            else if (row < 0)
            {
                ++dropped;
            }
        }
        in.close();
        if (dropped > 0)
        {
            Info<< "fsi: " << csv << ": dropped " << dropped
                << " incomplete row(s) left by the stopped run" << endl;
        }
        std::ofstream out(csv, std::ios::trunc);
        for (const std::string& line : kept)
        {
            out << line << '\n';
        }
    }
    iterationLog_.reset
    (
        new OFstream
        (
            csv, IOstream::ASCII, IOstream::currentVersion, IOstream::UNCOMPRESSED, resume
        )
    );
    iterationLog_().precision(12);
    if (!resume)
    {
        iterationLog_() << "iteration,Fx,Fy,Fz,residualU,residualP" << nl;
    }
}


void Foam::fluidSolidCoupling::writeRigidRestartPoint(const label iteration)
{
    if (rigidWriteInterval_ <= 0 || iteration % rigidWriteInterval_ != 0)
    {
        return;
    }
    Time& runTime = const_cast<Time&>(mesh_.time());
    runTime.writeNow();
    Info<< "fsi: rigid solve: fields of iteration " << rigidStartIteration_ + iteration
        << " written (time " << runTime.timeName() << "): a stopped solve goes on from here"
        << endl;
}


void Foam::fluidSolidCoupling::closeIterationLog()
{
    recordIterations_ = false;
    iterationLog_.clear();
}


void Foam::fluidSolidCoupling::recordIteration
(
    const label iteration,
    const vector& force,
    const scalar residualU,
    const scalar residualP
)
{
    if (!recordIterations_ || !Pstream::master())
    {
        return;
    }
    if (iterationLog_.valid())
    {
        iterationLog_() << rigidStartIteration_ + iteration << ',' << force.x() << ','
            << force.y() << ',' << force.z() << ',' << residualU << ',' << residualP << nl;
        if (iteration % 100 == 0)
        {
            iterationLog_().flush();   // a long solve can be watched while it runs
        }
    }
    else if (solveIterationLog_.valid())
    {
        solveIterationLog_() << solveStep_ << ',' << solveIteration_ << ',' << iteration << ','
            << force.x() << ',' << force.y() << ',' << force.z() << ',' << residualU << ','
            << residualP << nl;
        if (iteration % 100 == 0)
        {
            solveIterationLog_().flush();
        }
    }
}


void Foam::fluidSolidCoupling::writeRigidForces
(
    const SolveResult& r,
    const vector& total,
    const vector& pressure
) const
{
    if (!Pstream::master())
    {
        return;
    }
    mkDir(logDir());
    OFstream os(logDir()/"forces.csv");
    os.precision(12);
    const vector viscous(total - pressure);
    os  << "Fx,Fy,Fz,pressureFx,pressureFy,pressureFz,viscousFx,viscousFy,viscousFz,"
        << "simpleIterations,converged,residualU,residualP,clock_s,inTheMean,band,meanChange"
        << nl
        << total.x() << ',' << total.y() << ',' << total.z() << ','
        << pressure.x() << ',' << pressure.y() << ',' << pressure.z() << ','
        << viscous.x() << ',' << viscous.y() << ',' << viscous.z() << ','
        << r.iterations << ',' << int(r.converged) << ',' << r.residualU << ','
        << r.residualP << ',' << mesh_.time().elapsedClockTime() << ','
        << int(r.inTheMean) << ',' << r.band << ',' << r.meanChange << nl;
}


void Foam::fluidSolidCoupling::writeInterfaceGeometry
(
    const fsi::fluid::InterfaceGeometry& geometry
) const
{
    std::vector<double> faceData(6*nGlobalFaces_);
    for (label i = 0; i < nGlobalFaces_ && Pstream::master(); ++i)
    {
        for (label c = 0; c < 3; ++c)
        {
            faceData[6*i + c] = geometry.faceCentres[3*i + c];
            faceData[6*i + 3 + c] = geometry.faceAreaVectors[3*i + c];
        }
    }
    writeInterfaceCsv("interfacePoints.csv", geometry.pointCoordinates, nGlobalPoints_, "i,x,y,z");
    writeInterfaceCsv("interfaceFaces.csv", faceData, nGlobalFaces_, "i,cx,cy,cz,Sx,Sy,Sz");
}


void Foam::fluidSolidCoupling::writeInterfaceCsv
(
    const fileName& name,
    const std::vector<double>& values,
    const label n,
    const std::string& header
) const
{
    if (!Pstream::master() || !writeInterfaceData_)
    {
        return;
    }
    OFstream os(logDir()/name);
    os.precision(17);
    os  << header.c_str() << nl;
    const label width = n ? label(values.size())/n : 0;
    for (label i = 0; i < n; ++i)
    {
        os  << i;
        for (label c = 0; c < width; ++c)
        {
            os  << ',' << values[width*i + c];
        }
        os  << nl;
    }
}


Foam::fileName Foam::fluidSolidCoupling::warmStartFile() const
{
    return mesh_.time().timePath()/"uniform"/"fsiWarmStart";
}


void Foam::fluidSolidCoupling::writeLevel(const scalar time)
{
    Time& runTime = const_cast<Time&>(mesh_.time());
    const scalar iterTime = runTime.value();
    const label iterIndex = runTime.timeIndex();
    runTime.setTime(time, iterIndex);
    Info<< "fsi: writing fields to time " << runTime.timeName() << nl << endl;
    runTime.writeNow();
    if (warmStart_.settings().secant)
    {
        // Snapshots of the newest two levels only (a restart starts from the solid's latest
        // checkpoint, at most one level behind the fluid's); older ones would double the disk
        // use of a run (six flows per level and rank).
        warmStart_.write(warmStartFile());
        warmStartFiles_.push_back(warmStartFile());
        while (warmStartFiles_.size() > 2)
        {
            Foam::rm(warmStartFiles_.front());
            warmStartFiles_.pop_front();
        }
    }
    runTime.setTime(iterTime, iterIndex);
}

// ************************************************************************* //
