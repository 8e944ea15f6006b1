// SPDX-License-Identifier: GPL-3.0-or-later
#include "driver/Checkpoint.hpp"

#include "io/Archive.hpp"
#include "io/AtomicFile.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

namespace fsi::driver
{

namespace
{
namespace fs = std::filesystem;

std::string levelFolderName(int level)
{
    char name[32];
    std::snprintf(name, sizeof name, "level_%06d", level);
    return name;
}

std::vector<double> toDoubles(const std::vector<long>& v)
{
    return {v.begin(), v.end()};
}

} // namespace

void throwIfAnyRankFailed(MPI_Comm comm, const std::string& localError)
{
    int rank = 0, size = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &size);
    const int mine = localError.empty() ? size : rank;
    int first = size;
    MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
    if (first == size)
        return;
    int length = rank == first ? static_cast<int>(localError.size()) : 0;
    MPI_Bcast(&length, 1, MPI_INT, first, comm);
    std::string message = rank == first ? localError : std::string(length, ' ');
    MPI_Bcast(message.data(), length, MPI_CHAR, first, comm);
    throw std::runtime_error(message);
}

void CheckpointParameters::validate() const
{
    if (every < 0)
        throw std::runtime_error("coupling.checkpoint.every must be >= 0 (0 = no checkpoints)");
    if (keep < 1)
        throw std::runtime_error("coupling.checkpoint.keep must be >= 1");
}

CheckpointStore::CheckpointStore(MPI_Comm comm, std::string folder, int keep)
    : comm_(comm), folder_(std::move(folder)), keep_(keep)
{
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &size_);
}

void CheckpointStore::write(const DriverState& d, const fe::CommittedState& solid) const
{
    const fs::path dir = fs::path(folder_) / levelFolderName(d.level);
    // Every step is collective: a rank that fails makes all ranks throw the same message.
    const auto step = [&](bool allRanks, const std::function<void()>& action)
    {
        std::string error;
        if (allRanks || rank_ == 0)
        {
            try
            {
                action();
            }
            catch (const std::exception& e)
            {
                error = std::string("checkpoint: ") + e.what();
            }
        }
        throwIfAnyRankFailed(comm_, error);
    };
    step(false, [&] { fs::create_directories(dir); });
    step(true,
         [&]
         {
             io::ArchiveWriter s;
             s.put("ranks", size_);
             s.put("displacement", solid.displacement);
             s.put("external_forces", solid.externalForces);
             s.put("load_factor", solid.loadFactor);
             s.put("cells", solid.cells);
             s.put("history", solid.history);
             s.commit((dir / ("solid_rank_" + std::to_string(rank_) + ".bin")).string());
             if (rank_ != 0)
                 return;
             io::ArchiveWriter w;
             w.put("level", d.level);
             w.put("ranks", size_);
             w.put("time", d.time);
             w.put("last_step", d.lastStep);
             w.put("interface_displacement", d.interfaceDisplacement);
             w.put("previous_interface_displacement", d.previousInterfaceDisplacement);
             w.put("interface_force", d.interfaceForce);
             w.put("previous_interface_force", d.previousInterfaceForce);
             w.put("secant_meta", d.secantMeta);
             w.put("secant_values", d.secantValues);
             w.putText("accelerator_type", d.accelerator.type);
             w.put("accelerator_sizes", toDoubles(d.accelerator.sizes));
             w.put("accelerator_values", d.accelerator.values);
             w.put("relaxation_scale", d.relaxationScale);
             w.put("level_measures", std::vector<double>{d.firstResidual, d.pathError});
             w.put("accepted_times", d.acceptedTimes);
             w.put("totals_int",
                   std::vector<int>{d.couplingIterations, d.fluidIterations, d.factorizations});
             w.put("totals_seconds", std::vector<double>{d.wallSeconds, d.fluidSeconds,
                                                         d.solidSeconds, d.mappingSeconds});
             w.commit((dir / "driver.bin").string());
         });
    step(false,
         [&]
         {
             std::ostringstream latest;
             latest.precision(17);
             latest << "level " << d.level << "\ntime " << d.time << "\nfolder "
                    << levelFolderName(d.level) << "\n";
             io::writeFileAtomically((fs::path(folder_) / "latest").string(), latest.str());
             // Prune. Folders of levels after this one are stale (an earlier, longer run in the
             // same folder, or the levels a restart went back over): remove them, else they would
             // count as the newest and this run's own checkpoints would be pruned. Of the others
             // keep the newest `keep`.
             std::vector<fs::path> levels;
             for (const auto& entry : fs::directory_iterator(folder_))
             {
                 const std::string name = entry.path().filename().string();
                 if (!entry.is_directory() || name.rfind("level_", 0) != 0)
                     continue;
                 if (name > levelFolderName(d.level))
                     fs::remove_all(entry.path());
                 else
                     levels.push_back(entry.path());
             }
             std::sort(levels.begin(), levels.end());
             for (std::size_t i = 0; i + keep_ < levels.size(); ++i)
                 if (levels[i] != dir)
                     fs::remove_all(levels[i]);
         });
}

