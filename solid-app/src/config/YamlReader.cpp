// SPDX-License-Identifier: GPL-3.0-or-later
#include "config/YamlReader.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <stdexcept>

namespace fsi::config
{
namespace
{

std::string baseName(const std::string& file)
{
    return std::filesystem::path(file).filename().string();
}

std::size_t editDistance(const std::string& a, const std::string& b)
{
    std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        prev[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
    {
        cur[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j)
            cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
        std::swap(prev, cur);
    }
    return prev[b.size()];
}

// "line N" of a node, for messages (yaml-cpp counts from 0).
std::string lineOf(const YAML::Node& n)
{
    return "line " + std::to_string(n.Mark().line + 1);
}

// Duplicate keys (yaml-cpp keeps both, the first wins on lookup) and over-long lists anywhere
// in the tree are errors. `path` is the dotted key path of `n`.
void checkTree(const std::string& file, const YAML::Node& n, const std::string& path, int depth)
{
    const std::string where = path.empty() ? std::string("top level") : "'" + path + "'";
    if (depth > kMaxConfigDepth)
        throw std::runtime_error(baseName(file) + ": " + where + " is nested deeper than " +
                                 std::to_string(kMaxConfigDepth) +
                                 " levels; a config has a few levels of blocks");
    if (n.IsMap())
    {
        std::set<std::string> seen;
        for (const auto& entry : n)
        {
            const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "?";
            if (!seen.insert(key).second)
                throw std::runtime_error(baseName(file) + ": duplicate key '" + key + "' in " +
                                         where + " at " + lineOf(entry.first) +
                                         "; keep only one of them");
            checkTree(file, entry.second, path.empty() ? key : path + "." + key, depth + 1);
        }
    }
    else if (n.IsSequence())
    {
        if (n.size() > kMaxListEntries)
            throw std::runtime_error(baseName(file) + ": " + where + " has " +
                                     std::to_string(n.size()) + " entries, more than the " +
                                     std::to_string(kMaxListEntries) +
                                     " a config list may have; shorten the list");
        for (std::size_t i = 0; i < n.size(); ++i)
            checkTree(file, n[i], path + "[" + std::to_string(i) + "]", depth + 1);
    }
}

double finite(const Block& b, const std::string& key, double value)
{
    if (!std::isfinite(value))
        b.fail(key, "must be a finite number (not .inf or .nan)");
    return value;
}

} // namespace

std::string formatNumber(double value)
{
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates)
{
    std::string best;
    std::size_t bestDistance = std::max<std::size_t>(2, word.size() / 3) + 1;
    for (const auto& c : candidates)
    {
        const std::size_t d = editDistance(word, c);
        if (d < bestDistance)
        {
            bestDistance = d;
            best = c;
        }
    }
    return best;
}

Block::Block(std::string file, std::string path, const YAML::Node& node)
    : file_(std::move(file)), path_(std::move(path)), node_(std::make_unique<YAML::Node>(node))
{
}
Block::Block(const Block& o)
    : file_(o.file_), path_(o.path_), node_(std::make_unique<YAML::Node>(*o.node_))
{
}
Block& Block::operator=(const Block& o)
{
    file_ = o.file_;
    path_ = o.path_;
    node_ = std::make_unique<YAML::Node>(*o.node_);
    return *this;
}
Block::~Block() = default;

Block Block::load(const std::string& file)
{
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec))
        throw std::runtime_error(file + ": is a directory, not a config file; give the path of "
                                        "the YAML config");
    const auto bytes = std::filesystem::file_size(file, ec);
    if (!ec && bytes > kMaxConfigBytes)
        throw std::runtime_error(file + ": " + std::to_string(bytes) + " bytes, more than the " +
                                 std::to_string(kMaxConfigBytes) +
                                 " a config file may have; is this the right file?");
    YAML::Node root;
    try
    {
        root = YAML::LoadFile(file);
    }
    catch (const YAML::BadFile&)
    {
        throw std::runtime_error(file + ": cannot open the config file");
    }
    catch (const YAML::Exception& e)
    {
        throw std::runtime_error(baseName(file) + ": YAML syntax error at line " +
                                 std::to_string(e.mark.line + 1) + ": " + e.msg);
    }
    if (!root.IsMap())
        throw std::runtime_error(baseName(file) + ": the top level must be a mapping of keys");
    checkTree(file, root, "", 0);
    return Block(file, "", root);
}

const YAML::Node& Block::node() const
{
    return *node_;
}

std::string Block::keyName(const std::string& key) const
{
    return path_.empty() ? key : path_ + "." + key;
}

void Block::fail(const std::string& key, const std::string& what) const
{
    throw std::runtime_error(baseName(file_) + ": '" + keyName(key) + "' " + what);
}

bool Block::has(const std::string& key) const
{
    return static_cast<bool>(node()[key]);
}

void Block::allowOnly(const std::vector<std::string>& known) const
{
    for (const auto& entry : node())
    {
        const std::string key = entry.first.as<std::string>();
        if (std::find(known.begin(), known.end(), key) != known.end())
            continue;
        std::string msg = baseName(file_) + ": unknown key '" + key + "' in '" +
                          (path_.empty() ? std::string("top level") : path_) + "'";
        const std::string hint = closestMatch(key, known);
        if (!hint.empty())
            msg += " (did you mean '" + hint + "'?)";
        else
        {
            msg += " (known keys:";
            for (const auto& k : known)
                msg += " " + k;
            msg += ")";
        }
        throw std::runtime_error(msg);
    }
}

