// What the planar area lights (rectangle, disk: src/lights/) share: the
// light sample of a point p on the shape, drawn with density 1 / area, and
// the density of a BSDF-sampled hit on it, both turned into solid angle at
// x by distance^2 / cos at the light. They emit towards n = cross(u, v)
// only: seen from behind, the sample carries no radiance.

#if HAS_PLANAR_LIGHTS

LightSample planarAreaSample(PlanarLight l, vec3 x, vec3 p, float area, vec3 radiance) {
  LightSample s;
  vec3 toLight = p - x;
  float d = length(toLight);
  s.direction = toLight / d;
  float cosLight = -dot(s.direction, normalize(cross(l.u, l.v)));
  s.pdf = pick(cosLight > 0.0, d * d / (cosLight * area), 0.0);
  s.radiance = radiance;
  // The shadow ray stops short of the light's own plane.
  s.distance = d * 0.9999;
  s.skipSphere = -1;
  s.delta = false;
  return s;
}

// Once the light is picked (lights.glsl multiplies in the choice).
float planarAreaPdf(vec3 direction, Hit hit, float area) {
  float cosLight = abs(dot(direction, hit.normal));
  return pick(cosLight > 0.0, hit.t * hit.t / (cosLight * area), 0.0);
}

#endif
