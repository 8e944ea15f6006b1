// SPDX-License-Identifier: GPL-3.0-or-later
// The shipped examples document exactly the keys the registries of the flat strategy blocks
// accept: solid.material (material/Registry.hpp) in config/solid.example.yaml, and the time
// blocks (schedule/Registry.hpp) of config/solid.example.yaml and config/coupled.example.yaml.
#include "config/ExampleSection.hpp"
#include "material/Material.hpp"
#include "material/MaterialParameters.hpp"
#include "material/Registry.hpp"
#include "schedule/Registry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

namespace
{

struct DocumentedBlock
{
    std::set<std::string> keys;                  // the block's own keys, commented or not
    std::map<std::string, std::string> comments; // key -> the comment on its line
};

// The keys directly under "  <section>:" of `file` (a "# key:" line counts: the examples show
// alternatives commented out).
DocumentedBlock documentedBlock(const std::string& file, const std::string& section)
{
    const std::regex keyLine("^    #? ?([A-Za-z_]+):[^#]*(#.*)?$");
    DocumentedBlock block;
    for (const std::string& line : fsi::testing::exampleSection(file, section))
    {
        std::smatch m;
        if (std::regex_match(line, m, keyLine))
        {
            block.keys.insert(m[1]);
            block.comments[m[1]] = m[2];
        }
    }
    return block;
}

} // namespace

TEST(DocumentedKeys, MaterialBlockMatchesTheLawRegistry)
{
    using fsi::material::materialTypes;
    const DocumentedBlock doc = documentedBlock("solid.example.yaml", "material");
    std::set<std::string> registered{"type", "density"}; // density: read by the solid
    for (const auto& law : materialTypes())
        registered.insert(law.keys.begin(), law.keys.end());
    EXPECT_EQ(doc.keys, registered);
    // the type line lists every law
    std::size_t listed = 0;
    for (const auto& law : materialTypes())
    {
        EXPECT_NE(doc.comments.at("type").find(law.name), std::string::npos) << law.name;
        ++listed;
    }
    EXPECT_EQ(listed, materialTypes().size());
    // a key only some laws read says so ("viscoelastic only")
    for (const auto& key : registered)
    {
        std::string owners;
        std::size_t count = 0;
        for (const auto& law : materialTypes())
            if (std::find(law.keys.begin(), law.keys.end(), key) != law.keys.end())
            {
                owners = law.name;
                ++count;
            }
        if (count == 1)
        {
            EXPECT_NE(doc.comments.at(key).find(owners + " only"), std::string::npos) << key;
        }
    }
}

TEST(MaterialRegistry, EachLawBuildsItselfFromItsKeyword)
{
    for (const auto& law : fsi::material::materialTypes())
    {
        fsi::material::MaterialParameters p;
        p.type = law.name;
        p.youngsModulus = 1.0e6;
        p.poissonRatio = 0.3;
        if (law.name == "viscoelastic")
        {
            p.modulusBasis = "long-term";
            p.pronyConvention = "long-term-gamma";
            p.pronyCoefficients = {0.5};
            p.pronyTimes = {2.0};
        }
        const auto m = fsi::material::makeMaterial(p, fsi::material::Kinematics::TotalLagrangian);
        EXPECT_EQ(m->name(), law.name);
        // every law is Hooke at zero strain: the instantaneous tangent's shear entry is G_inst
        EXPECT_NEAR(m->initialTangent()(3, 3), p.instantaneousShearModulus(),
                    1e-9 * p.instantaneousShearModulus())
            << law.name;
    }
    EXPECT_EQ(fsi::material::findMaterialType("hookean"), nullptr);
}

// The time blocks of both examples document every registered schedule and exactly the keys the
// schedules read (solid.time also has its own load_factor).
TEST(DocumentedKeys, TimeBlocksMatchTheScheduleRegistry)
{
    using fsi::schedule::scheduleTypes;
    std::set<std::string> registered{"type"};
    for (const auto& type : scheduleTypes())
        registered.insert(type.keys.begin(), type.keys.end());
    std::set<std::string> standalone = registered;
    standalone.insert("load_factor");
    const DocumentedBlock coupled = documentedBlock("coupled.example.yaml", "time");
    const DocumentedBlock solid = documentedBlock("solid.example.yaml", "time");
    EXPECT_EQ(coupled.keys, registered);
    EXPECT_EQ(solid.keys, standalone);
    for (const auto& type : scheduleTypes())
    {
        EXPECT_NE(coupled.comments.at("type").find(type.name), std::string::npos) << type.name;
        EXPECT_NE(solid.comments.at("type").find(type.name), std::string::npos) << type.name;
    }
}
