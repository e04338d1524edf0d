// The principled material: Mitsuba 3's `principled` BSDF term for term
// (src/bsdfs/principled.cpp and principledhelpers.h of Mitsuba 3.9, its
// scalar variant, every sampling rate 1, no anisotropy, flatness 0). Our wo
// is Mitsuba's si.wi and our wi its wo; +z is the outside normal, wo.z < 0
// a direction inside the solid (only with specTrans > 0: an opaque
// principled surface is one-sided, its back reflects nothing and samples
// nothing, as Mitsuba's, whose lobes there all carry the weight
// (1 - metallic) specTrans = 0).
//
// Lobes, with brdf = (1 - metallic)(1 - specTrans) and
// bsdf = (1 - metallic) specTrans:
//   main reflection: GGX (alpha = max(0.001, roughness^2), visible normals)
//     times principled_fresnel: outside (1 - metallic)(1 - specTint) F +
//     metallic Schlick(baseColor) + (1 - metallic) specTint
//     Schlick(tint R0(eta)), F the boundary's exact Fresnel term; inside
//     bsdf F (untinted);
//   transmission: sqrt(baseColor) bsdf times the rough refracting boundary's
//     (radiance mode: the 1 / eta^2 factors cancel eta_path^2);
//   clear coat (outside): 0.25 clearcoat Schlick(0.04) D_GTR1 G |cos wi|,
//     alpha = 0.1 - 0.099 clearcoatGloss, separable Smith G with alpha 0.25
//     (Mitsuba's value, no 1 / (4 cos cos));
//   diffuse (outside): brdf baseColor / pi (Disney diffuse + retro);
//   sheen (outside, only where brdf > 0: the scalar variant evaluates it in
//     the diffuse branch): sheen (1 - metallic) Schlick weight(cos_d)
//     mix(1, baseColor / luminance, sheenTint) |cos wi|.
// Lobe choice outside: diffuse brdf, clear coat 0.25 clearcoat, reflection
// 1 - bsdf (1 - F), transmission bsdf (1 - F), over their sum
// (1 + brdf + 0.25 clearcoat, whatever F); inside: F and 1 - F.

// Mitsuba's GGX smith_g1: 0 where v sees the back of the microfacet m.
float principledG1(vec3 v, vec3 m, float alpha) {
  float xy = alpha * alpha * (v.x * v.x + v.y * v.y);
  float g = pick(xy == 0.0, 1.0, 2.0 / (1.0 + sqrt(1.0 + xy / (v.z * v.z))));
  return dot(v, m) * v.z <= 0.0 ? 0.0 : g;
}

// GGX D (the 1 - cos^2 written as x^2 + y^2: alpha may be 0.001).
float principledD(vec3 m, float alpha) {
  float a2 = alpha * alpha;
  float d = (m.x * m.x + m.y * m.y) + m.z * m.z * a2;
  float result = a2 / (PI * d * d);
  return result * m.z > 1e-20 ? result : 0.0;
}

// GTR1 (the clear coat's distribution): Mitsuba's GTR1Isotropic::eval.
float principledGtr1(vec3 m, float alpha) {
  float a2 = alpha * alpha;
  float result = (a2 - 1.0) / (PI * log(a2) * (1.0 + (a2 - 1.0) * m.z * m.z));
  return result * m.z > 1e-20 ? result : 0.0;
}

// smith_ggx1 of principledhelpers.h (the clear coat's shadowing).
float principledSmithGgx1(vec3 v, vec3 wh, float alpha) {
  float c2 = v.z * v.z;
  float tan2 = (1.0 - c2) / c2;
  float g = pick(v.z == 1.0, 1.0, 2.0 / (1.0 + sqrt(1.0 + alpha * alpha * tan2)));
  return dot(v, wh) * v.z <= 0.0 ? 0.0 : g;
}

float principledSchlickWeight(float c) {
  float m = clamp(1.0 - c, 0.0, 1.0);
  float m2 = m * m;
  return m2 * m2 * m;
}

