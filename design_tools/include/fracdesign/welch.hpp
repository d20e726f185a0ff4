// welch.hpp - Welch cross-spectral estimate of a frequency response, like MATLAB tfestimate (H1).
//
// The record is cut into K segments of nperseg samples overlapping by noverlap (K = floor((M - noverlap)
// / (nperseg - noverlap)), trailing samples dropped), each multiplied by the window w, zero-padded to nfft
// and transformed. With X_k, Y_k the segment spectra (one-sided, bins f_i = i fs/nfft, i = 0..nfft/2):
//   Pxx = c mean_k |X_k|^2,  Pyy = c mean_k |Y_k|^2,  Pxy = c mean_k conj(X_k) Y_k,
//   c = 2/(fs sum w^2) (1/(fs sum w^2) at DC and, for even nfft, Nyquist)   (density scaling)
//   Txy = Pxy/Pxx (H1: output y over input x),  Cxy = |Pxy|^2/(Pxx Pyy)
// which is scipy.signal.csd/welch(..., scaling='density', detrend=False) and MATLAB cpsd/tfestimate.
// Seed 000 Sec. 5.1 used 8 Hamming segments with 15 % overlap and nfft = 160000 at fs = 1 kHz
// (welch_matlab_segments gives MATLAB's segment length for such a specification).
#pragma once
#include <complex>
#include <cstddef>
#include <vector>

namespace fracdesign {

struct WelchOptions {
    double fs = 1.0;             // sampling frequency [Hz]
    int nperseg = 256;           // segment length
    int noverlap = 128;          // overlap in samples, 0 <= noverlap < nperseg
    int nfft = 0;                // FFT length >= nperseg (0: nperseg)
    bool detrend_mean = false;   // subtract each segment's mean (scipy detrend='constant'); MATLAB: false
    std::vector<double> window;  // nperseg weights; empty: symmetric Hamming (MATLAB hamming(nperseg))
};

struct WelchResult {
    std::vector<double> f;                     // Hz, nfft/2 + 1 bins
    std::vector<double> Pxx, Pyy;              // auto spectral densities [unit^2/Hz]
    std::vector<std::complex<double>> Pxy;     // cross spectral density conj(X) Y
    std::vector<std::complex<double>> Txy;     // H1 frequency response estimate Pxy/Pxx
    std::vector<double> Cxy;                   // magnitude-squared coherence
    int segments = 0;
};

// Symmetric Hamming window 0.54 - 0.46 cos(2 pi n/(N-1)), n = 0..N-1 (N = 1: {1}).
std::vector<double> hamming_symmetric(int n);

// MATLAB's segmentation for `nsegments` segments overlapping by the fraction `overlap` of a record of
// M samples: nperseg = floor(M / (K - (K-1) overlap)), noverlap = round(overlap nperseg).
WelchOptions welch_matlab_segments(std::size_t M, int nsegments, double overlap, int nfft, double fs);

// Throws std::invalid_argument with a one-line message naming the bad option or signal (lengths differ,
// a sample is not finite, nperseg > M or < 2, noverlap out of range, nfft < nperseg, fs <= 0, window size).
WelchResult welch_tfestimate(const std::vector<double>& x, const std::vector<double>& y, const WelchOptions& opt);

// Auto spectral density of one signal by the same segmentation, window and scaling (Pxx of
// welch_tfestimate, one FFT per segment instead of two): scipy.signal.welch(..., scaling='density').
// Same errors as welch_tfestimate.
struct WelchPsd {
    std::vector<double> f;  // Hz, nfft/2 + 1 bins
    std::vector<double> P;  // [unit^2/Hz]
    int segments = 0;
};
WelchPsd welch_psd(const std::vector<double>& x, const WelchOptions& opt);

}  // namespace fracdesign
