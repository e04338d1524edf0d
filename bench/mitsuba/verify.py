#!/usr/bin/env python3
"""Check the Mitsuba exporter against the reference images.

    python3 bench/mitsuba/verify.py [--spp 256] [--scenes glossy,seed] [--keep DIR]

For each test/fixtures/scenes/NAME.json with a references/NAME.pfm: export it
with bench/mitsuba/export.ts, render it twice with bench/mitsuba/render.py
(spp/2 each, different seeds), average, and compare with the reference:

- relMSE   = mean over pixels and channels of (x - ref)^2 / (ref^2 + 0.01)
- noise    = the relMSE that Mitsuba's own noise at this spp explains:
             mean of ((a - b)^2 / 4) / (ref^2 + 0.01), a and b the two halves
             (a - b is pure noise; Var(x) = Var(a - b) / 4).
- ratio    = relMSE / noise. The reference's own noise (16384 spp) adds to
             relMSE, so agreement within noise gives ratio ~ expect =
             1 + spp / 16384; a systematic error gives a ratio well above it.
- worst block: the largest |mean(x) - mean(ref)| / mean(ref) over 16x16 blocks
  (mean of the three channels; blocks whose reference mean is below 0.01 are
  skipped as relative error is meaningless there).
- max |z|: the largest block difference in units of its standard error,
  sqrt(var(a - b) / (4 N) * (1 + spp / 16384)) per channel (our noise and the
  reference's); with ~600 block-channels, up to ~4 is expected from Gaussian
  noise, and 'z>4' counts the ones beyond. The standard error is floored at
  1e-4 of the block mean: noise-free blocks (the sky) still differ by the
  float rounding of the reference's sums (~3e-5).
  Caveat: where light arrives by rare paths (mirrors.json: the light seen in
  a mirror from the diffuse ground) the noise is heavily skewed; at low spp a
  block that caught none of the rare paths sits a few sigma low with an
  underestimated standard error (mirrors: max |z| 6.5 at 256 spp, 3.8 at
  4096 spp). So z only fails the check beyond 8; between 4 and 8 the row is
  marked 'check': re-run that scene with more --spp.
Exits non-zero if a scene's ratio exceeds 1.5 x expect or max |z| exceeds 8.
"""
import argparse
import array
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SCENES = os.path.join(ROOT, "test", "fixtures", "scenes")
REFS = os.path.join(ROOT, "test", "fixtures", "references")
REFERENCE_SPP = 16384
BLOCK = 16


def read_pfm(path):
    """(width, height, rows top to bottom as one float array of RGB)."""
    with open(path, "rb") as f:
        data = f.read()
    magic, dims, scale, body = data.split(b"\n", 3)
    if magic != b"PF":
        raise ValueError(f"{path}: not an RGB PFM")
    width, height = map(int, dims.split())
    values = array.array("f")
    values.frombytes(body[: width * height * 12])
    if (float(scale) < 0) != (sys.byteorder == "little"):
        values.byteswap()
    row = width * 3
    top_down = array.array("f")
    for y in range(height - 1, -1, -1):  # PFM stores the bottom row first
        top_down.extend(values[y * row:(y + 1) * row])
    return width, height, top_down


def run(cmd):
    out = subprocess.run(cmd, check=True, capture_output=True, text=True, cwd=ROOT)
    return out.stdout


def render(xml, out, spp, seed, threads):
    cmd = [sys.executable, os.path.join(ROOT, "bench/mitsuba/render.py"), xml, "--out", out,
           "--spp", str(spp), "--seed", str(seed)]
    if threads:
        cmd += ["--threads", str(threads)]
    return json.loads(run(cmd).strip().splitlines()[-1])


