// SPDX-License-Identifier: GPL-3.0-or-later
#include "fsi/comm/Message.hpp"

#include "fsi/comm/Errors.hpp"

#include <cstring>

namespace fsi::comm
{

namespace
{
// Limit of one payload part; keeps byte counts inside MPI's int counts.
constexpr std::int64_t kMaxCount = std::int64_t(1) << 27;

std::int64_t checkWord(const EncodedHeader& w)
{
    std::uint64_t sum = 0x9E3779B97F4A7C15ull;
    for (int i = 0; i < kHeaderWords - 1; ++i)
    {
        sum = (sum << 7 | sum >> 57) ^ static_cast<std::uint64_t>(w[i]);
    }
    return static_cast<std::int64_t>(sum);
}
} // namespace

std::string toString(MessageKind kind)
{
    switch (kind)
    {
    case MessageKind::Hello:
        return "Hello";
    case MessageKind::HelloReply:
        return "HelloReply";
    case MessageKind::InterfaceGeometry:
        return "InterfaceGeometry";
    case MessageKind::Solve:
        return "Solve";
    case MessageKind::Forces:
        return "Forces";
    case MessageKind::Accept:
        return "Accept";
    case MessageKind::Finish:
        return "Finish";
    case MessageKind::Abort:
        return "Abort";
    }
    return "Unknown(" + std::to_string(static_cast<std::int64_t>(kind)) + ")";
}

bool isKnownKind(std::int64_t value)
{
    return value >= static_cast<std::int64_t>(MessageKind::Hello) &&
           value <= static_cast<std::int64_t>(MessageKind::Abort);
}

EncodedHeader encodeHeader(const MessageHeader& h)
{
    EncodedHeader w{kMessageMagic,
                    h.version,
                    static_cast<std::int64_t>(h.kind),
                    h.timeStep,
                    h.iteration,
                    h.valueCount,
                    h.scalarCount,
                    h.integerCount,
                    h.textBytes,
                    0};
    w[kHeaderWords - 1] = checkWord(w);
    return w;
}

MessageHeader decodeHeader(const EncodedHeader& w, std::int32_t expectedVersion)
{
    if (w[0] != kMessageMagic)
    {
        throw ProtocolError(
            "fsi::comm: received data that is not an fsi::comm message (bad magic " +
            std::to_string(w[0]) + "); is the peer an fsi program?");
    }
    if (w[kHeaderWords - 1] != checkWord(w))
    {
        throw ProtocolError("fsi::comm: corrupt message header (check word mismatch)");
    }
    if (w[1] != expectedVersion)
    {
        throw ProtocolError("fsi::comm: protocol version mismatch: peer speaks version " +
                            std::to_string(w[1]) + ", this program version " +
                            std::to_string(expectedVersion) +
                            "; build both programs from the same source");
    }
    if (!isKnownKind(w[2]))
    {
        throw ProtocolError("fsi::comm: unknown message kind " + std::to_string(w[2]));
    }
    for (int i = 5; i <= 8; ++i)
    {
        if (w[i] < 0 || w[i] > kMaxCount)
        {
            throw ProtocolError("fsi::comm: message header has an invalid count " +
                                std::to_string(w[i]));
        }
    }
    MessageHeader h;
    h.version = static_cast<std::int32_t>(w[1]);
    h.kind = static_cast<MessageKind>(w[2]);
    h.timeStep = w[3];
    h.iteration = w[4];
    h.valueCount = w[5];
    h.scalarCount = w[6];
    h.integerCount = w[7];
    h.textBytes = w[8];
    return h;
}

MessageHeader headerOf(const Message& m)
{
    MessageHeader h;
    h.kind = m.kind;
    h.timeStep = m.timeStep;
    h.iteration = m.iteration;
    h.valueCount = static_cast<std::int64_t>(m.values.size());
    h.scalarCount = static_cast<std::int64_t>(m.scalars.size());
    h.integerCount = static_cast<std::int64_t>(m.integers.size());
    h.textBytes = static_cast<std::int64_t>(m.text.size());
    if (h.valueCount > kMaxCount || h.scalarCount > kMaxCount || h.integerCount > kMaxCount ||
        h.textBytes > kMaxCount)
    {
        throw CommError("fsi::comm: message " + toString(m.kind) + " is too large (limit " +
                        std::to_string(kMaxCount) + " elements per part)");
    }
    return h;
}

std::vector<char> encodePayload(const Message& m)
{
    const std::size_t nv = m.values.size() * sizeof(double);
    const std::size_t ns = m.scalars.size() * sizeof(double);
    const std::size_t ni = m.integers.size() * sizeof(std::int64_t);
    std::vector<char> bytes(nv + ns + ni + m.text.size());
    char* p = bytes.data();
    if (nv)
        std::memcpy(p, m.values.data(), nv);
    p += nv;
    if (ns)
        std::memcpy(p, m.scalars.data(), ns);
    p += ns;
    if (ni)
        std::memcpy(p, m.integers.data(), ni);
    p += ni;
    if (!m.text.empty())
        std::memcpy(p, m.text.data(), m.text.size());
    return bytes;
}

void decodePayload(const MessageHeader& h, const std::vector<char>& bytes, Message& m)
{
    const std::size_t nv = static_cast<std::size_t>(h.valueCount) * sizeof(double);
    const std::size_t ns = static_cast<std::size_t>(h.scalarCount) * sizeof(double);
    const std::size_t ni = static_cast<std::size_t>(h.integerCount) * sizeof(std::int64_t);
    const std::size_t nt = static_cast<std::size_t>(h.textBytes);
    if (bytes.size() != nv + ns + ni + nt)
    {
        throw ProtocolError("fsi::comm: " + toString(h.kind) + " payload has " +
                            std::to_string(bytes.size()) + " bytes, header announces " +
                            std::to_string(nv + ns + ni + nt));
    }
    const char* p = bytes.data();
    m.kind = h.kind;
    m.timeStep = h.timeStep;
    m.iteration = h.iteration;
    m.valueCount = h.valueCount;
    m.values.resize(h.valueCount);
    if (nv)
        std::memcpy(m.values.data(), p, nv);
    p += nv;
    m.scalars.resize(h.scalarCount);
    if (ns)
        std::memcpy(m.scalars.data(), p, ns);
    p += ns;
    m.integers.resize(h.integerCount);
    if (ni)
        std::memcpy(m.integers.data(), p, ni);
    p += ni;
    m.text.assign(p, nt);
}

} // namespace fsi::comm
