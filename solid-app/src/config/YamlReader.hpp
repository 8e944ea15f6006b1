// SPDX-License-Identifier: GPL-3.0-or-later
// Strict access to a YAML mapping: every key a block knows is declared, unknown keys,
// missing required keys and wrong types are errors of one line naming the file and the
// key path ("beam.yaml: unknown key 'materail' in 'solid' (did you mean 'material'?)").
// Other layers' blocks (e.g. the driver's `coupling`) can reuse it.
// Block::load also rejects what yaml-cpp accepts silently: duplicate keys (anywhere), a
// directory, files over kMaxConfigBytes, lists over kMaxListEntries entries, nesting deeper
// than kMaxConfigDepth; number()/numbers()/table() reject .inf and .nan.
#pragma once
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace YAML
{
class Node;
}

namespace fsi::config
{

// Input size caps (a config is a few kB; large data belong in mesh or data files).
constexpr std::size_t kMaxConfigBytes = 1u << 20; // 1 MiB
constexpr std::size_t kMaxListEntries = 10000;    // any YAML list
constexpr int kMaxConfigDepth = 32;               // nesting of blocks and lists

class Block
{
public:
    // Loads `file` (throws one-line errors for unreadable files and YAML syntax).
    static Block load(const std::string& file);

    Block(const Block&);
    Block& operator=(const Block&);
    ~Block();

    const std::string& file() const { return file_; }
    const std::string& path() const { return path_; } // e.g. "solid.material"
    // Full dotted name of a child key, for messages.
    std::string keyName(const std::string& key) const;

    bool has(const std::string& key) const;
    // Throws unless every key of this block is in `known` (with a did-you-mean hint).
    void allowOnly(const std::vector<std::string>& known) const;

    Block block(const std::string& key) const; // required mapping
    std::optional<Block> optionalBlock(const std::string& key) const;
    std::vector<Block> blockList(const std::string& key) const; // required sequence of mappings

    double number(const std::string& key) const;
    double number(const std::string& key, double fallback) const;
    int integer(const std::string& key) const;
    int integer(const std::string& key, int fallback) const;
    bool flag(const std::string& key, bool fallback) const;
    std::string text(const std::string& key) const;
    std::string text(const std::string& key, const std::string& fallback) const;
    // text restricted to `choices`.
    std::string choice(const std::string& key, const std::vector<std::string>& choices) const;
    std::string choice(const std::string& key, const std::vector<std::string>& choices,
                       const std::string& fallback) const;
    std::vector<double> numbers(const std::string& key) const;
    std::array<double, 3> vector3(const std::string& key) const;
    std::vector<std::string> texts(const std::string& key) const;         // scalar or sequence
    std::vector<std::vector<double>> table(const std::string& key) const; // [[a, b], ...]

    // One-line error about `key` of this block.
    [[noreturn]] void fail(const std::string& key, const std::string& what) const;

private:
    Block(std::string file, std::string path, const YAML::Node& node);
    const YAML::Node& node() const;
    YAML::Node child(const std::string& key) const; // required
    std::string file_;
    std::string path_;
    std::unique_ptr<YAML::Node> node_;
};

// A number as printf's %g prints it (keeps small values: 1e-09, not 0.000000); for messages.
std::string formatNumber(double value);

// Closest candidate by edit distance, "" if none is close.
std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates);

} // namespace fsi::config
