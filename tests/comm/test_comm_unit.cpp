// SPDX-License-Identifier: GPL-3.0-or-later
// Serial parts of fsi::comm: header and payload encoding, launch flags, port files.
#include "fsi/comm/Errors.hpp"
#include "fsi/comm/LaunchOptions.hpp"
#include "fsi/comm/Message.hpp"
#include "fsi/comm/PortFile.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sys/wait.h>
#include <unistd.h>

using namespace fsi::comm;

namespace
{
template <class Error, class F> std::string messageOf(F&& f)
{
    try
    {
        f();
    }
    catch (const Error& e)
    {
        return e.what();
    }
    return "<no exception>";
}

double now()
{
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
        .count();
}
} // namespace

TEST(MessageHeader, RoundTripKeepsEveryField)
{
    MessageHeader h;
    h.kind = MessageKind::Forces;
    h.timeStep = 123456789012LL;
    h.iteration = -7;
    h.valueCount = 100000;
    h.scalarCount = 2;
    h.integerCount = 1;
    h.textBytes = 17;
    const EncodedHeader w = encodeHeader(h);
    EXPECT_EQ(w[0], kMessageMagic);
    EXPECT_EQ(w[1], kProtocolVersion);
    const MessageHeader d = decodeHeader(w);
    EXPECT_EQ(d.kind, MessageKind::Forces);
    EXPECT_EQ(d.version, kProtocolVersion);
    EXPECT_EQ(d.timeStep, 123456789012LL);
    EXPECT_EQ(d.iteration, -7);
    EXPECT_EQ(d.valueCount, 100000);
    EXPECT_EQ(d.scalarCount, 2);
    EXPECT_EQ(d.integerCount, 1);
    EXPECT_EQ(d.textBytes, 17);
}

TEST(MessageHeader, RejectsForeignCorruptAndMismatchedHeaders)
{
    MessageHeader h;
    h.kind = MessageKind::Solve;
    EncodedHeader w = encodeHeader(h);

    EncodedHeader badMagic = w;
    badMagic[0] = 42;
    EXPECT_EQ(messageOf<ProtocolError>([&] { decodeHeader(badMagic); }),
              "fsi::comm: received data that is not an fsi::comm message (bad magic 42); is the "
              "peer an fsi program?");

    EncodedHeader flipped = w;
    flipped[3] ^= 1; // time step changed in transit
    EXPECT_EQ(messageOf<ProtocolError>([&] { decodeHeader(flipped); }),
              "fsi::comm: corrupt message header (check word mismatch)");

    h.version = 99;
    EXPECT_EQ(messageOf<ProtocolError>([&] { decodeHeader(encodeHeader(h)); }),
              "fsi::comm: protocol version mismatch: peer speaks version 99, this program "
              "version " +
                  std::to_string(kProtocolVersion) + "; build both programs from the same source");
    h.version = kProtocolVersion;

    h.kind = static_cast<MessageKind>(77);
    EXPECT_EQ(messageOf<ProtocolError>([&] { decodeHeader(encodeHeader(h)); }),
              "fsi::comm: unknown message kind 77");
    h.kind = MessageKind::Solve;
    h.valueCount = -1;
    EXPECT_EQ(messageOf<ProtocolError>([&] { decodeHeader(encodeHeader(h)); }),
              "fsi::comm: message header has an invalid count -1");
}

TEST(MessageKindNames, AreReadable)
{
    EXPECT_EQ(toString(MessageKind::Hello), "Hello");
    EXPECT_EQ(toString(MessageKind::InterfaceGeometry), "InterfaceGeometry");
    EXPECT_EQ(toString(MessageKind::Abort), "Abort");
    EXPECT_EQ(toString(static_cast<MessageKind>(0)), "Unknown(0)");
    EXPECT_FALSE(isKnownKind(0));
    EXPECT_TRUE(isKnownKind(8));
    EXPECT_FALSE(isKnownKind(9));
}

