// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/Archive.hpp"

#include "io/AtomicFile.hpp"

#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace fsi::io
{

namespace
{
const char magic[8] = {'F', 'S', 'I', 'A', 'R', 'C', '1', '\n'};

std::uint64_t fnv1a(const char* data, std::size_t n)
{
    std::uint64_t h = 1469598103934665603ull;
    for (std::size_t i = 0; i < n; ++i)
    {
        h ^= static_cast<unsigned char>(data[i]);
        h *= 1099511628211ull;
    }
    return h;
}

template <class T> void append(std::string& out, const T& value)
{
    out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

void appendEntry(std::string& out, const std::string& name, char kind, const char* data,
                 std::uint64_t bytes)
{
    append(out, static_cast<std::uint32_t>(name.size()));
    out += name;
    out += kind;
    append(out, bytes);
    out.append(data, bytes);
}
} // namespace

void ArchiveWriter::put(const std::string& name, const std::vector<double>& values)
{
    appendEntry(bytes_, name, 'd', reinterpret_cast<const char*>(values.data()),
                values.size() * sizeof(double));
}

void ArchiveWriter::put(const std::string& name, const std::vector<int>& values)
{
    appendEntry(bytes_, name, 'i', reinterpret_cast<const char*>(values.data()),
                values.size() * sizeof(int));
}

void ArchiveWriter::putText(const std::string& name, const std::string& text)
{
    appendEntry(bytes_, name, 's', text.data(), text.size());
}

void ArchiveWriter::commit(const std::string& path) const
{
    std::string all(magic, sizeof magic);
    all += bytes_;
    const std::uint64_t sum = fnv1a(all.data(), all.size());
    append(all, sum);
    writeFileAtomically(path, all);
}

ArchiveReader::ArchiveReader(const std::string& path) : path_(path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw std::runtime_error(path + ": cannot read the restart file (missing? run without --restart)");
    const std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto corrupt = [&](const char* why) {
        return std::runtime_error(path + ": corrupted restart file (" + std::string(why) +
                                  "); restart from an older checkpoint or run from the start");
    };
    if (all.size() < sizeof magic + sizeof(std::uint64_t) || std::memcmp(all.data(), magic, sizeof magic) != 0)
        throw corrupt("not an fsi-toolkit archive or truncated");
    const std::size_t body = all.size() - sizeof(std::uint64_t);
    std::uint64_t sum = 0;
    std::memcpy(&sum, all.data() + body, sizeof sum);
    if (sum != fnv1a(all.data(), body))
        throw corrupt("checksum mismatch");
    std::size_t at = sizeof magic;
    while (at < body)
    {
        std::uint32_t nameLength = 0;
        std::uint64_t bytes = 0;
        if (at + sizeof nameLength > body)
            throw corrupt("bad entry header");
        std::memcpy(&nameLength, all.data() + at, sizeof nameLength);
        at += sizeof nameLength;
        if (at + nameLength + 1 + sizeof bytes > body)
            throw corrupt("bad entry header");
        const std::string name = all.substr(at, nameLength);
        at += nameLength;
        Entry e;
        e.kind = all[at++];
        std::memcpy(&bytes, all.data() + at, sizeof bytes);
        at += sizeof bytes;
        if (bytes > body - at)
            throw corrupt("entry runs past the end");
        e.bytes = all.substr(at, bytes);
        at += bytes;
        entries_[name] = std::move(e);
    }
}

const ArchiveReader::Entry& ArchiveReader::entry(const std::string& name, char kind) const
{
    const auto it = entries_.find(name);
    if (it == entries_.end())
        throw std::runtime_error(path_ + ": restart file has no entry '" + name +
                                 "' (written by another version or case?)");
    if (it->second.kind != kind)
        throw std::runtime_error(path_ + ": restart entry '" + name + "' has the wrong kind");
    return it->second;
}

std::vector<double> ArchiveReader::doubles(const std::string& name) const
{
    const auto& e = entry(name, 'd');
    std::vector<double> v(e.bytes.size() / sizeof(double));
    if (!v.empty())
        std::memcpy(v.data(), e.bytes.data(), v.size() * sizeof(double));
    return v;
}

std::vector<int> ArchiveReader::ints(const std::string& name) const
{
    const auto& e = entry(name, 'i');
    std::vector<int> v(e.bytes.size() / sizeof(int));
    if (!v.empty())
        std::memcpy(v.data(), e.bytes.data(), v.size() * sizeof(int));
    return v;
}

double ArchiveReader::scalar(const std::string& name) const
{
    const auto v = doubles(name);
    if (v.size() != 1)
        throw std::runtime_error(path_ + ": restart entry '" + name + "' is not a scalar");
    return v[0];
}

int ArchiveReader::integer(const std::string& name) const
{
    const auto v = ints(name);
    if (v.size() != 1)
        throw std::runtime_error(path_ + ": restart entry '" + name + "' is not a scalar");
    return v[0];
}

std::string ArchiveReader::text(const std::string& name) const
{
    return entry(name, 's').bytes;
}

} // namespace fsi::io
