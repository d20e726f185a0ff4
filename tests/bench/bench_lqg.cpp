// Predictor step + state-difference LQG law (frac_lqg_step, seed 004
// (7.21)/(7.27)) against the same step written with Eigen dynamic
// matrices on the dense augmented model (7.18)/(7.26).
//
// usage: bench_lqg {frac|eigen} {expd|full} CALLS [time]
//   expd: Exp. D size, n = 16 (4 drive + 12 reduced beam), d_i = 4,
//         d_o = 3 on the IMU output, + 1 disturbance state: 24 states, p = 3
//   full: unreduced beam, n = 36 + 4, d_i = 4, d_o = 3, + 1: 48 states
// Runs CALLS steps; with "time" prints the wall-clock ns per call.
// The matrices are deterministic pseudo-random values with a contractive
// A: the instruction count of the step does not depend on the values.
#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <vector>

extern "C" {
#include "frac/delay.h"
#include "frac/kalman.h"
#include "frac/lqg.h"
}

namespace {

struct Model {
    size_t n, d_i, p, nb, ne;
    size_t d_o[3];
    std::vector<frac_real> A, B, C, K, L;
};

double lcg(unsigned long &s)
{
    s = s * 6364136223846793005UL + 1442695040888963407UL;
    return (double)((s >> 11) & 0xFFFFF) / (double)0xFFFFF - 0.5;
}

Model make_model(size_t n)
{
    Model m;
    unsigned long s = 42;
    m.n = n;
    m.d_i = 4;
    m.p = 3;
    m.d_o[0] = 0;
    m.d_o[1] = 0;
    m.d_o[2] = 3;
    m.nb = n + m.d_i + 3;
    m.ne = m.nb + 1;
    m.A.resize(n * n);
    m.B.resize(n);
    m.C.resize(m.p * n);
    m.K.resize(m.nb);
    m.L.resize(m.ne * m.p);
    for (size_t i = 0; i < n * n; i++) m.A[i] = (frac_real)(0.9 * lcg(s) / std::sqrt((double)n));
    for (size_t i = 0; i < n; i++) m.A[i * n + i] += (frac_real)0.5;
    for (auto &v : m.B) v = (frac_real)lcg(s);
    for (auto &v : m.C) v = (frac_real)lcg(s);
    for (auto &v : m.K) v = (frac_real)(0.1 * lcg(s));
    for (auto &v : m.L) v = (frac_real)(0.05 * lcg(s));
    return m;
}

// The reference: dense (7.27) and (7.21) with Eigen dynamic matrices,
// temporaries preallocated so that no step allocates.
struct EigenLqg {
    Eigen::MatrixXd Ae, Ce, L;
    Eigen::VectorXd Be, K, e, en, nu;
    size_t nb;
};

}  // namespace

