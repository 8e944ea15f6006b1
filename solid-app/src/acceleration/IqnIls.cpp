// SPDX-License-Identifier: GPL-3.0-or-later
#include "acceleration/IqnIls.hpp"

#include "config/YamlReader.hpp"

namespace fsi::acceleration
{

IqnIlsParameters IqnIlsParameters::parse(const config::Block& layer)
{
    const config::Block b = layer.block(keyword);
    b.allowOnly(keys());
    IqnIlsParameters p;
    p.parseCommon(b);
    return p;
}

IqnIls::IqnIls(const IqnIlsParameters& params) : QuasiNewton(params) {}

Eigen::VectorXd IqnIls::step(const FilteredQr& qr, const Eigen::MatrixXd& w,
                             const Eigen::VectorXd& residual, const Eigen::VectorXd& solverOutput)
{
    // c = argmin |V c + r| = -R^{-1} Q^T r;  u = u_hat + W c.
    const Eigen::VectorXd c =
        -qr.r.triangularView<Eigen::Upper>().solve(qr.q.transpose() * residual);
    Eigen::VectorXd next = solverOutput;
    for (size_t i = 0; i < qr.kept.size(); ++i)
        next += c(static_cast<Eigen::Index>(i)) * w.col(qr.kept[i]);
    return next;
}

} // namespace fsi::acceleration
