// bind_libfrac.cpp - libfrac's per-cycle objects over numpy arrays (issue 20).
//
// Each Python class owns one libfrac object and its caller storage (a
// std::vector that is sized once at construction and never reallocated, so
// the pointers libfrac keeps into it stay valid), plus copies of every matrix
// or table the object points at. `run` calls the libfrac step once per sample
// in a plain C++ loop over the array, so the results are the C library's bit
// for bit: the same function, the same arguments, in the same order.
// Construction errors raise ValueError naming the init function and the
// frac_status (frac_status_str); per-sample statuses are returned on request.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

extern "C" {
#include "frac/fo_op.h"
#include "frac/fodamp.h"
#include "frac/fopid.h"
#include "frac/frac_types.h"
#include "frac/kalman.h"
#include "frac/lqg.h"
#include "frac/lut.h"
}

namespace py = pybind11;

namespace {

using Arr = py::array_t<double, py::array::c_style | py::array::forcecast>;

void check(int st, const char* fn)
{
    if (st < 0) throw py::value_error(std::string(fn) + ": " + frac_status_str(st) + " (status " + std::to_string(st) + ")");
}

int method_of(const std::string& m)
{
    if (m == "gl") return FRAC_FO_GL;
    if (m == "oustaloup") return FRAC_FO_OUSTALOUP;
    if (m == "oustaloup_refined") return FRAC_FO_OUSTALOUP_REFINED;
    if (m == "cfe_tustin") return FRAC_FO_CFE_TUSTIN;
    if (m == "cfe_alalaoui") return FRAC_FO_CFE_ALALAOUI;
    throw py::value_error("method: '" + m + "' is not one of gl, oustaloup, oustaloup_refined, cfe_tustin, cfe_alalaoui");
}

// The realization of a fractional operator: {"method", "memory", "wb", "wh", "n"}.
frac_fo_params op_params(const py::dict& d, double order, double ts)
{
    frac_fo_params p;
    p.method = method_of(d.contains("method") ? d["method"].cast<std::string>() : std::string("gl"));
    p.order = order;
    p.ts = ts;
    p.memory = d.contains("memory") ? d["memory"].cast<size_t>() : 0;
    p.wb = d.contains("wb") ? d["wb"].cast<double>() : 0.0;
    p.wh = d.contains("wh") ? d["wh"].cast<double>() : 0.0;
    p.n = d.contains("n") ? d["n"].cast<unsigned>() : 0u;
    return p;
}

// A 1-D array of n entries (explicit shape: the count constructor of pybind11
// 2.10 leaves a zero stride).
template <typename T>
py::array_t<T> vec(size_t n)
{
    return py::array_t<T>(std::vector<py::ssize_t>{py::ssize_t(n)});
}
py::array_t<double> like(size_t n) { return vec<double>(n); }

// Returns y, or (y, statuses) when `status` is true.
py::object result(py::array_t<double> y, py::array_t<int> st, bool status)
{
    if (status) return py::make_tuple(y, st);
    return std::move(y);
}

std::vector<double> flat(const Arr& a, size_t rows, size_t cols, const char* name)
{
    if (a.size() != py::ssize_t(rows * cols))
        throw py::value_error(std::string(name) + ": must have " + std::to_string(rows) + " x " + std::to_string(cols) +
                              " entries, has " + std::to_string(a.size()));
    return std::vector<double>(a.data(), a.data() + a.size());
}

size_t rows_of(const Arr& a) { return a.ndim() == 0 ? 1 : size_t(a.shape(0)); }
size_t cols_of(const Arr& a) { return a.ndim() < 2 ? 1 : size_t(a.shape(1)); }

class FoOperator {
public:
    FoOperator(double order, double ts, const py::dict& op)
    {
        p_ = op_params(op, order, ts);
        storage_.resize(frac_fo_storage_len(&p_) + 1);
        check(frac_fo_init(&op_, &p_, storage_.data(), storage_.size()), "frac_fo_init");
    }
    double step(double x)
    {
        double y;
        last_ = frac_fo_step(&op_, x, &y);
        return y;
    }
    py::object run(const Arr& x, bool status)
    {
        const size_t n = size_t(x.size());
        auto y = like(n);
        py::array_t<int> st = vec<int>(status ? n : 0);
        const double* xi = x.data();
        double* yo = y.mutable_data();
        int* so = st.mutable_data();
        for (size_t k = 0; k < n; ++k) {
            const int s = frac_fo_step(&op_, xi[k], &yo[k]);
            if (status) so[k] = s;
        }
        return result(y, st, status);
    }
    void reset() { check(frac_fo_reset(&op_), "frac_fo_reset"); }
    std::pair<double, double> freqresp(double w) const
    {
        double re, im;
        check(frac_fo_freqresp(&op_, w, &re, &im), "frac_fo_freqresp");
        return {re, im};
    }
    size_t storage_len() const { return frac_fo_storage_len(&p_); }

private:
    frac_fo_params p_;
    frac_fo op_;
    std::vector<double> storage_;
    int last_ = 0;
};

class FoPid {
public:
    explicit FoPid(const py::dict& d)
    {
        auto num = [&](const char* k, double def) { return d.contains(k) ? d[k].cast<double>() : def; };
        const double inf = std::numeric_limits<double>::infinity();
        p_.kp = num("kp", 0);
        p_.ki = num("ki", 0);
        p_.kd = num("kd", 0);
        p_.lambda = num("lam", 1);
        p_.mu = num("mu", 1);
        p_.tf = num("tf", 0);
        p_.b = num("b", 1);
        p_.c = num("c", 1);
        p_.delta = num("delta", 0);
        p_.umin = num("umin", -inf);
        p_.umax = num("umax", inf);
        const std::string aw = d.contains("antiwindup") ? d["antiwindup"].cast<std::string>() : std::string("none");
        if (aw == "none") p_.antiwindup = FRAC_FOPID_AW_NONE;
        else if (aw == "clamp") p_.antiwindup = FRAC_FOPID_AW_CLAMP;
        else if (aw == "backcalc") p_.antiwindup = FRAC_FOPID_AW_BACKCALC;
        else throw py::value_error("antiwindup: '" + aw + "' is not one of none, clamp, backcalc");
        p_.tt = num("tt", 1);
        p_.ts = num("ts", 0);
        p_.op = op_params(d.contains("op") ? d["op"].cast<py::dict>() : py::dict(), 0.0, p_.ts);
        storage_.resize(frac_fopid_storage_len(&p_) + 1);
        check(frac_fopid_init(&c_, &p_, storage_.data(), storage_.size()), "frac_fopid_init");
    }
    double step(double r, double y)
    {
        double u;
        frac_fopid_step(&c_, r, y, &u);
        return u;
    }
    py::object run(const Arr& r, const Arr& y, bool status)
    {
        if (r.size() != y.size()) throw py::value_error("r and y must have the same length");
        const size_t n = size_t(r.size());
        auto u = like(n);
        py::array_t<int> st = vec<int>(status ? n : 0);
        const double *ri = r.data(), *yi = y.data();
        double* uo = u.mutable_data();
        int* so = st.mutable_data();
        for (size_t k = 0; k < n; ++k) {
            const int s = frac_fopid_step(&c_, ri[k], yi[k], &uo[k]);
            if (status) so[k] = s;
        }
        return result(u, st, status);
    }
    void set_mode(const std::string& m)
    {
        if (m != "auto" && m != "manual") throw py::value_error("mode: '" + m + "' is not one of auto, manual");
        check(frac_fopid_set_mode(&c_, m == "auto" ? FRAC_FOPID_AUTO : FRAC_FOPID_MANUAL), "frac_fopid_set_mode");
    }
    void set_manual(double u) { check(frac_fopid_set_manual(&c_, u), "frac_fopid_set_manual"); }
    void reset() { check(frac_fopid_reset(&c_), "frac_fopid_reset"); }

private:
    frac_fopid_params p_;
    frac_fopid c_;
    std::vector<double> storage_;
};

class FoDamp {
public:
    explicit FoDamp(const py::dict& d)
    {
        auto num = [&](const char* k, double def) { return d.contains(k) ? d[k].cast<double>() : def; };
        p_.kc = num("kc", 0);
        p_.alpha = num("alpha", 0);
        p_.m = d.contains("m") ? d["m"].cast<unsigned>() : 0u;
        p_.n1 = num("n1", 0);
        p_.n2 = num("n2", 0);
        p_.d1 = num("d1", 0);
        p_.d2 = num("d2", 0);
        p_.fa = num("fa", 0);
        p_.fbeta = num("fbeta", 0);
        p_.fb = num("fb", 0);
        p_.ts = num("ts", 0);
        p_.op = op_params(d.contains("op") ? d["op"].cast<py::dict>() : py::dict(), 0.0, p_.ts);
        storage_.resize(frac_fodamp_storage_len(&p_) + 1);
        check(frac_fodamp_init(&c_, &p_, storage_.data(), storage_.size()), "frac_fodamp_init");
    }
    double step(double ref, double meas)
    {
        double u;
        frac_fodamp_step(&c_, ref, meas, &u);
        return u;
    }
    py::object run(const Arr& ref, const Arr& meas, bool status)
    {
        if (ref.size() != meas.size()) throw py::value_error("ref and meas must have the same length");
        const size_t n = size_t(ref.size());
        auto u = like(n);
        py::array_t<int> st = vec<int>(status ? n : 0);
        const double *ri = ref.data(), *mi = meas.data();
        double* uo = u.mutable_data();
        int* so = st.mutable_data();
        for (size_t k = 0; k < n; ++k) {
            const int s = frac_fodamp_step(&c_, ri[k], mi[k], &uo[k]);
            if (status) so[k] = s;
        }
        return result(u, st, status);
    }
    void reset() { check(frac_fodamp_reset(&c_), "frac_fodamp_reset"); }

private:
    frac_fodamp_params p_;
    frac_fodamp c_;
    std::vector<double> storage_;
};

// Time-varying Kalman filter (kalman.h): predict with u, update with y.
class Kalman {
public:
    Kalman(const Arr& A, const Arr& B, const Arr& C, const Arr& Q, const Arr& R, const Arr& P0, const py::object& x0)
    {
        n_ = rows_of(A);
        m_ = B.size() == 0 ? 0 : cols_of(B);
        p_ = rows_of(C);
        A_ = flat(A, n_, n_, "A");
        B_ = flat(B, m_ ? n_ : 0, m_, "B");
        C_ = flat(C, p_, n_, "C");
        Q_ = flat(Q, n_, n_, "Q");
        R_ = flat(R, p_, p_, "R");
        P0_ = flat(P0, n_, n_, "P0");
        if (!x0.is_none()) x0_ = flat(x0.cast<Arr>(), n_, 1, "x0");
        frac_kalman_params prm;
        prm.n = n_;
        prm.m = m_;
        prm.p = p_;
        prm.A = A_.data();
        prm.B = m_ ? B_.data() : nullptr;
        prm.C = C_.data();
        prm.Q = Q_.data();
        prm.R = R_.data();
        prm.P0 = P0_.data();
        prm.x0 = x0_.empty() ? nullptr : x0_.data();
        storage_.resize(FRAC_KALMAN_STORAGE(n_, p_));
        check(frac_kalman_init(&kf_, &prm, storage_.data(), storage_.size()), "frac_kalman_init");
    }
    int predict(const Arr& u)
    {
        if (size_t(u.size()) != m_) throw py::value_error("u: must have " + std::to_string(m_) + " entries");
        return frac_kalman_predict(&kf_, m_ ? u.data() : nullptr);
    }
    int update(const Arr& y)
    {
        if (size_t(y.size()) != p_) throw py::value_error("y: must have " + std::to_string(p_) + " entries");
        return frac_kalman_update(&kf_, y.data());
    }
    py::array_t<double> x() const
    {
        py::array_t<double> v = vec<double>(n_);
        std::copy(kf_.x, kf_.x + n_, v.mutable_data());
        return v;
    }
    py::array_t<double> P() const
    {
        py::array_t<double> v({py::ssize_t(n_), py::ssize_t(n_)});
        std::copy(kf_.P, kf_.P + n_ * n_, v.mutable_data());
        return v;
    }
    // For each sample k: update with Y[k], record x (a posteriori), predict with U[k].
    py::object filter(const Arr& U, const Arr& Y, bool status)
    {
        const size_t N = rows_of(Y);
        if (size_t(Y.size()) != N * p_) throw py::value_error("Y: must be N x " + std::to_string(p_));
        if (size_t(U.size()) != N * m_) throw py::value_error("U: must be N x " + std::to_string(m_));
        py::array_t<double> X({py::ssize_t(N), py::ssize_t(n_)});
        py::array_t<int> st({py::ssize_t(status ? N : 0), py::ssize_t(2)});
        double* xo = X.mutable_data();
        int* so = st.mutable_data();
        for (size_t k = 0; k < N; ++k) {
            const int s1 = frac_kalman_update(&kf_, Y.data() + k * p_);
            std::copy(kf_.x, kf_.x + n_, xo + k * n_);
            const int s2 = frac_kalman_predict(&kf_, m_ ? U.data() + k * m_ : nullptr);
            if (status) {
                so[2 * k] = s1;
                so[2 * k + 1] = s2;
            }
        }
        if (status) return py::make_tuple(X, st);
        return std::move(X);
    }
    void reset(const py::object& x0)
    {
        std::vector<double> v;
        if (!x0.is_none()) v = flat(x0.cast<Arr>(), n_, 1, "x0");
        check(frac_kalman_reset(&kf_, v.empty() ? nullptr : v.data()), "frac_kalman_reset");
    }

private:
    size_t n_, m_, p_;
    std::vector<double> A_, B_, C_, Q_, R_, P0_, x0_, storage_;
    frac_kalman kf_;
};

// The state-difference LQG step with delays (lqg.h).
class Lqg {
public:
    Lqg(size_t n, size_t d_i, const std::vector<size_t>& d_o, const Arr& A, const Arr& B, const Arr& C, const Arr& K,
        const Arr& L)
    {
        p_ = rows_of(C);
        if (!d_o.empty() && d_o.size() != p_) throw py::value_error("d_o: must have one delay per output");
        d_o_ = d_o;
        size_t nb = n + d_i;
        for (size_t d : d_o) nb += d;
        A_ = flat(A, n, n, "A");
        B_ = flat(B, n, 1, "B");
        C_ = flat(C, p_, n, "C");
        K_ = flat(K, nb, 1, "K");
        L_ = flat(L, nb + 1, p_, "L");
        frac_lqg_params prm;
        prm.n = n;
        prm.d_i = d_i;
        prm.p = p_;
        prm.d_o = d_o_.empty() ? nullptr : d_o_.data();
        prm.A = A_.data();
        prm.B = B_.data();
        prm.C = C_.data();
        prm.K = K_.data();
        prm.L = L_.data();
        storage_.resize(FRAC_LQG_STORAGE(nb + 1, p_));
        check(frac_lqg_init(&c_, &prm, storage_.data(), storage_.size()), "frac_lqg_init");
    }
    py::object run(const Arr& u_star, const Arr& y_ref, const Arr& y, bool status)
    {
        const size_t N = size_t(u_star.size());
        if (size_t(y_ref.size()) != N * p_ || size_t(y.size()) != N * p_)
            throw py::value_error("y_ref and y: must be N x " + std::to_string(p_) + " with N = len(u_star)");
        auto u = like(N);
        py::array_t<int> st = vec<int>(status ? N : 0);
        double* uo = u.mutable_data();
        int* so = st.mutable_data();
        for (size_t k = 0; k < N; ++k) {
            const int s = frac_lqg_step(&c_, u_star.data()[k], y_ref.data() + k * p_, y.data() + k * p_, &uo[k]);
            if (status) so[k] = s;
        }
        return result(u, st, status);
    }
    double friction_estimate() const { return frac_lqg_friction_estimate(&c_); }
    void reset() { check(frac_lqg_reset(&c_), "frac_lqg_reset"); }

private:
    size_t p_;
    std::vector<size_t> d_o_;
    std::vector<double> A_, B_, C_, K_, L_, storage_;
    frac_lqg c_;
};

int interp_of(const std::string& s)
{
    if (s == "linear") return FRAC_LUT_LINEAR;
    if (s == "cubic") return FRAC_LUT_CUBIC;
    throw py::value_error("interp: '" + s + "' is not one of linear, cubic");
}
int range_of(const std::string& s)
{
    if (s == "clamp") return FRAC_LUT_CLAMP;
    if (s == "extrapolate") return FRAC_LUT_EXTRAPOLATE;
    throw py::value_error("range: '" + s + "' is not one of clamp, extrapolate");
}

class Lut1 {
public:
    Lut1(const Arr& x, const Arr& y, const std::string& interp, const std::string& range)
        : x_(x.data(), x.data() + x.size()), y_(y.data(), y.data() + y.size()), d_(y_.size())
    {
        if (x_.size() != y_.size()) throw py::value_error("x and y must have the same length");
        check(frac_lut1_init(&t_, x_.data(), y_.data(), y_.size(), interp_of(interp), range_of(range), d_.data()),
              "frac_lut1_init");
    }
    py::object eval(const Arr& xq, bool status) { return map(xq, status, frac_lut1_eval); }
    py::object inverse(const Arr& yq, bool status) { return map(yq, status, frac_lut1_inverse); }

private:
    py::object map(const Arr& q, bool status, int (*f)(frac_lut1*, frac_real, frac_real*))
    {
        const size_t n = size_t(q.size());
        auto y = like(n);
        py::array_t<int> st = vec<int>(status ? n : 0);
        double* yo = y.mutable_data();
        int* so = st.mutable_data();
        for (size_t k = 0; k < n; ++k) {
            const int s = f(&t_, q.data()[k], &yo[k]);
            if (status) so[k] = s;
        }
        return result(y, st, status);
    }
    std::vector<double> x_, y_, d_;
    frac_lut1 t_;
};

class Lut2 {
public:
    Lut2(const Arr& x1, const Arr& x2, const Arr& z, const std::string& interp, const std::string& range)
        : x1_(x1.data(), x1.data() + x1.size()), x2_(x2.data(), x2.data() + x2.size()),
          z_(flat(z, x1_.size(), x2_.size(), "z"))
    {
        frac_lut_axis_params a1, a2;
        a1.x = x1_.data();
        a1.n = x1_.size();
        a1.x0 = a1.h = 0;
        a2.x = x2_.data();
        a2.n = x2_.size();
        a2.x0 = a2.h = 0;
        check(frac_lut2_init_interp(&t_, &a1, &a2, z_.data(), range_of(range), interp_of(interp)), "frac_lut2_init_interp");
    }
    py::object eval(const Arr& q1, const Arr& q2, bool status)
    {
        if (q1.size() != q2.size()) throw py::value_error("x1 and x2 must have the same length");
        const size_t n = size_t(q1.size());
        auto z = like(n);
        py::array_t<int> st = vec<int>(status ? n : 0);
        double* zo = z.mutable_data();
        int* so = st.mutable_data();
        for (size_t k = 0; k < n; ++k) {
            const int s = frac_lut2_eval(&t_, q1.data()[k], q2.data()[k], &zo[k]);
            if (status) so[k] = s;
        }
        return result(z, st, status);
    }

private:
    std::vector<double> x1_, x2_, z_;
    frac_lut2 t_;
};

}  // namespace