extern "C" __attribute__((noinline)) double ref_eigen_lqg_step(EigenLqg *r, double u_star, const double *y_ref,
                                                                const double *y)
{
    const Eigen::Index p = r->Ce.rows();
    Eigen::Map<const Eigen::VectorXd> yr(y_ref, p), ym(y, p);
    const double es = r->e(r->nb);
    const double fb = r->K.dot(r->e.head(r->nb)) - es;
    r->nu.noalias() = yr - ym;
    r->nu.noalias() -= r->Ce * r->e;
    r->en.noalias() = r->Ae * r->e;
    r->en.noalias() += r->Be * (-fb);
    r->en.noalias() += r->L * r->nu;
    r->e.swap(r->en);
    return u_star + fb;
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        std::fprintf(stderr, "usage: %s {frac|eigen} {expd|full} CALLS [time]\n", argv[0]);
        return 2;
    }
    const bool use_frac = std::strcmp(argv[1], "frac") == 0;
    const size_t n = std::strcmp(argv[2], "full") == 0 ? 40 : 16;
    const long calls = std::atol(argv[3]);
    const bool timing = argc > 4 && std::strcmp(argv[4], "time") == 0;
    Model m = make_model(n);

    frac_lqg c;
    std::vector<frac_real> st(FRAC_LQG_STORAGE(m.ne, m.p));
    frac_lqg_params prm;
    prm.n = m.n;
    prm.d_i = m.d_i;
    prm.p = m.p;
    prm.d_o = m.d_o;
    prm.A = m.A.data();
    prm.B = m.B.data();
    prm.C = m.C.data();
    prm.K = m.K.data();
    prm.L = m.L.data();
    if (frac_lqg_init(&c, &prm, st.data(), st.size()) != FRAC_OK) return 1;

    EigenLqg r;
    {
        std::vector<frac_real> Ab(m.nb * m.nb), Bb(m.nb), Eb(m.nb), Cb(m.p * m.nb);
        std::vector<frac_real> Ae(m.ne * m.ne), Be(m.ne), Ce(m.p * m.ne);
        frac_delay_augment(m.A.data(), m.B.data(), m.C.data(), m.n, m.d_i, m.p, m.d_o, Ab.data(), Bb.data(),
                           Eb.data(), Cb.data());
        frac_kalman_augment_disturbance(Ab.data(), Bb.data(), Eb.data(), Cb.data(), m.nb, 1, m.p, Ae.data(),
                                        Be.data(), Ce.data());
        const Eigen::Index ne = (Eigen::Index)m.ne, p = (Eigen::Index)m.p;
        r.Ae = Eigen::Map<Eigen::Matrix<frac_real, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(Ae.data(), ne, ne)
                   .cast<double>();
        r.Ce = Eigen::Map<Eigen::Matrix<frac_real, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(Ce.data(), p, ne)
                   .cast<double>();
        r.L = Eigen::Map<Eigen::Matrix<frac_real, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(m.L.data(), ne, p)
                  .cast<double>();
        r.Be = Eigen::Map<Eigen::Matrix<frac_real, Eigen::Dynamic, 1>>(Be.data(), ne).cast<double>();
        r.K = Eigen::Map<Eigen::Matrix<frac_real, Eigen::Dynamic, 1>>(m.K.data(), (Eigen::Index)m.nb).cast<double>();
        r.e = Eigen::VectorXd::Zero(ne);
        r.en = Eigen::VectorXd::Zero(ne);
        r.nu = Eigen::VectorXd::Zero(p);
        r.nb = m.nb;
    }

    // measurement and reference signals, precomputed so that only the step is timed
    const long NSIG = 1024;
    std::vector<double> yrd(3 * NSIG), yd(3 * NSIG);
    std::vector<frac_real> yref(3 * NSIG), y(3 * NSIG);
    for (long k = 0; k < NSIG; k++) {
        for (int j = 0; j < 3; j++) {
            yrd[3 * k + j] = std::sin(0.01 * (double)k + j);
            yd[3 * k + j] = yrd[3 * k + j] + 0.01 * std::cos(0.1 * (double)k * (j + 1));
            yref[3 * k + j] = (frac_real)yrd[3 * k + j];
            y[3 * k + j] = (frac_real)yd[3 * k + j];
        }
    }
    frac_real u = 0;
    double sum = 0.0;
    auto t0 = std::chrono::steady_clock::now();
    for (long k = 0; k < calls; k++) {
        const long i = 3 * (k & (NSIG - 1));
        if (use_frac) {
            frac_lqg_step(&c, (frac_real)0.1, &yref[i], &y[i], &u);
            sum += (double)u;
        } else {
            sum += ref_eigen_lqg_step(&r, 0.1, &yrd[i], &yd[i]);
        }
    }
    auto t1 = std::chrono::steady_clock::now();
    if (timing) std::printf("%.1f\n", std::chrono::duration<double, std::nano>(t1 - t0).count() / (double)calls);
    return std::isfinite(sum) ? 0 : 1;
}
