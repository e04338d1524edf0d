#!/usr/bin/env python3
"""Albedo and normal guides (OIDN conventions) of an exported scene, with Mitsuba 3.

    python3 bench/denoise/guides.py SCENE.xml --albedo A.pfm --normal N.pfm [--spp 64]

SCENE.xml comes from `pathtrace export-mitsuba` (src/scene/mitsuba.ts). The
guides follow the conventions the tracer's AOVs will follow (issue 12), which
are OIDN's recommendations:
  - albedo and normal of the first non-specular hit; "specular" = smooth
    conductors (roughness 0) and smooth dielectrics, whose chain is followed
    (up to max_depth), the albedo multiplied by the chain's specular weights;
  - albedo of a non-specular surface = its material color: each `blendbsdf`
    (rough conductor + diffuse of one color, how the exporter writes
    0 < roughness < 1) is replaced by its diffuse child before loading;
  - normals: world-space shading normal in [-1, 1] (not flipped to the viewer);
  - missed rays: albedo = environment radiance clamped to [0, 1], normal 0;
  - emitters hit: albedo = radiance clamped to [0, 1], normal = the surface's.
Mitsuba's own `aov` integrator (albedo:albedo,nn:sh_normal) stops at the
first hit (a mirror gives albedo 0) and reports a Monte Carlo-free but
BSDF-specific "diffuse reflectance", hence this small integrator.
Each pixel is the box-filtered mean of --spp samples (anti-aliased edges),
like the colour. Output PFMs: RGB, little-endian, rows bottom to top.
"""
import argparse
import re
import sys

import drjit as dr
import mitsuba as mi

# scalar: the llvm variants abort on this machine (LLVM cannot select fminimum/fmaximum).
mi.set_variant("scalar_rgb")

sys.path.insert(0, __file__.rsplit("/", 3)[0] + "/bench/mitsuba")
from render import tensor_bytes, write_pfm  # noqa: E402


def plain_materials(xml):
    """Replace each blendbsdf by its last child (the exporter's diffuse lobe, same color)."""
    pattern = re.compile(
        r'<bsdf type="blendbsdf">\s*<float name="weight" value="[^"]*"/>\s*'
        r'<bsdf type="roughconductor">.*?</bsdf>\s*(<bsdf type="diffuse">.*?</bsdf>)\s*</bsdf>',
        re.S)
    return pattern.sub(lambda m: m.group(1), xml)


def unit_clamp(x):
    
    return dr.clip(x, 0.0, 1.0)


class GuideIntegrator(mi.SamplingIntegrator):
    """Colour channels = albedo guide; AOVs nx, ny, nz = normal guide."""

    def __init__(self, props):
        super().__init__(props)
        self.max_depth = props.get("max_depth", 9)

    def sample(self, scene, sampler, ray, medium=None, active=True):
        albedo, normal = self.first_diffuse_hit(scene, sampler, mi.Ray3f(ray))
        return albedo, True, [normal.x, normal.y, normal.z]

    def first_diffuse_hit(self, scene, sampler, ray):
        """(albedo, normal) along the specular chain from `ray` (scalar variant: plain control flow)."""
        throughput = mi.Color3f(1.0)
        ctx = mi.BSDFContext()
        for _ in range(self.max_depth):
            si = scene.ray_intersect(ray)
            if not si.is_valid():
                env = scene.environment()
                sky = env.eval(si) if env is not None else mi.Color3f(0.0)
                return throughput * unit_clamp(sky), mi.Vector3f(0.0)
            emitter = si.emitter(scene)
            if emitter is not None:
                return throughput * unit_clamp(emitter.eval(si)), mi.Vector3f(si.sh_frame.n)
            bsdf = si.bsdf(ray)
            if not mi.has_flag(bsdf.flags(), mi.BSDFFlags.Delta):
                return throughput * unit_clamp(bsdf.eval_diffuse_reflectance(si)), mi.Vector3f(si.sh_frame.n)
            bs, weight = bsdf.sample(ctx, si, sampler.next_1d(), sampler.next_2d())
            throughput = throughput * weight
            if dr.all(throughput == 0.0):
                break
            ray = si.spawn_ray(si.to_world(bs.wo))
        return mi.Color3f(0.0), mi.Vector3f(0.0)

    def aov_names(self):
        return ["nx", "ny", "nz"]

    def to_string(self):
        return "GuideIntegrator"


mi.register_integrator("oidn_guides", lambda props: GuideIntegrator(props))


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("scene")
    p.add_argument("--albedo", required=True)
    p.add_argument("--normal", required=True)
    p.add_argument("--spp", type=int, default=64)
    args = p.parse_args(argv)
    xml = plain_materials(open(args.scene).read())
    xml = re.sub(r'<integrator type="path">', '<integrator type="oidn_guides">', xml)
    xml = re.sub(r'<integer name="rr_depth" value="\d+"/>', '', xml)
    xml = re.sub(r'<sampler type="independent">', '<sampler type="stratified">', xml)
    scene = mi.load_string(xml)
    img = mi.render(scene, spp=args.spp, seed=0)
    dr.eval(img)
    height, width, channels = img.shape
    # hdrfilm develops R, G, B, [A,] then the AOVs in order: first 3 and last 3.
    albedo = img[:, :, 0:3]
    normal = img[:, :, channels - 3:channels]
    write_pfm(args.albedo, tensor_bytes(mi, mi.TensorXf(albedo)), width, height)
    write_pfm(args.normal, tensor_bytes(mi, mi.TensorXf(normal)), width, height)
    print(f"{args.scene}: {width}x{height}, {args.spp} spp, {channels} channels")


if __name__ == "__main__":
    main(sys.argv[1:])
