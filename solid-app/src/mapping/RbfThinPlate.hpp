// SPDX-License-Identifier: GPL-3.0-or-later
//
// rbf-thin-plate: global thin-plate spline phi(r) = r^2 log r on normalised coordinates plus the
// linear polynomial, through the augmented (saddle-point) system
//   [ Phi  Q ] [c]   [f]          Phi_ij = phi(|x_i - x_j|),  Q = orthonormal linear basis
//   [ Q^T  0 ] [b] = [0],         target = Phi_ts c + Q_t b
// factorised once with dense LU (O(N_s^3) set-up, O(N_s^2 + N_t N_s) per apply and column).
// Reproduces linear fields exactly; for small interfaces (a few thousand points).
#pragma once

#include "mapping/Mapping.hpp"

#include <Eigen/LU>

namespace fsi::mapping
{

class RbfThinPlate;

// Block rbf-thin-plate (optional): phi(r) = r^2 log r, global and dense (O(N^3) set-up).
struct ThinPlateParameters
{
    static constexpr const char* keyword = "rbf-thin-plate";
    using Strategy = RbfThinPlate;
    long maxSourcePoints = 10000; // refuse larger interfaces (memory ~ 16 N^2 bytes)
    static const std::vector<std::string>& keys();
    static ThinPlateParameters
    parse(const config::Block& layer); // reads layer.<keyword> (optional)
    void validate() const;
    std::string echo() const;
};

class RbfThinPlate final : public Mapping
{
public:
    explicit RbfThinPlate(long maxSourcePoints = 10000) : maxSourcePoints_(maxSourcePoints) {}
    explicit RbfThinPlate(const ThinPlateParameters& params)
        : maxSourcePoints_(params.maxSourcePoints)
    {
    }
    std::string name() const override { return "rbf-thin-plate"; }
    void compute(const PointCloud& source, const PointCloud& target) override;
    void applyConsistent(const Eigen::Ref<const Values>& sourceValues,
                         Eigen::Ref<Values> targetValues) const override;
    void applyConservative(const Eigen::Ref<const Values>& targetValues,
                           Eigen::Ref<Values> sourceValues) const override;

private:
    long maxSourcePoints_;
    Eigen::PartialPivLU<Eigen::MatrixXd> lu_; // of the (N_s + r) saddle-point matrix
    Eigen::MatrixXd evaluation_;              // [Phi_ts Q_t], N_t x (N_s + r)
    mutable Eigen::MatrixXd rhs_, solution_;  // workspace, (N_s + r) x columns
};

} // namespace fsi::mapping
