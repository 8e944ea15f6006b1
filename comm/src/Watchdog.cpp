// SPDX-License-Identifier: GPL-3.0-or-later
#include "Watchdog.hpp"

#include "fsi/comm/LaunchOptions.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <unistd.h>

namespace fsi::comm::detail
{

Watchdog::Watchdog(double timeoutSeconds, std::string message, int exitCode, std::string removeFile)
{
    // Saturate: wait_for adds the limit to a clock whose nanosecond count overflows near 9.2e9 s.
    const auto limit = std::chrono::duration<double>(std::min(timeoutSeconds, kMaxTimeoutSeconds));
    thread_ = std::thread(
        [this, limit, exitCode, message = std::move(message), removeFile = std::move(removeFile)]
        {
            std::unique_lock<std::mutex> lock(mutex_);
            if (done_.wait_for(lock, limit, [this] { return disarmed_; }))
                return;
            if (!removeFile.empty())
                ::unlink(removeFile.c_str());
            if (!message.empty())
            {
                const std::string line = "error: " + message + "\n";
                std::fflush(stdout);
                (void)!::write(STDERR_FILENO, line.data(), line.size());
            }
            ::_exit(exitCode);
        });
}

Watchdog::~Watchdog()
{
    {
        std::lock_guard<std::mutex> lock(mutex_);
        disarmed_ = true;
    }
    done_.notify_all();
    thread_.join();
}

} // namespace fsi::comm::detail