CheckpointStore::Loaded CheckpointStore::loadLatest() const
{
    Loaded loaded;
    std::string error;
    try
    {
        const std::string latestFile = (fs::path(folder_) / "latest").string();
        std::ifstream in(latestFile);
        if (!in)
            throw std::runtime_error(latestFile + ": no checkpoint to restart from (run without "
                                                  "--restart, or check --out)");
        std::string key, name;
        while (in >> key)
        {
            if (key == "folder")
                in >> name;
            else
                in >> key; // value of level/time: the archives are authoritative
        }
        if (name.empty())
            throw std::runtime_error(latestFile +
                                     ": malformed (no 'folder' line); restart from an "
                                     "older level by editing it, or run from the start");
        loaded.folder = (fs::path(folder_) / name).string();
        const io::ArchiveReader r((fs::path(loaded.folder) / "driver.bin").string());
        DriverState& d = loaded.driver;
        d.level = r.integer("level");
        d.time = r.scalar("time");
        d.lastStep = r.scalar("last_step");
        d.interfaceDisplacement = r.doubles("interface_displacement");
        d.previousInterfaceDisplacement = r.doubles("previous_interface_displacement");
        if (r.has("interface_force"))
            d.interfaceForce = r.doubles("interface_force");
        if (r.has("previous_interface_force"))
            d.previousInterfaceForce = r.doubles("previous_interface_force");
        if (r.has("secant_meta") && r.has("secant_values"))
        {
            d.secantMeta = r.ints("secant_meta");
            d.secantValues = r.doubles("secant_values");
        }
        d.accelerator.type = r.text("accelerator_type");
        for (double s : r.doubles("accelerator_sizes"))
            d.accelerator.sizes.push_back(static_cast<long>(s));
        d.accelerator.values = r.doubles("accelerator_values");
        d.relaxationScale = r.scalar("relaxation_scale");
        if (r.has("level_measures"))
        {
            const auto measures = r.doubles("level_measures");
            if (measures.size() != 2)
                throw std::runtime_error(r.path() + ": malformed level_measures");
            d.firstResidual = measures[0];
            d.pathError = measures[1];
        }
        d.acceptedTimes = r.doubles("accepted_times");
        const auto ti = r.ints("totals_int");
        const auto ts = r.doubles("totals_seconds");
        if (ti.size() != 3 || ts.size() != 4)
            throw std::runtime_error(r.path() + ": malformed run totals");
        d.couplingIterations = ti[0];
        d.fluidIterations = ti[1];
        d.factorizations = ti[2];
        d.wallSeconds = ts[0];
        d.fluidSeconds = ts[1];
        d.solidSeconds = ts[2];
        d.mappingSeconds = ts[3];
        const int ranks = r.integer("ranks");
        for (int k = 0; k < ranks; ++k)
        {
            const io::ArchiveReader s(
                (fs::path(loaded.folder) / ("solid_rank_" + std::to_string(k) + ".bin")).string());
            fe::CommittedState part;
            part.displacement = s.doubles("displacement");
            part.externalForces = s.doubles("external_forces");
            part.loadFactor = s.scalar("load_factor");
            part.cells = s.ints("cells");
            part.history = s.doubles("history");
            loaded.solid.push_back(std::move(part));
        }
    }
    catch (const std::exception& e)
    {
        error = std::string("restart: ") + e.what();
    }
    throwIfAnyRankFailed(comm_, error);
    return loaded;
}

} // namespace fsi::driver
