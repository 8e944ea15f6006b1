// SPDX-License-Identifier: GPL-3.0-or-later
// How the two programs meet: chosen at run time from command-line flags.
#pragma once

#include <string>
#include <vector>

namespace fsi
{
namespace comm
{

enum class LaunchMode
{
    Port, // two separate mpiruns meeting through MPI_Open_port (needs an ompi-server)
    Mpmd, // one `mpirun -np A fluid : -np B solid`; MPI_COMM_WORLD split by MPI_APPNUM
};

std::string toString(LaunchMode mode); // "port" | "mpmd"

// Largest accepted timeout [s] (about 31 years): the waits add it to a std::chrono clock
// whose nanosecond count overflows near 9.2e9 s.
constexpr double kMaxTimeoutSeconds = 1.0e9;

struct LaunchOptions
{
    LaunchMode mode = LaunchMode::Mpmd;
    // Port mode: file the server (solid) writes its port name to and the client (fluid) reads.
    // Relative paths are relative to the working directory (usually the case folder).
    std::string portFile = "fsi-comm.port";
    // Bound [s] of every blocking wait: peer messages, port file, connect/accept, MPMD split.
    // In (0, kMaxTimeoutSeconds]; Channel::open rejects other values.
    double timeoutSeconds = 600.0;
};

// Flags (both "--flag value" and "--flag=value"):
//   --launch port|mpmd     (default mpmd)
//   --port-file PATH       (default fsi-comm.port; port mode only)
//   --comm-timeout SECONDS (default 600; > 0 and <= kMaxTimeoutSeconds = 1e9)
// Recognised flags are removed from args; other arguments are left in order.
// Throws std::runtime_error with a one-line message naming the flag and the fix.
LaunchOptions parseLaunchOptions(std::vector<std::string>& args);

// Same for main's argc/argv: removes the recognised flags in place (argv[argc] stays nullptr),
// so that OpenFOAM's argList never sees them. argv[0] is kept.
LaunchOptions parseLaunchOptions(int& argc, char** argv);

// One line for --help texts.
std::string launchOptionsUsage();

} // namespace comm
} // namespace fsi
