// SPDX-License-Identifier: GPL-3.0-or-later
// A small binary archive for restart files: named arrays of doubles, ints and one string each,
// little-endian host layout, a magic header and an FNV-1a checksum over everything before it.
// ArchiveWriter::commit writes atomically (temp file + rename): a killed run leaves either the
// old file or the new one, never half of one. ArchiveReader throws std::runtime_error naming
// the file for a missing entry, a wrong kind, a truncated or corrupted file.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace fsi::io
{

class ArchiveWriter
{
public:
    void put(const std::string& name, const std::vector<double>& values);
    void put(const std::string& name, const std::vector<int>& values);
    void put(const std::string& name, double value) { put(name, std::vector<double>{value}); }
    void put(const std::string& name, int value) { put(name, std::vector<int>{value}); }
    void putText(const std::string& name, const std::string& text);
    // Writes all entries to `path` atomically. Throws naming the path.
    void commit(const std::string& path) const;

private:
    std::string bytes_;
};

class ArchiveReader
{
public:
    explicit ArchiveReader(const std::string& path);
    bool has(const std::string& name) const { return entries_.count(name) > 0; }
    std::vector<double> doubles(const std::string& name) const;
    std::vector<int> ints(const std::string& name) const;
    double scalar(const std::string& name) const;
    int integer(const std::string& name) const;
    std::string text(const std::string& name) const;
    const std::string& path() const { return path_; }

private:
    struct Entry
    {
        char kind = 0;
        std::string bytes;
    };
    const Entry& entry(const std::string& name, char kind) const;
    std::string path_;
    std::map<std::string, Entry> entries_;
};

} // namespace fsi::io
