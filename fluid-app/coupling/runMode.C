// SPDX-License-Identifier: GPL-3.0-or-later
// fluid-app: the run mode, resolved once (see runMode.H).
#include "runMode.H"

#include "IFstream.H"
#include "dictionary.H"
#include "fileName.H"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace
{

bool hasFlag(int argc, char* argv[], const char* flag)
{
    for (int i = 1; i < argc; ++i)
    {
        if (std::strcmp(argv[i], flag) == 0)
        {
            return true;
        }
    }
    return false;
}

[[noreturn]] void fail(const std::string& message)
{
    std::fprintf(stderr, "error: fluid-app: %s\n", message.c_str());
    std::exit(1);
}

} // namespace


const char* fsi::fluid::toString(const RunMode mode)
{
    switch (mode)
    {
        case RunMode::rigid: return "rigid";
        case RunMode::prescribed: return "prescribed";
        case RunMode::coupled: break;
    }
    return "coupled";
}


fsi::fluid::RunMode fsi::fluid::resolveRunMode(int argc, char* argv[])
{
    for (const char* help : {"-help", "-help-full", "-doc", "-srcDoc"})
    {
        if (hasFlag(argc, argv, help))
        {
            return RunMode::coupled;
        }
    }

    const int switches =
        int(hasFlag(argc, argv, "-rigid")) + int(hasFlag(argc, argv, "-prescribed"))
      + int(hasFlag(argc, argv, "-coupled"));
    if (switches > 1)
    {
        fail("give at most one of -rigid, -prescribed and -coupled");
    }
    if (hasFlag(argc, argv, "-rigid"))
    {
        return RunMode::rigid;
    }
    if (hasFlag(argc, argv, "-prescribed"))
    {
        return RunMode::prescribed;
    }
    if (hasFlag(argc, argv, "-coupled"))
    {
        return RunMode::coupled;
    }

    Foam::fileName caseDir(".");
    for (int i = 1; i + 1 < argc; ++i)
    {
        if (std::strcmp(argv[i], "-case") == 0)
        {
            caseDir = argv[i + 1];
        }
    }
    const Foam::fileName path(caseDir/"system"/"fsiDict");
    Foam::IFstream is(path);
    if (!is.good())
    {
        return RunMode::coupled;
    }
    const Foam::dictionary dict(is);
    const Foam::word mode(dict.getOrDefault<Foam::word>("mode", "coupled"));
    for (const RunMode m : {RunMode::coupled, RunMode::rigid, RunMode::prescribed})
    {
        if (mode == toString(m))
        {
            return m;
        }
    }
    fail
    (
        path + ": mode must be coupled, rigid or prescribed, got '" + mode
      + "'; fix the entry or give -coupled, -rigid or -prescribed"
    );
}
