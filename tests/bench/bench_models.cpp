// bench_models.cpp - cost of building the seed 004 models (issue 5 goal: N = 9 build + reduce <= 20 ms).
//
//   bench_models arm N        build PS beam (N) + Krylov r = 12 + couple the arm: the project's path
//   bench_models modal N      reference: build PS beam (N) + dense eigendecomposition of the 4N x 4N
//                             (J - R) Q with eigenvectors, the core of a modal-truncation reduction
//                             to the same order (what the thesis compares Krylov with, Sec. 3.5.2)
//   bench_models table31      Table 3.1 as a whole (6 PS spectra) + Table C.1 (exact frequencies)
//   bench_models table31ref   reference: the same 6 spectra with eigenvectors (dense EigenSolver)
// Prints the median wall time per run in microseconds over `reps` runs (default 21).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "fracdesign/models/arm.hpp"
#include "fracdesign/models/timoshenko_beam.hpp"

using namespace fracdesign;

namespace {

volatile double g_sink;

void arm(int N)
{
    ArmOptions o;
    o.N = N;
    const ArmModel m = build_arm(wang_steel_beam(), wang_drive(), o);
    g_sink = m.arm.J(0, 2);
}

void modal(int N)
{
    const PsBeam b = build_ps_beam(wang_steel_beam(), N);
    Eigen::EigenSolver<Eigen::MatrixXd> es(b.ph.A(), true);
    g_sink = es.eigenvalues()[0].imag();
}

void table31(bool with_vectors)
{
    for (Collocation c : {Collocation::GaussLegendre, Collocation::Equidistant})
        for (int N : {5, 9, 12}) {
            const PsBeam b = build_ps_beam(wang_steel_beam(), N, c);
            if (with_vectors) {
                Eigen::EigenSolver<Eigen::MatrixXd> es(b.ph.A(), true);
                g_sink = es.eigenvalues()[0].imag();
            } else {
                g_sink = clamped_free_frequencies_hz(b, 5)[4];
            }
        }
    if (!with_vectors) g_sink = exact_clamped_free_frequencies_hz(wang_steel_beam(), 5)[4];
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc < 2) {
        std::fprintf(stderr, "usage: bench_models arm|modal N | table31|table31ref [reps]\n");
        return 2;
    }
    const std::string what = argv[1];
    const bool sized = what == "arm" || what == "modal";
    const int N = sized && argc > 2 ? std::atoi(argv[2]) : 9;
    const int reps = std::max(1, argc > (sized ? 3 : 2) ? std::atoi(argv[sized ? 3 : 2]) : 21);
    std::vector<double> us;
    for (int r = 0; r < reps; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        if (what == "arm") arm(N);
        else if (what == "modal") modal(N);
        else if (what == "table31") table31(false);
        else if (what == "table31ref") table31(true);
        else {
            std::fprintf(stderr, "bench_models: unknown case '%s'\n", what.c_str());
            return 2;
        }
        us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
    }
    std::nth_element(us.begin(), us.begin() + reps / 2, us.end());
    std::printf("%.1f\n", us[static_cast<size_t>(reps / 2)]);
    return 0;
}
