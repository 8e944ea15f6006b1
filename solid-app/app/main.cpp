// SPDX-License-Identifier: GPL-3.0-or-later
// solid-app CONFIG.yaml [--out DIR] [--restart] [--launch mpmd|port] [--port-file F]
// [--comm-timeout S] solid-app --help
#include "HeapSettings.hpp"
#include "Standalone.hpp"
#include "config/YamlReader.hpp"
#include "driver/RunCoupled.hpp"

#include <mpi.h>

#include <cstdio>
#include <exception>
#include <stdexcept>

int main(int argc, char** argv)
{
    fsi::app::keepLargeBlocksInHeap();
    MPI_Init(&argc, &argv);
    int rank = 0, code = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    try
    {
        fsi::driver::takeLaunchFlags(argc, argv); // --launch, --port-file, --comm-timeout
        const auto options = fsi::app::parseArguments(argc, argv);
        if (options.help)
        {
            if (rank == 0)
                std::printf("%s", fsi::app::usageText().c_str());
        }
        else
        {
            // The YAML is read once: a top-level `coupling:` block selects the coupled mode.
            const auto root = fsi::config::Block::load(options.configFile);
            if (root.has("coupling"))
                code = fsi::driver::runCoupled(root, options.configFile, options.outputFolder,
                                               options.restart);
            else if (options.restart)
                throw std::runtime_error(options.configFile +
                                         ": --restart applies to coupled runs (a config with a "
                                         "'coupling' block) only");
            else
                code = fsi::app::runStandalone(root, options);
        }
    }
    catch (const std::exception& e)
    {
        fsi::driver::endMpmdLaunchOnError(e); // MPMD: the fluid waits for us, end the whole job
        if (rank == 0)
            std::fprintf(stderr, "error: %s\n", e.what());
        code = 1;
    }
    MPI_Finalize();
    return code;
}