// calc_schlick: Schlick's approximation with R0 (per channel), at the
// transmitted angle where the path goes into the optically thinner side.
vec3 principledSchlick(vec3 r0, float cosThetaI, float eta) {
  bool outside = cosThetaI >= 0.0;
  float invEta = 1.0 / eta;
  float etaIT = outside ? eta : invEta;
  float etaTI = outside ? invEta : eta;
  float cosT = sqrt(max(0.0, 1.0 - (1.0 - cosThetaI * cosThetaI) * etaTI * etaTI));
  float w = principledSchlickWeight(pick(etaIT > 1.0, abs(cosThetaI), cosT));
  return mix(vec3(w), vec3(1.0), r0);
}

float principledLuminance(vec3 c) { return dot(c, vec3(0.212671, 0.715160, 0.072169)); }
vec3 principledTint(vec3 c) {
  float lum = principledLuminance(c);
  return pick(lum > 0.0, c / lum, vec3(1.0));
}

float principledAlpha(PrincipledParams p) { return max(0.001, p.roughness * p.roughness); }
float principledBrdf(PrincipledParams p) { return (1.0 - p.metallic) * (1.0 - p.specTrans); }
float principledBsdf(PrincipledParams p) { return (1.0 - p.metallic) * p.specTrans; }

// Mitsuba's mac_mic_compatibility: wo on the front of the microfacet m
// (turned to wo's side) and wi on its front (reflection) or back
// (transmission).
bool principledCompatible(vec3 m, vec3 wo, vec3 wi, bool reflection) {
  vec3 ms = pick(wo.z < 0.0, -m, m);
  float wims = dot(wi, ms);
  bool wiSide = pick(reflection, wims > 0.0, wims < 0.0);
  bool woSide = dot(wo, ms) > 0.0;
  return woSide && wiSide;
}

// The lobe-selection probabilities (diffuse, clear coat, reflection,
// transmission), normalized, for F the boundary's Fresnel term at the
// microfacet.
vec4 principledLobeProbabilities(PrincipledParams p, bool front, float F) {
  float bsdf = principledBsdf(p);
  bool transmits = p.specTrans > 0.0;
  vec4 outside = vec4(principledBrdf(p), 0.25 * p.clearcoat, 1.0 - bsdf * (1.0 - F), pick(transmits, bsdf * (1.0 - F), 0.0));
  vec4 inside = vec4(0.0, 0.0, F, pick(transmits, 1.0 - F, 0.0));
  vec4 prob = front ? outside : inside;
  return prob / (prob.x + prob.y + prob.z + prob.w);
}

// A side Mitsuba samples and evaluates: any outside, inside only where the
// transmission lobe has weight.
bool principledActive(PrincipledParams p, vec3 wo) {
  bool transmitsInside = wo.z < 0.0 && principledBsdf(p) > 0.0;
  return wo.z > 0.0 || transmitsInside;
}

