// bench_dare: fracdesign's DARE (structured doubling) on a delayed flexible arm,
// timed here; bench_dare.sh runs scipy.linalg.solve_discrete_are on the same
// matrices in the same run (bench_dare_ref.py) and compares time and residual.
//
// Test system: the Kalman-filter DARE of the seed 004 Exp. D design (Table 8.8:
// T = 1.2 ms, d_i = 4, d_o = 3, integrating friction state), i.e. the dual problem
// X = A_e' ... with A <- A_e', B <- C_e', Q <- Q_o, R <- S_o (3 outputs), on
//   n = 24: the Krylov-reduced arm (16 + 4 + 3 + 1), the Exp. D size;
//   n = 48: the unreduced arm (N = 9, 40 + 4 + 3 + 1).
// Beam damping r_t = 0.5 N s/m^2 (the thesis gives none; project choice).
//
// usage: bench_dare N REPS OUTDIR  (N = 24 or 48) -> writes OUTDIR/{A,B,Q,R,X}_N.txt and
//        prints "n median_us residual iterations spectral_radius"
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "fracdesign/design/lqg.hpp"
#include "fracdesign/design/riccati.hpp"

using Eigen::MatrixXd;
using namespace fracdesign;

static void save(const std::string& path, const MatrixXd& M)
{
    std::ofstream f(path);
    f.precision(17);
    for (Eigen::Index i = 0; i < M.rows(); ++i) {
        for (Eigen::Index j = 0; j < M.cols(); ++j) f << (j ? " " : "") << M(i, j);
        f << "\n";
    }
}

int main(int argc, char** argv)
{
    if (argc != 4) {
        std::fprintf(stderr, "usage: bench_dare N REPS OUTDIR\n");
        return 2;
    }
    const int n = std::atoi(argv[1]), reps = std::atoi(argv[2]);
    const std::string out = argv[3];
    if ((n != 24 && n != 48) || reps < 1) {
        std::fprintf(stderr, "bench_dare: N must be 24 or 48, REPS >= 1\n");
        return 2;
    }
    TimoshenkoParams beam = wang_steel_beam();
    beam.r_t = 0.5;
    ArmOptions opt;
    opt.reduce = n == 24;
    const StateSpace plant = design::arm_measured_model(build_arm(beam, wang_drive(), opt).arm);
    const design::LqgDesign d = design::design_lqg(plant, design::LqgParams::exp_d());
    const MatrixXd A = d.Ae.transpose(), B = d.Ce.transpose(), Q = d.Qo, R = d.So;

    std::vector<double> us;
    design::RiccatiSolution s;
    for (int r = 0; r < reps; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        s = design::solve_dare(A, B, Q, R);
        const auto t1 = std::chrono::steady_clock::now();
        us.push_back(std::chrono::duration<double, std::micro>(t1 - t0).count());
    }
    std::sort(us.begin(), us.end());
    const std::string sfx = "_" + std::to_string(n) + ".txt";
    save(out + "/A" + sfx, A);
    save(out + "/B" + sfx, B);
    save(out + "/Q" + sfx, Q);
    save(out + "/R" + sfx, R);
    save(out + "/X" + sfx, s.X);
    std::printf("%d %.1f %.3e %d %.9f\n", n, us[us.size() / 2], s.residual, s.iterations, s.stability);
    return 0;
}
