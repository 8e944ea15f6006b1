// SPDX-License-Identifier: GPL-3.0-or-later
#include "config/SolidConfig.hpp"

#include "config/YamlReader.hpp"
#include "material/Registry.hpp"
#include "schedule/Adaptive.hpp"
#include "schedule/Geometric.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace fsi::config
{
namespace fs = std::filesystem;

namespace
{
std::string resolve(const std::string& path, const std::string& dir)
{
    fs::path p(path);
    return p.is_absolute() ? path : (fs::path(dir) / p).lexically_normal().string();
}
} // namespace

MeshParameters MeshParameters::parse(const Block& b, const std::string& configDir)
{
    b.allowOnly({"file", "volume", "clamped", "wetted"});
    MeshParameters p;
    p.file = resolve(b.text("file"), configDir);
    p.volume = b.text("volume");
    p.clamped = b.has("clamped") ? b.texts("clamped") : std::vector<std::string>{};
    p.wetted = b.text("wetted", "");
    return p;
}

// The law named by `type` reads its own keys (material/Registry.hpp); a key of another law gets
// "is only for type ..." rather than "unknown key".
material::MaterialParameters parseMaterial(const Block& b)
{
    std::vector<std::string> names;
    for (const auto& law : material::materialTypes())
        names.push_back(law.name);
    const material::MaterialType& law = *material::findMaterialType(b.choice("type", names));
    for (const auto& other : material::materialTypes())
        for (const auto& key : other.keys)
            if (b.has(key) && std::find(law.keys.begin(), law.keys.end(), key) == law.keys.end())
            {
                std::string owners;
                for (const auto& t : material::materialTypes())
                    if (std::find(t.keys.begin(), t.keys.end(), key) != t.keys.end())
                        owners += (owners.empty() ? "" : " or ") + t.name;
                b.fail(key, "is only for type " + owners + " (remove it)");
            }
    std::vector<std::string> allowed{"type", "density"};
    allowed.insert(allowed.end(), law.keys.begin(), law.keys.end());
    b.allowOnly(allowed);
    material::MaterialParameters m;
    m.file = fs::path(b.file()).filename().string();
    m.keyPrefix = b.path();
    m.type = law.name;
    law.parse(b, m);
    m.validate();
    return m;
}

linalg::DirectSolverOptions parseLinearSolver(const Block& b)
{
    b.allowOnly({"verbosity", "ordering", "low_rank", "low_rank_min_size", "low_rank_tolerance",
                 "low_rank_variant", "refinement_tolerance", "max_refinement_steps",
                 "check_residual", "memory_relaxation", "threads", "refactor_shear_drift"});
    using linalg::LowRank;
    using linalg::Ordering;
    linalg::DirectSolverOptions o;
    o.verbosity = b.integer("verbosity", o.verbosity);
    const std::string ordering = b.choice(
        "ordering", {"metis", "scotch", "ptscotch", "amd", "amf", "pord", "qamd", "auto"}, "metis");
    const std::pair<const char*, Ordering> orderings[] = {
        {"metis", Ordering::Metis}, {"scotch", Ordering::Scotch}, {"ptscotch", Ordering::PtScotch},
        {"amd", Ordering::Amd},     {"amf", Ordering::Amf},       {"pord", Ordering::Pord},
        {"qamd", Ordering::Qamd},   {"auto", Ordering::Automatic}};
    for (const auto& [name, value] : orderings)
        if (ordering == name)
            o.ordering = static_cast<int>(value);
    // true / false read as on / off
    const std::string lowRank =
        b.choice("low_rank", {"auto", "on", "off", "true", "false"}, "auto");
    o.lowRank = lowRank == "auto"                        ? LowRank::Auto
                : (lowRank == "on" || lowRank == "true") ? LowRank::On
                                                         : LowRank::Off;
    o.lowRankMinSize = b.integer("low_rank_min_size", o.lowRankMinSize);
    o.lowRankTolerance = b.number("low_rank_tolerance", o.lowRankTolerance);
    o.lowRankUcfs = b.choice("low_rank_variant", {"ucfs", "ufsc"}, "ucfs") == "ucfs";
    o.refinementTolerance = b.number("refinement_tolerance", o.refinementTolerance);
    o.maxRefinementSteps = b.integer("max_refinement_steps", o.maxRefinementSteps);
    o.checkResidual = b.flag("check_residual", o.checkResidual);
    o.memoryRelaxationPercent = b.integer("memory_relaxation", o.memoryRelaxationPercent);
    o.threadsPerRank = b.integer("threads", o.threadsPerRank);
    if (const auto e = o.firstError())
        b.fail(e->key, "= " + e->value + " is invalid: " + e->fix);
    return o;
}

fe::NewtonSettings parseNewton(const Block& b)
{
    b.allowOnly({"max_iterations", "residual_tolerance", "absolute_tolerance", "line_search",
                 "max_load_cuts"});
    fe::NewtonSettings p;
    p.maxIterations = b.integer("max_iterations", p.maxIterations);
    p.residualTolerance = b.number("residual_tolerance", p.residualTolerance);
    p.absoluteTolerance = b.number("absolute_tolerance", p.absoluteTolerance);
    // true/false: the former switch (line search on every step / never)
    std::string lineSearch =
        b.choice("line_search", {"fallback", "always", "never", "true", "false"},
                 std::string(fe::toString(p.lineSearch)));
    if (lineSearch == "true")
        lineSearch = "always";
    else if (lineSearch == "false")
        lineSearch = "never";
    p.lineSearch = fe::lineSearchFromName(lineSearch);
    p.maxLoadCuts = b.integer("max_load_cuts", p.maxLoadCuts);
    if (p.maxIterations < 1)
        b.fail("max_iterations", "must be >= 1");
    if (!(p.residualTolerance > 0.0))
        b.fail("residual_tolerance", "must be > 0");
    if (!(p.absoluteTolerance >= 0.0))
        b.fail("absolute_tolerance", "must be >= 0");
    if (p.maxLoadCuts < 0)
        b.fail("max_load_cuts", "must be >= 0");
    return p;
}

LoadParameters LoadParameters::parse(const Block& b)
{
    b.allowOnly({"gravity", "displacements", "tractions", "forces"});
    LoadParameters p;
    if (b.has("gravity"))
    {
        p.gravity = b.vector3("gravity");
        p.hasGravity = true;
    }
    if (b.has("displacements"))
        for (const Block& d : b.blockList("displacements"))
        {
            d.allowOnly({"surface", "x", "y", "z"});
            fe::PrescribedDisplacement load;
            load.surface = d.text("surface");
            const char* names[3] = {"x", "y", "z"};
            for (int c = 0; c < 3; ++c)
                if (d.has(names[c]))
                    load.value[c] = d.number(names[c]);
            if (!load.value[0] && !load.value[1] && !load.value[2])
                d.fail("x", "missing: give at least one of x, y, z [m]");
            p.displacements.push_back(load);
        }
    if (b.has("tractions"))
        for (const Block& t : b.blockList("tractions"))
        {
            t.allowOnly({"surface", "traction"});
            p.tractions.push_back({t.text("surface"), t.vector3("traction")});
        }
    if (b.has("forces"))
        for (const Block& f : b.blockList("forces"))
        {
            f.allowOnly({"surface", "total"});
            p.forces.push_back({f.text("surface"), f.vector3("total")});
        }
    return p;
}

double TimeParameters::factorAt(double t) const
{
    if (loadFactor.empty())
        return 1.0;
    if (t <= loadFactor.front()[0])
        return loadFactor.front()[1];
    for (std::size_t i = 1; i < loadFactor.size(); ++i)
        if (t <= loadFactor[i][0])
        {
            const auto& a = loadFactor[i - 1];
            const auto& b = loadFactor[i];
            return a[1] + (b[1] - a[1]) * (t - a[0]) / (b[0] - a[0]);
        }
    return loadFactor.back()[1];
}

TimeParameters TimeParameters::parse(const Block& b, const std::vector<double>& relaxationTimes)
{
    TimeParameters p;
    p.schedule = schedule::parseSchedule(b, schedule::UniformParameters::keyword, {"load_factor"});
    if (b.has("load_factor"))
    {
        for (const auto& row : b.table("load_factor"))
        {
            if (row.size() != 2)
                b.fail("load_factor", "rows must be [time, factor]");
            if (!p.loadFactor.empty() && !(row[0] > p.loadFactor.back()[0]))
                b.fail("load_factor", "times must increase");
            p.loadFactor.push_back({row[0], row[1]});
        }
    }
    // the load-factor corners are landed on, as the hit times
    auto addCorners = [&p](auto* params)
    {
        if (!params)
            return;
        for (const auto& row : p.loadFactor)
            if (row[0] > 0.0 && row[0] < params->end)
                params->hit.push_back(row[0]);
    };
    addCorners(p.schedule.get<schedule::GeometricParameters>());
    addCorners(p.schedule.get<schedule::AdaptiveParameters>());
    if (auto* adaptive = p.schedule.get<schedule::AdaptiveParameters>())
    {
        if (adaptive->errorTolerance != 0.0)
            b.fail("error_tolerance", "is for coupled runs only (coupling.time): a standalone "
                                      "adaptive schedule follows target_change; remove it");
        adaptive->resolveFirstStep(relaxationTimes);
    }
    p.schedule.validate();
    return p;
}

OutputParameters OutputParameters::parse(const Block& b, const std::string& configDir)
{
    b.allowOnly({"folder", "vtu", "format", "every", "watch"});
    OutputParameters p;
    p.folder = resolve(b.text("folder", p.folder), configDir);
    p.vtu = b.flag("vtu", p.vtu);
    p.binary = b.choice("format", {"binary", "ascii"}, "binary") == "binary";
    p.every = b.integer("every", p.every);
    if (p.every < 1)
        b.fail("every", "must be >= 1");
    if (b.has("watch"))
    {
        const std::vector<Block> watch = b.blockList("watch");
        if (watch.size() > kMaxWatchPoints)
            b.fail("watch", "has " + std::to_string(watch.size()) + " points, more than the " +
                                std::to_string(kMaxWatchPoints) +
                                " allowed; watch a few points (the VTU output has every node)");
        for (const Block& w : watch)
        {
            w.allowOnly({"name", "point"});
            p.watch.push_back({w.text("name"), w.vector3("point")});
        }
    }
    return p;
}

SolidConfig SolidConfig::load(const std::string& file)
{
    return fromRoot(Block::load(file), file);
}

SolidConfig SolidConfig::fromRoot(const Block& root, const std::string& file)
{
    const std::string dir = fs::path(file).parent_path().string();
    root.allowOnly({"solid", "coupling"});
    SolidConfig c;
    c.file = file;
    const Block s = root.block("solid");
    s.allowOnly({"mesh", "material", "kinematics", "element", "newton", "linear_solver", "loads",
                 "time", "output"});
    c.mesh = MeshParameters::parse(s.block("mesh"), dir);
    const Block m = s.block("material");
    c.material = parseMaterial(m);
    c.density = m.number("density", 0.0);
    if (c.density < 0.0)
        m.fail("density", "must be >= 0 [kg/m^3]");
    const std::string kin = s.choice("kinematics", {"small-strain", "total-lagrangian"});
    c.kinematics = kin == "small-strain" ? material::Kinematics::SmallStrain
                                         : material::Kinematics::TotalLagrangian;
    if (material::findMaterialType(c.material.type)->needsTotalLagrangian &&
        c.kinematics == material::Kinematics::SmallStrain)
        s.fail("kinematics", "must be total-lagrangian for a " + c.material.type + " material");
    if (auto e = s.optionalBlock("element"))
    {
        e->allowOnly({"type"});
        c.elementType = e->choice("type", {"displacement", "projected-dilatation"});
    }
    if (auto n = s.optionalBlock("newton"))
        c.newton = parseNewton(*n);
    if (auto l = s.optionalBlock("linear_solver"))
    {
        c.linearSolver = parseLinearSolver(*l);
        c.refactorShearDrift = l->number("refactor_shear_drift", c.refactorShearDrift);
        if (!(c.refactorShearDrift >= 0.0))
            l->fail("refactor_shear_drift", "must be >= 0 (a fraction, e.g. 0.05; 0 = never)");
    }
    c.loads = LoadParameters::parse(s.block("loads"));
    if (c.loads.hasGravity && !m.has("density"))
        m.fail("density", "missing: loads.gravity needs the density [kg/m^3]");
    if (auto t = s.optionalBlock("time"))
        c.time = TimeParameters::parse(*t, c.material.relaxationTimes());
    if (auto o = s.optionalBlock("output"))
        c.output = OutputParameters::parse(*o, dir);
    else
        c.output.folder = resolve(c.output.folder, dir);
    if (c.mesh.clamped.empty() && c.loads.displacements.empty())
        s.fail("mesh.clamped", "missing: give clamped surfaces or loads.displacements (rigid-body "
                               "motion is singular)");
    return c;
}

std::string SolidConfig::echo() const
{
    std::ostringstream o;
    auto vec = [](const std::array<double, 3>& v)
    {
        std::ostringstream s;
        s << "[" << v[0] << ", " << v[1] << ", " << v[2] << "]";
        return s.str();
    };
    o << "# resolved solid configuration (from " << file << ")\n";
    o << "solid:\n  mesh:\n    file: " << mesh.file << "\n    volume: " << mesh.volume
      << "\n    clamped: [";
    for (std::size_t i = 0; i < mesh.clamped.size(); ++i)
        o << (i ? ", " : "") << mesh.clamped[i];
    o << "]\n    wetted: '" << mesh.wetted << "'\n";
    o << "  material:\n    density: " << density << "\n";
    std::istringstream d(material.describe());
    for (std::string line; std::getline(d, line);)
        o << "    # " << line << "\n";
    o << "  kinematics: "
      << (kinematics == material::Kinematics::SmallStrain ? "small-strain" : "total-lagrangian")
      << "\n";
    o << "  element: {type: " << elementType << "}\n";
    o << "  newton: {max_iterations: " << newton.maxIterations
      << ", residual_tolerance: " << newton.residualTolerance
      << ", absolute_tolerance: " << newton.absoluteTolerance
      << ", line_search: " << fe::toString(newton.lineSearch)
      << ", max_load_cuts: " << newton.maxLoadCuts << "}\n";
    o << "  linear_solver: {verbosity: " << linearSolver.verbosity
      << ", refactor_shear_drift: " << refactorShearDrift << "}  # "
      << linalg::describe(linearSolver) << "\n";
    o << "  loads:\n";
    if (loads.hasGravity)
        o << "    gravity: " << vec(loads.gravity) << "\n";
    for (const auto& dl : loads.displacements)
    {
        o << "    - displacement: {surface: " << dl.surface;
        const char* n[3] = {"x", "y", "z"};
        for (int c = 0; c < 3; ++c)
            if (dl.value[c])
                o << ", " << n[c] << ": " << *dl.value[c];
        o << "}\n";
    }
    for (const auto& t : loads.tractions)
        o << "    - traction: {surface: " << t.surface << ", traction: " << vec(t.traction)
          << "}\n";
    for (const auto& f : loads.forces)
        o << "    - force: {surface: " << f.surface << ", total: " << vec(f.total) << "}\n";
    {
        std::string coefficients = time.schedule.echo(); // "{key: value, ...}"
        coefficients = coefficients.substr(1, coefficients.size() - 2);
        o << "  time: {type: " << time.schedule.type() << (coefficients.empty() ? "" : ", ")
          << coefficients;
        if (const auto schedule = time.schedule.make(); schedule->plannedLevels() > 0)
            o << ", levels: " << schedule->plannedLevels();
        o << ", load_factor: [";
        for (std::size_t i = 0; i < time.loadFactor.size(); ++i)
            o << (i ? ", " : "") << "[" << time.loadFactor[i][0] << ", " << time.loadFactor[i][1]
              << "]";
        o << "]}\n";
    }
    o << "  output: {folder: " << output.folder << ", vtu: " << (output.vtu ? "true" : "false")
      << ", format: " << (output.binary ? "binary" : "ascii") << ", every: " << output.every
      << ", watch: " << output.watch.size() << " points}\n";
    return o.str();
}

} // namespace fsi::config
