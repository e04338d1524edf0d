// The dielectric material: the boundary of a transparent solid, exactly
// Mitsuba 3's `dielectric` (roughness 0) and `roughdielectric` (GGX,
// alpha = r^2, visible-normal sampling; Walter et al. 2007) with
// int_ior = m.ior, ext_ior = 1, specular_transmittance = m.color, in
// radiance mode: refracted radiance is multiplied by 1 / ior^2 entering the
// solid and by ior^2 leaving it. Two-sided: wo.z < 0 is a direction inside
// the solid (the frame's normal points outside).

float dielectricAlpha(DielectricParams m) { return m.roughness * m.roughness; }
bool dielectricSmooth(DielectricParams m) { return dielectricAlpha(m) < DELTA_ALPHA; }

// f(wo, wi) |cos wi| of the rough dielectric (0 for the smooth one, all of
// which is a delta); `pdf` receives the density of dielectricSampleDirection
// drawing wi (as Mitsuba's roughdielectric evaluates them).
vec3 dielectricEval(Bsdf b, vec3 wo, vec3 wi, out float pdf) {
  DielectricParams m = dielectricParams(b);
  pdf = 0.0;
  if (dielectricSmooth(m) || wo.z == 0.0 || wi.z == 0.0) return vec3(0.0);
  float alpha = dielectricAlpha(m);
  bool isReflection = wo.z * wi.z > 0.0;
  float eta = pick(wo.z > 0.0, m.ior, 1.0 / m.ior);
  vec3 h = normalize(wo + wi * (isReflection ? 1.0 : eta));
  h = pick(h.z < 0.0, -h, h);
  float woh = dot(wo, h);
  float wih = dot(wi, h);
  // A microfacet is seen from one side only (Mitsuba's smith_g1 and pdf).
  if (woh * wo.z <= 0.0 || wih * wi.z <= 0.0) return vec3(0.0);
  float cosThetaT, etaTI;
  float F = fresnelDielectric(woh, m.ior, cosThetaT, etaTI);
  float d = ggxD(h, alpha);
  float g1o = ggxG1Either(wo, alpha);
  float g = g1o * ggxG1Either(wi, alpha);
  // Density of the visible normal h seen from wo.
  float visible = d * g1o * abs(woh) / abs(wo.z);
  if (isReflection) {
    pdf = visible * F / (4.0 * abs(wih));
    return vec3(F * d * g / (4.0 * abs(wo.z)));
  }
  float denom = woh + eta * wih;
  float jacobian = eta * eta * abs(wih) / (denom * denom);
  pdf = visible * (1.0 - F) * jacobian;
  // (1 / eta^2): the radiance-mode solid-angle compression.
  float value = abs((1.0 - F) * d * g * woh * wih / (wo.z * denom * denom));
  return m.color * value;
}

// Draws wi: a microfacet normal (visible normals; the macro normal when
// smooth), then reflection with the Fresnel probability F, else
// refraction. For the smooth boundary `isDelta` is set and `deltaWeight` is
// f cos / pdf: 1 for reflection, color / eta^2 (radiance mode) for
// refraction. u: .x and `circle` the disk point, .z the lobe.
vec3 dielectricSampleDirection(Bsdf b, vec3 wo, vec3 u, vec2 circle, out bool isDelta, out vec3 deltaWeight) {
  DielectricParams m = dielectricParams(b);
  isDelta = dielectricSmooth(m);
  float side = wo.z < 0.0 ? -1.0 : 1.0;
  vec3 woUp = side * wo;
  vec3 h = pick(isDelta, vec3(0.0, 0.0, 1.0), sampleGgxVisibleNormal(woUp, dielectricAlpha(m), sqrt(u.x) * circle));
  float woh = dot(wo, h);
  float cosThetaT, etaTI;
  float F = fresnelDielectric(woh, m.ior, cosThetaT, etaTI);
  bool reflects = u.z < F;
  deltaWeight = pick(reflects, vec3(1.0), m.color * (etaTI * etaTI));
  vec3 wi = pick(reflects, 2.0 * woh * h - wo, h * (woh * etaTI + cosThetaT) - wo * etaTI);
  // A rough microfacet can send the reflection below the macro surface or
  // the refraction above it: no sample (as Mitsuba's roughdielectric), since
  // bsdfEval would weigh that direction by the other lobe's pdf.
  bool sideOk = pick(reflects, wi.z * wo.z > 0.0, wi.z * wo.z < 0.0);
  return isDelta || sideOk ? wi : vec3(0.0);
}

bool dielectricHasNonDeltaLobe(Bsdf b) { return !dielectricSmooth(dielectricParams(b)); }
bool dielectricIsDelta(Bsdf b) { return dielectricSmooth(dielectricParams(b)); }
// The guide buffers: reflection is untinted, refraction tinted by the color
// (the radiance-mode 1/eta^2 is a change of solid angle, not an albedo).
vec3 dielectricDeltaTint(Bsdf b, vec3 wo, vec3 wi) { return wi.z * wo.z > 0.0 ? vec3(1.0) : dielectricParams(b).color; }
vec3 dielectricAlbedo(Bsdf b) { return dielectricParams(b).color; }
float dielectricGuideWeight(Bsdf b) { return 0.0; }
