#!/usr/bin/env python3
"""The PyTorch peer of MotionStyle's neural core (issue 3, "Speed"): the same networks in PyTorch on
CPU, timed the same way as tests/bench/nn (bench_nn), and printed side by side with bench_nn's figures.

Not a CI step; for people comparing. Needs Debian's python3-torch (1.13) at /usr/bin/python3.
Its loss terms only stand in for eq. 7-9's cost; the exact definitions, checked against the C++ by a
unit test, are in dump_reference.py.

    /usr/bin/python3 tests/peer/pytorch_peer.py BUILD/tests/bench/nn/bench_nn [--threads 2]
        [--runs N] [--full-training-epochs N]

Networks (paper, Holden et al. 2017, and core/nn):
  loss network L: Conv1d 66 -> 256, width 25, "same" padding; max-pool 2; ReLU. Decoder: depool x2
                  (each hidden frame repeated), subtract the encoder bias, Conv1d 256 -> 66 width 25, no bias.
  transformation T: Conv1d 66 -> 128 -> 128 -> 66, width 25, ReLU on all but the last, plus the input
                  (MotionStyle's default residual form; one addition).
Figures (medians of --runs calls after warm-up, wall and process CPU time, float32, no_grad for stylize):
  stylize F frames: T, then the projection decode(encode(.)), batch 1, F = 240, 960, 14,400.
  training step 16 x 240: T forward + backward through the frozen encoder of L with the content
                  (hidden-unit MSE, eq. 4), style (Gram MSE, eq. 5), foot (eq. 7, velocity of the four foot
                  joints times contact), bone (eq. 8) and trajectory (eq. 9) terms, plus one Adam step.
  100 epochs over 72,000 frames: 240-frame windows with step 120 give 599 windows, 38 steps of 16 per
                  epoch: 3,800 x the step time (an estimate: no data loading, no checkpoints).
"""

import argparse
import math
import os
import re
import statistics
import subprocess
import sys
import time

