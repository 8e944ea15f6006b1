// SPDX-License-Identifier: GPL-3.0-or-later
#include "config/SolidConfig.hpp"
#include "config/YamlReader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <unistd.h>

using fsi::config::SolidConfig;

namespace
{

const char* valid = R"(solid:
  mesh: {file: beam.msh, volume: solid, clamped: [root]}
  material: {type: linear-elastic, E: 1.0e6, nu: 0.3}
  kinematics: small-strain
  loads: {tractions: [{surface: tip, traction: [0, -1, 0]}]}
)";

std::string write(const std::string& text, const std::string& name = "beam.yaml")
{
    auto dir =
        std::filesystem::temp_directory_path() / ("fsi_test_config_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto path = (dir / name).string();
    std::ofstream(path) << text;
    return path;
}

std::string errorOf(const std::string& text)
{
    try
    {
        SolidConfig::load(write(text));
    }
    catch (const std::exception& e)
    {
        const std::string msg = e.what();
        EXPECT_EQ(msg.find('\n'), std::string::npos) << "not one line: " << msg;
        EXPECT_EQ(msg.rfind("beam.yaml: ", 0), 0u) << "does not name the file first: " << msg;
        return msg;
    }
    ADD_FAILURE() << "no error for:\n" << text;
    return "";
}

std::string replaced(std::string text, const std::string& from, const std::string& to)
{
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
}

// The level times of a planned or adaptive schedule, every level's change 0.
std::vector<double> levelTimes(const fsi::config::TimeParameters& time)
{
    const auto schedule = time.schedule.make();
    std::vector<double> t{schedule->time()};
    while (schedule->hasNext())
        t.push_back(schedule->advance(0.0));
    return t;
}

} // namespace

TEST(SolidConfig, ValidCaseParsesWithDefaults)
{
    const auto c = SolidConfig::load(write(valid));
    EXPECT_EQ(c.mesh.volume, "solid");
    EXPECT_EQ(c.mesh.clamped, std::vector<std::string>{"root"});
    EXPECT_EQ(c.newton.maxIterations, 25);
    EXPECT_EQ(c.time.schedule.type(), "steady");
    EXPECT_EQ(levelTimes(c.time), std::vector<double>{0.0});
    EXPECT_EQ(c.loads.tractions.size(), 1u);
    EXPECT_DOUBLE_EQ(c.loads.tractions[0].traction[1], -1.0);
    EXPECT_NE(c.echo().find("small-strain"), std::string::npos);
    EXPECT_TRUE(std::filesystem::path(c.mesh.file).is_absolute());
}

TEST(SolidConfig, UnknownKeyWithSuggestion)
{
    const auto msg = errorOf(replaced(valid, "material:", "materail:"));
    EXPECT_EQ(msg, "beam.yaml: unknown key 'materail' in 'solid' (did you mean 'material'?)");
    EXPECT_NE(errorOf(replaced(valid, "volume:", "volumes:")).find("'volumes' in 'solid.mesh'"),
              std::string::npos);
}

TEST(SolidConfig, MissingKey)
{
    EXPECT_EQ(errorOf(replaced(valid, "  kinematics: small-strain\n", "")),
              "beam.yaml: missing key 'kinematics' in 'solid'");
    EXPECT_NE(errorOf(replaced(valid, "volume: solid, ", ""))
                  .find("missing key 'volume' in 'solid.mesh'"),
              std::string::npos);
}

TEST(SolidConfig, WrongTypesAndChoices)
{
    EXPECT_NE(
        errorOf(replaced(valid, "E: 1.0e6", "E: soft")).find("'solid.material.E' must be a number"),
        std::string::npos);
    EXPECT_NE(
        errorOf(replaced(valid, "small-strain", "large")).find("'solid.kinematics' is 'large'"),
        std::string::npos);
    EXPECT_NE(errorOf(replaced(valid, "[0, -1, 0]", "[0, -1]")).find("3 components"),
              std::string::npos);
    EXPECT_NE(errorOf(std::string(valid) + "  newton: {max_iterations: 2.5}\n")
                  .find("must be an integer"),
              std::string::npos);
}

