// visibility.hpp - the visibility rule of the simulated families (docs/gap.md
// "gap-bench", "Visibility"): an injected effect must change at least one
// compared output by at least kVisibleNoiseMultiple times that output's
// noise std (rms over the record, both runs noise-free, same reference); a
// draw that does not is redrawn, up to kVisibleDraws times. A plant on which
// no size in the family's range is visible (InvisibleEffect) is redrawn with
// its record, up to kPlantDraws times (a servo loop on which 1-2 extra
// cycles of delay stay below the rule and 3 undamp it; a process whose
// drawn input levels stay inside every drawn limit), then refused
// (std::runtime_error naming the family, the case and the effect: a size
// range that no drawn plant shows is a defect of the family, not a case to
// score).
#pragma once
#include <Eigen/Dense>
#include <stdexcept>
#include <string>
#include <vector>

namespace fracbench {

constexpr double kVisibleNoiseMultiple = 5.0;
// Two injections whose noise-free records differ on every compared output by
// less than this many noise std (rms) are the same record to any fit (400x
// below the visibility rule in energy): the families list such an injection
// of another label as the truth's equivalent (gap_bench.hpp, TruthEffect).
constexpr double kEquivalentNoiseMultiple = 0.05;
constexpr int kVisibleDraws = 20;
constexpr int kPlantDraws = 10;

// No visible size of the drawn effect on this plant in kVisibleDraws draws:
// the family draws another plant.
struct InvisibleEffect : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Runs `attempt` (draw a plant, its record and its effects; InvisibleEffect
// when no drawn size shows on that plant) until it returns, at most
// kPlantDraws times; then std::runtime_error naming the family, the case,
// what was drawn (`plants`, e.g. "axes") and the last attempt's reason.
template <class Attempt>
void with_plant_redraws(const std::string& family, int id, const std::string& plants, Attempt attempt)
{
    std::string why;
    for (int i = 0; i < kPlantDraws; ++i) {
        try {
            attempt();
            return;
        } catch (const InvisibleEffect& e) {
            why = e.what();
        }
    }
    throw std::runtime_error("gap-bench: family " + family + ": case " + std::to_string(id) + ": " +
                             std::to_string(kPlantDraws) + " " + plants + " drawn, none shows the drawn effect; the last: " + why);
}

// rms over samples of (with - without) per column, divided by noise_std per
// column; returns the largest ratio.
double visibility(const Eigen::MatrixXd& with, const Eigen::MatrixXd& without, const std::vector<double>& noise_std);

}  // namespace fracbench