TEST(MessagePayload, RoundTripIsBitExact)
{
    Message m;
    m.kind = MessageKind::Forces;
    m.values = {1.0, -0.0, 1e-308, 6.02214076e23, 0.1};
    m.scalars = {3.5e-9};
    m.integers = {-1, 42, INT64_MAX};
    m.text = std::string("reason with\nnewline and \0 byte", 30);
    const MessageHeader h = headerOf(m);
    EXPECT_EQ(h.valueCount, 5);
    EXPECT_EQ(h.textBytes, 30);
    const std::vector<char> bytes = encodePayload(m);
    EXPECT_EQ(bytes.size(), 5u * 8 + 8 + 3 * 8 + 30);
    Message back;
    decodePayload(h, bytes, back);
    EXPECT_EQ(back.values, m.values);
    EXPECT_TRUE(std::signbit(back.values[1]));
    EXPECT_EQ(back.scalars, m.scalars);
    EXPECT_EQ(back.integers, m.integers);
    EXPECT_EQ(back.text, m.text);
    EXPECT_EQ(back.valueCount, 5);

    std::vector<char> shortBytes(bytes.begin(), bytes.end() - 1);
    EXPECT_EQ(messageOf<ProtocolError>([&] { decodePayload(h, shortBytes, back); }),
              "fsi::comm: Forces payload has 101 bytes, header announces 102");
}

TEST(LaunchOptionsParsing, DefaultsAndBothFlagForms)
{
    std::vector<std::string> none = {"case"};
    const LaunchOptions d = parseLaunchOptions(none);
    EXPECT_EQ(d.mode, LaunchMode::Mpmd);
    EXPECT_EQ(d.portFile, "fsi-comm.port");
    EXPECT_EQ(d.timeoutSeconds, 600.0);
    EXPECT_EQ(none, std::vector<std::string>{"case"});

    std::vector<std::string> args = {
        "-parallel", "--launch", "port",           "--port-file=dir/p.txt",
        "-case",     "x",        "--comm-timeout", "2.5"};
    const LaunchOptions o = parseLaunchOptions(args);
    EXPECT_EQ(o.mode, LaunchMode::Port);
    EXPECT_EQ(o.portFile, "dir/p.txt");
    EXPECT_EQ(o.timeoutSeconds, 2.5);
    EXPECT_EQ(args, (std::vector<std::string>{"-parallel", "-case", "x"}));
}

TEST(LaunchOptionsParsing, OneLineErrors)
{
    auto fails = [](std::vector<std::string> args)
    { return messageOf<std::runtime_error>([&] { parseLaunchOptions(args); }); };
    EXPECT_EQ(fails({"--launch", "tcp"}),
              "--launch: unknown mode 'tcp'; use --launch port or --launch mpmd");
    EXPECT_EQ(fails({"--comm-timeout", "-3"}),
              "--comm-timeout: '-3' is not a positive number of seconds (e.g. --comm-timeout 600)");
    EXPECT_EQ(fails({"--comm-timeout", "5s"}),
              "--comm-timeout: '5s' is not a positive number of seconds (e.g. --comm-timeout 600)");
    // Issue 15: 1e10 s overflowed the clock and a valid run aborted after 1.7 s.
    EXPECT_EQ(fails({"--comm-timeout", "1e10"}),
              "--comm-timeout: '1e10' is more than the maximum of 1e9 s (31 years); give at most "
              "--comm-timeout 1e9");
    std::vector<std::string> largest{"--comm-timeout", "1e9"};
    EXPECT_EQ(parseLaunchOptions(largest).timeoutSeconds, 1e9);
    EXPECT_EQ(fails({"--port-file"}),
              "--port-file: missing value (--launch port|mpmd [--port-file PATH] "
              "[--comm-timeout SECONDS])");
}

TEST(LaunchOptionsParsing, ArgvIsCompactedForOpenFoam)
{
    std::string a0 = "fluid-app", a1 = "-case", a2 = "c", a3 = "--launch", a4 = "mpmd",
                a5 = "-parallel", a6 = "--comm-timeout=9";
    char* argv[] = {a0.data(), a1.data(), a2.data(), a3.data(),
                    a4.data(), a5.data(), a6.data(), nullptr};
    int argc = 7;
    const LaunchOptions o = parseLaunchOptions(argc, argv);
    EXPECT_EQ(o.timeoutSeconds, 9.0);
    ASSERT_EQ(argc, 4);
    EXPECT_STREQ(argv[0], "fluid-app");
    EXPECT_STREQ(argv[1], "-case");
    EXPECT_STREQ(argv[2], "c");
    EXPECT_STREQ(argv[3], "-parallel");
    EXPECT_EQ(argv[4], nullptr);
}