TEST(SolidConfig, PhysicalBoundsOfTheMaterial)
{
    EXPECT_NE(errorOf(replaced(valid, "nu: 0.3", "nu: 0.5")).find("nu"), std::string::npos);
    EXPECT_NE(errorOf(replaced(valid, "E: 1.0e6", "E: -1.0e6")).find("E"), std::string::npos);
    const std::string visco =
        replaced(valid, "{type: linear-elastic, E: 1.0e6, nu: 0.3}",
                 "{type: viscoelastic, E: 1.0e6, nu: 0.3, modulus_basis: long-term,"
                 " prony: {convention: long-term-gamma, coefficients: [0.5], times: [0.0]}}");
    EXPECT_NE(errorOf(visco).find("times"), std::string::npos);
    // a Prony block in an elastic case is an error, not silently ignored
    const std::string elasticWithProny =
        replaced(valid, "nu: 0.3}", "nu: 0.3, prony: {convention: abaqus-g}}");
    EXPECT_NE(
        errorOf(elasticWithProny).find("'solid.material.prony' is only for type viscoelastic"),
        std::string::npos);
    // the convention must be stated
    const std::string noConvention = replaced(visco, "convention: long-term-gamma, ", "");
    EXPECT_NE(errorOf(noConvention).find("missing key 'convention'"), std::string::npos);
}

TEST(SolidConfig, TimeBlock)
{
    const auto c = SolidConfig::load(
        write(std::string(valid) + "  time: {dt: 0.5, end: 2, load_factor: [[0, 0], [1, 1]]}\n"));
    EXPECT_EQ(levelTimes(c.time), (std::vector<double>{0, 0.5, 1.0, 1.5, 2.0}));
    EXPECT_DOUBLE_EQ(c.time.factorAt(0.5), 0.5);
    EXPECT_DOUBLE_EQ(c.time.factorAt(3.0), 1.0);
    EXPECT_NE(errorOf(std::string(valid) + "  time: {dt: 0, end: 2}\n")
                  .find("'solid.time.dt' must be > 0"),
              std::string::npos);
}

TEST(SolidConfig, ListGeometricAndAdaptiveSchedules)
{
    const auto list = SolidConfig::load(
        write(std::string(valid) + "  time: {type: list, times: [0, 0.1, 1, 10]}\n"));
    EXPECT_EQ(levelTimes(list.time), (std::vector<double>{0, 0.1, 1, 10}));
    // geometric: 0, 0.1, 0.25, 0.475 ... lands on the hit 1 and the end 100
    const auto geo = SolidConfig::load(write(
        std::string(valid) + "  time: {type: geometric, first_step: 0.1, growth: 1.5, end: 100, "
                             "hit: [1, 10]}\n"));
    const auto t = levelTimes(geo.time);
    ASSERT_GE(t.size(), 4u);
    EXPECT_DOUBLE_EQ(t[1], 0.1);
    EXPECT_DOUBLE_EQ(t[2], 0.25);
    EXPECT_EQ(t.back(), 100.0);
    for (double mark : {1.0, 10.0})
        EXPECT_NE(std::find(t.begin(), t.end(), mark), t.end()) << mark;
    EXPECT_LT(t.size(), 30u);
    for (std::size_t i = 1; i < t.size(); ++i)
        EXPECT_GT(t[i], t[i - 1]);
    // adaptive: step control and landing on the hit and end times
    const auto ad = SolidConfig::load(
        write(std::string(valid) +
              "  time: {type: adaptive, end: 50, first_step: 0.5, target_change: 0.1, "
              "max_step: 20, hit: [7]}\n"));
    const auto schedule = ad.time.schedule.make();
    EXPECT_EQ(schedule->plannedLevels(), -1);
    EXPECT_DOUBLE_EQ(schedule->advance(0.3), 0.5);   // level 1: first_step
    EXPECT_DOUBLE_EQ(schedule->advance(0.0), 1.5);   // no change: growth_limit 2
    EXPECT_DOUBLE_EQ(schedule->advance(0.05), 3.5);  // half the target: doubled (limit 2)
    EXPECT_DOUBLE_EQ(schedule->advance(0.125), 5.1); // 0.1 / 0.125: dt 1.6
    EXPECT_DOUBLE_EQ(schedule->advance(0.0), 7.0);   // dt 3.2 would pass the hit: lands on it
    EXPECT_DOUBLE_EQ(schedule->advance(10.0), 7.95); // shrink_limit 0.5 of the last dt 1.9
    double last = 0.0;
    while (schedule->hasNext())
    {
        last = schedule->advance(0.0);
        EXPECT_LE(schedule->lastStep(), 20.0 + 1e-12); // max_step
    }
    EXPECT_DOUBLE_EQ(last, 50.0);
    // the load-factor corners are landed on like hit times
    const auto ramp = SolidConfig::load(write(std::string(valid) +
                                              "  time: {type: adaptive, end: 50, first_step: 0.5, "
                                              "load_factor: [[0, 0], [3.2, 1], [50, 1]]}\n"));
    const auto rampTimes = levelTimes(ramp.time);
    EXPECT_NE(std::find(rampTimes.begin(), rampTimes.end(), 3.2), rampTimes.end());
    EXPECT_NE(errorOf(std::string(valid) + "  time: {type: adaptive, end: 50}\n")
                  .find("'solid.time.first_step' missing"),
              std::string::npos); // elastic: no Prony times to derive it from
    EXPECT_NE(errorOf(std::string(valid) + "  time: {type: list, times: [1, 2]}\n")
                  .find("'solid.time.times' must start at 0"),
              std::string::npos);
    EXPECT_NE(errorOf(std::string(valid) + "  time: {type: geometric, first_step: 0.1, end: 9, "
                                           "dt: 1}\n")
                  .find("unknown key 'dt'"),
              std::string::npos);
    EXPECT_NE(errorOf(std::string(valid) + "  time: {type: geometric, first_step: 0.1, end: 9, "
                                           "hit: [10]}\n")
                  .find("'solid.time.hit'"),
              std::string::npos);
}

