#!/usr/bin/env python3
"""Sweep of scripts/wang-tiles-experiment.py scored by `stex compare`: one table row per setting.

    scripts/wang-tiles-sweep.py STEX OUTDIR PHOTO T,T.. C,C.. K,K.. [--band B] [--seed S] [--separation F] [--control]

Writes OUTDIR/NAME_T{T}_C{C}_k{K}.png (and .txt: the generator's and compare's output) and
prints a Markdown table: structure distance and its parts, radial log-PSD dB (mean of R, G, B),
2D log-PSD dB, worst W1/sigma, false colour %, tile-set and samples bytes, distinct fraction.
"""
import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def nums(line):
    return [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?(?:e-?\d+)?", line)]


def parse_compare(text):
    r = {}
    for line in text.splitlines():
        s = line.strip()
        if s.startswith("W1/sigma"):
            r["w1"] = max(nums(s)[1:])  # skip the '1' in 'W1'
        elif s.startswith("log-PSD dB"):
            v = nums(s)
            r["radial"] = sum(v) / len(v)
        elif s.startswith("2D log-PSD distance"):
            v = nums(s.split(":", 1)[1])
            r["psd2d"] = v[0]
        elif s.startswith("false-colour rate"):
            r["fc"] = nums(s.split(":", 1)[1])[0]
        elif s.startswith("structure distance"):
            r["sd"] = nums(s.split(":", 1)[1])[0]
        elif s.startswith("marginals"):
            v = nums(s)
            r["parts"] = v
        elif s.startswith("gradient orientation W1"):
            r["orient"] = nums(s.split(":", 1)[1])[0]
        elif s.startswith("gradient magnitude W1"):
            r["gmag"] = nums(s.split(":", 1)[1])[0]
    return r


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("stex")
    ap.add_argument("outdir")
    ap.add_argument("photo")
    ap.add_argument("Ts")
    ap.add_argument("Cs")
    ap.add_argument("ks")
    ap.add_argument("--band", default="0.25")
    ap.add_argument("--seed", default="1")
    ap.add_argument("--separation", default="0")
    ap.add_argument("--control", action="store_true", help="pass --control (whole samples per cell)")
    a = ap.parse_args()
    name = os.path.splitext(os.path.basename(a.photo))[0]
    os.makedirs(a.outdir, exist_ok=True)
    print("| photo | T | C | k | structure | marg / autocorr / cross-or / cross-sc / phase | radial dB | 2D dB "
          "| worst W1/σ | false colour % | orient ° | \\|∇\\| W1 | tile-set bytes | samples bytes | distinct |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for T in a.Ts.split(","):
        for C in a.Cs.split(","):
            for k in a.ks.split(","):
                out = os.path.join(a.outdir, f"{name}_T{T}_C{C}_k{k}.png")
                gen = subprocess.run([sys.executable, os.path.join(HERE, "wang-tiles-experiment.py"), a.photo, out,
                                      "-T", T, "-C", C, "-k", k, "--band", a.band, "--seed", a.seed,
                                      "--separation", a.separation] + (["--control"] if a.control else []),
                                     capture_output=True, text=True)
                if gen.returncode:
                    print(f"| {name} | {T} | {C} | {k} | failed: {gen.stderr.strip()[-200:]} |")
                    continue
                cmp_ = subprocess.run([a.stex, "compare", a.photo, out], capture_output=True, text=True)
                with open(out[:-4] + ".txt", "w") as f:
                    f.write(gen.stdout + "\n" + cmp_.stdout + cmp_.stderr)
                g = gen.stdout
                tb = int(re.search(r"tile-set bytes \(8-bit RGB\) (\d+)", g).group(1))
                sb = int(re.search(r"\) (\d+)\n", g[g.index("samples bytes"):] + "\n").group(1))
                dist = float(re.search(r"px = ([\d.]+) of the synthesis", g).group(1))
                r = parse_compare(cmp_.stdout)
                parts = " / ".join(f"{p:.3f}" for p in r.get("parts", []))
                print(f"| {name} | {T} | {C} | {k} | {r.get('sd', float('nan')):.3f} | {parts} | {r['radial']:.2f} "
                      f"| {r['psd2d']:.2f} | {r['w1']:.3f} | {r['fc']:.2f} | {r.get('orient', float('nan')):.2f} "
                      f"| {r.get('gmag', float('nan')):.3f} | {tb} | {sb} | {dist:.3f} |", flush=True)


if __name__ == "__main__":
    main()