void bind_libfrac(py::module_& m)
{
    static_assert(sizeof(frac_real) == sizeof(double), "the Python binding is built with frac_real = double");
    m.def("status_str", &frac_status_str, "The name of a frac_status code.");
    m.def("version", &frac_version, "libfrac's version string.");
    py::class_<FoOperator>(m, "FoOperator")
        .def(py::init<double, double, const py::dict&>(), py::arg("order"), py::arg("ts"), py::arg("op"))
        .def("step", &FoOperator::step)
        .def("run", &FoOperator::run, py::arg("x"), py::arg("status") = false)
        .def("reset", &FoOperator::reset)
        .def("freqresp", &FoOperator::freqresp)
        .def_property_readonly("storage_len", &FoOperator::storage_len);
    py::class_<FoPid>(m, "FoPid")
        .def(py::init<const py::dict&>())
        .def("step", &FoPid::step)
        .def("run", &FoPid::run, py::arg("r"), py::arg("y"), py::arg("status") = false)
        .def("set_mode", &FoPid::set_mode)
        .def("set_manual", &FoPid::set_manual)
        .def("reset", &FoPid::reset);
    py::class_<FoDamp>(m, "FoDamp")
        .def(py::init<const py::dict&>())
        .def("step", &FoDamp::step)
        .def("run", &FoDamp::run, py::arg("ref"), py::arg("meas"), py::arg("status") = false)
        .def("reset", &FoDamp::reset);
    py::class_<Kalman>(m, "Kalman")
        .def(py::init<const Arr&, const Arr&, const Arr&, const Arr&, const Arr&, const Arr&, const py::object&>())
        .def("predict", &Kalman::predict)
        .def("update", &Kalman::update)
        .def("filter", &Kalman::filter, py::arg("U"), py::arg("Y"), py::arg("status") = false)
        .def("reset", &Kalman::reset, py::arg("x0") = py::none())
        .def_property_readonly("x", &Kalman::x)
        .def_property_readonly("P", &Kalman::P);
    py::class_<Lqg>(m, "Lqg")
        .def(py::init<size_t, size_t, const std::vector<size_t>&, const Arr&, const Arr&, const Arr&, const Arr&,
                      const Arr&>())
        .def("run", &Lqg::run, py::arg("u_star"), py::arg("y_ref"), py::arg("y"), py::arg("status") = false)
        .def("friction_estimate", &Lqg::friction_estimate)
        .def("reset", &Lqg::reset);
    py::class_<Lut1>(m, "Lut1")
        .def(py::init<const Arr&, const Arr&, const std::string&, const std::string&>())
        .def("eval", &Lut1::eval, py::arg("x"), py::arg("status") = false)
        .def("inverse", &Lut1::inverse, py::arg("y"), py::arg("status") = false);
    py::class_<Lut2>(m, "Lut2")
        .def(py::init<const Arr&, const Arr&, const Arr&, const std::string&, const std::string&>())
        .def("eval", &Lut2::eval, py::arg("x1"), py::arg("x2"), py::arg("status") = false);
}
