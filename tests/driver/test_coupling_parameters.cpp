// SPDX-License-Identifier: GPL-3.0-or-later
// The `coupling` block: the shipped example parses; bad input gives one-line errors naming
// the file and the key.
#include "acceleration/Aitken.hpp"
#include "acceleration/Registry.hpp"
#include "config/ExampleSection.hpp"
#include "config/YamlReader.hpp"
#include "driver/CouplingParameters.hpp"
#include "mapping/RbfPartitionOfUnity.hpp"
#include "mapping/RbfWendlandC2.hpp"
#include "mapping/Registry.hpp"
#include "schedule/Adaptive.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <regex>
#include <set>

using namespace fsi;

namespace
{
std::string writeTemp(const std::string& text)
{
    static int counter = 0;
    const std::string file = "/tmp/fsi-coupling-" + std::to_string(::getpid()) + "-" +
                             std::to_string(counter++) + ".yaml";
    std::ofstream(file) << text;
    return file;
}

driver::CouplingParameters parseText(const std::string& coupling)
{
    const auto file = writeTemp("coupling:\n" + coupling);
    auto p = driver::CouplingParameters::parse(config::Block::load(file).block("coupling"));
    std::remove(file.c_str());
    return p;
}

std::string errorOf(const std::string& coupling)
{
    try
    {
        parseText(coupling);
    }
    catch (const std::runtime_error& e)
    {
        return e.what();
    }
    return "no error";
}

const std::string minimal = "  convergence: {absolute_tolerance: 1.0e-7}\n"
                            "  acceleration: {type: aitken, aitken: {initial_relaxation: 0.5}}\n"
                            "  mapping: {type: nearest-neighbour}\n";
} // namespace

TEST(CouplingParameters, ShippedExampleParses)
{
    const auto p = driver::CouplingParameters::parse(
        config::Block::load(FSI_SOURCE_DIR "/config/coupled.example.yaml").block("coupling"));
    EXPECT_EQ(p.acceleration.type(), "aitken");
    EXPECT_DOUBLE_EQ(p.acceleration.get<acceleration::AitkenParameters>()->initialRelaxation, 0.5);
    EXPECT_EQ(p.mapping.type(), "rbf-wendland-c2");
    EXPECT_DOUBLE_EQ(p.mapping.strategy.get<mapping::WendlandParameters>()->supportRadius, 0.004);
    EXPECT_EQ(p.time.type(), "adaptive");
    EXPECT_DOUBLE_EQ(p.time.get<schedule::AdaptiveParameters>()->end, 3600.0);
    ASSERT_TRUE(p.sectionAngle.has_value());
    EXPECT_DOUBLE_EQ(p.sectionAngle->liftDirection[1], -1.0);
    EXPECT_EQ(p.mapping.strategy.get<mapping::WendlandParameters>()->solver, "auto");
    EXPECT_EQ(p.mapping.strategy.get<mapping::WendlandParameters>()->directMaxPoints, 20000);
    EXPECT_NE(p.echo().find("rbf-wendland-c2: {support_radius: 0.004, solver: auto"),
              std::string::npos);
    EXPECT_EQ(p.checkpoint.every, 1);
    EXPECT_EQ(p.checkpoint.keep, 2);
    EXPECT_EQ(p.recovery.maxRetries, 3);
    EXPECT_DOUBLE_EQ(p.recovery.stepFactor, 0.25);
}

TEST(CouplingParameters, MinimalBlockHasSteadyDefaults)
{
    const auto p = parseText(minimal);
    EXPECT_EQ(p.time.type(), "steady");
    EXPECT_EQ(p.maxIterations, 30);
    EXPECT_FALSE(p.continueOnMaxIterations);
    EXPECT_EQ(p.launch.mode, "mpmd");
}