TEST(PortFile, FormatParseRoundTrip)
{
    PortFileRecord r;
    r.portName = "1234.0:567;tcp://127.0.0.1:4000+1235.0;tcp://127.0.0.1:4001:300";
    r.pid = 4321;
    r.host = "node17";
    r.createdSeconds = 1700000000.25;
    const std::string text = formatPortFile(r);
    EXPECT_EQ(text, "fsi-comm-port-file 1\nport=" + r.portName +
                        "\npid=4321\nhost=node17\ncreated=1700000000.250\n");
    const PortFileRecord back = parsePortFile(text, "p");
    EXPECT_EQ(back.portName, r.portName);
    EXPECT_EQ(back.pid, 4321);
    EXPECT_EQ(back.host, "node17");
    EXPECT_EQ(back.createdSeconds, 1700000000.25);
}

TEST(PortFile, GarbageIsRejectedWithTheReason)
{
    auto fails = [](const std::string& text)
    { return messageOf<CommError>([&] { parsePortFile(text, "case/fsi.port"); }); };
    const std::string fix = "; delete it and restart the solid (server) side";
    EXPECT_EQ(fails("hello world\n"),
              "port file case/fsi.port: first line is not 'fsi-comm-port-file 1' (not a port "
              "file or written by another version)" +
                  fix);
    EXPECT_EQ(fails("fsi-comm-port-file 1\nport=x\nnonsense\n"),
              "port file case/fsi.port: line 'nonsense' is not key=value" + fix);
    EXPECT_EQ(fails("fsi-comm-port-file 1\nport=x\npid=12ab\nhost=h\ncreated=1\n"),
              "port file case/fsi.port: key 'pid' missing or invalid" + fix);
    EXPECT_EQ(fails("fsi-comm-port-file 1\nport=x\npid=12\nhost=h\n"),
              "port file case/fsi.port: key 'created' missing or invalid" + fix);
    EXPECT_EQ(fails("fsi-comm-port-file 1\nport=x\npid=12\nhost=h\ncreated=1\ncolour=red\n"),
              "port file case/fsi.port: unknown key 'colour'" + fix);
    EXPECT_EQ(fails(""), "port file case/fsi.port: first line is not 'fsi-comm-port-file 1' "
                         "(not a port file or written by another version)" +
                             fix);
}

TEST(PortFile, AtomicWriteLeavesOnlyTheFile)
{
    char folder[] = "/tmp/fsi-comm-unit-XXXXXX";
    ASSERT_NE(mkdtemp(folder), nullptr);
    const std::string path = std::string(folder) + "/fsi.port";
    PortFileRecord r{"port-name", 77, "h", 5.0};
    writePortFileAtomically(path, r);
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text, formatPortFile(r));
    EXPECT_NE(access((path + ".tmp." + std::to_string(getpid())).c_str(), F_OK), 0);
    std::remove(path.c_str());
    rmdir(folder);

    EXPECT_EQ(messageOf<CommError>([&] { writePortFileAtomically("/nonexistent-dir/p", r); }),
              "cannot write port file /nonexistent-dir/p.tmp." + std::to_string(getpid()) +
                  ": No such file or directory; check --port-file and that the folder exists "
                  "and is writable");
}

TEST(PortFile, StaleDetection)
{
    PortFileRecord live{"p", static_cast<long>(getpid()), thisHostName(), now()};
    EXPECT_EQ(staleReason(live), "");

    // A pid that certainly ended: a child we started and reaped.
    const pid_t child = fork();
    if (child == 0)
        _exit(0);
    waitpid(child, nullptr, 0);
    PortFileRecord dead{"p", static_cast<long>(child), thisHostName(), now()};
    EXPECT_EQ(staleReason(dead), "the server that wrote it (pid " + std::to_string(child) + " on " +
                                     thisHostName() + ") is no longer running");

    // Our pid, but the file claims to be older than this process: pid reused after a crash.
    const double started = processStartSeconds(getpid());
    ASSERT_GT(started, 0.0);
    EXPECT_LE(started, now() + 1.0);
    PortFileRecord reused{"p", static_cast<long>(getpid()), thisHostName(), started - 3600.0};
    EXPECT_EQ(staleReason(reused), "pid " + std::to_string(getpid()) +
                                       " now belongs to a process started after the file was "
                                       "written (the server crashed)");

    // Another host: cannot be checked here, assumed live.
    PortFileRecord remote{"p", static_cast<long>(child), thisHostName() + "-elsewhere", now()};
    EXPECT_EQ(staleReason(remote), "");
}
