// haro_synthetic.hpp - synthetic antenna FRFs for testing the seed 000 fit:
// the model G (eq. 25, corrected beta^4) on a grid, plus optional complex
// Gaussian noise proportional to |G| (the measured FRFs of Haro-Olmo et al.
// are noisier where the response is larger and at high frequency, Sec. 6.1).
#pragma once
#include "fracdesign/ident/antenna_fit.hpp"

namespace fracdesign {
namespace ident {

// G_p = G(j w_p) (1 + rel_noise (n_re + j n_im)), n ~ N(0, 1) independent,
// drawn from a generator seeded with `seed` (53-bit uniforms and Box-Muller
// written out, so the data are the same on every standard library).
Frf haro_synthetic_frf(const AntennaDamping<double>& d, const std::vector<double>& w, double rel_noise,
                       unsigned seed, const AntennaLink& link = AntennaLink());

}  // namespace ident
}  // namespace fracdesign