TEST(CouplingParameters, BadInputNamesTheKey)
{
    EXPECT_NE(errorOf(minimal + "  max_iteration: 3\n").find("unknown key 'max_iteration'"),
              std::string::npos);
    EXPECT_NE(errorOf(minimal + "  max_iterations: 0\n").find("max_iterations"), std::string::npos);
    // Coefficients of a strategy that is not selected.
    const std::string nnWithRbf =
        "  convergence: {absolute_tolerance: 1.0e-7}\n"
        "  acceleration: {type: aitken, aitken: {initial_relaxation: 0.5}}\n"
        "  mapping: {type: nearest-neighbour, rbf-wendland-c2: {support_radius: 1}}\n";
    EXPECT_NE(errorOf(nnWithRbf).find("remove the block or change type"), std::string::npos);
    // Aitken without its required omega_0.
    const std::string noOmega = "  convergence: {absolute_tolerance: 1.0e-7}\n"
                                "  acceleration: {type: aitken, aitken: {}}\n"
                                "  mapping: {type: nearest-neighbour}\n";
    EXPECT_NE(errorOf(noOmega).find("initial_relaxation"), std::string::npos);
    // No tolerance at all.
    const std::string noTolerance =
        "  convergence: {}\n"
        "  acceleration: {type: aitken, aitken: {initial_relaxation: 0.5}}\n"
        "  mapping: {type: nearest-neighbour}\n";
    EXPECT_NE(errorOf(noTolerance).find("coupling.convergence"), std::string::npos);
    // Time list not starting at 0.
    EXPECT_NE(
        errorOf(minimal + "  time: {type: list, times: [1, 2]}\n").find("coupling.time.times"),
        std::string::npos);
    // Negative timeout.
    EXPECT_NE(errorOf(minimal + "  launch: {timeout: -1}\n").find("timeout"), std::string::npos);
    EXPECT_NE(errorOf(minimal + "  checkpoint: {keep: 0}\n").find("coupling.checkpoint.keep"),
              std::string::npos);
    EXPECT_NE(errorOf(minimal + "  checkpoint: {every: -1}\n").find("every"), std::string::npos);
    EXPECT_NE(errorOf(minimal + "  recovery: {relaxation_factor: 1.5}\n").find("relaxation_factor"),
              std::string::npos);
    EXPECT_NE(errorOf(minimal + "  recovery: {retries: 2}\n").find("unknown key 'retries'"),
              std::string::npos);
    EXPECT_NE(errorOf(minimal + "  secant: {response_tolerance: 0.5}\n")
                  .find("coupling.secant.response_tolerance"),
              std::string::npos);
    EXPECT_NEAR(parseText(minimal).secant.responseTolerance, 1e-2, 1e-15); // the default
    EXPECT_NEAR(parseText(minimal).convergence.bandFactor, 2.0, 1e-15);    // the default
    const std::string negativeBand =
        "  convergence: {absolute_tolerance: 1.0e-7, band_factor: -1}\n"
        "  acceleration: {type: aitken, aitken: {initial_relaxation: 0.5}}\n"
        "  mapping: {type: nearest-neighbour}\n";
    EXPECT_NE(errorOf(negativeBand).find("coupling.convergence.band_factor"), std::string::npos)
        << errorOf(negativeBand);
    EXPECT_EQ(parseText(minimal + "  secant: {response_tolerance: 0}\n").secant.responseTolerance,
              0.0);
    EXPECT_NE(errorOf(minimal + "  secant: {min_feedback_margin: 1}\n")
                  .find("coupling.secant.min_feedback_margin"),
              std::string::npos);
    EXPECT_EQ(parseText(minimal).secant.minFeedbackMargin, 0.0); // the default: off
    EXPECT_NEAR(
        parseText(minimal + "  secant: {min_feedback_margin: 0.01}\n").secant.minFeedbackMargin,
        0.01, 1e-15);
}