TEST(SolidConfig, RefactorShearDrift)
{
    EXPECT_DOUBLE_EQ(SolidConfig::load(write(valid)).refactorShearDrift, 0.0); // default: never
    const auto c = SolidConfig::load(
        write(std::string(valid) + "  linear_solver: {refactor_shear_drift: 0.2}\n"));
    EXPECT_DOUBLE_EQ(c.refactorShearDrift, 0.2);
    EXPECT_NE(errorOf(std::string(valid) + "  linear_solver: {refactor_shear_drift: -1}\n")
                  .find("'solid.linear_solver.refactor_shear_drift' must be >= 0"),
              std::string::npos);
}

TEST(SolidConfig, LineSearchPolicy)
{
    EXPECT_EQ(fsi::fe::toString(SolidConfig::load(write(valid)).newton.lineSearch),
              std::string("fallback"));
    for (const auto& [given, meant] : std::vector<std::pair<std::string, std::string>>{
             {"always", "always"}, {"never", "never"}, {"true", "always"}, {"false", "never"}})
        EXPECT_EQ(
            fsi::fe::toString(SolidConfig::load(write(std::string(valid) +
                                                      "  newton: {line_search: " + given + "}\n"))
                                  .newton.lineSearch),
            meant);
    EXPECT_NE(
        errorOf(std::string(valid) + "  newton: {line_search: sometimes}\n").find("line_search"),
        std::string::npos);
}

TEST(SolidConfig, GravityNeedsDensityAndYamlSyntaxErrors)
{
    EXPECT_NE(errorOf(replaced(valid, "loads: {", "loads: {gravity: [0, -2, 0], ")).find("density"),
              std::string::npos);
    EXPECT_NE(errorOf("solid: [unclosed\n").find("YAML syntax error"), std::string::npos);
}

TEST(SolidConfig, ShippedExampleIsValid)
{
    const auto c = SolidConfig::load(std::string(FSI_SOURCE_DIR) + "/config/solid.example.yaml");
    EXPECT_EQ(c.material.type, "viscoelastic");
    EXPECT_NE(c.time.schedule.type(), "steady");
}

