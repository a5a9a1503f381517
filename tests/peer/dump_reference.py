#!/usr/bin/env python3
"""Writes tests/data/nn_reference.txt: one training batch through the transformation network T and the
frozen loss network L in PyTorch (float64), with the five eq. 10 terms and every parameter gradient of
T, for the C++ unit test tests/unit/nn/pytorch_reference_test.cpp (issue 14, "in the spirit of llm.c").

Why: the gradient checks prove that the C++ backward passes match the C++ forward passes, not that the
forward passes compute the paper's networks and losses. This file is a second, independent
implementation of both, written from the formulas (paper, Holden et al. 2017; core/nn/losses.h and
style_loss.h's stated definitions), not from the C++ code.

    /usr/bin/python3 tests/peer/dump_reference.py tests/data/nn_reference.txt

Needs Debian's python3-torch (1.13). Everything is synthetic and deterministic (sinusoids, Python's
seeded Mersenne Twister); no dataset is read. Running it again writes the same bytes.

THE BATCH. B = 2 windows of T = 16 frames, 66 features (the real representation); reduced network
sizes so that the file stays small: T is 66 -> 8 -> 8 -> 66, L's encoder 66 -> 12, width 5 for all,
T residual (output = input + T(input), MotionStyle's default). One style clip of 23 frames (odd, so
the loss network's repeat-the-last-frame padding is covered). Inputs are rounded to 4 significant
digits: both sides parse the same decimal text into the same doubles, so they compute from identical
inputs.

NETWORKS (cross-correlation, zero "same" padding inside each window, as torch.nn.functional.conv1d):
    T(x) = x + conv3(relu(conv2(relu(conv1(x)))))
    L(x) = relu(maxpool2(conv_enc(x)))   an odd window first gets its last frame repeated

LOSSES on y = T(I), h = L(y), with de-normalised frames Y = y * std + mean (cm, cm/frame, rad/frame):
    content    = mean over entries of (h - L(I))^2                                    eq. 4
    style      = mean over windows b and entries of (h_b h_b^T / n - G)^2,            eq. 5, 6
                 n = pooled frames of a window; G = L(S) L(S)^T / n_S of the style clip S
    foot       = mean over (window, t < T-1, contact c labelled at t) of |d|^2,        eq. 7
                 d = (v_x(t), 0, v_z(t)) + R_y(w(t)) p_j(t+1) - p_j(t), where the foot joint p_j is in
                 frame t's root frame; R_y(a) (x, y, z) = (cos a x + sin a z, y, -sin a x + cos a z)
                 (facing +Z turns toward +X), because P_j(t) = r(t) + R(t) p_j(t) (feature_layout.h)
    bone       = mean over the 20 bones and all B*T frames of (|p_child - p_parent| - l_b)^2   eq. 8
    trajectory = sum over (v_x, v_z, w) of the squared difference to the content's,   eq. 9
                 divided by the number of frames B*T
    total      = sum of weight * term                                                eq. 10

FILE FORMAT (text, UTF-8). Lines starting with '#' are comments. Every other record is
    tensor NAME RANK D0 D1 ... D(RANK-1)
followed by D0*...*D(RANK-1) numbers (a scalar: RANK 0, one number), row-major (the last index
fastest), one last-axis row per line, written as Python's shortest round-trip repr. Layouts are
PyTorch's: a batch is [window, feature, frame], a convolution weight [out, in, tap] (the C++ stores
W(o, tap*in + c), tensor.h). Names:
    config.*                     windows, frames, style_frames, features, t_hidden, ae_hidden, width,
                                 residual (1 or 0)
    weights.*                    content, style, foot, bone, trajectory (eq. 10)
    normalisation.mean / .std    [66]
    input.content [B,66,T]  input.contacts [B,4,T]  input.bone_lengths [B,20]  input.style_clip [66,S]
    loss_network.encoder.weight / .bias
    transformer.conv{1,2,3}.weight / .bias
    expected.content_hidden [B,h,T/2]   L(I)
    expected.style_gram [h,h]           Gram(L(S))
    expected.output [B,66,T]            T(I)
    expected.output_hidden [B,h,T/2]    L(T(I))
    expected.terms.*                    content, style, foot, bone, trajectory, total (unweighted terms)
    expected.grad.transformer.conv{1,2,3}.weight / .bias    d total / d parameter
"""

import argparse
import math
import random
import sys