TEST(CouplingParameters, PartitionOfUnityMappingParsesWithDefaultsAndNamesBadKeys)
{
    const std::string head = "  convergence: {absolute_tolerance: 1.0e-7}\n"
                             "  acceleration: {type: aitken, aitken: {initial_relaxation: 0.5}}\n";
    const auto defaults = parseText(head + "  mapping: {type: rbf-pu}\n");
    EXPECT_EQ(defaults.mapping.type(), "rbf-pu");
    EXPECT_EQ(defaults.mapping.strategy.get<mapping::PartitionOfUnityParameters>()->pointsPerPatch,
              20);
    EXPECT_DOUBLE_EQ(
        defaults.mapping.strategy.get<mapping::PartitionOfUnityParameters>()->centreSpacing, 0.85);
    EXPECT_NE(defaults.echo().find("rbf-pu: {points_per_patch: 20, centre_spacing: 0.85}"),
              std::string::npos)
        << defaults.echo();
    const auto given = parseText(
        head + "  mapping: {type: rbf-pu, rbf-pu: {points_per_patch: 30, centre_spacing: 0.7}}\n");
    EXPECT_EQ(given.mapping.strategy.get<mapping::PartitionOfUnityParameters>()->pointsPerPatch,
              30);
    EXPECT_DOUBLE_EQ(
        given.mapping.strategy.get<mapping::PartitionOfUnityParameters>()->centreSpacing, 0.7);
    const std::string few =
        errorOf(head + "  mapping: {type: rbf-pu, rbf-pu: {points_per_patch: 2}}\n");
    EXPECT_NE(few.find("coupling.mapping.rbf-pu"), std::string::npos) << few;
    EXPECT_NE(few.find("mapping.rbf-pu.points_per_patch must be in [4, 200] (got 2)"),
              std::string::npos)
        << few;
    EXPECT_NE(errorOf(head + "  mapping: {type: rbf-pu, rbf-pu: {support_radius: 1}}\n")
                  .find("unknown key 'support_radius'"),
              std::string::npos);
    EXPECT_NE(errorOf(head + "  mapping: {type: rbf-wendland-c2, rbf-wendland-c2: "
                             "{support_radius: 1}, rbf-pu: {}}\n")
                  .find("remove the block or change type"),
              std::string::npos);
}

// The forces may take their own mapping strategy (force_mapping); absent, mapping serves both.
TEST(CouplingParameters, ForceMappingIsOptionalAndValidatedLikeTheMapping)
{
    EXPECT_FALSE(parseText(minimal).forceMapping.has_value());
    const auto both = parseText(minimal + "  force_mapping: {type: nearest-projection}\n");
    EXPECT_EQ(both.mapping.type(), "nearest-neighbour");
    ASSERT_TRUE(both.forceMapping.has_value());
    EXPECT_EQ(both.forceMapping->type(), "nearest-projection");
    EXPECT_NE(both.echo().find("force_mapping:\n    type: nearest-projection"), std::string::npos)
        << both.echo();
    const std::string bad = errorOf(minimal + "  force_mapping: {type: rbf-wendland-c2, "
                                              "rbf-wendland-c2: {support_radius: -1}}\n");
    EXPECT_NE(bad.find("force_mapping.rbf-wendland-c2"), std::string::npos) << bad;
    EXPECT_NE(errorOf(minimal + "  force_mapping: {type: linear}\n").find("force_mapping.type"),
              std::string::npos);
}

// mapping.smoothing_radius: 0 (off) by default, echoed, and a negative radius is a one-line
// error naming the key.
TEST(CouplingParameters, MappingSmoothingRadiusIsOptionalAndValidated)
{
    EXPECT_EQ(parseText(minimal).mapping.smoothingRadius, 0.0);
    const auto smoothed = parseText("  convergence: {absolute_tolerance: 1.0e-7}\n"
                                    "  acceleration: {type: aitken, aitken: {initial_relaxation: "
                                    "0.5}}\n"
                                    "  mapping: {type: nearest-projection, smoothing_radius: "
                                    "2.0e-4}\n");
    EXPECT_DOUBLE_EQ(smoothed.mapping.smoothingRadius, 2.0e-4);
    EXPECT_NE(smoothed.echo().find("smoothing_radius: 0.0002"), std::string::npos)
        << smoothed.echo();
    const std::string bad = errorOf("  convergence: {absolute_tolerance: 1.0e-7}\n"
                                    "  acceleration: {type: aitken, aitken: {initial_relaxation: "
                                    "0.5}}\n"
                                    "  mapping: {type: nearest-neighbour, smoothing_radius: -1}\n");
    EXPECT_NE(bad.find("'coupling.mapping.smoothing_radius'"), std::string::npos) << bad;
    EXPECT_EQ(bad.find('\n'), std::string::npos) << bad;
}

// mapping.overlap_tolerance out of range is named under its own key (it used to be reported
// under coupling.mapping.type).
TEST(CouplingParameters, MappingOverlapToleranceIsNamedUnderItsKey)
{
    const std::string bad = errorOf("  convergence: {absolute_tolerance: 1.0e-7}\n"
                                    "  acceleration: {type: aitken, aitken: {initial_relaxation: "
                                    "0.5}}\n"
                                    "  mapping: {type: nearest-neighbour, overlap_tolerance: 0}\n");
    EXPECT_NE(bad.find("'coupling.mapping.overlap_tolerance'"), std::string::npos) << bad;
    EXPECT_EQ(bad.find('\n'), std::string::npos) << bad;
}

