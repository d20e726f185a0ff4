// bench_dare: fracdesign's DARE (structured doubling) on a delayed flexible arm,
// timed here; bench_dare.sh runs scipy.linalg.solve_discrete_are on the same
// matrices in the same run (bench_dare_ref.py) and compares time and residual.
//
// Test system (seed 004 Exp. D structure, T = 1.2 ms, d_i = 4): a rigid-body
// mode plus `m` lightly damped bending modes (zeta 0.5-2.5 %), ZOH-discretised,
// with an input delay line of d_i = 4 samples (thesis (7.8)-(7.12)):
// n = 2 + 2m + 4 states; m = 9 gives the Exp. D size 24, m = 21 the unreduced 48.
// Weights: Q = 1e4 C'C + 1e-3 I, R = 1.
//
// usage: bench_dare N REPS OUTDIR  -> writes OUTDIR/{A,B,Q,R,X}_N.txt and prints
//        "n median_us residual iterations spectral_radius"
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <random>
#include <string>
#include <vector>

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
    const int di = 4, m = (n - 2 - di) / 2;
    if (m < 1 || 2 + 2 * m + di != n || reps < 1) {
        std::fprintf(stderr, "bench_dare: N must be even and >= 8\n");
        return 2;
    }
    std::mt19937 rng(2024);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int nc = 2 + 2 * m;
    StateSpace c;
    c.A = MatrixXd::Zero(nc, nc);
    c.B = MatrixXd::Zero(nc, 1);
    c.C = MatrixXd::Zero(1, nc);
    c.D = MatrixXd::Zero(1, 1);
    c.A(0, 1) = 1.0;
    c.A(1, 1) = -0.05;
    c.B(1, 0) = 1.0;
    c.C(0, 0) = 1.0;
    for (int i = 0; i < m; ++i) {
        const double w = 2.0 * 3.14159265358979 * 3.0 * (i + 1) * (i + 1) * (1.0 + 0.1 * u(rng));
        const double z = 0.005 + 0.02 * u(rng);
        const int k = 2 + 2 * i;
        c.A(k, k + 1) = 1.0;
        c.A(k + 1, k) = -w * w;
        c.A(k + 1, k + 1) = -2.0 * z * w;
        c.B(k + 1, 0) = (i % 2 ? -1.0 : 1.0) * (0.5 + u(rng));
        c.C(0, k) = (0.2 + 0.3 * u(rng)) / (i + 1);
    }
    const StateSpace d = design::c2d_zoh(c, 1.2e-3);
    // Input delay line: x+ = Ad x + Bd z_1, z_j+ = z_{j+1}, z_di+ = u.
    MatrixXd A = MatrixXd::Zero(n, n), B = MatrixXd::Zero(n, 1), Cy = MatrixXd::Zero(1, n);
    A.topLeftCorner(nc, nc) = d.A;
    A.block(0, nc, nc, 1) = d.B;
    for (int j = 0; j + 1 < di; ++j) A(nc + j, nc + j + 1) = 1.0;
    B(n - 1, 0) = 1.0;
    Cy.leftCols(nc) = d.C;
    const MatrixXd Q = 1e4 * Cy.transpose() * Cy + 1e-3 * MatrixXd::Identity(n, n);
    const MatrixXd R = MatrixXd::Identity(1, 1);

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
