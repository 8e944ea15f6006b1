// SPDX-License-Identifier: GPL-3.0-or-later
#include "fsi/comm/LaunchOptions.hpp"

#include <cmath>
#include <stdexcept>

namespace fsi::comm
{

std::string toString(LaunchMode mode)
{
    return mode == LaunchMode::Port ? "port" : "mpmd";
}

std::string launchOptionsUsage()
{
    return "--launch port|mpmd [--port-file PATH] [--comm-timeout SECONDS]";
}

namespace
{
double parseSeconds(const std::string& text)
{
    std::size_t used = 0;
    double value = 0.0;
    try
    {
        value = std::stod(text, &used);
    }
    catch (const std::exception&)
    {
        used = 0;
    }
    if (used != text.size() || text.empty() || !std::isfinite(value) || value <= 0.0)
    {
        throw std::runtime_error("--comm-timeout: '" + text +
                                 "' is not a positive number of seconds (e.g. --comm-timeout 600)");
    }
    if (value > kMaxTimeoutSeconds)
        throw std::runtime_error("--comm-timeout: '" + text +
                                 "' is more than the maximum of 1e9 s (31 years); give at most "
                                 "--comm-timeout 1e9");
    return value;
}
} // namespace

LaunchOptions parseLaunchOptions(std::vector<std::string>& args)
{
    LaunchOptions options;
    std::vector<std::string> rest;
    for (std::size_t i = 0; i < args.size(); ++i)
    {
        const std::string& arg = args[i];
        std::string name = arg;
        std::string value;
        bool hasValue = false;
        if (const auto eq = arg.find('='); arg.rfind("--", 0) == 0 && eq != std::string::npos)
        {
            name = arg.substr(0, eq);
            value = arg.substr(eq + 1);
            hasValue = true;
        }
        if (name != "--launch" && name != "--port-file" && name != "--comm-timeout")
        {
            rest.push_back(arg);
            continue;
        }
        if (!hasValue)
        {
            if (i + 1 >= args.size())
            {
                throw std::runtime_error(name + ": missing value (" + launchOptionsUsage() + ")");
            }
            value = args[++i];
        }
        if (name == "--launch")
        {
            if (value == "port")
                options.mode = LaunchMode::Port;
            else if (value == "mpmd")
                options.mode = LaunchMode::Mpmd;
            else
                throw std::runtime_error("--launch: unknown mode '" + value +
                                         "'; use --launch port or --launch mpmd");
        }
        else if (name == "--port-file")
        {
            if (value.empty())
                throw std::runtime_error("--port-file: empty path; give a file in the case folder");
            options.portFile = value;
        }
        else
        {
            options.timeoutSeconds = parseSeconds(value);
        }
    }
    args.swap(rest);
    return options;
}

LaunchOptions parseLaunchOptions(int& argc, char** argv)
{
    std::vector<std::string> args;
    for (int i = 1; i < argc; ++i)
        args.emplace_back(argv[i]);
    const std::vector<std::string> before = args;
    LaunchOptions options = parseLaunchOptions(args);
    // Compact argv in place: the kept arguments are a subsequence of the original ones.
    int out = 1;
    std::size_t k = 0;
    for (int i = 1; i < argc && k < args.size(); ++i)
    {
        if (args[k] == argv[i])
        {
            argv[out++] = argv[i];
            ++k;
        }
    }
    for (int i = out; i < argc; ++i)
        argv[i] = nullptr;
    argc = out;
    return options;
}

} // namespace fsi::comm
