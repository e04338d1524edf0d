#!/usr/bin/env python3
"""Writes test/fixtures/bitmap-lookups/: a tiny 8-bit RGBA PNG and Mitsuba's
`bitmap` texture evaluated on it (lookups.json), the reference of
src/scene/texture/bitmapLookup.test.ts and of the GLSL texture kernel test.

Mitsuba 3.9.1, scalar_rgb, `bitmap` at the contract's settings (bilinear,
repeat, default format). Four groups of lookups:
- srgb: the colour as a colour input reads it (raw=false, eval);
- raw: RGB as stored (raw=true, eval);
- channel: one channel as a scalar input reads it. Mitsuba's bitmap drops
  alpha and its eval_1 of an RGB image is the luminance, so it cannot pick a
  channel: each channel is written as its own grey PNG (the contract's
  reference baking) and read with raw=true, eval_1;
- transform: srgb through `to_uv` = translate(offset) * rotate(-rotation) *
  scale(scale), which is the contract's uv transform (checked below against
  the contract's formula evaluated here and the plain texture at the
  transformed point, and against the XML form the exporter writes).

The uv of every lookup is stored as the float32 value Mitsuba evaluated.
See test/fixtures/bitmap-lookups/README.md for what bitmap.cpp does.

Run from the repository root: python3 scripts/make-bitmap-lookups.py
"""
import json
import math
import os
import struct
import zlib

import mitsuba as mi

mi.set_variant('scalar_rgb')

OUT = 'test/fixtures/bitmap-lookups'
WIDTH, HEIGHT = 5, 3
CHANNELS = 'rgba'


def texel(x, y, c):
    """Byte of texel (x, y) (row 0 on top), channel c: distinct, asymmetric in x and y, some in sRGB's linear segment."""
    return (7 + 53 * x + 89 * y + 61 * c + 17 * x * y * (c + 1)) % 256


def rgba_rows():
    return [[texel(x, y, c) for x in range(WIDTH) for c in range(4)] for y in range(HEIGHT)]


def write_png(path, rows, width, height, colour_type):
    """8-bit PNG, filter 0 on every row, no gAMA/sRGB chunks (Mitsuba then assumes sRGB)."""
    def chunk(kind, data):
        return struct.pack('>I', len(data)) + kind + data + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)
    header = struct.pack('>IIBBBBB', width, height, 8, colour_type, 0, 0, 0)
    raw = b''.join(b'\x00' + bytes(row) for row in rows)
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', header) + chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b''))


def f32(x):
    return struct.unpack('<f', struct.pack('<f', x))[0]


# Texel centres, interior points, the edges and corners (within half a texel
# of an edge the filter wraps), negative and > 1 coordinates, large ones.
UVS = [
    (0.1, 1 / 6), (0.5, 0.5), (0.9, 5 / 6), (0.3, 0.5),
    (0.37, 0.61), (0.123, 0.456), (0.71, 0.29), (0.55, 0.95),
    (0.0, 0.0), (1.0, 1.0), (0.0, 0.5), (0.5, 0.0), (1.0, 0.5), (0.5, 1.0), (0.04, 0.08), (0.97, 0.99),
    (-0.3, -0.7), (-1.05, 0.2), (-0.02, 1.03), (1.3, 2.7), (2.0, -3.0),
    (37.3, -12.85), (37.3, 37.3), (-101.77, 64.123),
]

TRANSFORMS = [
    {'offset': [0.25, -0.4], 'scale': [2.0, 3.0], 'rotation': 30.0},
    {'offset': [-1.3, 0.7], 'scale': [0.6, -1.7], 'rotation': -127.5},
]
TRANSFORM_UVS = [(0.37, 0.61), (0.0, 0.0), (0.9, 0.1), (-0.45, 1.8), (3.2, -2.6)]


def mitsuba_to_uv(t):
    return mi.ScalarTransform3f().translate(t['offset']).rotate(-t['rotation']).scale(t['scale'])


def xml_to_uv(t):
    """The same transform as Mitsuba XML (each element left-multiplies the ones above)."""
    (ox, oy), (sx, sy) = t['offset'], t['scale']
    return (f'<transform name="to_uv"><scale x="{sx!r}" y="{sy!r}"/>'
            f'<rotate z="1" angle="{-t["rotation"]!r}"/><translate x="{ox!r}" y="{oy!r}"/></transform>')


def contract_uv(t, u, v):
    """The scene format's uv transform, in double precision."""
    (ox, oy), (sx, sy), r = t['offset'], t['scale'], math.radians(t['rotation'])
    return (ox + math.cos(r) * sx * u + math.sin(r) * sy * v,
            oy - math.sin(r) * sx * u + math.cos(r) * sy * v)


def bitmap(filename, raw, to_uv=None):
    desc = {'type': 'bitmap', 'filename': filename, 'raw': raw, 'filter_type': 'bilinear', 'wrap_mode': 'repeat'}
    if to_uv is not None:
        desc['to_uv'] = to_uv
    return mi.load_dict(desc)


