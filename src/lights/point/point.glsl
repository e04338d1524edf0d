// The point light (src/lights/point/kind.ts): intensity I (the record's
// radiance) gives I / d^2 at distance d. A Dirac delta.

LightSample pointLightSample(Emitter e, vec3 x, vec2 u) {
  PointLight p = pointLight(e);
  LightSample s;
  vec3 toLight = p.position - x;
  float d2 = dot(toLight, toLight);
  s.distance = sqrt(d2);
  s.direction = toLight / s.distance;
  s.radiance = e.radiance / d2;
  s.pdf = d2 > 0.0 ? 1.0 : 0.0;
  s.skipSphere = -1;
  s.delta = true;
  return s;
}
