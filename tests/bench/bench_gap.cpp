// bench_gap.cpp - time of the gap diagnosis (issue 10 goal: a 10 s, 1 kHz,
// 3-output record with all candidates in <= 30 s on 2 cores), and how it
// grows with the record length and the number of candidates.
// Plant: two masses coupled by a spring (outputs x1, x2, v1), force on mass 1,
// with Coulomb friction injected; open loop, multisine force. The spring is
// declared as gap.coupling, so "all candidates" includes the play and the
// fractional damping in it (docs/gap.md).
#include <algorithm>
#include <chrono>
#include <thread>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "fracdesign/gap/diagnosis.hpp"

using namespace fracdesign::gap;

namespace {

nlohmann::json model_doc()
{
    const double m1 = 1.0, m2 = 0.5, k = 400.0, c = 2.0, d1 = 5.0;
    return {{"schema", "frac.model"}, {"version", 1}, {"kind", "statespace"}, {"name", "two_mass"},
            {"time", "continuous"},
            {"A", {{0, 0, 1, 0}, {0, 0, 0, 1}, {-k / m1, k / m1, -(c + d1) / m1, c / m1}, {k / m2, -k / m2, c / m2, -c / m2}}},
            {"B", {{0}, {0}, {1 / m1}, {0}}},
            {"C", {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}},
            {"D", {{0}, {0}, {0}}},
            {"inputs", {"F"}}, {"outputs", {"x1", "x2", "v1"}},
            {"gap", {{"velocity", "v1"}, {"force_input", "F"},
                     // the spring as a coupling: backlash and fractional damping are also fitted in it
                     {"coupling", {{"name", "spring"}, {"twist", {1, -1, 0, 0}}, {"torque", {0, 0, -1 / m1, 1 / m2}}, {"stiffness", k}}}}}};
}

Signals record(const NominalModel& m, Eigen::Index n, double Ts)
{
    Signals s;
    s.source = "bench";
    s.names = {"F", "x1", "x2", "v1"};
    s.Ts = Ts;
    s.values = Eigen::MatrixXd::Zero(n, 4);
    for (Eigen::Index k = 0; k < n; ++k) {
        const double t = double(k) * Ts;
        s.values(k, 0) = 20 * std::sin(2 * M_PI * 0.5 * t) + 8 * std::sin(2 * M_PI * 2.1 * t + 1) + 3 * std::sin(2 * M_PI * 7.3 * t);
    }
    const ReplaySetup setup = make_replay_setup(m, s, {}, {"x1", "x2", "v1"});
    const ReplayTrace tr = replay(setup, {{Effect::coulomb_friction, {4.0, 0.5}}});
    std::mt19937 rng(1);
    std::normal_distribution<double> nd(0, 1);
    for (int c = 0; c < 3; ++c) {
        const double sd = std::sqrt((tr.y.col(c).array() - tr.y.col(c).mean()).square().mean());
        for (Eigen::Index k = 0; k < n; ++k) s.values(k, c + 1) = tr.y(k, c) + 0.002 * sd * nd(rng);
    }
    return s;
}

double seconds(const NominalModel& m, Eigen::Index n, const std::vector<Effect>& effects, std::string* top, int threads = 0)
{
    const Signals s = record(m, n, m.Ts);
    GapOptions opt;
    opt.effects = effects;
    opt.threads = threads;
    const auto t0 = std::chrono::steady_clock::now();
    const GapResult r = diagnose(m, s, nullptr, opt);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (top) *top = r.candidates.front().effects.empty() ? "none" : effect_name(r.candidates.front().effects[0].kind);
    return dt;
}

}  // namespace

int main()
{
    const double Ts = 0.001;
    const NominalModel m = nominal_from_json(model_doc(), Ts);
    std::string top;
    const double full = seconds(m, 10000, all_effects(), &top);
    std::printf("%-44s %10s %10s %8s\n", "case", "fracdesign", "goal", "ratio");
    const std::string label = "10 s, 1 kHz, 3 outputs, all " + std::to_string(all_effects().size()) + " at every site";
    std::printf("%-44s %9.2fs %9.0fs %8.3f   (top: %s)\n", label.c_str(), full, 30.0,
                full / 30.0, top.c_str());
    // The single candidate fits on one worker against one per core (GapOptions.threads).
    const double one = seconds(m, 10000, all_effects(), nullptr, 1);
    std::printf("%-44s %9.2fs   speed-up of %u threads over 1: %.2fx\n", "  the same on 1 thread", one,
                std::max(1u, std::thread::hardware_concurrency()), one / full);
    std::printf("\ngrowth with the record length (all candidates):\n");
    for (Eigen::Index n : {2500, 5000, 10000, 20000})
        std::printf("  %6ld samples  %8.2f s\n", long(n), n == 10000 ? full : seconds(m, n, all_effects(), nullptr));
    std::printf("growth with the number of candidates (10000 samples):\n");
    const std::vector<Effect>& all = all_effects();
    for (size_t k : {size_t(1), size_t(4), size_t(8), all.size()}) {
        const std::vector<Effect> sub(all.begin() + 2, all.begin() + 2 + std::min(k, all.size() - 2));
        std::vector<Effect> eff = sub;
        if (k == all.size()) eff = all;
        std::printf("  %2zu candidates  %8.2f s\n", eff.size(), k == all.size() ? full : seconds(m, 10000, eff, nullptr));
    }
    return full <= 30.0 ? 0 : 1;
}
