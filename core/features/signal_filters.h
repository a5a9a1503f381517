#pragma once
// Small 1-D signal helpers used by the representation (time runs along rows: one row per frame).

#include <Eigen/Core>
#include <vector>

namespace motionstyle {

// Gaussian smoothing of every column over time (rows), sigma in frames, edges clamped (the first and
// last frames are repeated), kernel truncated at 3 sigma. sigma <= 0 returns the input unchanged.
Eigen::MatrixXd gaussianSmoothRows(const Eigen::MatrixXd& signal, double sigma_frames);

// The [1 2 1] / 4 filter along time of features with one COLUMN per frame, in place, edges clamped
// (the first and last frames repeated): y_t = (x_{t-1} + 2 x_t + x_{t+1}) / 4. Its gain at frequency f
// is cos^2(pi f / fps): zero for an alternation between even and odd frames (the Nyquist frequency),
// 0.93 at 5 Hz and 0.75 at 10 Hz at 60 fps. Fewer than 3 frames: unchanged (nothing alternates).
void removeFrameAlternation(Eigen::MatrixXd& features);

// 3x^2 - 2x^3 of x clamped to [0, 1]: 0 at and below 0, 1 at and above 1, with zero slope at both
// ends (ramps that start and stop without a kink).
double smoothstep(double x);

// The q-quantile (0..1) of the values, by partial sort of a copy. Empty input: 0.
double quantile(const Eigen::VectorXd& values, double q);

// The median: the value of rank size / 2 (the upper of the two middle values of an even count), by
// partial sort of the copy it is given. Empty input: 0.
double median(std::vector<double> values);

}  // namespace motionstyle
