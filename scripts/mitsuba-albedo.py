"""Adds Mitsuba 3's directional albedo (mean BSDF sample weight, per RGB
channel, and its standard error) to each case of a furnace fixture: a JSON
list of {material, xml, thetas} (make-conductor-furnace.ts,
make-principled-furnace.ts). The view direction is (sin theta, 0, cos theta)
in the shading frame: theta above 90 degrees looks from below the surface
(inside a solid). Scalar RGB variant, N samples per angle, seed 7.
  python3 scripts/mitsuba-albedo.py FIXTURE.json"""
import json, math, sys
import mitsuba as mi
mi.set_variant('scalar_rgb')

N = 400_000
path = sys.argv[1]
cases = json.load(open(path))
for case in cases:
    bsdf = mi.load_string('<bsdf version="3.0.0"' + case['xml'].strip()[5:]) if case['xml'].startswith('<bsdf') else None
    sampler = mi.load_dict({'type': 'independent'})
    sampler.seed(7)
    ctx = mi.BSDFContext()
    albedo = []
    for theta in case['thetas']:
        t = math.radians(theta)
        si = mi.SurfaceInteraction3f()
        si.wi = mi.Vector3f(math.sin(t), 0, math.cos(t))
        si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
        total = [0.0, 0.0, 0.0]
        total2 = [0.0, 0.0, 0.0]
        for _ in range(N):
            bs, w = bsdf.sample(ctx, si, sampler.next_1d(), sampler.next_2d())
            for c in range(3):
                total[c] += w[c]
                total2[c] += w[c] * w[c]
        mean = [x / N for x in total]
        se = [math.sqrt(max(total2[c] / N - mean[c] ** 2, 0) / N) for c in range(3)]
        albedo.append({'theta': theta, 'mean': mean, 'standardError': se})
        print(case['material'], theta, mean, se)
    case['mitsuba'] = albedo
json.dump(cases, open(path, 'w'), indent=2)