WINDOWS, FRAMES, STYLE_FRAMES = 2, 16, 23
FEATURES, JOINTS, CONTACTS, BONES = 66, 21, 4, 20
T_HIDDEN, AE_HIDDEN, WIDTH = 8, 12, 5
SIDEWAYS, FORWARD, TURNING = 63, 64, 65
# The canonical tree (core/features/feature_layout.h): hips; left leg; right leg; spine, chest, neck,
# head; the arms hang off the chest (joint 10).
PARENT = [-1, 0, 1, 2, 3, 0, 5, 6, 7, 0, 9, 10, 11, 10, 13, 14, 15, 10, 17, 18, 19]
CONTACT_JOINT = [3, 4, 7, 8]  # left heel = left ankle, left toe, right heel = right ankle, right toe
# Loss weights (not the training defaults) chosen so that each weighted term has a gradient norm of
# about 1: a wrong term cannot hide behind another in the gradient comparison (shares printed when run).
WEIGHTS = {"content": 5.0, "style": 10.0, "foot": 0.06, "bone": 0.03, "trajectory": 4.0}
# A rest pose in cm, root frame (hips over the origin, facing +Z, +X the character's left).
REST = [(0, 95, 0), (9, 90, 0), (9, 50, 2), (9, 9, -2), (9, 2, 13), (-9, 90, 0), (-9, 50, 2),
        (-9, 9, -2), (-9, 2, 13), (0, 108, -1), (0, 124, -2), (0, 142, 0), (0, 156, 3), (16, 138, -2),
        (19, 111, -3), (21, 86, 2), (21, 78, 4), (-16, 138, -2), (-19, 111, -3), (-21, 86, 2), (-21, 78, 4)]
# Minimum distance of any ReLU input from 0 and of any max-pool pair from a tie: the reference must not
# depend on which side of a kink rounding puts a value.
KINK_MARGIN = 1e-6


def short(value, digits=4):
    """The value rounded to `digits` significant digits (both sides parse the same decimal text)."""
    return float("%.*g" % (digits, value))


def normalisation():
    mean = [float(c) for joint in REST for c in joint] + [0.0, 1.5, 0.0]
    std = [6.0 + (f % 5) * 1.5 for f in range(63)] + [0.5, 1.25, 0.03]
    return mean, std


def motion(rng, frames, phase, amplitude):
    """Normalised frames [66][frames]: the rest pose swinging with smooth sinusoids plus a little noise,
    walking forward and turning slowly."""
    mean, std = normalisation()
    x = [[0.0] * frames for _ in range(FEATURES)]
    for f in range(FEATURES):
        joint_phase = rng.uniform(0, 2 * math.pi)
        for t in range(frames):
            s = math.sin(2 * math.pi * t / 16 + phase + joint_phase)
            if f < 63:
                value = mean[f] + amplitude * (1 + f % 3) * s + rng.gauss(0, 0.3)
            elif f == SIDEWAYS:
                value = 0.3 * s
            elif f == FORWARD:
                value = 1.5 + 0.4 * s
            else:
                value = 0.02 * s + 0.01
            x[f][t] = short((value - mean[f]) / std[f])
    return x


def conv_weight(rng, out, inp, scale):
    bound = scale * math.sqrt(6.0 / (inp * WIDTH))  # He-uniform, as the C++ initialisation
    return [[[short(rng.uniform(-bound, bound)) for _ in range(WIDTH)] for _ in range(inp)] for _ in range(out)]


def conv_bias(rng, out, scale):
    return [short(rng.uniform(-scale, scale)) for _ in range(out)]


def make_case():
    rng = random.Random(14)
    case = {"mean_std": normalisation()}
    case["content"] = [motion(rng, FRAMES, 0.9 * b, 2.0) for b in range(WINDOWS)]
    case["style_clip"] = motion(rng, STYLE_FRAMES, 0.3, 5.0)
    contacts = []
    for b in range(WINDOWS):
        rows = []
        for c in range(CONTACTS):
            side = 0 if c < 2 else math.pi  # right foot half a cycle after the left
            toe = 0.6 if c % 2 else 0.0     # toe contact later than the heel's
            rows.append([1.0 if math.sin(2 * math.pi * t / 16 + side - toe + 0.9 * b) > 0 else 0.0
                         for t in range(FRAMES)])
        contacts.append(rows)
    case["contacts"] = contacts
    case["bone_lengths"] = []
    for b in range(WINDOWS):
        lengths = []
        for child in range(1, JOINTS):
            u = [REST[child][a] - REST[PARENT[child]][a] for a in range(3)]
            lengths.append(short(math.sqrt(sum(c * c for c in u)) * (1 + 0.03 * b) + rng.uniform(-1, 1)))
        case["bone_lengths"].append(lengths)
    case["encoder.weight"] = conv_weight(rng, AE_HIDDEN, FEATURES, 1.0)
    case["encoder.bias"] = conv_bias(rng, AE_HIDDEN, 0.3)
    case["conv1.weight"] = conv_weight(rng, T_HIDDEN, FEATURES, 1.0)
    case["conv1.bias"] = conv_bias(rng, T_HIDDEN, 0.2)
    case["conv2.weight"] = conv_weight(rng, T_HIDDEN, T_HIDDEN, 1.0)
    case["conv2.bias"] = conv_bias(rng, T_HIDDEN, 0.2)
    case["conv3.weight"] = conv_weight(rng, FEATURES, T_HIDDEN, 0.3)
    case["conv3.bias"] = conv_bias(rng, FEATURES, 0.05)
    return case


