// SPDX-License-Identifier: GPL-3.0-or-later
// Strict access to a YAML mapping: every key a block knows is declared, unknown keys,
// missing required keys and wrong types are errors of one line naming the file and the
// key path ("beam.yaml: unknown key 'materail' in 'solid' (did you mean 'material'?)").
// Other layers' blocks (e.g. the driver's `coupling`) can reuse it.
#pragma once
#include <array>
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

// Closest candidate by edit distance, "" if none is close.
std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates);

} // namespace fsi::config