def interaction(u, v):
    si = mi.SurfaceInteraction3f()
    si.uv = mi.Point2f(u, v)
    return si


def rgb(tex, u, v):
    return [float(x) for x in tex.eval(interaction(u, v))]


def verify_transform(tex_plain, t):
    """to_uv must equal the contract's formula: Mitsuba with to_uv vs plain Mitsuba at the formula's point."""
    tex = bitmap(os.path.join(OUT, 'tiny.png'), False, mitsuba_to_uv(t))
    xml = mi.load_string(f'<texture version="3.0.0" type="bitmap"><string name="filename" '
                         f'value="{os.path.join(OUT, "tiny.png")}"/>{xml_to_uv(t)}</texture>')
    wrong_sign = bitmap(os.path.join(OUT, 'tiny.png'), False, mi.ScalarTransform3f().translate(t['offset'])
                        .rotate(t['rotation']).scale(t['scale']))
    worst, worst_wrong, worst_xml = 0.0, 0.0, 0.0
    for u, v in TRANSFORM_UVS + UVS:
        got = rgb(tex, u, v)
        pu, pv = contract_uv(t, u, v)
        want = rgb(tex_plain, pu, pv)
        # Mitsuba rounds M * uv to float32: the texel position moves by up to a few ulps of |u'| W + |v'| H
        bound = 8 * 2.0 ** -24 * (abs(pu) * WIDTH + abs(pv) * HEIGHT + 1)
        worst = max(worst, max(abs(a - b) for a, b in zip(got, want)) / bound)
        worst_wrong = max(worst_wrong, max(abs(a - b) for a, b in zip(rgb(wrong_sign, u, v), want)))
        worst_xml = max(worst_xml, max(abs(a - b) for a, b in zip(rgb(xml, u, v), got)) / bound)
    assert worst <= 1, f'to_uv differs from the contract formula by {worst} times the float32 bound'
    assert worst_xml <= 1, f'the XML to_uv differs from translate * rotate(-r) * scale by {worst_xml} times the bound'
    assert worst_wrong > 0.05, 'the check cannot tell the rotation sign'
    return tex, worst


def main():
    os.makedirs(OUT, exist_ok=True)
    rows = rgba_rows()
    write_png(os.path.join(OUT, 'tiny.png'), rows, WIDTH, HEIGHT, 6)
    for c, name in enumerate(CHANNELS):
        grey = [[row[4 * x + c] for x in range(WIDTH)] for row in rows]
        write_png(os.path.join(OUT, f'tiny-{name}.png'), grey, WIDTH, HEIGHT, 0)

    srgb = bitmap(os.path.join(OUT, 'tiny.png'), False)
    raw = bitmap(os.path.join(OUT, 'tiny.png'), True)
    mono = {name: bitmap(os.path.join(OUT, f'tiny-{name}.png'), True) for name in CHANNELS}
    uvs = [[f32(u), f32(v)] for u, v in UVS]

    lookups = []
    for u, v in uvs:
        lookups.append({'group': 'srgb', 'srgb': True, 'uv': [u, v], 'mitsuba': rgb(srgb, u, v)})
    for u, v in uvs:
        lookups.append({'group': 'raw', 'srgb': False, 'uv': [u, v], 'mitsuba': rgb(raw, u, v)})
    for name in CHANNELS:
        for u, v in uvs:
            value = float(mono[name].eval_1(interaction(u, v)))
            lookups.append({'group': 'channel', 'srgb': False, 'channel': name, 'uv': [u, v], 'mitsuba': [value]})
    worst = 0.0
    for t in TRANSFORMS:
        tex, w = verify_transform(srgb, t)
        worst = max(worst, w)
        for u, v in TRANSFORM_UVS:
            u, v = f32(u), f32(v)
            lookups.append({'group': 'transform', 'srgb': True, 'uv': [u, v], 'transform': t, 'mitsuba': rgb(tex, u, v)})

    fixture = {
        'about': 'Mitsuba bitmap texture lookups on tiny.png; made by scripts/make-bitmap-lookups.py, see README.md',
        'mitsuba': mi.__version__,
        'variant': mi.variant(),
        'settings': {'filter_type': 'bilinear', 'wrap_mode': 'repeat', 'format': 'auto'},
        'toUv': 'translate(offset) * rotate(-rotation) * scale(scale); XML: ' + xml_to_uv(TRANSFORMS[0]),
        'image': {'file': 'tiny.png', 'width': WIDTH, 'height': HEIGHT,
                  'rgba': [b for row in rows for b in row]},
        'channelImages': {name: f'tiny-{name}.png' for name in CHANNELS},
        'lookups': lookups,
    }
    with open(os.path.join(OUT, 'lookups.json'), 'w') as f:
        json.dump(fixture, f, indent=1)
        f.write('\n')
    print(f'{len(lookups)} lookups; to_uv vs the contract formula: at most {worst:.3g} of the float32 bound')


if __name__ == '__main__':
    main()
