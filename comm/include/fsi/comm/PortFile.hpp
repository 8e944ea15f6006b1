// SPDX-License-Identifier: GPL-3.0-or-later
// The file through which the port-mode server (solid) tells the client (fluid) its MPI port.
// Format (text, one key=value per line after a first line "fsi-comm-port-file 1"):
//   port=<MPI port name>   pid=<server pid>   host=<server hostname>
//   created=<seconds since the epoch, decimal>
#pragma once

#include <string>
#include <sys/types.h>

namespace fsi
{
namespace comm
{

struct PortFileRecord
{
    std::string portName;
    long pid = 0;
    std::string host;
    double createdSeconds = 0.0; // wall clock (epoch) when the server wrote the file
};

std::string formatPortFile(const PortFileRecord& record);
// Throws CommError naming path and the offending line when text is not a complete port file.
PortFileRecord parsePortFile(const std::string& text, const std::string& path);

// Writes the file atomically: write <path>.tmp.<pid>, fsync, rename onto path.
// Throws CommError naming the path on I/O failure.
void writePortFileAtomically(const std::string& path, const PortFileRecord& record);

// Empty when the record can still be live; otherwise a one-line reason why it is stale:
// same host and the pid no longer runs, or the pid runs but started after the file was
// written (pid reused after a crash). Records from another host are assumed live.
std::string staleReason(const PortFileRecord& record);

std::string thisHostName();

// Start time of a running process as epoch seconds (from /proc), negative if unknown.
double processStartSeconds(long pid);

} // namespace comm
} // namespace fsi
