// Posterior Cramer-Rao lower bound of the TBD tracking problem (docs/algorithms.md section 7):
// Tichavsky's recursion J_{k+1} = (V + F J_k^-1 F^T)^-1 + J_z on the 5-D state
// [x, vx, y, vy, I], with the sub-pixel-offset-averaged measurement information J_z
// (continuum form) and a birth prior on velocity and intensity at the first frame.
#pragma once
#include <vector>

namespace pft::host::tbd {

struct PcrlbInput {
    double peak = 6.4961;     ///< A = I dx dy / (2 pi Sigma^2)
    double sigma = 3.256;     ///< pixel noise std
    double psf_sigma = 0.7;
    double intensity = 20.0;
    double dx = 1.0, dy = 1.0;
    double T = 1.0, q1 = 0.005, q2 = 0.01;
    bool stochastic = true;   ///< false: deterministic straight-line truth (V = 0)
    double vel_info = 3.0;    ///< birth prior information on each velocity (1/P0)
    double int_info = 0.03;   ///< birth prior information on intensity (12/(Imax-Imin)^2)
    int frames = 16;          ///< frames tracked from the birth frame
};

struct PcrlbResult {
    std::vector<double> radial;   ///< per frame k = 1..frames: sqrt(Pxx + Pyy)
    double track_rmse = 0;        ///< sqrt(mean over the frames of Pxx + Pyy): floor on eq. 25
    double frame1_axis = 0;       ///< single-frame per-axis std 1/sqrt(Jxx)
    double steady_axis = 0;       ///< steady state (stochastic CV) per-axis position std
    double steady_radial = 0;
    double steady_vel = 0;        ///< steady-state per-axis velocity std
};

PcrlbResult pcrlb(const PcrlbInput &in);

/** Offset-averaged J_xx computed by the discrete pixel sum (window half-size p, p < 0: whole
 *  plane), averaging over an n x n grid of sub-pixel offsets. For the self-check against the
 *  continuum form pi A^2 / (2 sigma^2 dx dy). */
double jxx_discrete(double peak, double sigma, double psf_sigma, int p, int n_offsets);

/** Runs the self-checks of this module (table 7.2 of docs/algorithms.md to 3 digits); prints each
 *  check and returns the number of failures. */
int pcrlb_selftest(bool verbose);

}  // namespace pft::host::tbd
