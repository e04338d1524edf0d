#!/usr/bin/env python3
"""Writes the small environment-map fixtures of test/unit/envmap-decode.test.ts.

One image, given by a formula that the test evaluates too (gradient(x, y, c)
below), written as Radiance .hdr (flat and RLE scanlines, by the writer
below: Bruce Walter's rgbe.c conversion) and as OpenEXR in every
compression the decoder is tested on, half and float (OpenEXR's own Python
bindings: pip install OpenEXR numpy).

Run from the repository root: python3 scripts/make-envmap-fixtures.py
"""
import os

import numpy as np
import OpenEXR

OUT = 'test/fixtures/envmaps/gradient'
WIDTH, HEIGHT = 24, 12


def gradient(x, y, c):
    """Radiance of texel (x, y) (row 0 on top), channel c; asymmetric in x and y so flips show."""
    if 4 <= x < 12 and 3 <= y < 6:  # a constant block: RLE runs
        return [5.0, 2.5, 1.25][c]
    return 2.0 ** ((x - 10) / 2.5) * (1 + y / 4) * (c + 1) / 3


def image():
    return np.array([[[gradient(x, y, c) for c in range(3)] for x in range(WIDTH)] for y in range(HEIGHT)])


def rgbe_bytes(rgb):
    v = max(rgb)
    if v < 1e-32:
        return bytes(4)
    mantissa, exponent = np.frexp(v)
    scale = mantissa * 256.0 / v
    return bytes([int(rgb[0] * scale), int(rgb[1] * scale), int(rgb[2] * scale), int(exponent) + 128])


def rle_plane(plane):
    """New-style RLE of one channel plane: runs of 4+ equal bytes, literal dumps between."""
    out = bytearray()
    i = 0
    while i < len(plane):
        run = 1
        while i + run < len(plane) and run < 127 and plane[i + run] == plane[i]:
            run += 1
        if run >= 4:
            out += bytes([128 + run, plane[i]])
            i += run
            continue
        start = i
        while i < len(plane) and i - start < 128:
            ahead = plane[i:i + 4]
            if len(ahead) == 4 and len(set(ahead)) == 1:
                break
            i += 1
        out += bytes([i - start]) + bytes(plane[start:i])
    return bytes(out)


def write_hdr(path, pixels, rle):
    with open(path, 'wb') as f:
        f.write(b'#?RADIANCE\n# envmap fixture\nFORMAT=32-bit_rle_rgbe\n\n')
        f.write(f'-Y {HEIGHT} +X {WIDTH}\n'.encode())
        for row in pixels:
            texels = [rgbe_bytes(p) for p in row]
            if not rle:
                f.write(b''.join(texels))
                continue
            f.write(bytes([2, 2, WIDTH >> 8, WIDTH & 255]))
            for c in range(4):
                f.write(rle_plane(bytes(t[c] for t in texels)))


def write_exr(path, pixels, dtype, compression):
    header = {'compression': compression, 'type': OpenEXR.scanlineimage}
    OpenEXR.File(header, {'RGB': pixels.astype(dtype)}).write(path)


def main():
    pixels = image()
    write_hdr(f'{OUT}-flat.hdr', pixels, rle=False)
    write_hdr(f'{OUT}-rle.hdr', pixels, rle=True)
    for name, compression in [('none', OpenEXR.NO_COMPRESSION), ('zip', OpenEXR.ZIP_COMPRESSION),
                              ('zips', OpenEXR.ZIPS_COMPRESSION), ('piz', OpenEXR.PIZ_COMPRESSION),
                              ('rle', OpenEXR.RLE_COMPRESSION)]:
        write_exr(f'{OUT}-half-{name}.exr', pixels, np.float16, compression)
        write_exr(f'{OUT}-float-{name}.exr', pixels, np.float32, compression)
    # Lossy (DCT) compressions: half channels only.
    write_exr(f'{OUT}-half-dwaa.exr', pixels, np.float16, OpenEXR.DWAA_COMPRESSION)
    write_exr(f'{OUT}-half-dwab.exr', pixels, np.float16, OpenEXR.DWAB_COMPRESSION)
    # What OpenEXR itself decodes from the lossy files (float32 RGB, rows from the top).
    for name in ['dwaa', 'dwab']:
        decoded = OpenEXR.File(f'{OUT}-half-{name}.exr').channels()['RGB'].pixels
        decoded.astype('<f4').tofile(f'{OUT}-half-{name}.openexr.f32')
    for f in sorted(os.listdir(os.path.dirname(OUT))):
        if f.startswith('gradient'):
            print(f, os.path.getsize(os.path.join(os.path.dirname(OUT), f)))


if __name__ == '__main__':
    main()
