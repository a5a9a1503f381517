#pragma once
// What a network file's numbers may be beyond "finite": bounds that no trained network reaches, checked
// by the reader (InputError naming the file) and by the writer (std::invalid_argument), so that every
// file we write reads back. Why: a network file is user input, and later code computes with what it
// holds (the networks run in float32; adapt and retraining reuse a loaded network's sparsity, dropout
// and loss weights; the GUI plots the loss history).
//
//   normalisation       |mean| <= 1e6 and 1e-6 <= std <= 1e6 (cm, cm/frame, rad/frame). Real statistics
//                       sit far inside (positions within 2 m of the root; computeFeatureStatistics
//                       floors std at 1e-4; shipped: |mean| < 132, std in [0.0055, 11]); outside them
//                       x_n = (x - mean) / std of a real frame overflows float32 (the reported
//                       crashes: mean +-1e308, std 1e-301).
//   weights             |w| <= 1e5. Trained weights are O(1): the shipped networks stay below 0.3,
//                       Xavier initialisation gives ~0.03, and Adam moves a weight by about the learning
//                       rate per step. Above f16's largest value (65504), so every finite f16 weight
//                       stays readable.
//   style targets       |g| <= 1e12 per Gram entry: a mean of products of hidden units (shipped: < 5).
//   representation      fps in [1, 1e4] (the representation's is 60), reference body height in
//                       [1, 1e4] cm (the shipped networks': 127).
//   training            epochs, batch windows, window frames fit an int; sparsity and each loss weight
//                       in [0, 1e9] (defaults <= 100); dropout in [0, 1) (the trainer's own rule); the
//                       learning rate finite and >= 0 (only shown, and the trainer bounds it no further:
//                       a bound here could refuse to save a finished run).
//   loss history        every value finite and within float32's range (|v| <= 3.4e38): the trainer
//                       computes in float32 and stops on a non-finite loss.
// Strings (valid UTF-8 without control characters) are checked by ByteReader::str (binary_io.h).

#include <string>

#include "nn/network_file.h"

namespace motionstyle::nn {

inline constexpr double kMaxNormalisationMean = 1e6;
inline constexpr double kMinNormalisationStd = 1e-6;
inline constexpr double kMaxNormalisationStd = 1e6;
inline constexpr float kMaxWeightMagnitude = 1e5f;
inline constexpr float kMaxStyleTargetMagnitude = 1e12f;
inline constexpr double kMinRepresentationValue = 1.0;  // fps, reference body height (cm)
inline constexpr double kMaxRepresentationValue = 1e4;
inline constexpr double kMaxTrainingCoefficient = 1e9;  // sparsity, loss weights
inline constexpr double kMaxLossValue = 3.4e38;         // float32's largest finite value, rounded down

// "" when the metadata's numbers are within the bounds above; otherwise what is wrong, naming the field
// ("dropout = 1.5 is outside [0, 1)"). Strings are not checked here.
std::string metadataProblem(const NetworkMetadata& metadata);

// "" when mean and std have kFeatureCount entries within the bounds above; otherwise what is wrong,
// naming the first bad entry ("normalisation std[3] = 1e-301 is outside [1e-6, 1e6]").
std::string normalisationProblem(const FeatureStatistics& normalisation);

// "" when every entry of `values` is finite with |v| <= max_magnitude; otherwise e.g.
// "tensor 'encoder.bias' has the value 1e+30 at (0, 0); trained networks stay within +-100000".
std::string valuesProblem(const std::string& tensor_name, const Mat<float>& values, float max_magnitude);

}  // namespace motionstyle::nn