FEATURES = 66
AE_HIDDEN = 256
T_HIDDEN = 128
WIDTH = 25
STEPS_PER_100_EPOCHS = 100 * math.ceil(((72000 - 240) // 120 + 1) / 16)  # 100 x 38


def median_ms(fn, warmup, runs):
    """(wall ms, process CPU ms over all threads), medians over `runs` calls. The CPU figure is what
    bench_nn also prints: other processes on a shared machine inflate it much less than wall time."""
    for _ in range(warmup):
        fn()
    wall, cpu = [], []
    for _ in range(runs):
        cpu_start = time.process_time()
        start = time.perf_counter()
        fn()
        wall.append((time.perf_counter() - start) * 1e3)
        cpu.append((time.process_time() - cpu_start) * 1e3)
    return statistics.median(wall), statistics.median(cpu)


def build_networks(torch):
    nn = torch.nn

    class LossNetwork(nn.Module):
        def __init__(self):
            super().__init__()
            self.encoder = nn.Conv1d(FEATURES, AE_HIDDEN, WIDTH, padding=WIDTH // 2)
            self.decoder = nn.Conv1d(AE_HIDDEN, FEATURES, WIDTH, padding=WIDTH // 2, bias=False)

        def encode(self, x):
            return torch.relu(torch.nn.functional.max_pool1d(self.encoder(x), 2))

        def decode(self, h):
            h = h.repeat_interleave(2, dim=2) - self.encoder.bias.view(1, -1, 1)
            return self.decoder(h)

    class TransformationNetwork(nn.Module):
        def __init__(self):
            super().__init__()
            self.conv1 = nn.Conv1d(FEATURES, T_HIDDEN, WIDTH, padding=WIDTH // 2)
            self.conv2 = nn.Conv1d(T_HIDDEN, T_HIDDEN, WIDTH, padding=WIDTH // 2)
            self.conv3 = nn.Conv1d(T_HIDDEN, FEATURES, WIDTH, padding=WIDTH // 2)

        def forward(self, x):
            y = torch.relu(self.conv1(x))
            y = torch.relu(self.conv2(y))
            return x + self.conv3(y)

    return LossNetwork(), TransformationNetwork()


def pytorch_figures(args):
    import torch

    def gram(h):
        # batch x hidden x frames -> batch x hidden x hidden, normalised by frames (eq. 6)
        return torch.bmm(h, h.transpose(1, 2)) / h.shape[2]

    torch.set_num_threads(args.threads)
    torch.manual_seed(1)
    ae, t = build_networks(torch)
    ae.eval()
    t.eval()
    figures = {}
    with torch.no_grad():
        for frames in (240, 960, 14400):
            x = torch.randn(1, FEATURES, frames)
            runs = args.runs if frames < 5000 else max(3, args.runs // 4)
            figures[f"stylize {frames}"] = median_ms(lambda: ae.decode(ae.encode(t(x))), 3, runs)

    # One training step, batch 16 x 240.
    batch, frames = 16, 240
    content = torch.randn(batch, FEATURES, frames)
    with torch.no_grad():
        content_hidden = ae.encode(content)
        style_gram = gram(ae.encode(torch.randn(1, FEATURES, 480)))
    contacts = (torch.rand(batch, 4, frames) < 0.3).float()
    bone_targets = torch.rand(batch, 20) * 40
    parents = [0, 0, 1, 2, 3, 0, 5, 6, 7, 0, 9, 10, 11, 11, 13, 14, 15, 11, 17, 18, 19]
    feet = [3, 4, 7, 8]
    for p in ae.parameters():
        p.requires_grad_(False)
    t.train()
    optimiser = torch.optim.Adam(t.parameters(), lr=1e-3)

    def step():
        optimiser.zero_grad()
        y = t(content)
        h = ae.encode(y)
        content_loss = torch.mean((h - content_hidden) ** 2)
        style_loss = torch.mean((gram(h) - style_gram) ** 2)
        joints = y[:, :63, :].reshape(batch, 21, 3, frames)
        bones = (joints[:, 1:] - joints[:, parents[1:]]).norm(dim=2).mean(dim=2)
        bone_loss = torch.mean((bones - bone_targets) ** 2)
        foot_velocity = (joints[:, feet, :, 1:] - joints[:, feet, :, :-1]).norm(dim=2)
        foot_loss = torch.mean(contacts[:, :, 1:] * foot_velocity ** 2)
        trajectory_loss = torch.mean((y[:, 63:, :] - content[:, 63:, :]) ** 2)
        loss = content_loss + 0.01 * style_loss + 0.01 * (foot_loss + bone_loss + trajectory_loss)
        loss.backward()
        optimiser.step()

    figures["training step 16x240"] = median_ms(step, 1, max(3, args.runs // 4))
    figures["100 epochs 72000 frames (min)"] = tuple(v * STEPS_PER_100_EPOCHS / 60e3 for v in figures["training step 16x240"])
    return figures


def bench_nn_figures(bench, threads, full_training_epochs):
    env = dict(os.environ)
    out = subprocess.run([bench, "--threads", str(threads)], env=env, check=True, capture_output=True, text=True).stdout
    sys.stdout.write("---- bench_nn --threads %d\n%s" % (threads, out))
    figures = {}
    for frames, wall, cpu in re.findall(r"stylize\s+(\d+) frames: wall\s+([\d.]+) ms.*?cpu\s+([\d.]+) ms", out):
        figures[f"stylize {frames}"] = (float(wall), float(cpu))
    match = re.search(r"T training step .*?wall\s+([\d.]+) ms \| cpu\s+([\d.]+) ms", out)
    if match:
        step = (float(match.group(1)), float(match.group(2)))
        figures["training step 16x240"] = step
        figures["100 epochs 72000 frames (min)"] = tuple(v * STEPS_PER_100_EPOCHS / 60e3 for v in step)
    if full_training_epochs > 0:
        out = subprocess.run([bench, "--full-training", "--epochs", str(full_training_epochs), "--threads", str(threads)],
                             env=env, check=True, capture_output=True, text=True).stdout
        sys.stdout.write("---- bench_nn --full-training --epochs %d\n%s" % (full_training_epochs, out))
        match = re.search(r"100 epochs over \d+ frames: ([\d.]+) min", out)
        if match:
            figures["full training run, 100 epochs (min)"] = float(match.group(1))
    return figures


def load_average():
    try:
        return os.getloadavg()[0]
    except OSError:
        return float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("bench_nn", help="path to the built bench_nn (BUILD/tests/bench/nn/bench_nn)")
    parser.add_argument("--threads", type=int, default=2, help="threads for both (default 2)")
    parser.add_argument("--runs", type=int, default=21, help="timed calls per figure (default 21)")
    parser.add_argument("--full-training-epochs", type=int, default=0,
                        help="also run bench_nn --full-training with this many epochs (0: skip)")
    args = parser.parse_args()
    try:
        import torch  # noqa: F401
    except ImportError:
        print("pytorch_peer: python3-torch is not installed (apt-get install python3-torch); nothing to compare")
        return 0
    print("load average before: %.2f (2-core machine; figures assume it idle)" % load_average())
    cpp = bench_nn_figures(args.bench_nn, args.threads, args.full_training_epochs)
    py = pytorch_figures(args)
    print("load average after: %.2f" % load_average())
    import torch
    print("\nPyTorch %s on CPU, %d threads, vs MotionStyle bench_nn, %d threads (medians)" %
          (torch.__version__, args.threads, args.threads))
    print("%-30s %11s %11s %8s | %11s %11s %8s" %
          ("figure", "ours wall", "torch wall", "ratio", "ours cpu", "torch cpu", "ratio"))
    for key, (py_wall, py_cpu) in py.items():
        unit = "min" if "(min)" in key else "ms"
        ours = cpp.get(key)
        if ours is None:
            print("%-30s %11s %7.2f %-3s %8s | %11s %7.2f %-3s" % (key, "n/a", py_wall, unit, "", "n/a", py_cpu, unit))
            continue
        print("%-30s %7.2f %-3s %7.2f %-3s %7.2fx | %7.2f %-3s %7.2f %-3s %7.2fx" %
              (key, ours[0], unit, py_wall, unit, py_wall / ours[0], ours[1], unit, py_cpu, unit, py_cpu / ours[1]))
        if key.startswith("stylize"):
            frames = int(key.split()[1])
            print("%-30s %11.0f %11.0f %8s   (frames/s, wall)" % ("", frames / ours[0] * 1e3, frames / py_wall * 1e3, ""))
    if "full training run, 100 epochs (min)" in cpp:
        print("%-30s %7.2f min (bench_nn --full-training: real data path incl. checkpoints)" %
              ("full training, 100 epochs", cpp["full training run, 100 epochs (min)"]))
    print("ratio = PyTorch / MotionStyle (> 1: MotionStyle is faster). cpu = process CPU time over all threads.")
    print("100-epoch rows are the step time x %d steps (estimates, no data loading or checkpoints)." %
          STEPS_PER_100_EPOCHS)
    return 0


if __name__ == "__main__":
    sys.exit(main())