// Issue 15: a bad RBF coefficient is named under its own block with its value in %g, and the
// launch timeout is capped (1e10 s overflowed the comm layer's clock).
TEST(CouplingParameters, StrategyErrorsNameTheirBlockAndKeepSmallValues)
{
    const std::string badRadius =
        "  convergence: {absolute_tolerance: 1.0e-7}\n"
        "  acceleration: {type: aitken, aitken: {initial_relaxation: 0.5}}\n"
        "  mapping: {type: rbf-wendland-c2, rbf-wendland-c2: {support_radius: -1.0e-7}}\n";
    const std::string what = errorOf(badRadius);
    EXPECT_NE(what.find("mapping.rbf-wendland-c2"), std::string::npos) << what;
    EXPECT_EQ(what.find("mapping.type"), std::string::npos) << what;
    const std::string tinyOmega =
        "  convergence: {absolute_tolerance: 1.0e-7}\n"
        "  acceleration: {type: aitken, aitken: {initial_relaxation: -1.0e-7}}\n"
        "  mapping: {type: nearest-neighbour}\n";
    EXPECT_NE(errorOf(tinyOmega).find("got -1e-07"), std::string::npos) << errorOf(tinyOmega);
    EXPECT_NE(errorOf(minimal + "  launch: {timeout: 1.0e10}\n").find("coupling.launch.timeout"),
              std::string::npos);
    EXPECT_NO_THROW(parseText(minimal + "  launch: {timeout: 1.0e9}\n"));
}

namespace
{
// The keys documented for each strategy block in config/coupled.example.yaml's `section`
// (e.g. "acceleration"): the selected strategy's block and the commented-out alternatives
// ("# iqn-ils:" followed by "#   key: value" lines).
std::map<std::string, std::set<std::string>> documentedKeys(const std::string& section,
                                                            const std::vector<std::string>& names)
{
    const std::regex keyLine("^( *)([a-z0-9_-]+):.*");
    std::map<std::string, std::set<std::string>> keys;
    std::string current;
    std::size_t currentIndent = 0;
    for (std::string line : fsi::testing::exampleSection("coupled.example.yaml", section))
    {
        // uncomment "    #   key:" -> "        key:" (the column of the key is kept)
        line = std::regex_replace(line, std::regex("^( *)# "), "$1  ");
        std::smatch m;
        if (!std::regex_match(line, m, keyLine))
            continue;
        const std::size_t indent = m[1].length();
        if (std::find(names.begin(), names.end(), m[2].str()) != names.end())
        {
            current = m[2];
            currentIndent = indent;
            keys[current];
        }
        else if (!current.empty() && indent > currentIndent)
            keys[current].insert(m[2]);
        else
            current.clear();
    }
    return keys;
}
} // namespace

// Every registered strategy of `section` with coefficients is documented in the shipped example
// with exactly its keys; one without coefficients has no block.
template <class Product>
void expectDocumented(const std::string& section,
                      const std::vector<config::StrategyType<Product>>& types)
{
    std::vector<std::string> names;
    for (const auto& t : types)
        names.push_back(t.name);
    const auto documented = documentedKeys(section, names);
    std::size_t withKeys = 0;
    for (const auto& t : types)
    {
        if (t.keys.empty())
        {
            EXPECT_EQ(documented.count(t.name), 0u) << t.name << " has no coefficients";
            continue;
        }
        ++withKeys;
        ASSERT_EQ(documented.count(t.name), 1u)
            << t.name << " is registered but not documented in config/coupled.example.yaml";
        EXPECT_EQ(documented.at(t.name), std::set<std::string>(t.keys.begin(), t.keys.end()))
            << "keys of " << section << "." << t.name;
    }
    EXPECT_EQ(documented.size(), withKeys);
}

TEST(CouplingParameters, DocumentedAcceleratorKeysMatchTheRegistry)
{
    expectDocumented("acceleration", acceleration::acceleratorTypes());
}

TEST(CouplingParameters, DocumentedMappingKeysMatchTheRegistry)
{
    expectDocumented("mapping", mapping::mappingTypes());
}
