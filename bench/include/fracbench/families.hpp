// families.hpp - the plant families of gap-bench (docs/gap.md "gap-bench",
// "Families"). A family draws, per case, its plant's parameters, the hidden
// effect and its size, simulates the record and writes the nominal model
// document the diagnosis gets:
//   twomass    seed 004 two-mass drive on the lockstep HIL rig, PD loop (gap_bench.cpp)
//   servo      rigid servo axis, PD with filtered difference, +-10 V clip (family_servo.cpp)
//   foprocess  y = K e^{-tau s} / (1 + T s^lambda) u in open loop (family_foprocess.cpp)
//   arm        a drawn arm document (frac.arm) on the lockstep HIL rig, ArmCtrl from the
//              document, its open-loop gap nominal (family_arm.cpp)
// Every draw depends only on (bench seed, case id) and the options.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "fracbench/gap_bench.hpp"

extern "C" {
#include "hil/rng.h"
}

namespace fracbench {

struct Family {
    std::string name;
    std::string summary;                   // one line for --help and the JSON
    std::vector<std::string> labels;       // the labels drawn, "none" last
    std::function<BenchCase(const BenchOptions&, int)> draw;
    std::function<CaseRun(const BenchOptions&, const BenchCase&)> run;
};

// All families, twomass first.
const std::vector<Family>& families();
// std::invalid_argument naming the allowed names when `name` is none of them.
const Family& family(const std::string& name);

// The label of case `id`: shuffled rounds of `labels` (every label equally
// often over labels.size() consecutive cases), the round's order from `seed`.
std::string drawn_label(const std::vector<std::string>& labels, std::uint64_t seed, int id);
// The case's own seed (sizes, plant parameters, noise).
std::uint64_t case_seed(std::uint64_t seed, int id);
// A second effect for a two-effect case: any label but "none" (the last),
// `first` and a second friction model.
std::string second_label(const std::vector<std::string>& labels, const std::string& first, hil_rng* rng);

// Uniform in [lo, hi) from rng.
inline double uniform(hil_rng* rng, double lo, double hi) { return lo + (hi - lo) * hil_rng_uniform(rng); }

// The families (gap_bench.cpp, family_servo.cpp, family_foprocess.cpp).
Family twomass_family();
Family servo_family();
Family foprocess_family();
Family arm_family();
// The nominal model documents of the simulated families for a case.
nlohmann::json servo_nominal_doc(const BenchCase& c);
nlohmann::json foprocess_nominal_doc(const BenchCase& c);
// The arm document (frac.arm) of an arm case, as the case files' arm.json.
nlohmann::json arm_document_of(const BenchCase& c);

}  // namespace fracbench
