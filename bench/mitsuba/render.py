#!/usr/bin/env python3
"""Render a Mitsuba 3 XML scene (from bench/mitsuba/export.ts) to a linear PFM.

    python3 bench/mitsuba/render.py SCENE.xml --out OUT.pfm [--spp N | --time SECONDS]
        [--variant scalar_rgb] [--threads N] [--seed S]

Prints one JSON line: {"spp", "seconds", "variant", "threads", "passes",
"load_seconds", "cpu_seconds", "width", "height", "samples_per_second"}
(samples = spp * width * height, i.e. camera paths; cpu_seconds is the
process's CPU time while rendering, all threads: it tells a run slowed by other
load on the machine from a slow renderer).

Fixed spp (--spp, or the sample_count in the XML when neither option is given):
one mi.render call.

Equal time (--time T): progressive passes, each an independent mi.render with
its own seed (Mitsuba scales the seed by the pixel count in scalar mode, so
passes never share random streams), averaged with weights = their spp (the box
filter gives every pixel exactly spp samples per pass, so this is the exact
mean of all samples). The first pass is 1 spp and measures the rate; each
later pass is sized to take about half of the remaining time (so a bad rate
estimate cannot overshoot much), until not even one more spp fits. Nothing is
thrown away: every sample traced inside the budget is in the image. `seconds`
is the wall time of all passes (JIT compilation included for llvm variants);
scene loading is reported separately as `load_seconds`. Rendering stops short
of T by at most about one pass of the last size plus the time of 1 spp.

Output: PFM, little-endian (scale -1), rows bottom to top as the format
prescribes; mi.TensorXf rows are top to bottom, so they are written reversed.
This matches mi.Bitmap.write and the reference images in
test/fixtures/references (checked: their last stored row is the image's top).
"""
import argparse
import json
import struct
import sys
import time


def write_pfm(path, data, width, height):
    """data: float32 bytes, rows top to bottom, 3 channels."""
    row = width * 3 * 4
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (width, height))
        if sys.byteorder != "little":
            raise RuntimeError("write_pfm assumes a little-endian host")
        for y in range(height - 1, -1, -1):
            f.write(data[y * row:(y + 1) * row])


def tensor_bytes(mi, img):
    """Float32 bytes of an (H, W, 3) tensor, on any variant, without numpy."""
    if hasattr(img, "memview"):
        try:
            return bytes(img.memview())
        except Exception:  # JIT tensors: fall through to a copy
            pass
    values = list(img.array)
    return struct.pack("<%df" % len(values), *values)


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("scene")
    p.add_argument("--out", required=True)
    g = p.add_mutually_exclusive_group()
    g.add_argument("--spp", type=int, help="fixed samples per pixel")
    g.add_argument("--time", type=float, help="wall-time budget in seconds")
    p.add_argument("--variant", default="scalar_rgb")
    p.add_argument("--threads", type=int, default=0, help="0 = all cores")
    p.add_argument("--seed", type=int, default=0,
                   help="render seed of the first pass (combined with the XML sampler seed)")
    return p.parse_args(argv)


def sync(dr, value):
    dr.eval(value)
    dr.sync_thread()


def render_fixed(mi, dr, scene, spp, seed):
    start = time.perf_counter()
    img = mi.render(scene, spp=spp, seed=seed)
    sync(dr, img)
    return img, spp, time.perf_counter() - start, 1


def render_timed(mi, dr, scene, budget, seed):
    start = time.perf_counter()
    total, acc, passes, n = 0, None, 0, 1
    rate = None  # spp per second, from the most recent pass
    while True:
        t0 = time.perf_counter()
        img = mi.render(scene, spp=n, seed=seed + passes)
        acc = img * n if acc is None else acc + img * n
        sync(dr, acc)
        dt = time.perf_counter() - t0
        total += n
        passes += 1
        # The first pass of a JIT variant includes compilation: do not trust its rate.
        if passes > 1 or not dr.is_jit_v(mi.Float):
            rate = n / max(dt, 1e-6)
        remaining = budget - (time.perf_counter() - start)
        if rate is None:
            n = 1
            if remaining <= 0:
                break
            continue
        fits = rate * remaining
        if fits < 1:
            break
        n = max(1, int(fits / 2)) if fits >= 4 else int(fits)
    return acc / total, total, time.perf_counter() - start, passes


def main(argv):
    args = parse_args(argv)
    import drjit as dr
    import mitsuba as mi

    mi.set_variant(args.variant)
    # Negative samples (an environment map's negative texels) are legitimate
    # here; Mitsuba warns about each one, which would flood the output.
    mi.set_log_level(mi.LogLevel.Error)
    if args.threads > 0:
        dr.set_thread_count(args.threads)
    threads = dr.thread_count()

    t0 = time.perf_counter()
    scene = mi.load_file(args.scene)
    load_seconds = time.perf_counter() - t0

    cpu0 = time.process_time()
    if args.time is not None:
        img, spp, seconds, passes = render_timed(mi, dr, scene, args.time, args.seed)
    else:
        spp = args.spp or scene.sensors()[0].sampler().sample_count()
        img, spp, seconds, passes = render_fixed(mi, dr, scene, spp, args.seed)

    cpu_seconds = time.process_time() - cpu0
    height, width = img.shape[0], img.shape[1]
    write_pfm(args.out, tensor_bytes(mi, img), width, height)
    print(json.dumps({
        "spp": spp,
        "seconds": round(seconds, 4),
        "variant": args.variant,
        "threads": threads,
        "passes": passes,
        "load_seconds": round(load_seconds, 4),
        "cpu_seconds": round(cpu_seconds, 4),
        "width": width,
        "height": height,
        "samples_per_second": round(spp * width * height / max(seconds, 1e-9)),
    }))


if __name__ == "__main__":
    main(sys.argv[1:])