def compute(torch, case):
    """Forward and backward in PyTorch; returns the tensors to write and the per-term gradient norms."""
    F = torch.nn.functional
    tensor = lambda v: torch.tensor(v, dtype=torch.float64)
    mean, std = (tensor(v).view(1, FEATURES, 1) for v in case["mean_std"])
    content = tensor(case["content"])
    style_clip = tensor(case["style_clip"]).unsqueeze(0)
    contacts = tensor(case["contacts"])
    bone_lengths = tensor(case["bone_lengths"])
    enc_w, enc_b = tensor(case["encoder.weight"]), tensor(case["encoder.bias"])
    params = {name: tensor(case[name]).requires_grad_(True)
              for name in ("conv1.weight", "conv1.bias", "conv2.weight", "conv2.bias", "conv3.weight", "conv3.bias")}
    relu_inputs, pool_pairs = [], []

    def relu(z):
        relu_inputs.append(z.detach())
        return torch.relu(z)

    def encode(x):
        if x.shape[2] % 2:
            x = torch.cat([x, x[:, :, -1:]], dim=2)
        z = F.conv1d(x, enc_w, enc_b, padding=WIDTH // 2)
        pool_pairs.append(z.detach())
        return relu(F.max_pool1d(z, 2))

    def transform(x):
        z = relu(F.conv1d(x, params["conv1.weight"], params["conv1.bias"], padding=WIDTH // 2))
        z = relu(F.conv1d(z, params["conv2.weight"], params["conv2.bias"], padding=WIDTH // 2))
        return x + F.conv1d(z, params["conv3.weight"], params["conv3.bias"], padding=WIDTH // 2)

    def gram(h):
        return torch.bmm(h, h.transpose(1, 2)) / h.shape[2]

    with torch.no_grad():
        content_hidden = encode(content)
        style_gram = gram(encode(style_clip))[0]
    y = transform(content)
    h = encode(y)

    world = y * std + mean  # de-normalised: cm, cm/frame, rad/frame
    joints = world[:, :63, :].reshape(WINDOWS, JOINTS, 3, FRAMES)
    terms = {"content": torch.mean((h - content_hidden) ** 2),
             "style": torch.mean((gram(h) - style_gram) ** 2)}
    turn = world[:, TURNING, :-1]
    cos_w, sin_w = torch.cos(turn), torch.sin(turn)
    foot_sum, labelled = 0.0, contacts[:, :, :-1].sum()
    for c, j in enumerate(CONTACT_JOINT):
        p, q = joints[:, j, :, :-1], joints[:, j, :, 1:]
        dx = world[:, SIDEWAYS, :-1] + cos_w * q[:, 0] + sin_w * q[:, 2] - p[:, 0]
        dy = q[:, 1] - p[:, 1]
        dz = world[:, FORWARD, :-1] - sin_w * q[:, 0] + cos_w * q[:, 2] - p[:, 2]
        foot_sum = foot_sum + (contacts[:, c, :-1] * (dx * dx + dy * dy + dz * dz)).sum()
    terms["foot"] = foot_sum / labelled
    children = list(range(1, JOINTS))
    lengths = (joints[:, children] - joints[:, [PARENT[c] for c in children]]).norm(dim=2)  # [B, 20, T]
    terms["bone"] = torch.mean((lengths - bone_lengths.unsqueeze(2)) ** 2)
    velocity_error = (y - content)[:, SIDEWAYS:, :] * std[:, SIDEWAYS:, :]
    terms["trajectory"] = (velocity_error ** 2).sum() / (WINDOWS * FRAMES)

    shares = {}
    for name, term in terms.items():
        grads = torch.autograd.grad(WEIGHTS[name] * term, list(params.values()), retain_graph=True)
        shares[name] = math.sqrt(sum(float((g ** 2).sum()) for g in grads))
    total = sum(WEIGHTS[name] * term for name, term in terms.items())
    total.backward()

    relu_margin = min(float(z.abs().min()) for z in relu_inputs)
    pool_margin = min(float((z[..., 0::2] - z[..., 1::2]).abs().min()) for z in pool_pairs)
    if relu_margin < KINK_MARGIN or pool_margin < KINK_MARGIN:
        raise SystemExit("dump_reference: a ReLU input or max-pool pair lies within %g of its kink "
                         "(relu %.3g, pool %.3g): change the seed" % (KINK_MARGIN, relu_margin, pool_margin))

    out = {"expected.content_hidden": content_hidden, "expected.style_gram": style_gram,
           "expected.output": y.detach(), "expected.output_hidden": h.detach()}
    for name, term in terms.items():
        out["expected.terms." + name] = term.detach()
    out["expected.terms.total"] = total.detach()
    for name, p in params.items():
        out["expected.grad.transformer." + name] = p.grad
    return out, shares, relu_margin, pool_margin, float(labelled)


def write_tensor(lines, name, value):
    """value: a nested list or a float64 tensor."""
    import torch
    t = value if isinstance(value, torch.Tensor) else torch.tensor(value, dtype=torch.float64)
    dims = list(t.shape)
    lines.append("tensor %s %d%s" % (name, len(dims), "".join(" %d" % d for d in dims)))
    rows = t.reshape(-1, dims[-1]) if dims else t.reshape(1, 1)
    for row in rows.tolist():
        lines.append(" ".join(repr(float(v)) for v in row))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", help="file to write (tests/data/nn_reference.txt)")
    args = parser.parse_args()
    try:
        import torch
    except ImportError:
        print("dump_reference: python3-torch is not installed "
              "(apt-get install python3-torch; run with /usr/bin/python3)")
        return 1
    torch.set_num_threads(1)
    case = make_case()
    expected, shares, relu_margin, pool_margin, labelled = compute(torch, case)
    total_share = sum(shares.values())

    lines = ["# MotionStyle nn reference (issue 14): written by tests/peer/dump_reference.py with PyTorch %s,"
             % torch.__version__,
             "# float64. Do not edit: regenerate with",
             "#   /usr/bin/python3 tests/peer/dump_reference.py tests/data/nn_reference.txt",
             "# Format and definitions: that script's docstring. Synthetic data only (no dataset).",
             "# Smallest |ReLU input| %.3g, smallest max-pool pair difference %.3g; %d labelled foot contacts." %
             (relu_margin, pool_margin, labelled),
             "# Gradient norm of each weighted term (share of their sum): " +
             ", ".join("%s %.3g (%.0f%%)" % (k, v, 100 * v / total_share) for k, v in shares.items())]
    config = {"windows": WINDOWS, "frames": FRAMES, "style_frames": STYLE_FRAMES, "features": FEATURES,
              "t_hidden": T_HIDDEN, "ae_hidden": AE_HIDDEN, "width": WIDTH, "residual": 1}
    for name, value in config.items():
        write_tensor(lines, "config." + name, float(value))
    for name, value in WEIGHTS.items():
        write_tensor(lines, "weights." + name, value)
    write_tensor(lines, "normalisation.mean", case["mean_std"][0])
    write_tensor(lines, "normalisation.std", case["mean_std"][1])
    for name in ("content", "contacts", "bone_lengths", "style_clip"):
        write_tensor(lines, "input." + name, case[name])
    write_tensor(lines, "loss_network.encoder.weight", case["encoder.weight"])
    write_tensor(lines, "loss_network.encoder.bias", case["encoder.bias"])
    for layer in ("conv1", "conv2", "conv3"):
        write_tensor(lines, "transformer.%s.weight" % layer, case[layer + ".weight"])
        write_tensor(lines, "transformer.%s.bias" % layer, case[layer + ".bias"])
    for name, value in expected.items():
        write_tensor(lines, name, value)
    with open(args.out, "w", encoding="utf-8", newline="\n") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(line for line in lines if line.startswith("#")))
    for name in ("content", "style", "foot", "bone", "trajectory", "total"):
        print("%-10s %.17g" % (name, float(expected["expected.terms." + name])))
    return 0


if __name__ == "__main__":
    sys.exit(main())
