#!/usr/bin/env python3
"""Mutation test of motionstyle-cli (issue 13): hundreds of damaged BVH and network files through info,
convert, cleanup and stylize. Every run must exit 0 or 2 (never 1, never a signal), finish within the
timeout (never hang), and leave no partial output: on failure the existing output file is unchanged
and no temporary is left beside it; on success the output reads back.

Usage: mutation_test.py CLI DATA_DIR [--bvh N] [--networks N] [--seed S] [--timeout SECONDS]
Deterministic for a given seed. Prints each finding with the command and keeps the mutant in a
folder it names; exits 1 if there is any.
"""
import argparse
import os
import random
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

EXTREME_NUMBERS = ["1e308", "-1e308", "1e309", "nan", "inf", "-inf", "0", "-0", "5e-324", "1e-320",
                   "99999999999999999999999", "0x10", "1e", "--1", "", "1.2.3", "\x00", "é"]


def bvh_mutants(text, rng, count):
    """Damaged copies of a BVH text: each mutant applies one to three random edits."""
    lines = text.split("\n")
    motion = next(i for i, line in enumerate(lines) if line.startswith("MOTION"))

    def edit(ls):
        kind = rng.randrange(10)
        i = rng.randrange(len(ls))
        if kind == 0:  # a number replaced by an extreme or malformed value
            words = ls[i].split(" ")
            w = rng.randrange(len(words))
            words[w] = rng.choice(EXTREME_NUMBERS)
            ls[i] = " ".join(words)
        elif kind == 1:
            del ls[i]
        elif kind == 2:
            ls.insert(i, ls[rng.randrange(len(ls))])
        elif kind == 3:  # the frame count or frame time
            j = motion + rng.choice([1, 2])
            if j < len(ls):
                head = ls[j].split(":")[0]
                ls[j] = head + ": " + rng.choice(EXTREME_NUMBERS + ["0", "1", "3", "100000000", "-5", "0.5"])
        elif kind == 4:  # a channel count
            hits = [k for k, l in enumerate(ls) if "CHANNELS" in l]
            if hits:
                k = rng.choice(hits)
                ls[k] = ls[k].replace("CHANNELS 3", "CHANNELS " + rng.choice(["0", "2", "4", "9", "-3", "3000000000"]), 1)
        elif kind == 5:  # braces and keywords
            ls[i] = ls[i].replace(rng.choice(["{", "}", "JOINT", "End Site", "ROOT", "OFFSET"]),
                                  rng.choice(["", "{", "}", "JOINT", "ROOT"]), 1)
        elif kind == 6:  # control and binary bytes
            pos = rng.randrange(len(ls[i]) + 1)
            ls[i] = ls[i][:pos] + "".join(chr(rng.choice([0, 7, 27, 127, 0xFF, 0x2028])) for _ in range(3)) + ls[i][pos:]
        elif kind == 7:  # a very long line
            ls[i] = ls[i] + " 1" * rng.choice([10, 1000, 100000])
        elif kind == 8:  # a joint name
            hits = [k for k, l in enumerate(ls) if l.strip().startswith("JOINT")]
            if hits:
                k = rng.choice(hits)
                ls[k] = ls[k].split("JOINT")[0] + "JOINT " + rng.choice(["", "Hips", "a b", "\x1b[31mred", "x" * 5000])
        else:
            ls[i] = ""
        return ls

    for n in range(count):
        ls = list(lines)
        for _ in range(rng.randint(1, 3)):
            ls = edit(ls)
        data = "\n".join(ls).encode("utf-8", "surrogatepass")
        if n % 10 == 9:  # truncation anywhere
            data = data[: rng.randrange(len(data) + 1)]
        yield data


def network_mutants(data, rng, count):
    """Damaged copies of a network file: byte flips with the CRC made valid again (so the parser's
    deeper checks are reached), extreme floats over stored numbers, truncations and appended junk."""
    for n in range(count):
        body = bytearray(data[:-4])
        kind = n % 4
        if kind == 0:
            for _ in range(rng.randint(1, 8)):
                body[rng.randrange(len(body))] = rng.randrange(256)
        elif kind == 1:
            value = rng.choice([1e308, -1e308, float("inf"), float("nan"), 1e-45, 0.0, 65504.0, 1e30])
            for _ in range(rng.randint(1, 4)):
                pos = rng.randrange(len(body) - 8)
                as_float = value if abs(value) < 3e38 or value != value or abs(value) == float("inf") else float("inf")
                body[pos:pos + 8] = struct.pack("<d", value) if rng.random() < 0.5 else struct.pack("<f", as_float) * 2
        elif kind == 2:
            pos = rng.randrange(len(body))
            body[pos:pos + 4] = struct.pack("<I", rng.choice([0, 1, 0xFFFFFFFF, 0x7FFFFFFF, 1 << 20]))
        else:
            yield bytes(data[: rng.randrange(len(data))]) if rng.random() < 0.5 else data + os.urandom(rng.randint(1, 64))
            continue
        yield bytes(body) + struct.pack("<I", zlib.crc32(bytes(body)) & 0xFFFFFFFF)


