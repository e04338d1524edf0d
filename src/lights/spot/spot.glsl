// The spot light (src/lights/spot/kind.ts): a point light of intensity I
// (the record's radiance) times Mitsuba's falloff (spot.cpp falloff_curve):
// 1 inside the beam, (cutoff - theta) / (cutoff - beamWidth) in the
// transition, 0 from the cutoff on. A Dirac delta.

float spotFalloff(SpotLight p, float cosTheta) {
  float beam = pick(cosTheta >= p.cosBeam, 1.0, (p.cutoff - acos(clamp(cosTheta, -1.0, 1.0))) * p.invTransition);
  return cosTheta > p.cosCutoff ? beam : 0.0;
}

LightSample spotLightSample(Emitter e, vec3 x, vec2 u) {
  SpotLight p = spotLight(e);
  LightSample s = positionLightSample(p.position, e.radiance, x);
  s.radiance *= spotFalloff(p, -dot(s.direction, p.axis));
  return s;
}
