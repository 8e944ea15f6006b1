// SPDX-License-Identifier: GPL-3.0-or-later
// Compile check: fluid-app is C++14 (OpenFOAM v1912's headers), so every public comm header
// must compile as C++14 with -Wpedantic -Werror, including the usage the README shows.
#include "fsi/comm/Channel.hpp"
#include "fsi/comm/Collectives.hpp"
#include "fsi/comm/Errors.hpp"
#include "fsi/comm/LaunchOptions.hpp"
#include "fsi/comm/Message.hpp"
#include "fsi/comm/MpmdWorld.hpp"
#include "fsi/comm/PortFile.hpp"
#include "fsi/comm/Protocol.hpp"

#include <memory>

int fsiCommCxx14UsageCompiles(int argc, char** argv)
{
    std::unique_ptr<fsi::comm::Channel> channel;
    try
    {
        fsi::comm::LaunchOptions launch = fsi::comm::initialiseMpmdWorld(argc, argv);
        fsi::comm::Identity self;
        self.role = fsi::comm::Role::Fluid;
        self.program = "fluid-app";
        self.interfaceSizes = {10, 8};
        channel = std::make_unique<fsi::comm::Channel>(fsi::comm::Channel::open(launch, self));
        channel->send(fsi::comm::MessageKind::InterfaceGeometry, 0, 0, {1.0, 2.0});
        const fsi::comm::Message m = channel->receiveAny();
        channel->close();
        return static_cast<int>(m.valueCount);
    }
    catch (const std::exception& e)
    {
        fsi::comm::exitOnError(e, channel.get());
    }
}
