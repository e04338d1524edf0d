// The conductor: a metal, exactly Mitsuba 3's `conductor` (roughness 0: an
// ideal mirror) and `roughconductor` (GGX, alpha = r^2, visible-normal
// sampling) with the exact complex Fresnel term, times the tint `color`
// (specular_reflectance). One-sided: seen from below (wo.z <= 0) it
// reflects nothing; on meshes the integrator turns the frame over first.
// Below DELTA_ALPHA the lobe is an ideal mirror, as in every BSDF here.

// Unpolarized reflectance of a conductor of relative complex index
// eta + i k, per channel, at incidence cosine cosThetaI >= 0: Mitsuba's
// fresnel_conductor, term for term (K. D. Moeller, "Optics").
vec3 fresnelConductor(float cosThetaI, vec3 eta, vec3 k) {
  float cos2 = cosThetaI * cosThetaI;
  float sin2 = 1.0 - cos2;
  float sin4 = sin2 * sin2;
  vec3 temp1 = eta * eta - k * k - sin2;
  vec3 a2pb2 = sqrt(max(temp1 * temp1 + 4.0 * k * k * eta * eta, 0.0));
  vec3 a = sqrt(max(0.5 * (a2pb2 + temp1), 0.0));
  vec3 term1 = a2pb2 + cos2;
  vec3 term2 = 2.0 * cosThetaI * a;
  vec3 rs = (term1 - term2) / (term1 + term2);
  vec3 term3 = a2pb2 * cos2 + sin4;
  vec3 term4 = term2 * sin2;
  vec3 rp = rs * (term3 - term4) / (term3 + term4);
  return 0.5 * (rs + rp);
}

float conductorAlpha(ConductorParams m) { return m.roughness * m.roughness; }
bool conductorSmooth(ConductorParams m) { return conductorAlpha(m) < DELTA_ALPHA; }

// f(wo, wi) cos(wi) of the rough lobe, F D G1(wo) G1(wi) / (4 cos wo), and
// the visible-normal density of drawing wi, D G1(wo) / (4 cos wo).
vec3 conductorEval(Bsdf b, vec3 wo, vec3 wi, out float pdf) {
  ConductorParams m = conductorParams(b);
  pdf = 0.0;
  if (conductorSmooth(m) || wo.z <= 0.0 || wi.z <= 0.0) return vec3(0.0);
  float alpha = conductorAlpha(m);
  vec3 h = normalize(wo + wi);
  float d = ggxD(h, alpha);
  float g1o = ggxG1(wo, alpha);
  vec3 F = fresnelConductor(dot(wo, h), m.eta, m.k) * m.color;
  pdf = g1o * d / (4.0 * wo.z);
  return F * (d * g1o * ggxG1(wi, alpha) / (4.0 * wo.z));
}

// Reflection about a visible normal (the macro normal when smooth: then
// `isDelta`, and f cos / pdf is the Fresnel term at wo times the tint).
vec3 conductorSampleDirection(Bsdf b, vec3 wo, vec3 u, vec2 circle, out bool isDelta, out vec3 deltaWeight) {
  ConductorParams m = conductorParams(b);
  isDelta = conductorSmooth(m);
  deltaWeight = fresnelConductor(wo.z, m.eta, m.k) * m.color;
  vec3 h = pick(isDelta, vec3(0.0, 0.0, 1.0), sampleGgxVisibleNormal(wo, conductorAlpha(m), sqrt(u.x) * circle));
  vec3 wi = reflect(-wo, h);
  return wo.z > 0.0 && wi.z > 0.0 ? wi : vec3(0.0);
}

bool conductorHasNonDeltaLobe(Bsdf b) { return !conductorSmooth(conductorParams(b)); }
bool conductorIsDelta(Bsdf b) { return conductorSmooth(conductorParams(b)); }
// The guide buffers: what the mirror reflects at this angle; a rough metal's
// reflectance at normal incidence.
vec3 conductorDeltaTint(Bsdf b, vec3 wo, vec3 wi) {
  ConductorParams m = conductorParams(b);
  return fresnelConductor(abs(wo.z), m.eta, m.k) * m.color;
}
vec3 conductorAlbedo(Bsdf b) {
  ConductorParams m = conductorParams(b);
  return fresnelConductor(1.0, m.eta, m.k) * m.color;
}
float conductorGuideWeight(Bsdf b) { return 0.0; }
