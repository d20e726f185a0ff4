// bench_ident: all 6 structures x 2 weightings of the seed 000 antenna fit on
// one FRF (Type VI nominal + 5 % noise, generator seed 1, bins 94..8000,
// N = 7907), with `starts` multi-start points per fit. Writes the FRF and the
// start points to DIR for the scipy reference (bench_ident_ref.py), then
// prints one line per fit: structure weighting J cpu-seconds, and a total line.
// usage: bench_ident STARTS DIR
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "fracdesign/ident/haro_synthetic.hpp"
#include "fracdesign/io/frf_csv.hpp"

using namespace fracdesign;

// Process CPU time: the bench machine is shared, so wall time would measure
// the neighbours; the reference measures time.process_time() likewise.
static double cpu_seconds()
{
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

int main(int argc, char** argv)
{
    if (argc != 3) {
        std::fprintf(stderr, "usage: bench_ident STARTS DIR\n");
        return 2;
    }
    const int starts = std::atoi(argv[1]);
    const std::string dir = argv[2];
    const ident::Frf f = ident::haro_synthetic_frf({7.1e-5, 0.996, 0.055, 0.594}, ident::haro_grid(94, 8000), 0.05, 1);
    io::write_frf_csv(dir + "/frf.csv", {f.w, f.G});
    std::ofstream st(dir + "/starts.txt");
    st.precision(17);
    double total = 0.0;
    for (int s = 1; s <= 6; ++s)
        for (int wt = 0; wt < 2; ++wt) {
            ident::AntennaFitOptions o;
            o.weighting = wt ? ident::FrfWeighting::InverseOmega : ident::FrfWeighting::Constant;
            o.starts = starts;
            o.covariance = false;
            const auto x0 = ident::antenna_starts(AntennaStructure(s), o.bounds, starts, o.seed);
            std::vector<double> lo, hi;
            ident::antenna_box(AntennaStructure(s), o.bounds, lo, hi);
            st << s << " " << wt << " " << lo.size();
            for (std::size_t i = 0; i < lo.size(); ++i) st << " " << lo[i] << " " << hi[i];
            for (const auto& x : x0)
                for (double v : x) st << " " << v;
            st << "\n";
            const double t0 = cpu_seconds();
            const auto r = ident::fit_antenna(f, AntennaStructure(s), o);
            const double dt = cpu_seconds() - t0;
            total += dt;
            std::printf("%s %s %.10g %.4f\n", ident::structure_name(AntennaStructure(s)), ident::weighting_name(o.weighting),
                        r.cost, dt);
        }
    std::printf("total %.4f\n", total);
    return 0;
}
