// filters.hpp - the signal processing of inverse-model identification:
// Butterworth low-pass design, zero-phase filtering, derivatives, decimation.
//
// IDIM-LS (Gautier, Janot & Vandanjon 2013; EMPS description, Janot, Gautier
// & Brunot 2019, sec. 3) estimates velocities and accelerations from the
// measured position with a zero-phase low-pass filter followed by central
// differences, and "decimates in parallel": every column of the observation
// matrix and the torque are low-pass filtered at 0.8 of the decimated Nyquist
// frequency and then down-sampled, so the unmodelled high-frequency part of
// the torque does not enter the least-squares fit.
#pragma once
#include <vector>

namespace fracdesign {
namespace ident {

// One direct-form II transposed biquad: y = (b0 + b1 z^-1 + b2 z^-2)/(1 + a1 z^-1 + a2 z^-2) x.
struct Biquad {
    double b0, b1, b2, a1, a2;
};

// Digital Butterworth low-pass of `order` (1..16), cut-off `fc_hz` < fs/2,
// by the bilinear transform with pre-warping, as cascaded sections (a
// first-order section has b2 = a2 = 0). Unity DC gain.
// Throws std::invalid_argument for an order or cut-off out of range.
std::vector<Biquad> butter_lowpass(int order, double fc_hz, double fs_hz);

// Zero-phase forward-backward filtering (the square of the magnitude response,
// no phase), with odd reflection of `pad` samples at each end and each
// section started in its steady state, so a constant or a ramp passes without
// an edge transient. pad = 0 picks 3*(2*sections+1), capped at size()-1.
// Throws std::invalid_argument if x has fewer than 2 samples.
std::vector<double> filtfilt(const std::vector<Biquad>& sos, const std::vector<double>& x, std::size_t pad = 0);

// Central difference (x[k+1]-x[k-1])/(2 dt); one-sided at the two ends.
std::vector<double> central_difference(const std::vector<double>& x, double dt);

}  // namespace ident
}  // namespace fracdesign
