#!/usr/bin/env python3
"""Memory of `motionstyle-cli cleanup` on long clips (issue 13): how much the peak resident memory grows
per frame of the clip, measured between two lengths of the same motion so that the program's fixed
cost (code, libraries, solver state) cancels out. The goal is at most 2 KB per frame; before the
clean-up was streamed a block of frames at a time it was about 10 KB.

The clips are the committed CMU fixture (31 joints, 96 channels, 120 fps) played forwards and backwards
until long enough. `--time-limit` keeps the test short: past the limit the frames keep their warm
start, but every frame still goes the whole way through the pipeline (targets, locks, cost evaluation,
the writer, the metrics), which is what holds memory; the solver's own state does not grow with the clip.

Usage: cli_memory_test.py CLI DATA_DIR [--frames N1,N2] [--limit-kb-per-frame K]
Prints both peaks and the growth per frame; exits 1 when the growth is over the limit or a run fails.
"""
import argparse
import os
import subprocess
import sys
import tempfile


def long_clip(fixture_text, frames):
    head, motion = fixture_text.split("MOTION", 1)
    lines = [line for line in motion.strip().split("\n")[2:] if line.strip()]
    cycle = lines + lines[-2:0:-1]  # forwards, then backwards: no jump where it repeats
    body = [cycle[i % len(cycle)] for i in range(frames)]
    frame_time = motion.strip().split("\n")[1]
    return head + "MOTION\nFrames: %d\n%s\n%s\n" % (frames, frame_time, "\n".join(body))


def peak_rss_bytes(command):
    """Runs `command`, returns (exit code, output, its own peak resident set in bytes)."""
    with tempfile.TemporaryFile() as output:
        process = subprocess.Popen(command, stdout=output, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(process.pid, 0)
        process.returncode = os.waitstatus_to_exitcode(status)
        output.seek(0)
        return process.returncode, output.read().decode(errors="replace"), usage.ru_maxrss * 1024


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("cli")
    parser.add_argument("data_dir")
    parser.add_argument("--frames", default="20000,60000")
    parser.add_argument("--limit-kb-per-frame", type=float, default=2.0)
    parser.add_argument("--time-limit", default="0.5")
    args = parser.parse_args()
    lengths = [int(n) for n in args.frames.split(",")]
    with open(os.path.join(args.data_dir, "cmu_131_01.bvh")) as fixture:
        text = fixture.read()

    peaks = []
    with tempfile.TemporaryDirectory() as folder:
        for frames in lengths:
            clip = os.path.join(folder, "long_%d.bvh" % frames)
            with open(clip, "w") as out:
                out.write(long_clip(text, frames))
            result = os.path.join(folder, "out_%d.bvh" % frames)
            code, log, peak = peak_rss_bytes([args.cli, "cleanup", clip, "--out", result, "--time-limit", args.time_limit])
            if code != 0 or ("wrote %s: %d frames" % (result, frames)) not in log:
                print("FAIL: cleanup of %d frames exited %d:\n%s" % (frames, code, log[:2000]))
                return 1
            print("%7d frames: peak %.1f MB" % (frames, peak / 1e6))
            peaks.append(peak)
            os.remove(clip)
            os.remove(result)

    growth = (peaks[-1] - peaks[0]) / float(lengths[-1] - lengths[0])
    print("growth: %.2f KB per frame (limit %.2f KB)" % (growth / 1024.0, args.limit_kb_per_frame))
    if growth > args.limit_kb_per_frame * 1024.0:
        print("FAIL: memory grows by more than %.2f KB per frame" % args.limit_kb_per_frame)
        return 1
    print("OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