// Issue 15 item 3: silent acceptance.
TEST(SolidConfig, DuplicateKeysAreErrors)
{
    const std::string twice = std::string(valid) + "  kinematics: total-lagrangian\n";
    const std::string msg = errorOf(twice);
    EXPECT_NE(msg.find("duplicate key 'kinematics' in 'solid' at line 6"), std::string::npos)
        << msg;
    const std::string nested = replaced(valid, "E: 1.0e6,", "E: 1.0e6, E: 2.0e6,");
    EXPECT_NE(errorOf(nested).find("duplicate key 'E' in 'solid.material'"), std::string::npos);
}

TEST(SolidConfig, NonFiniteNumbersAreErrors)
{
    EXPECT_NE(errorOf(std::string(valid) + "  time: {dt: 1, end: .inf}\n")
                  .find("'solid.time.end' must be a finite number"),
              std::string::npos);
    EXPECT_NE(errorOf(replaced(valid, "E: 1.0e6", "E: .nan"))
                  .find("'solid.material.E' must be a "
                        "finite number"),
              std::string::npos);
    EXPECT_NE(
        errorOf(replaced(valid, "[0, -1, 0]", "[0, -.inf, 0]")).find("must be a finite number"),
        std::string::npos);
}

TEST(SolidConfig, FluidBlockIsUnknown)
{
    EXPECT_NE(errorOf(std::string(valid) + "fluid:\n  inlet: 2\n").find("unknown key 'fluid'"),
              std::string::npos);
}

// Issue 15 item 7: a directory as the config named neither the file nor the problem.
TEST(SolidConfig, DirectoryIsNotAConfig)
{
    const std::string dir = std::filesystem::path(write(valid)).parent_path().string();
    try
    {
        SolidConfig::load(dir);
        ADD_FAILURE() << "no error for a directory";
    }
    catch (const std::exception& e)
    {
        EXPECT_EQ(std::string(e.what()), dir + ": is a directory, not a config file; give the "
                                               "path of the YAML config");
    }
}

// Issue 15 item 9: input sizes are capped with a clear error.
TEST(SolidConfig, InputSizesAreCapped)
{
    std::string watch = std::string(valid) + "  output:\n    watch:\n";
    for (int i = 0; i < 1001; ++i)
        watch += "      - {name: p" + std::to_string(i) + ", point: [0, 0, 0]}\n";
    EXPECT_NE(errorOf(watch).find("'solid.output.watch' has 1001 points, more than the 1000"),
              std::string::npos);

    std::string list = std::string(valid) + "  extra: [";
    for (int i = 0; i < 10001; ++i)
        list += (i ? ",0" : "0");
    list += "]\n";
    EXPECT_NE(errorOf(list).find("'solid.extra' has 10001 entries, more than the 10000"),
              std::string::npos);

    EXPECT_NE(errorOf(std::string(valid) + "  time: {dt: 1e-6, end: 10}\n")
                  .find("levels of dt = 1e-06 s, more than the 1000000 allowed"),
              std::string::npos);

    const std::string big =
        write(std::string(valid) + "# " + std::string(1u << 20, 'x') + "\n", "big.yaml");
    try
    {
        SolidConfig::load(big);
        ADD_FAILURE() << "no error for a file over 1 MiB";
    }
    catch (const std::exception& e)
    {
        EXPECT_NE(std::string(e.what()).find(big + ": "), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("more than the 1048576 a config file may have"),
                  std::string::npos)
            << e.what();
    }
}

TEST(ClosestMatch, EditDistance)
{
    EXPECT_EQ(fsi::config::closestMatch("kinematic", {"kinematics", "mesh"}), "kinematics");
    EXPECT_EQ(fsi::config::closestMatch("zzz", {"kinematics", "mesh"}), "");
}

TEST(SolidConfig, ElementType)
{
    EXPECT_EQ(SolidConfig::load(write(valid)).elementType, "displacement");
    const auto c =
        SolidConfig::load(write(std::string(valid) + "  element: {type: projected-dilatation}\n"));
    EXPECT_EQ(c.elementType, "projected-dilatation");
    EXPECT_NE(c.echo().find("element: {type: projected-dilatation}"), std::string::npos);
    EXPECT_NE(errorOf(std::string(valid) + "  element: {type: bbar}\n")
                  .find("'solid.element.type' is 'bbar'"),
              std::string::npos);
    EXPECT_NE(errorOf(std::string(valid) + "  element: {formulation: displacement}\n")
                  .find("unknown key 'formulation' in 'solid.element'"),
              std::string::npos);
}