class Runner:
    def __init__(self, cli, work, timeout):
        self.cli, self.work, self.timeout = cli, work, timeout
        self.findings, self.runs = [], 0
        self.old_output = os.path.join(work, "old.bvh")

    def run(self, name, args, mutant, output=None):
        """Runs the CLI; checks the exit code, the time, and (with `output`) all-or-nothing writing."""
        self.runs += 1
        if output:
            shutil.copyfile(self.old_output, output)
        try:
            result = subprocess.run([self.cli] + args, capture_output=True, timeout=self.timeout)
            code, err = result.returncode, result.stderr[-400:].decode("utf-8", "replace")
        except subprocess.TimeoutExpired:
            code, err = "hang", ""
        problem = None
        if code == "hang":
            problem = "no answer within %d s" % self.timeout
        elif code < 0:
            problem = "killed by signal %d" % -code
        elif code not in (0, 2):
            problem = "exit %d: %s" % (code, err.strip())
        elif output:
            folder, base = os.path.split(output)
            if any(f.startswith("." + base + ".tmp-") for f in os.listdir(folder)):
                problem = "a temporary was left beside the output"
            elif code != 0 and not filecmp(output, self.old_output):
                problem = "failed (exit 2) but changed the existing output"
            elif code == 0 and subprocess.run([self.cli, "info", output], capture_output=True).returncode != 0:
                problem = "succeeded but its output does not read back"
        if problem:
            keep = os.path.join(self.work, "finding-%d" % len(self.findings))
            with open(keep, "wb") as f:
                f.write(mutant)
            self.findings.append("%s: %s\n  mutant kept as %s\n  command: %s" % (name, problem, keep, " ".join(args)))


def filecmp(a, b):
    with open(a, "rb") as fa, open(b, "rb") as fb:
        return fa.read() == fb.read()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("cli")
    parser.add_argument("data")
    parser.add_argument("--bvh", type=int, default=int(os.environ.get("MOTIONSTYLE_MUTANTS_BVH", 150)))
    parser.add_argument("--networks", type=int, default=int(os.environ.get("MOTIONSTYLE_MUTANTS_NETWORK", 100)))
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--timeout", type=int, default=60)
    options = parser.parse_args()
    rng = random.Random(options.seed)
    work = tempfile.mkdtemp(prefix="motionstyle-mutants-")
    keep_work = False
    try:
        # Seeds: the zombie clip cut to 60 frames, a tiny loss network and style network trained here.
        with open(os.path.join(options.data, "zombie.bvh"), encoding="utf-8") as f:
            lines = f.read().split("\n")
        frames_at = next(i for i, l in enumerate(lines) if l.startswith("Frames:"))
        seed_text = "\n".join(lines[:frames_at] + ["Frames: 60"] + lines[frames_at + 1: frames_at + 62]) + "\n"
        clip = os.path.join(work, "seed.bvh")
        with open(clip, "w", encoding="utf-8") as f:
            f.write(seed_text)
        shutil.copyfile(clip, os.path.join(work, "old.bvh"))
        tiny = ["--epochs", "1", "--hidden", "8", "--threads", "1"]
        ae, net = os.path.join(work, "ae.net"), os.path.join(work, "net.net")
        for args in (["train-loss-network", "--data", clip, "--out", ae] + tiny,
                     ["train-style", "--loss-network", ae, "--content", clip, "--style", clip, "--out", net] + tiny):
            setup = subprocess.run([options.cli] + args, capture_output=True)
            if setup.returncode != 0:
                print("setup failed:", " ".join(args), setup.stderr.decode(errors="replace"))
                return 1

        runner = Runner(options.cli, work, options.timeout)
        mutant_file, out = os.path.join(work, "mutant.bvh"), os.path.join(work, "out.bvh")
        metrics = os.path.join(work, "out.json")
        for n, mutant in enumerate(bvh_mutants(seed_text, rng, options.bvh)):
            with open(mutant_file, "wb") as f:
                f.write(mutant)
            runner.run("bvh %d info" % n, ["info", mutant_file, "--loss-network", ae], mutant)
            runner.run("bvh %d convert" % n, ["convert", mutant_file, out], mutant, out)
            runner.run("bvh %d cleanup" % n, ["cleanup", mutant_file, "--out", out, "--metrics", metrics], mutant, out)
            runner.run("bvh %d stylize" % n, ["stylize", "--net", net, mutant_file, "--out", out], mutant, out)
        with open(net, "rb") as f:
            network_bytes = f.read()
        mutant_net = os.path.join(work, "mutant.net")
        for n, mutant in enumerate(network_mutants(network_bytes, rng, options.networks)):
            with open(mutant_net, "wb") as f:
                f.write(mutant)
            runner.run("network %d info" % n, ["info", mutant_net], mutant)
            runner.run("network %d info --json" % n, ["info", "--json", mutant_net], mutant)
            runner.run("network %d stylize" % n, ["stylize", "--net", mutant_net, clip, "--out", out], mutant, out)
        print("%d runs on %d BVH and %d network mutants: %d finding(s)" %
              (runner.runs, options.bvh, options.networks, len(runner.findings)))
        for finding in runner.findings[:30]:
            print("FINDING " + finding)
        keep_work = bool(runner.findings)
        if keep_work:
            print("mutants kept in " + work)
        return 1 if runner.findings else 0
    finally:
        if not keep_work:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
