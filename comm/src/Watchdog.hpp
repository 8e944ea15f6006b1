// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: bounds MPI calls that cannot time out by themselves (connect/accept, the MPMD
// split, intercommunicator creation, disconnect). If the guarded scope is still running after
// the timeout, a helper thread prints the message and ends the process with _exit (no MPI call
// from the helper thread, so MPI_THREAD_FUNNELED suffices). mpirun then stops the job.
#pragma once

#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace fsi::comm::detail
{

class Watchdog
{
public:
    // message is printed as "error: <message>" when the watchdog fires (empty = silent);
    // removeFile (if not empty) is deleted first (the server's port file).
    Watchdog(double timeoutSeconds, std::string message, int exitCode, std::string removeFile = {});
    ~Watchdog(); // disarms
    Watchdog(const Watchdog&) = delete;
    Watchdog& operator=(const Watchdog&) = delete;

private:
    std::mutex mutex_;
    std::condition_variable done_;
    bool disarmed_ = false;
    std::thread thread_;
};

} // namespace fsi::comm::detail
