// The denoiser's guide buffers (AOVs, arbitrary output variables): adds
// uSamplesPerDraw samples per pixel of the albedo and the shading normal
// seen by a jittered camera ray, to two running sums (rgb = sum of valid
// samples, a = count of samples rejected as non-finite, as trace.frag).
//
// Open Image Denoise's conventions: the ray follows the chain of ideal
// specular surfaces (roughness-0 mirrors, smooth glass; reflection or
// refraction picked with the Fresnel probability) and stops at the first
// surface that is not a Dirac delta: albedo = its color times the chain's
// tint, clamped to [0, 1]; normal = its world-space shading normal. A ray
// that escapes sees the sky's radiance clamped to [0, 1] as albedo and a
// zero normal; an emitter-only `light` gives its clamped radiance.
//
// A separate small pass rather than code in the integrator: SwiftShader runs
// every masked branch, so AOV code there would slow every colour sample.
uniform sampler2D uAlbedoSums;
uniform sampler2D uNormalSums;
uniform uint uFirstSample;
uniform uint uSamplesPerDraw;
uniform uint uSeed;

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;

// Longest specular chain followed: a ray through a glass sphere takes two
// events, total internal reflection a few more; a longer chain (a hall of
// mirrors) gives black albedo and a zero normal.
const int AOV_MAX_CHAIN = 12;

struct Aov {
  vec3 albedo;
  vec3 normal;
};

// Whether the chain goes on through this surface (a Dirac delta BSDF).
bool isSpecular(Material m) {
  bool specular = m.type == MATERIAL_STANDARD && standardIsDelta(m);
#if HAS_DIELECTRIC
  specular = specular || (m.type == MATERIAL_DIELECTRIC && dielectricIsDelta(m));
#endif
  return specular;
}

// The direction leaving a specular surface (wo, wi in the shading frame)
// and its tint: a mirror reflects, tinted by its color; glass reflects
// (untinted) with the Fresnel probability and otherwise refracts, tinted by
// its color (the radiance-mode 1/eta^2 is a change of solid angle, not an
// albedo, so it is left out). A one-sided mirror seen from below: none.
vec3 specularDirection(Material m, vec3 wo, float u, out vec3 tint) {
  tint = m.color;
  vec3 wi = wo.z > 0.0 ? vec3(-wo.xy, wo.z) : vec3(0.0);
#if HAS_DIELECTRIC
  if (m.type == MATERIAL_DIELECTRIC) {
    bool isDelta;
    vec3 deltaWeight;
    wi = dielectricSampleDirection(m, wo, vec3(0.0, 0.0, u), vec2(1.0, 0.0), isDelta, deltaWeight);
    tint = wi.z * wo.z > 0.0 ? vec3(1.0) : m.color;
  }
#endif
  return wi;
}

// The loop body is one specular event ending in the next intersection, and
// the albedo is shaded once after it: SwiftShader runs every masked line,
// so a quad whose rays all stop at their first hit pays for one pass.
Aov firstNonSpecularHit(vec3 origin, vec3 direction) {
  vec3 tint = vec3(1.0);
  Hit hit;
  Material m;
  vec3 normal;
  for (int depth = 0; ; depth++) {
    hit = intersectScene(origin, direction);
    m = loadMaterial(hit.material);
    // Two-sided standard materials shade with the normal facing the ray (traceRadiance).
    bool flip = hit.twoSided && m.type == MATERIAL_STANDARD && dot(direction, hit.normal) > 0.0;
    normal = flip ? -hit.normal : hit.normal;
    if (hit.kind == HIT_NONE || !isSpecular(m)) break;
    if (depth + 1 >= AOV_MAX_CHAIN) {
      tint = vec3(0.0);
      normal = vec3(0.0);
      break;
    }
    mat3 frame = basisAround(normal);
    vec3 surfaceTint;
    vec3 wi = specularDirection(m, -direction * frame, rand4().x, surfaceTint);
    if (wi == vec3(0.0)) {
      tint = vec3(0.0);  // black from this side; its normal stays
      break;
    }
    tint *= surfaceTint;
    direction = normalize(frame * wi);
    origin = spawnRayOrigin(hit, direction);
  }
  bool escaped = hit.kind == HIT_NONE;
  vec3 color = escaped ? escapedRadiance(direction) : m.type == MATERIAL_EMITTER_ONLY ? m.emission : m.color;
  return Aov(tint * clamp(color, 0.0, 1.0), escaped ? vec3(0.0) : normal);
}

// NaN fails every comparison (see trace.frag's isValidRadiance).
bool isFinite(vec3 v) { return all(lessThan(abs(v), vec3(MAX_RADIANCE))); }

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 albedoSum = texelFetch(uAlbedoSums, pixel, 0);
  vec4 normalSum = texelFetch(uNormalSums, pixel, 0);
  rngBeginPixel(uvec2(pixel), uSeed);
  for (uint i = 0u; i < uSamplesPerDraw; i++) {
    // The colour's camera jitter of the same sample index (same seed).
    rngBeginSample(uFirstSample + i);
    vec3 origin, direction;
    generateCameraRay(vec2(pixel), origin, direction);
    Aov aov = firstNonSpecularHit(origin, direction);
    bool valid = isFinite(aov.albedo) && isFinite(aov.normal);
    albedoSum += valid ? vec4(aov.albedo, 0.0) : vec4(0.0, 0.0, 0.0, 1.0);
    normalSum += valid ? vec4(aov.normal, 0.0) : vec4(0.0, 0.0, 0.0, 1.0);
  }
  outAlbedo = albedoSum;
  outNormal = normalSum;
}