// Issue 14: the linear_solver block. The shipped example spells out every default: parsing it
// gives linalg::DirectSolverOptions{}; bad values are one-line errors naming the key and the fix.
TEST(SolidConfig, LinearSolverDefaultsAreTheDocumentedOnes)
{
    const fsi::linalg::DirectSolverOptions defaults;
    for (const auto& c :
         {SolidConfig::load(write(valid)),
          SolidConfig::load(std::string(FSI_SOURCE_DIR) + "/config/solid.example.yaml")})
    {
        const auto& o = c.linearSolver;
        EXPECT_EQ(o.verbosity, defaults.verbosity);
        EXPECT_EQ(o.ordering, defaults.ordering);
        EXPECT_EQ(o.lowRank, defaults.lowRank);
        EXPECT_EQ(o.lowRankMinSize, defaults.lowRankMinSize);
        EXPECT_EQ(o.lowRankTolerance, defaults.lowRankTolerance);
        EXPECT_EQ(o.lowRankUcfs, defaults.lowRankUcfs);
        EXPECT_EQ(o.refinementTolerance, defaults.refinementTolerance);
        EXPECT_EQ(o.maxRefinementSteps, defaults.maxRefinementSteps);
        EXPECT_EQ(o.memoryRelaxationPercent, defaults.memoryRelaxationPercent);
        EXPECT_EQ(o.threadsPerRank, defaults.threadsPerRank);
        EXPECT_EQ(o.checkResidual, defaults.checkResidual);
    }
    const std::string block = std::string(valid) +
                              "  linear_solver: {ordering: pord, low_rank: off, threads: 2, "
                              "low_rank_tolerance: 1.0e-6, memory_relaxation: 50}\n";
    const auto c = SolidConfig::load(write(block));
    EXPECT_EQ(c.linearSolver.ordering, static_cast<int>(fsi::linalg::Ordering::Pord));
    EXPECT_EQ(c.linearSolver.lowRank, fsi::linalg::LowRank::Off);
    EXPECT_EQ(c.linearSolver.threadsPerRank, 2);
    EXPECT_EQ(c.linearSolver.lowRankTolerance, 1e-6);
    EXPECT_EQ(c.linearSolver.memoryRelaxationPercent, 50);
}

TEST(SolidConfig, LinearSolverBadValuesAreOneLineErrors)
{
    const std::pair<std::string, std::string> cases[] = {
        {"low_rank_tolerance: 0.5", "'solid.linear_solver.low_rank_tolerance' = 0.5 is invalid"},
        {"threads: -2", "'solid.linear_solver.threads' = -2 is invalid"},
        {"max_refinement_steps: -1", "'solid.linear_solver.max_refinement_steps' = -1 is invalid"},
        {"refinement_tolerance: 2", "'solid.linear_solver.refinement_tolerance' = 2 is invalid"},
        {"memory_relaxation: -1", "'solid.linear_solver.memory_relaxation' = -1 is invalid"},
        {"low_rank_min_size: 0", "'solid.linear_solver.low_rank_min_size' = 0 is invalid"},
        {"verbosity: 9", "'solid.linear_solver.verbosity' = 9 is invalid"},
        {"ordering: nested", "'solid.linear_solver.ordering'"},
        {"low_rank: maybe", "'solid.linear_solver.low_rank'"},
        {"low_rank_variant: hodlr", "'solid.linear_solver.low_rank_variant'"},
        {"blr: on", "unknown key 'blr' in 'solid.linear_solver'"},
    };
    for (const auto& [entry, expected] : cases)
    {
        const std::string msg = errorOf(std::string(valid) + "  linear_solver: {" + entry + "}\n");
        EXPECT_NE(msg.find(expected), std::string::npos) << entry << " -> " << msg;
    }
}
