// SPDX-License-Identifier: GPL-3.0-or-later
// The coupling protocol codec (fsi/comm/Protocol.hpp): every message survives encode -> wire
// bytes -> decode exactly, and a payload that does not match the announced sizes is refused
// with a one-line ProtocolError.
#include "fsi/comm/Protocol.hpp"

#include <gtest/gtest.h>

using namespace fsi::comm;

namespace
{
// Through the wire encoding, as the receiving root sees it.
Message overTheWire(const Message& sent)
{
    Message received;
    const MessageHeader header = decodeHeader(encodeHeader(headerOf(sent)));
    received.kind = header.kind;
    received.timeStep = header.timeStep;
    received.iteration = header.iteration;
    decodePayload(header, encodePayload(sent), received);
    received.valueCount = header.valueCount;
    return received;
}
} // namespace

TEST(Protocol, GeometryRoundTripSplitsPointsCentresAndAreas)
{
    protocol::InterfaceGeometry g{{0, 1, 2, 3, 4, 5}, {6, 7, 8}, {9, 10, 11}}; // 2 points, 1 face
    const protocol::InterfaceGeometry back =
        protocol::decodeGeometry(overTheWire(protocol::encode(g)), 2, 1);
    EXPECT_EQ(back.points, g.points);
    EXPECT_EQ(back.faceCentres, g.faceCentres);
    EXPECT_EQ(back.faceAreas, g.faceAreas);
    EXPECT_THROW(protocol::decodeGeometry(overTheWire(protocol::encode(g)), 1, 1), ProtocolError);
}

TEST(Protocol, SolveWithAndWithoutTheDriversAccuracy)
{
    protocol::Solve own;
    own.level = 3;
    own.iteration = 2;
    own.time = 50.5;
    protocol::Solve back = protocol::decodeSolve(overTheWire(protocol::encode(own)));
    EXPECT_EQ(back.level, 3);
    EXPECT_EQ(back.iteration, 2);
    EXPECT_EQ(back.time, 50.5);
    EXPECT_FALSE(back.accuracyGiven);

    protocol::Solve asked = own;
    asked.accuracyGiven = true;
    asked.forceTolerance = 5e-5;
    asked.residualDrop = 0.01;
    asked.minIterations = 10;
    back = protocol::decodeSolve(overTheWire(protocol::encode(asked)));
    EXPECT_TRUE(back.accuracyGiven);
    EXPECT_EQ(back.forceTolerance, 5e-5);
    EXPECT_EQ(back.residualDrop, 0.01);
    EXPECT_EQ(back.minIterations, 10);

    // the displacements travel as distributed rows, never in the message (version 3)
    Message withValues = protocol::encode(own);
    withValues.values = {1e-3, -2e-3, 3e-3};
    EXPECT_THROW(protocol::decodeSolve(overTheWire(withValues)), ProtocolError);
}

TEST(Protocol, ForcesRoundTripAndTheAnswerMustMatchTheQuestion)
{
    protocol::Forces f;
    f.level = 4;
    f.iteration = 7;
    f.iterations = 31;
    f.converged = false;
    f.residuals = {1e-4, 2e-5};
    const protocol::Forces back = protocol::decodeForces(overTheWire(protocol::encode(f)), 4, 7);
    EXPECT_EQ(back.iterations, 31);
    EXPECT_FALSE(back.converged);
    EXPECT_EQ(back.residuals, f.residuals);
    EXPECT_EQ(back.band, 0.0); // a steady solve
    f.band = 1.4e-3;           // converged in the mean: the band rides after the residuals
    const protocol::Forces banded = protocol::decodeForces(overTheWire(protocol::encode(f)), 4, 7);
    EXPECT_EQ(banded.band, 1.4e-3);
    EXPECT_EQ(banded.residuals, f.residuals);
    EXPECT_THROW(protocol::decodeForces(overTheWire(protocol::encode(f)), 4, 6), ProtocolError);
    Message withValues = protocol::encode(f); // the forces travel as distributed rows
    withValues.values = {0.5, -1.5, 2.5};
    EXPECT_THROW(protocol::decodeForces(overTheWire(withValues), 4, 7), ProtocolError);
    try
    {
        protocol::decodeForces(overTheWire(protocol::encode(f)), 5, 7);
        FAIL() << "a Forces answer to another level was accepted";
    }
    catch (const ProtocolError& e)
    {
        EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos); // one line
        EXPECT_NE(std::string(e.what()).find("answered level 4 iteration 7 to level 5"),
                  std::string::npos);
    }
}

TEST(Protocol, AcceptCarriesTheTime)
{
    const protocol::Accept back =
        protocol::decodeAccept(overTheWire(protocol::encode(protocol::Accept{12, 360.0})));
    EXPECT_EQ(back.level, 12);
    EXPECT_EQ(back.time, 360.0);
}

TEST(Protocol, AKindMismatchIsAProtocolError)
{
    const Message accept = overTheWire(protocol::encode(protocol::Accept{1, 2.0}));
    EXPECT_THROW(protocol::decodeSolve(Message(accept)), ProtocolError);
    EXPECT_THROW(protocol::decodeForces(Message(accept), 1, 0), ProtocolError);
}
