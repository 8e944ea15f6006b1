// SPDX-License-Identifier: GPL-3.0-or-later
#include "driver/CouplingParameters.hpp"

#include "acceleration/Registry.hpp"
#include "config/YamlReader.hpp"
#include "mapping/Registry.hpp"

#include <cmath>
#include <sstream>

namespace fsi::driver
{

namespace
{

// A coefficients block may only be given for the selected strategy.
void onlySelectedCoefficients(const config::Block& b, const std::string& type,
                              const std::vector<std::string>& strategies)
{
    for (const auto& s : strategies)
        if (s != type && b.has(s))
            b.fail(s, "coefficients for '" + s + "' but type is '" + type +
                          "': remove the block or change type");
}

// Runs check(); the message of a std::exception it throws is re-thrown as a one-line error naming
// the config file and `key` of block b.
template <class Check> void failUnder(const config::Block& b, const std::string& key, Check&& check)
{
    try
    {
        check();
    }
    catch (const std::exception& e)
    {
        b.fail(key, e.what());
    }
}

// Runs the strategy's own validate() under `key` (failUnder).
template <class Parameters>
void validateIn(const Parameters& p, const config::Block& b, const std::string& key)
{
    failUnder(b, key, [&] { p.validate(); });
}

// acceleration: {type: NAME, NAME: {coefficients}}; the strategies and their keys come from
// the acceleration layer's registry.
acceleration::AcceleratorParameters parseAcceleration(const config::Block& b)
{
    std::vector<std::string> types;
    for (const auto& t : acceleration::acceleratorTypes())
        types.push_back(t.name);
    std::vector<std::string> allowed{"type"};
    allowed.insert(allowed.end(), types.begin(), types.end());
    b.allowOnly(allowed);
    const std::string type = b.choice("type", types);
    onlySelectedCoefficients(b, type, types);
    const acceleration::AcceleratorParameters p = acceleration::acceleratorType(type).parse(b);
    validateIn(p, b, "type");
    return p;
}

// mapping: {type: NAME, overlap_tolerance: x, smoothing_radius: r, NAME: {coefficients}}; the
// strategies and their keys come from the mapping layer's registry.
mapping::MappingParameters parseMapping(const config::Block& b)
{
    std::vector<std::string> types;
    for (const auto& t : mapping::mappingTypes())
        types.push_back(t.name);
    std::vector<std::string> allowed{"type", "overlap_tolerance", "smoothing_radius"};
    for (const auto& t : mapping::mappingTypes())
        if (!t.keys.empty())
            allowed.push_back(t.name);
    b.allowOnly(allowed);
    const std::string type = b.choice("type", types);
    onlySelectedCoefficients(b, type, types);
    mapping::MappingParameters p = mapping::mappingType(type).parse(b);
    p.overlapTolerance = b.number("overlap_tolerance", p.overlapTolerance);
    failUnder(b, "overlap_tolerance", [&] { p.validateOverlapTolerance(); });
    p.smoothingRadius = b.number("smoothing_radius", p.smoothingRadius);
    failUnder(b, "smoothing_radius", [&] { p.validateSmoothingRadius(); });
    // a coefficient error is named under the strategy's own block, e.g.
    // coupling.mapping.rbf-wendland-c2 (the block holds the offending key); the two keys above
    // are checked already
    validateIn(p.strategy, b, b.has(type) ? type : std::string("type"));
    return p;
}

} // namespace

CouplingParameters CouplingParameters::parse(const config::Block& b)
{
    b.allowOnly({"launch", "max_iterations", "on_max_iterations", "divergence_factor", "predictor",
                 "convergence", "acceleration", "mapping", "force_mapping", "time", "section_angle",
                 "checkpoint", "recovery", "fluid_accuracy", "secant"});
    CouplingParameters p;
    if (auto l = b.optionalBlock("launch"))
    {
        l->allowOnly({"mode", "port_file", "timeout"});
        p.launch.mode = l->choice("mode", {"mpmd", "port"}, p.launch.mode);
        p.launch.portFile = l->text("port_file", p.launch.portFile);
        p.launch.timeout = l->number("timeout", p.launch.timeout);
        if (!(p.launch.timeout > 0 && p.launch.timeout <= 1e9))
            l->fail("timeout", "must be in (0, 1e9] s (the longest wait for the peer, e.g. 600)");
    }
    p.maxIterations = b.integer("max_iterations", p.maxIterations);
    if (p.maxIterations < 1)
        b.fail("max_iterations", "must be >= 1");
    p.continueOnMaxIterations =
        b.choice("on_max_iterations", {"stop", "continue"}, "stop") == "continue";
    p.divergenceFactor = b.number("divergence_factor", p.divergenceFactor);
    if (!(p.divergenceFactor > 1))
        b.fail("divergence_factor", "must be > 1");
    p.predictor =
        b.choice("predictor", {"constant", "linear", "structural", "structural-linear", "secant"},
                 p.predictor);
    if (auto m = b.optionalBlock("secant"))
    {
        m->allowOnly({"max_columns", "levels", "coupling_iterations", "response_tolerance",
                      "min_feedback_margin"});
        p.secant.maxColumns = m->integer("max_columns", p.secant.maxColumns);
        p.secant.levels = m->integer("levels", p.secant.levels);
        p.secant.couplingIterations = m->flag("coupling_iterations", p.secant.couplingIterations);
        p.secant.responseTolerance = m->number("response_tolerance", p.secant.responseTolerance);
        if (!(p.secant.responseTolerance >= 0.0 && p.secant.responseTolerance <= 0.1))
            m->fail("response_tolerance",
                    "must be in [0, 0.1] (a relative residual; 0: a full solid solve per column)");
        p.secant.minFeedbackMargin = m->number("min_feedback_margin", p.secant.minFeedbackMargin);
        if (!(p.secant.minFeedbackMargin >= 0.0 && p.secant.minFeedbackMargin < 1.0))
            m->fail("min_feedback_margin",
                    "must be in [0, 1) (the smallest singular value of I - V^+ Z trusted; 0: any)");
        if (p.secant.maxColumns < 1 || p.secant.maxColumns > 50)
            m->fail("max_columns", "must be in [1, 50] (each column may cost a solid solve)");
        if (p.secant.levels < 1 || p.secant.levels > 20)
            m->fail("levels", "must be in [1, 20] (older levels whose fluid solves are kept)");
    }

    auto c = b.block("convergence");
    c.allowOnly({"absolute_tolerance", "relative_tolerance", "band_factor"});
    p.convergence.absoluteTolerance = c.number("absolute_tolerance", 0.0);
    p.convergence.relativeTolerance = c.number("relative_tolerance", 0.0);
    p.convergence.bandFactor = c.number("band_factor", p.convergence.bandFactor);
    const bool bandFactorValid =
        p.convergence.bandFactor >= 0.0 && std::isfinite(p.convergence.bandFactor);
    validateIn(p.convergence, c, bandFactorValid ? "absolute_tolerance" : "band_factor");
    p.acceleration = parseAcceleration(b.block("acceleration"));
    p.mapping = parseMapping(b.block("mapping"));
    if (auto f = b.optionalBlock("force_mapping"))
        p.forceMapping = parseMapping(*f);
    if (auto t = b.optionalBlock("time"))
        p.time = schedule::parseSchedule(*t, ""); // type required
    if (auto s = b.optionalBlock("section_angle"))
    {
        s->allowOnly({"name", "leading_edge", "trailing_edge", "lift_direction"});
        SectionAngleParameters a;
        a.name = s->text("name", a.name);
        a.leadingEdge = s->vector3("leading_edge");
        a.trailingEdge = s->vector3("trailing_edge");
        a.liftDirection = s->vector3("lift_direction");
        double n = std::sqrt(a.liftDirection[0] * a.liftDirection[0] +
                             a.liftDirection[1] * a.liftDirection[1] +
                             a.liftDirection[2] * a.liftDirection[2]);
        if (!(n > 0))
            s->fail("lift_direction", "must be a non-zero vector");
        for (double& x : a.liftDirection)
            x /= n;
        p.sectionAngle = a;
    }
    if (auto a = b.optionalBlock("fluid_accuracy"))
    {
        a->allowOnly({"final", "forcing_factor", "max_force_tolerance", "min_iterations"});
        FluidAccuracyParameters f;
        if (auto fin = a->optionalBlock("final"))
        {
            fin->allowOnly({"force_tolerance", "residual_drop"});
            f.finalForceTolerance = fin->number("force_tolerance", f.finalForceTolerance);
            f.finalResidualDrop = fin->number("residual_drop", f.finalResidualDrop);
        }
        f.forcingFactor = a->number("forcing_factor", f.forcingFactor);
        f.maxForceTolerance = a->number("max_force_tolerance", f.maxForceTolerance);
        f.minIterations = a->integer("min_iterations", f.minIterations);
        try
        {
            f.validate();
        }
        catch (const std::exception& e)
        {
            throw std::runtime_error(a->file() + ": " + e.what());
        }
        p.fluidAccuracy = f;
    }
    if (auto k = b.optionalBlock("checkpoint"))
    {
        k->allowOnly({"every", "keep"});
        p.checkpoint.every = k->integer("every", p.checkpoint.every);
        p.checkpoint.keep = k->integer("keep", p.checkpoint.keep);
        validateIn(p.checkpoint, *k, p.checkpoint.every < 0 ? "every" : "keep");
    }
    if (auto r = b.optionalBlock("recovery"))
    {
        r->allowOnly({"max_retries", "relaxation_factor", "step_factor"});
        p.recovery.maxRetries = r->integer("max_retries", p.recovery.maxRetries);
        p.recovery.relaxationFactor = r->number("relaxation_factor", p.recovery.relaxationFactor);
        p.recovery.stepFactor = r->number("step_factor", p.recovery.stepFactor);
        if (p.recovery.maxRetries < 0)
            r->fail("max_retries", "must be >= 0 (0 = no automatic cures)");
        if (!(p.recovery.relaxationFactor > 0 && p.recovery.relaxationFactor < 1))
            r->fail("relaxation_factor", "must be in (0, 1)");
        if (!(p.recovery.stepFactor > 0 && p.recovery.stepFactor < 1))
            r->fail("step_factor", "must be in (0, 1)");
    }
    return p;
}

std::string CouplingParameters::echo() const
{
    std::ostringstream s;
    s << "coupling:\n"
      << "  launch: {mode: " << launch.mode << ", port_file: " << launch.portFile
      << ", timeout: " << launch.timeout << "}\n"
      << "  max_iterations: " << maxIterations << "\n"
      << "  on_max_iterations: " << (continueOnMaxIterations ? "continue" : "stop") << "\n"
      << "  divergence_factor: " << divergenceFactor << "\n"
      << "  predictor: " << predictor << "\n"
      << "  secant: {max_columns: " << secant.maxColumns << ", levels: " << secant.levels
      << ", coupling_iterations: " << (secant.couplingIterations ? "true" : "false")
      << ", response_tolerance: " << secant.responseTolerance
      << ", min_feedback_margin: " << secant.minFeedbackMargin << "}\n"
      << "  convergence: {absolute_tolerance: " << convergence.absoluteTolerance
      << ", relative_tolerance: " << convergence.relativeTolerance
      << ", band_factor: " << convergence.bandFactor << "}\n"
      << "  acceleration:\n    type: " << acceleration.type() << "\n"
      << "    " << acceleration.type() << ": " << acceleration.echo() << "\n";
    const auto echoMapping = [&s](const char* key, const mapping::MappingParameters& m)
    {
        s << "  " << key << ":\n    type: " << m.type()
          << "\n    overlap_tolerance: " << m.overlapTolerance
          << "\n    smoothing_radius: " << m.smoothingRadius << "\n";
        if (!mapping::mappingType(m.type()).keys.empty())
            s << "    " << m.type() << ": " << m.strategy.echo() << "\n";
    };
    echoMapping("mapping", mapping);
    if (forceMapping)
        echoMapping("force_mapping", *forceMapping);
    std::string timeCoefficients = time.echo(); // "{key: value, ...}"
    timeCoefficients = timeCoefficients.substr(1, timeCoefficients.size() - 2);
    s << "  time: {type: " << time.type() << (timeCoefficients.empty() ? "" : ", ")
      << timeCoefficients << "}\n";
    if (fluidAccuracy)
        s << "  fluid_accuracy: {final: {force_tolerance: " << fluidAccuracy->finalForceTolerance
          << ", residual_drop: " << fluidAccuracy->finalResidualDrop
          << "}, forcing_factor: " << fluidAccuracy->forcingFactor
          << ", max_force_tolerance: " << fluidAccuracy->maxForceTolerance
          << ", min_iterations: " << fluidAccuracy->minIterations << "}\n";
    else
        s << "  fluid_accuracy: none (the fluid's own fsiDict controls)\n";
    if (sectionAngle)
        s << "  section_angle: {name: " << sectionAngle->name << "}\n";
    s << "  checkpoint: {every: " << checkpoint.every << ", keep: " << checkpoint.keep << "}\n"
      << "  recovery: {max_retries: " << recovery.maxRetries
      << ", relaxation_factor: " << recovery.relaxationFactor
      << ", step_factor: " << recovery.stepFactor << "}\n";
    return s.str();
}

} // namespace fsi::driver
