#pragma once
// bench_nn --full-training [--epochs N] [--synthetic] (bench_training.cpp).
namespace motionstyle::bench {
// Returns the process exit code. Prints the figures.
int fullTrainingBench(int epochs, bool synthetic_only);
}  // namespace motionstyle::bench