YAML::Node Block::child(const std::string& key) const
{
    YAML::Node n = node()[key];
    if (!n)
        throw std::runtime_error(baseName(file_) + ": missing key '" + key + "' in '" +
                                 (path_.empty() ? std::string("top level") : path_) + "'");
    return n;
}

Block Block::block(const std::string& key) const
{
    YAML::Node n = child(key);
    if (!n.IsMap())
        fail(key, "must be a mapping of keys");
    return Block(file_, keyName(key), n);
}

std::optional<Block> Block::optionalBlock(const std::string& key) const
{
    if (!has(key))
        return std::nullopt;
    return block(key);
}

std::vector<Block> Block::blockList(const std::string& key) const
{
    YAML::Node n = child(key);
    if (!n.IsSequence())
        fail(key, "must be a list of mappings");
    std::vector<Block> out;
    for (std::size_t i = 0; i < n.size(); ++i)
    {
        if (!n[i].IsMap())
            fail(key, "entry " + std::to_string(i) + " must be a mapping of keys");
        out.push_back(Block(file_, keyName(key) + "[" + std::to_string(i) + "]", n[i]));
    }
    return out;
}

double Block::number(const std::string& key) const
{
    YAML::Node n = child(key);
    try
    {
        if (!n.IsScalar())
            throw YAML::Exception(YAML::Mark(), "");
        return finite(*this, key, n.as<double>());
    }
    catch (const YAML::Exception&)
    {
        fail(key, "must be a number");
    }
}
double Block::number(const std::string& key, double fallback) const
{
    return has(key) ? number(key) : fallback;
}

int Block::integer(const std::string& key) const
{
    YAML::Node n = child(key);
    try
    {
        if (!n.IsScalar())
            throw YAML::Exception(YAML::Mark(), "");
        return n.as<int>();
    }
    catch (const YAML::Exception&)
    {
        fail(key, "must be an integer");
    }
}
int Block::integer(const std::string& key, int fallback) const
{
    return has(key) ? integer(key) : fallback;
}

bool Block::flag(const std::string& key, bool fallback) const
{
    if (!has(key))
        return fallback;
    try
    {
        return node()[key].as<bool>();
    }
    catch (const YAML::Exception&)
    {
        fail(key, "must be true or false");
    }
}

std::string Block::text(const std::string& key) const
{
    YAML::Node n = child(key);
    if (!n.IsScalar())
        fail(key, "must be a text value");
    return n.as<std::string>();
}
std::string Block::text(const std::string& key, const std::string& fallback) const
{
    return has(key) ? text(key) : fallback;
}

std::string Block::choice(const std::string& key, const std::vector<std::string>& choices) const
{
    const std::string value = text(key);
    if (std::find(choices.begin(), choices.end(), value) == choices.end())
    {
        std::string list;
        for (const auto& c : choices)
            list += (list.empty() ? "" : " | ") + c;
        fail(key, "is '" + value + "', must be one of: " + list);
    }
    return value;
}
std::string Block::choice(const std::string& key, const std::vector<std::string>& choices,
                          const std::string& fallback) const
{
    return has(key) ? choice(key, choices) : fallback;
}

std::vector<double> Block::numbers(const std::string& key) const
{
    YAML::Node n = child(key);
    if (!n.IsSequence())
        fail(key, "must be a list of numbers, e.g. [1.0, 2.0]");
    std::vector<double> out;
    try
    {
        for (std::size_t i = 0; i < n.size(); ++i)
            out.push_back(n[i].as<double>());
    }
    catch (const YAML::Exception&)
    {
        fail(key, "must be a list of numbers, e.g. [1.0, 2.0]");
    }
    for (const double v : out)
        finite(*this, key, v);
    return out;
}

std::array<double, 3> Block::vector3(const std::string& key) const
{
    const auto v = numbers(key);
    if (v.size() != 3)
        fail(key, "must have 3 components [x, y, z]");
    return {v[0], v[1], v[2]};
}

std::vector<std::string> Block::texts(const std::string& key) const
{
    YAML::Node n = child(key);
    std::vector<std::string> out;
    if (n.IsScalar())
        out.push_back(n.as<std::string>());
    else if (n.IsSequence())
    {
        for (std::size_t i = 0; i < n.size(); ++i)
        {
            if (!n[i].IsScalar())
                fail(key, "must be a name or a list of names");
            out.push_back(n[i].as<std::string>());
        }
    }
    else
        fail(key, "must be a name or a list of names");
    return out;
}

std::vector<std::vector<double>> Block::table(const std::string& key) const
{
    YAML::Node n = child(key);
    if (!n.IsSequence())
        fail(key, "must be a list of rows, e.g. [[0, 0], [1, 1]]");
    std::vector<std::vector<double>> out;
    try
    {
        for (std::size_t i = 0; i < n.size(); ++i)
        {
            if (!n[i].IsSequence())
                throw YAML::Exception(YAML::Mark(), "");
            std::vector<double> row;
            for (std::size_t j = 0; j < n[i].size(); ++j)
                row.push_back(n[i][j].as<double>());
            out.push_back(row);
        }
    }
    catch (const YAML::Exception&)
    {
        fail(key, "must be a list of rows of numbers, e.g. [[0, 0], [1, 1]]");
    }
    for (const auto& row : out)
        for (const double v : row)
            finite(*this, key, v);
    return out;
}

} // namespace fsi::config
