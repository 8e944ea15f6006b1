// SPDX-License-Identifier: GPL-3.0-or-later
#include "acceleration/ConstantRelaxation.hpp"

#include "acceleration/ParameterChecks.hpp"
#include "config/YamlReader.hpp"

#include <sstream>

namespace fsi::acceleration
{

const std::vector<std::string>& ConstantParameters::keys()
{
    static const std::vector<std::string> k{"relaxation"};
    return k;
}

ConstantParameters ConstantParameters::parse(const config::Block& layer)
{
    const config::Block b = layer.block(keyword);
    b.allowOnly(keys());
    ConstantParameters p;
    p.relaxation = b.number("relaxation");
    return p;
}

void ConstantParameters::validate() const
{
    if (!(relaxation > 0.0 && relaxation < 2.0))
        throw std::runtime_error("acceleration.relaxation must be in (0, 2) for type constant "
                                 "(got " +
                                 valueText(relaxation) + "); set it, e.g. 0.5");
}

std::string ConstantParameters::echo() const
{
    std::ostringstream s;
    s << "{relaxation: " << relaxation << "}";
    return s.str();
}

ConstantRelaxation::ConstantRelaxation(const ConstantParameters& params) : omega_(params.relaxation)
{
    params.validate();
}

Eigen::VectorXd ConstantRelaxation::update(const Eigen::VectorXd& previousIterate,
                                           const Eigen::VectorXd& solverOutput)
{
    checkSizes(previousIterate, solverOutput, -1);
    return previousIterate + omega_ * (solverOutput - previousIterate);
}

} // namespace fsi::acceleration
