// The point light (src/lights/point/kind.ts): intensity I (the record's
// radiance) gives I / d^2 at distance d. A Dirac delta.

LightSample pointLightSample(Emitter e, vec3 x, vec2 u) {
  return positionLightSample(pointLight(e).position, e.radiance, x);
}
