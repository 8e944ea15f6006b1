// SPDX-License-Identifier: GPL-3.0-or-later
#include "fsi/comm/PortFile.hpp"

#include "fsi/comm/Errors.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <iomanip>
#include <signal.h>
#include <sstream>
#include <unistd.h>

namespace fsi::comm
{

namespace
{
constexpr const char* kFirstLine = "fsi-comm-port-file 1";
}

std::string thisHostName()
{
    char name[256] = {};
    if (gethostname(name, sizeof(name) - 1) != 0)
        return "unknown-host";
    return name;
}

std::string formatPortFile(const PortFileRecord& r)
{
    std::ostringstream out;
    out << kFirstLine << "\nport=" << r.portName << "\npid=" << r.pid << "\nhost=" << r.host
        << "\ncreated=" << std::fixed << std::setprecision(3) << r.createdSeconds << "\n";
    return out.str();
}

PortFileRecord parsePortFile(const std::string& text, const std::string& path)
{
    const std::string fix = "; delete it and restart the solid (server) side";
    std::istringstream in(text);
    std::string line;
    if (!std::getline(in, line) || line != kFirstLine)
    {
        throw CommError("port file " + path + ": first line is not '" + kFirstLine +
                        "' (not a port file or written by another version)" + fix);
    }
    PortFileRecord r;
    bool havePort = false, havePid = false, haveHost = false, haveCreated = false;
    while (std::getline(in, line))
    {
        if (line.empty())
            continue;
        const auto eq = line.find('=');
        if (eq == std::string::npos)
        {
            throw CommError("port file " + path + ": line '" + line.substr(0, 60) +
                            "' is not key=value" + fix);
        }
        const std::string key = line.substr(0, eq);
        const std::string value = line.substr(eq + 1);
        try
        {
            std::size_t used = 0;
            if (key == "port")
            {
                r.portName = value;
                havePort = !value.empty();
            }
            else if (key == "pid")
            {
                r.pid = std::stol(value, &used);
                havePid = used == value.size() && r.pid > 0;
            }
            else if (key == "host")
            {
                r.host = value;
                haveHost = !value.empty();
            }
            else if (key == "created")
            {
                r.createdSeconds = std::stod(value, &used);
                haveCreated = used == value.size() && std::isfinite(r.createdSeconds);
            }
            else
            {
                throw CommError("port file " + path + ": unknown key '" + key + "'" + fix);
            }
        }
        catch (const std::logic_error&)
        {
            throw CommError("port file " + path + ": bad value in line '" + line.substr(0, 60) +
                            "'" + fix);
        }
    }
    const char* missing = !havePort      ? "port"
                          : !havePid     ? "pid"
                          : !haveHost    ? "host"
                          : !haveCreated ? "created"
                                         : nullptr;
    if (missing)
    {
        throw CommError("port file " + path + ": key '" + missing + "' missing or invalid" + fix);
    }
    return r;
}

void writePortFileAtomically(const std::string& path, const PortFileRecord& record)
{
    const std::string tmp = path + ".tmp." + std::to_string(getpid());
    const std::string text = formatPortFile(record);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0)
    {
        throw CommError("cannot write port file " + tmp + ": " + std::strerror(errno) +
                        "; check --port-file and that the folder exists and is writable");
    }
    const char* p = text.data();
    std::size_t left = text.size();
    bool ok = true;
    while (left > 0 && ok)
    {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0 && errno == EINTR)
            continue;
        ok = n > 0;
        p += n > 0 ? n : 0;
        left -= n > 0 ? static_cast<std::size_t>(n) : 0;
    }
    ok = ok && ::fsync(fd) == 0;
    ok = (::close(fd) == 0) && ok;
    if (!ok || std::rename(tmp.c_str(), path.c_str()) != 0)
    {
        const std::string why = std::strerror(errno);
        std::remove(tmp.c_str());
        throw CommError("cannot publish port file " + path + ": " + why);
    }
}

double processStartSeconds(long pid)
{
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string content;
    if (!std::getline(stat, content))
        return -1.0;
    // Field 22 (starttime, clock ticks after boot) follows the ')' closing the command name.
    const auto close = content.rfind(')');
    if (close == std::string::npos)
        return -1.0;
    std::istringstream fields(content.substr(close + 2));
    std::string field;
    unsigned long long startTicks = 0;
    for (int i = 3; i <= 22 && fields >> field; ++i)
    {
        if (i == 22)
            startTicks = std::stoull(field);
    }
    std::ifstream procStat("/proc/stat");
    std::string key;
    double bootTime = -1.0;
    while (procStat >> key)
    {
        if (key == "btime")
        {
            procStat >> bootTime;
            break;
        }
    }
    const long ticks = sysconf(_SC_CLK_TCK);
    if (bootTime < 0.0 || ticks <= 0 || startTicks == 0)
        return -1.0;
    return bootTime + static_cast<double>(startTicks) / static_cast<double>(ticks);
}

std::string staleReason(const PortFileRecord& r)
{
    if (r.host != thisHostName())
        return {};
    const std::string who = "pid " + std::to_string(r.pid) + " on " + r.host;
    if (::kill(static_cast<pid_t>(r.pid), 0) != 0 && errno == ESRCH)
    {
        return "the server that wrote it (" + who + ") is no longer running";
    }
    const double started = processStartSeconds(r.pid);
    // 2 s slack: btime and the clock tick make the start time coarse.
    if (started > 0.0 && started > r.createdSeconds + 2.0)
    {
        return "pid " + std::to_string(r.pid) +
               " now belongs to a process started after the file was written (the server crashed)";
    }
    return {};
}

} // namespace fsi::comm