def compare(width, height, a, b, ref, spp):
    rel_mse = noise = 0.0
    n = len(ref)
    for i in range(n):
        r, x = ref[i], 0.5 * (a[i] + b[i])
        w = 1.0 / (r * r + 0.01)
        rel_mse += (x - r) ** 2 * w
        noise += 0.25 * (a[i] - b[i]) ** 2 * w
    worst, max_z, over4, blocks = 0.0, 0.0, 0, 0
    for by in range(0, height, BLOCK):
        for bx in range(0, width, BLOCK):
            s_x, s_r, s_d, s_d2, count = [0.0] * 3, [0.0] * 3, [0.0] * 3, [0.0] * 3, 0
            for y in range(by, min(by + BLOCK, height)):
                base = y * width * 3
                for x in range(bx, min(bx + BLOCK, width)):
                    i = base + x * 3
                    count += 1
                    for c in range(3):
                        d = a[i + c] - b[i + c]
                        s_x[c] += 0.5 * (a[i + c] + b[i + c])
                        s_r[c] += ref[i + c]
                        s_d[c] += d
                        s_d2[c] += d * d
            blocks += 1
            mean_x, mean_r = sum(s_x) / (3 * count), sum(s_r) / (3 * count)
            if mean_r >= 0.01:
                worst = max(worst, abs(mean_x - mean_r) / mean_r)
            for c in range(3):
                var_d = max(s_d2[c] / count - (s_d[c] / count) ** 2, 0.0)
                # Floor: noise-free pixels (the sky) still differ by float
                # rounding of the reference's 16384-sample sums (~3e-5).
                var_mean = var_d / (4 * count) * (1 + spp / REFERENCE_SPP)
                se = max(math.sqrt(var_mean), 1e-4 * abs(s_r[c]) / count, 1e-7)
                z = abs(s_x[c] - s_r[c]) / count / se
                max_z = max(max_z, z)
                over4 += z > 4
    return {"relMSE": rel_mse / n, "noise": noise / n, "worst_block": worst,
            "max_z": max_z, "z_over_4": over4, "blocks": blocks}


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--spp", type=int, default=256, help="total spp (two halves)")
    p.add_argument("--scenes", help="comma-separated names (default: all with a reference)")
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--keep", help="directory for the XML and PFM files")
    args = p.parse_args()

    names = sorted(f[:-5] for f in os.listdir(SCENES) if f.endswith(".json")
                   and os.path.exists(os.path.join(REFS, f[:-5] + ".pfm")))
    if args.scenes:
        names = [n for n in names if n in args.scenes.split(",")]
    work = args.keep or tempfile.mkdtemp(prefix="mitsuba-verify-")
    os.makedirs(work, exist_ok=True)
    half = max(1, args.spp // 2)

    header = f"{'scene':<12} {'size':>8} {'spp':>5} {'relMSE':>9} {'noise':>9} {'ratio':>6} {'expect':>6} " \
             f"{'worst blk':>9} {'max|z|':>7} {'z>4':>7} {'Msamples/s':>10}"
    print(header)
    print("-" * len(header))
    failed = False
    for name in names:
        xml = os.path.join(work, name + ".xml")
        run(["npx", "tsx", "bench/mitsuba/export.ts", os.path.join(SCENES, name + ".json"), xml,
             "--spp", str(half)])
        pa, pb = os.path.join(work, name + ".a.pfm"), os.path.join(work, name + ".b.pfm")
        ra = render(xml, pa, half, 1, args.threads)
        rb = render(xml, pb, half, 2, args.threads)
        w, h, a = read_pfm(pa)
        _, _, b = read_pfm(pb)
        rw, rh, ref = read_pfm(os.path.join(REFS, name + ".pfm"))
        if (w, h) != (rw, rh):
            raise SystemExit(f"{name}: rendered {w}x{h}, reference is {rw}x{rh}")
        m = compare(w, h, a, b, ref, 2 * half)
        ratio = m["relMSE"] / m["noise"] if m["noise"] > 0 else (1.0 if m["relMSE"] < 1e-10 else math.inf)
        rate = (ra["spp"] + rb["spp"]) * w * h / (ra["seconds"] + rb["seconds"]) / 1e6
        expect = 1 + 2 * half / REFERENCE_SPP
        bad = ratio > 1.5 * expect or m["max_z"] > 8
        mark = "  FAIL" if bad else "  check" if m["max_z"] > 4 else ""
        failed |= bad
        print(f"{name:<12} {f'{w}x{h}':>8} {2 * half:>5} {m['relMSE']:>9.2e} {m['noise']:>9.2e} "
              f"{ratio:>6.2f} {expect:>6.2f} {100 * m['worst_block']:>8.2f}% {m['max_z']:>7.2f} "
              f"{m['z_over_4']:>3}/{3 * m['blocks']:<3} {rate:>10.2f}{mark}")
    print(f"(files in {work})")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
