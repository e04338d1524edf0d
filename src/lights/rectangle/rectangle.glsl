// The rectangle light (src/lights/rectangle/kind.ts): corners center +- u +- v.
// Sampled uniformly by area (lights/planar.glsl).

float rectangleArea(PlanarLight l) { return 4.0 * length(cross(l.u, l.v)); }

LightSample rectangleLightSample(Emitter e, vec3 x, vec2 u) {
  PlanarLight l = loadPlanarLight(e.primitive);
  vec3 p = l.center + (2.0 * u.x - 1.0) * l.u + (2.0 * u.y - 1.0) * l.v;
  return planarAreaSample(l, x, p, rectangleArea(l), e.radiance);
}

float rectangleLightPdf(vec3 x, vec3 direction, Hit hit) {
  return planarAreaPdf(direction, hit, rectangleArea(loadPlanarLight(int(hit.geometry.x))));
}
