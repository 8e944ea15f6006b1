// SPDX-License-Identifier: GPL-3.0-or-later
// solid-app CONFIG.yaml [--out DIR] [--restart] [--launch mpmd|port] [--port-file F] [--comm-timeout S]
// solid-app --help
#include "Standalone.hpp"

#include <mpi.h>

#include <cstdio>
#include <exception>

#ifdef FSI_HAVE_DRIVER
#include "driver/RunCoupled.hpp" // int fsi::driver::runCoupled(configFile, outputFolder, restart)
#endif

int main(int argc, char** argv)
{
    MPI_Init(&argc, &argv);
    int rank = 0, code = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    try
    {
#ifdef FSI_HAVE_DRIVER
        fsi::driver::takeLaunchFlags(argc, argv); // --launch, --port-file, --comm-timeout
#endif
        const auto options = fsi::app::parseArguments(argc, argv);
        if (options.help)
        {
            if (rank == 0)
                std::printf("%s", fsi::app::usageText().c_str());
        }
        else if (fsi::app::isCoupledConfig(options.configFile))
        {
#ifdef FSI_HAVE_DRIVER
            code = fsi::driver::runCoupled(options.configFile, options.outputFolder, options.restart);
#else
            throw std::runtime_error(options.configFile +
                                     ": has a 'coupling' block but this solid-app "
                                     "was built without the coupling driver");
#endif
        }
        else if (options.restart)
            throw std::runtime_error(options.configFile + ": --restart applies to coupled runs (a config "
                                                          "with a 'coupling' block) only");
        else
            code = fsi::app::runStandalone(options);
    }
    catch (const std::exception& e)
    {
#ifdef FSI_HAVE_DRIVER
        fsi::driver::endMpmdLaunchOnError(e); // MPMD: the fluid waits for us, end the whole job
#endif
        if (rank == 0)
            std::fprintf(stderr, "error: %s\n", e.what());
        code = 1;
    }
    MPI_Finalize();
    return code;
}
