// The disk light (src/lights/disk/kind.ts): center + a u + b v, a^2 + b^2 <= 1
// (u and v orthogonal, of length the radius). Sampled uniformly by area
// (lights/planar.glsl).

float diskArea(PlanarLight l) { return PI * length(cross(l.u, l.v)); }

LightSample diskLightSample(Emitter e, vec3 x, vec2 u) {
  PlanarLight l = loadPlanarLight(e.primitive);
  vec2 ab = sampleUniformDisk(u);
  return planarAreaSample(l, x, l.center + ab.x * l.u + ab.y * l.v, diskArea(l), e.radiance);
}

float diskLightPdf(vec3 x, vec3 direction, Hit hit) {
  return planarAreaPdf(direction, hit, diskArea(loadPlanarLight(int(hit.geometry.x))));
}
