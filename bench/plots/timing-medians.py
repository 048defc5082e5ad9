#!/usr/bin/env python3
"""Frame-time medians of repeated holotrace-bench-quality runs, joined with the PSNRs of a quality run.

Timing runs (--json of `holotrace-bench-quality ... --ref-spp 2`) are noisy on a shared 2-core host, so every point's
frame time is compared with the cheapest vendor-lerp quilt's *in the same run*, and the median of those same-run
ratios is reported (with their range). Frames are deterministic (bit-identical from run to run), so their PSNR is taken
from the quality CSVs (--psnr, measured against a converged reference). The equal-time gain is read off the Pareto
front of the adaptive and direct points, interpolated in log2(time) at ratio 1, as holotrace-bench-quality does.

holotrace-bench-quality --runs N now does the same within one process (bench/quality_points.cpp); this script
stays for timing runs made as separate processes (docs/bench/equal_time*/).

Usage: timing-medians.py --psnr quality_adaptive.csv[,more.csv] run1.json run2.json ...
Standard library only (Debian's python3).
"""
import argparse
import json
import math
import statistics
import sys


def point_key(p):
    return (p["path"], p["spp"], p["refine_spp"], round(p["refine_contrast"], 3))


def label(key):
    path, spp, refine, contrast = key
    if path == "adaptive":
        return f"{spp} + {refine} at {contrast:.2f}"
    return f"{path} spp {spp}"


def load_psnr(paths):
    table = {}
    for path in paths:
        with open(path) as f:
            header = f.readline().strip().split(",")
            for line in f:
                row = dict(zip(header, line.strip().split(",")))
                if row["path"] == "quilt":
                    key = (row["display"], "quilt", int(row["spp"]), row["quilt"], row["filter"])
                else:
                    key = (row["display"], row["path"], int(row["spp"]), int(row["refine_spp"]),
                           round(float(row["refine_contrast"]), 3))
                table[key] = float(row["psnr_corrected_db"])
    return table


def pareto(points):
    """Points (ratio, psnr) not beaten by a faster-or-equal point of higher PSNR, by time."""
    front = []
    for ratio, psnr in sorted(points):
        if not front or psnr > front[-1][1]:
            front.append((ratio, psnr))
    return front


def psnr_at(front, ratio):
    for (r0, p0), (r1, p1) in zip(front, front[1:]):
        if r0 <= ratio <= r1:
            w = (math.log2(ratio) - math.log2(r0)) / (math.log2(r1) - math.log2(r0))
            return p0 + w * (p1 - p0)
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--psnr", required=True, help="comma-separated quality CSVs (holotrace-bench-quality --csv)")
    parser.add_argument("runs", nargs="+", help="timing runs (holotrace-bench-quality --json)")
    args = parser.parse_args()
    psnr = load_psnr(args.psnr.split(","))
    runs = []
    for path in args.runs:
        with open(path) as f:
            runs.append(json.load(f))
    for d, display in enumerate(runs[0]["displays"]):
        name = display["display"]
        times, ratios, quilt_ms, quilt_key = {}, {}, [], None
        per_run = []  # each run's own (ratio, key) points
        for run in runs:
            disp = run["displays"][d]
            assert disp["display"] == name, f"runs list their displays in different orders ({path})"
            quilt = [p for p in disp["points"] if p["path"] == "quilt" and p["filter"] == "vendor-lerp"]
            cheapest = min(quilt, key=lambda p: p["frame_ms"])
            quilt_key = (name, "quilt", cheapest["spp"], cheapest["quilt"], "vendor-lerp")
            quilt_ms.append(cheapest["frame_ms"])
            per_run.append([])
            for p in disp["points"]:
                if p["path"] == "quilt":
                    continue
                times.setdefault(point_key(p), []).append(p["frame_ms"])
                ratios.setdefault(point_key(p), []).append(p["frame_ms"] / cheapest["frame_ms"])
                per_run[-1].append((p["frame_ms"] / cheapest["frame_ms"], point_key(p)))
        quilt_psnr = psnr.get(quilt_key)
        print(f"\n{name}: {len(runs)} runs; quilt {quilt_key[3]} spp {quilt_key[2]} vendor-lerp median "
              f"{statistics.median(quilt_ms):.0f} ms, PSNR {quilt_psnr if quilt_psnr else 'n/a'}")
        print(f"  {'point':<22} {'median ms':>10} {'time/quilt':>11} {'range':>13} {'PSNR':>7} {'vs quilt':>9}")
        front_points = []
        for key in sorted(times, key=lambda k: statistics.median(ratios[k])):
            r = statistics.median(ratios[key])
            value = psnr.get((name,) + key)
            if value is not None:
                front_points.append((r, value))
            gain = f"{value - quilt_psnr:+.2f}" if value is not None and quilt_psnr else "n/a"
            print(f"  {label(key):<22} {statistics.median(times[key]):>10.0f} {r:>11.3f} "
                  f"{min(ratios[key]):>6.3f}-{max(ratios[key]):.3f} {value if value else float('nan'):>7.2f} {gain:>9}")
        at_quilt = psnr_at(pareto(front_points), 1.0)
        if at_quilt is not None and quilt_psnr:
            print(f"  at the quilt's time (Pareto front, log2-time interpolation): {at_quilt:.2f} dB, "
                  f"{at_quilt - quilt_psnr:+.2f} dB vs the quilt")
        else:
            print("  at the quilt's time: outside the measured points")
        if quilt_psnr:
            gains = []
            for points in per_run:
                value = psnr_at(pareto([(r, psnr[(name,) + k]) for r, k in points if (name,) + k in psnr]), 1.0)
                gains.append("n/a" if value is None else f"{value - quilt_psnr:+.2f}")
            print(f"  each run on its own: {', '.join(gains)} dB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
