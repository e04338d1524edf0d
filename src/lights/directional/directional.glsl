// The directional light (src/lights/directional/kind.ts): irradiance E
// (the record's radiance) arriving against its unit direction of travel,
// from infinitely far: the shadow ray is unbounded. A Dirac delta.

LightSample directionalLightSample(Emitter e, vec3 x, vec2 u) {
  LightSample s;
  s.direction = -directionalLight(e).direction;
  s.distance = INFINITY;
  s.radiance = e.radiance;
  s.pdf = 1.0;
  s.skipSphere = -1;
  s.delta = true;
  return s;
}