// Straight-line code (no early return, no if/else: see pick() in
// common/math.glsl); the lobes' ifs have no else.
vec3 principledEval(Bsdf b, vec3 wo, vec3 wi, out float pdf) {
  PrincipledParams p = principledParams(b);
  bool reflects = wo.z * wi.z > 0.0;
  bool refracts = wo.z * wi.z < 0.0;
  bool sided = reflects || refracts;
  bool applies = principledActive(p, wo) && sided;
  bool front = wo.z > 0.0;
  float alpha = principledAlpha(p);
  float brdf = principledBrdf(p);
  float bsdf = principledBsdf(p);
  bool transmits = p.specTrans > 0.0;
  float invIor = 1.0 / p.ior;
  float etaPath = front ? p.ior : invIor;
  float invEtaPath = front ? invIor : p.ior;
  float whScale = reflects ? 1.0 : etaPath;
  vec3 wh = normalize(wo + wi * whScale);
  wh = pick(wh.z < 0.0, -wh, wh);
  float woh = dot(wo, wh);
  float wih = dot(wi, wh);
  float cosThetaT, etaTI;
  float F = fresnelDielectric(woh, p.ior, cosThetaT, etaTI);
  bool reflectCompatible = principledCompatible(wh, wo, wi, true);
  bool refractCompatible = principledCompatible(wh, wo, wi, false);
  float D = principledD(wh, alpha);
  float G = principledG1(wo, wh, alpha) * principledG1(wi, wh, alpha);
  float cosO = abs(wi.z);
  vec3 value = vec3(0.0);

  // Main specular reflection: outside, the tinted Schlick blend; inside, bsdf F.
  if (reflects && reflectCompatible && F > 0.0) {
    float etaIT = woh >= 0.0 ? p.ior : invIor;
    float r0 = (etaIT - 1.0) / (etaIT + 1.0);
    vec3 schlick = p.metallic * principledSchlick(p.baseColor, woh, p.ior)
      + (1.0 - p.metallic) * p.specTint * principledSchlick(principledTint(p.baseColor) * (r0 * r0), woh, p.ior);
    vec3 fresnel = pick(front, vec3((1.0 - p.metallic) * (1.0 - p.specTint) * F) + schlick, vec3(bsdf * F));
    value += fresnel * (D * G / (4.0 * abs(wo.z)));
  }
  // Main specular transmission (radiance mode: scale = 1 / eta_path^2).
  if (transmits && bsdf > 0.0 && refracts && refractCompatible && F < 1.0) {
    float scale = invEtaPath * invEtaPath;
    float denom = woh + etaPath * wih;
    value += sqrt(p.baseColor) * bsdf * abs(scale * (1.0 - F) * D * G * etaPath * etaPath * woh * wih / (wo.z * denom * denom));
  }
  float alphaCc = mix(0.1, 0.001, p.clearcoatGloss);
  // Clear coat.
  if (p.clearcoat > 0.0 && reflects && reflectCompatible && front) {
    float Fcc = principledSchlick(vec3(0.04), woh, p.ior).x;
    float Gcc = principledSmithGgx1(wo, wh, 0.25) * principledSmithGgx1(wi, wh, 0.25);
    value += vec3((p.clearcoat * 0.25) * Fcc * principledGtr1(wh, alphaCc) * Gcc * cosO);
  }
  // Diffuse and retro-reflection, then sheen (evaluated only with them).
  if (brdf > 0.0 && reflects && front) {
    float Fo = principledSchlickWeight(cosO);
    float Fi = principledSchlickWeight(abs(wo.z));
    float fDiff = (1.0 - 0.5 * Fi) * (1.0 - 0.5 * Fo);
    float cosThetaD = wih;
    float Rr = 2.0 * p.roughness * cosThetaD * cosThetaD;
    float fRetro = Rr * (Fo + Fi + Fo * Fi * (Rr - 1.0));
    value += p.baseColor * (brdf * cosO * INV_PI * (fDiff + fRetro));
    if (p.sheen > 0.0 && 1.0 - p.metallic > 0.0) {
      float Fd = principledSchlickWeight(abs(cosThetaD));
      vec3 cSheen = mix(vec3(1.0), principledTint(p.baseColor), p.sheenTint);
      value += cSheen * (p.sheen * (1.0 - p.metallic) * Fd * cosO);
    }
  }

  // The density of principledSampleDirection drawing wi (Mitsuba's pdf()).
  vec4 prob = principledLobeProbabilities(p, front, F);
  float refractDwh = abs(etaPath * etaPath * wih / ((woh + etaPath * wih) * (woh + etaPath * wih)));
  float dwhDwo = pick(transmits && refracts, refractDwh, abs(1.0 / (4.0 * wih)));
  vec3 woUp = pick(front, wo, -wo);
  float visible = D * principledG1(woUp, wh, alpha) * abs(dot(woUp, wh)) / woUp.z;
  float density = 0.0;
  if (reflects && reflectCompatible) {
    density += prob.z * visible * dwhDwo;
    if (p.clearcoat > 0.0) density += prob.y * wh.z * principledGtr1(wh, alphaCc) * dwhDwo;
  }
  if (reflects) density += prob.x * INV_PI * wi.z;
  if (transmits && refracts && refractCompatible) density += prob.w * visible * dwhDwo;
  pdf = applies ? density : 0.0;
  return pick(applies, value, vec3(0.0));
}

