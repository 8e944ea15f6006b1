// SPDX-License-Identifier: GPL-3.0-or-later
// Typed, versioned coupling messages. Pure data and encoding: no MPI in this header.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace fsi
{
namespace comm
{

// Bumped whenever the header layout or the meaning of a kind's payload changes.
// 2: Solve carries the fluid accuracy; 3: displacements and forces travel as distributed rows
constexpr std::int32_t kProtocolVersion = 3;
// "FSIC" as a little-endian 32-bit number; identifies our messages on the wire.
constexpr std::int64_t kMessageMagic = 0x43495346;

// What a message carries. Payload parts: values (bulk doubles, e.g. interface arrays),
// scalars (a few doubles), integers (a few int64), text.
//  Hello, HelloReply  the handshake (Channel does it): integers = [role, ranks, interface
//                     sizes...], text = program name; verdict [accepted 0|1], text = reason
//  Abort              either way: text = reason; the receiver throws PeerAbortError
//  InterfaceGeometry, Solve, Forces, Accept, Finish: the coupling protocol; their payloads are
//                     laid out in fsi/comm/Protocol.hpp (the one description, used by both
//                     programs)
enum class MessageKind : std::int32_t
{
    Hello = 1,
    HelloReply = 2,
    InterfaceGeometry = 3,
    Solve = 4,
    Forces = 5,
    Accept = 6,
    Finish = 7,
    Abort = 8,
};

// "Hello", "Solve", ...; "Unknown(<n>)" for a value outside the enum.
std::string toString(MessageKind kind);
bool isKnownKind(std::int64_t value);

// Fixed-size header sent before every payload. Counts are element counts.
struct MessageHeader
{
    std::int32_t version = kProtocolVersion;
    MessageKind kind = MessageKind::Finish;
    std::int64_t timeStep = 0;     // time level index, 0 before the first level
    std::int64_t iteration = 0;    // coupling iteration within the level
    std::int64_t valueCount = 0;   // number of bulk doubles in the payload
    std::int64_t scalarCount = 0;  // number of small doubles in the payload
    std::int64_t integerCount = 0; // number of int64 in the payload
    std::int64_t textBytes = 0;    // bytes of text in the payload (no terminator)
};

// The header travels as kHeaderWords int64: magic, version, kind, step, iteration, four
// counts and a check word, so truncated or foreign data is caught.
constexpr int kHeaderWords = 10;
using EncodedHeader = std::array<std::int64_t, kHeaderWords>;

EncodedHeader encodeHeader(const MessageHeader& header);
// Throws ProtocolError with a one-line message when magic, check word, kind or a count is
// invalid, or when the version differs from expectedVersion (names both versions).
MessageHeader decodeHeader(const EncodedHeader& words,
                           std::int32_t expectedVersion = kProtocolVersion);

// One message as the API sees it. Values are in SI units as agreed per kind.
struct Message
{
    MessageKind kind = MessageKind::Finish;
    std::int64_t timeStep = 0;
    std::int64_t iteration = 0;
    std::vector<double> values;         // on the receiving side: on the local root only
    std::vector<double> scalars;        // on the receiving side: on every local rank
    std::vector<std::int64_t> integers; // on the receiving side: on every local rank
    std::string text;                   // on the receiving side: on every local rank
    std::int64_t valueCount = 0;        // on the receiving side: on every local rank
};

MessageHeader headerOf(const Message& message);

// Payload bytes: values, scalars, integers, then text, native byte order (homogeneous clusters).
std::vector<char> encodePayload(const Message& message);
// Fills values/scalars/integers/text of message from bytes laid out as encodePayload does; counts
// come from header. Throws ProtocolError when the size does not match.
void decodePayload(const MessageHeader& header, const std::vector<char>& bytes, Message& message);

} // namespace comm
} // namespace fsi
