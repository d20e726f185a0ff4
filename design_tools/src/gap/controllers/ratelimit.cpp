// ratelimit.cpp - the "rate_limit" stage (kinds.hpp): frac_ramp_step, the
// one-cycle rate limiter of libfrac (frac/ramp.h; seed 004 part 2 (9.2)).
#include <cmath>

#include "kinds.hpp"

#include "frac/ramp.h"

namespace fracdesign {
namespace gap {

double RateLimit::step(double target)
{
    if (!started_) {
        reset(target);
        return target;
    }
    frac_real y = frac_real(x_);
    frac_ramp_step(frac_real(x_), frac_real(target), frac_real(rate_), frac_real(Ts_), &y);
    x_ = double(y);
    return x_;
}

double read_rate(const json& doc, const char* key, const std::string& where)
{
    if (!doc.contains(key)) return 0.0;
    const double r = number(doc, key, where);
    if (!(r > 0)) refuse(where, key, doc.at(key), "a rate > 0 per second");
    return r;
}

}  // namespace gap
}  // namespace fracdesign