// Draws wi as Mitsuba's sample(): a visible normal m of the main lobe
// (from the disk point sqrt(u.x) circle) gives the Fresnel term that sets
// the lobe probabilities; u.z picks the lobe; the clear coat draws its GTR1
// normal from (u.x, circle) (cos^2 theta from u.x, the azimuth from the
// circle), the diffuse lobe projects the disk point up (cosine-weighted).
// Directions on the wrong side of the surface or of their microfacet give
// no sample. Never a delta (alpha >= 0.001). Every lobe's direction is
// computed and the chosen one picked (straight-line code: see pick()).
vec3 principledSampleDirection(Bsdf b, vec3 wo, vec3 u, vec2 circle, out bool isDelta, out vec3 deltaWeight) {
  PrincipledParams p = principledParams(b);
  isDelta = false;
  deltaWeight = vec3(0.0);
  bool applies = principledActive(p, wo);
  bool front = wo.z > 0.0;
  vec3 woUp = pick(front, wo, -wo);
  vec2 disk = sqrt(u.x) * circle;
  vec3 m = sampleGgxVisibleNormal(woUp, principledAlpha(p), disk);
  float woh = dot(wo, m);
  float cosThetaT, etaTI;
  float F = fresnelDielectric(woh, p.ior, cosThetaT, etaTI);
  vec4 prob = principledLobeProbabilities(p, front, F);
  float coatEnd = prob.x + prob.y;
  float transmissionEnd = prob.x + prob.y + prob.w;
  bool diffuse = u.z < prob.x;
  bool belowCoatEnd = u.z < coatEnd;
  bool belowTransmissionEnd = u.z < transmissionEnd;
  bool coat = !diffuse && belowCoatEnd;
  bool transmission = !belowCoatEnd && belowTransmissionEnd;

  vec3 wiDiffuse = vec3(disk, sqrt(max(0.0, 1.0 - u.x)));
  float a2 = mix(0.1, 0.001, p.clearcoatGloss);
  a2 *= a2;
  float cos2 = (1.0 - pow(a2, 1.0 - u.x)) / (1.0 - a2);
  vec3 mc = vec3(sqrt(max(0.0, 1.0 - cos2)) * circle, sqrt(max(0.0, cos2)));
  vec3 wiCoat = reflect(-wo, mc);
  vec3 wiTransmission = m * (woh * etaTI + cosThetaT) - wo * etaTI;
  vec3 wiReflection = reflect(-wo, m);
  vec3 wi = pick(diffuse, wiDiffuse, pick(coat, wiCoat, pick(transmission, wiTransmission, wiReflection)));
  m = coat ? mc : m;
  bool reflection = !transmission;

  float side = wo.z * wi.z;
  bool sideOk = pick(reflection, side > 0.0, side < 0.0);
  // The diffuse direction has no microfacet to agree with.
  bool microfacetOk = principledCompatible(m, wo, wi, reflection);
  bool compatible = diffuse || microfacetOk;
  bool valid = applies && sideOk && compatible;
  return valid ? wi : vec3(0.0);
}

bool principledHasNonDeltaLobe(Bsdf b) { return true; }
bool principledIsDelta(Bsdf b) { return false; }
vec3 principledDeltaTint(Bsdf b, vec3 wo, vec3 wi) { return vec3(1.0); }
// Mitsuba's eval_diffuse_reflectance.
vec3 principledAlbedo(Bsdf b) { return principledParams(b).baseColor; }
// The diffuse lobe's share of the sampling outside (the caustic guides may
// take over the diffuse part of the sampling, as for every kind).
float principledGuideWeight(Bsdf b) {
  PrincipledParams p = principledParams(b);
  float brdf = principledBrdf(p);
  return brdf / (1.0 + 0.25 * p.clearcoat + brdf);
}
