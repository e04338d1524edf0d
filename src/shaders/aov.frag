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

// The direction leaving a specular surface (wo, wi in the shading frame,
// the event picked with u as light transport picks it) and its tint
// (bsdfDeltaTint: each kind says what a delta event's albedo is). None
// (the zero vector) where the surface is black from this side.
vec3 specularDirection(Bsdf b, vec3 wo, float u, out vec3 tint) {
  bool isDelta;
  vec3 deltaWeight;
  vec3 wi = bsdfSampleDirection(b, wo, vec3(0.0, 0.0, u), vec2(1.0, 0.0), isDelta, deltaWeight);
  tint = bsdfDeltaTint(b, wo, wi);
  return wi;
}

// The loop body is one specular event ending in the next intersection, and
// the albedo is shaded once after it: SwiftShader runs every masked line,
// so a quad whose rays all stop at their first hit pays for one pass.
Aov firstNonSpecularHit(vec3 origin, vec3 direction) {
  vec3 tint = vec3(1.0);
  Hit hit;
  Material m;
  Bsdf bsdf;
  vec3 normal;
  for (int depth = 0; ; depth++) {
    hit = intersectScene(origin, direction);
    m = loadMaterial(hit.material);
    Surface surface = surfaceAt(hit);
    bsdf = evalMaterial(m, surface);
    normal = facingNormal(surface, bsdf, direction);
    if (hit.kind == HIT_NONE || !bsdfScatters(m) || !bsdfIsDelta(bsdf)) break;
    if (depth + 1 >= AOV_MAX_CHAIN) {
      tint = vec3(0.0);
      normal = vec3(0.0);
      break;
    }
    mat3 frame = basisAround(normal);
    vec3 surfaceTint;
    vec3 wi = specularDirection(bsdf, -direction * frame, rand4().x, surfaceTint);
    if (wi == vec3(0.0)) {
      tint = vec3(0.0);  // black from this side; its normal stays
      break;
    }
    tint *= surfaceTint;
    direction = normalize(frame * wi);
    origin = spawnRayOrigin(hit, direction);
  }
  bool escaped = hit.kind == HIT_NONE;
  vec3 color = escaped ? escapedRadiance(direction) : !bsdfScatters(m) ? materialEmission(m) : bsdfAlbedo(bsdf);
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
