// SPDX-License-Identifier: GPL-3.0-or-later
// adaptive: the steps follow the solution.
//   dt_1 = first_step (default: a tenth of the shortest Prony time, resolveFirstStep());
//   dt_{k+1} = dt_k * clamp(target_change / change_k, shrink_limit, growth_limit), change_k the
//   relative change of the solution over level k (the caller's measure: the interface
//   displacement in coupled runs, the displacement field standalone); or, with
//   error_tolerance > 0, steered by the error of the quasi-steady path:
//   dt_{k+1} = dt_k * clamp(0.9 sqrt(error_tolerance / e_k), shrink_limit, growth_limit), e_k =
//   |u_k - u_lin| / |u_k|, u_lin the linear extrapolation of the two levels before k to t_k (the
//   local error of a history piecewise linear in time, as the Prony recursion assumes); levels
//   whose e_k is unknown (NaN) use the change rule. dt within [min_step, max_step]; `hit` times
//   are landed on exactly (two equal steps when one step would leave a sliver before the hit
//   time), and no sliver is left before end.
#pragma once

#include "config/Strategy.hpp"
#include "schedule/Schedule.hpp"

#include <string>
#include <vector>

namespace fsi::schedule
{

class Adaptive;

struct AdaptiveParameters
{
    static constexpr const char* keyword = "adaptive";
    using Strategy = Adaptive;
    KeyOrigin origin;
    double end = 0.0;            // [s] > 0
    double firstStep = 0.0;      // [s]; 0 = from the Prony times (resolveFirstStep)
    double minStep = 0.0;        // [s]
    double maxStep = 0.0;        // [s]; 0 = unlimited
    double targetChange = 0.02;  // wanted relative change per level
    double errorTolerance = 0.0; // relative path error per level (0 = the change rule)
    double growthLimit = 2.0;    // largest dt_{k+1}/dt_k
    double shrinkLimit = 0.5;    // smallest dt_{k+1}/dt_k
    std::vector<double> hit;     // times landed on exactly [s], in (0, end]
    static const std::vector<std::string>& keys();
    static AdaptiveParameters parse(const config::Block& timeBlock);
    void validate() const;
    std::string echo() const;
    // first_step 0 becomes min(relaxationTimes) / 10; throws naming first_step when there are
    // none (elastic material).
    void resolveFirstStep(const std::vector<double>& relaxationTimes);
};

class Adaptive final : public Schedule
{
public:
    // Pre: params.firstStep resolved (> 0); validates.
    explicit Adaptive(const AdaptiveParameters& params);
    bool hasNext() const override;
    double advance(double relativeChangeOfLastLevel,
                   double pathErrorOfLastLevel = std::numeric_limits<double>::quiet_NaN()) override;
    double endTime() const override { return params_.end; }
    double maxStep() const override { return params_.maxStep; }
    int plannedLevels() const override { return -1; }
    std::string describe() const override;

private:
    double nextStepCandidate(double change, double pathError) const;
    AdaptiveParameters params_;
};

} // namespace fsi::schedule
