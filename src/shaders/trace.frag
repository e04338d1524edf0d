// Adds uSamplesPerDraw samples per pixel to the running sums.
// rgb = sum of radiance samples, a = count of rejected (non-finite) samples.
// Samples are added one by one onto the stored sum, so the result is the
// same sequence of float additions however the samples are split into draws:
// a seed gives the same bits whatever the caller's chunking.
uniform sampler2D uAccumulation;
uniform uint uFirstSample;
uniform uint uSamplesPerDraw;
uniform uint uSeed;
// Adaptive sampling (src/render/adaptive.ts), when uCellSize > 0: each cell
// of uCellSize pixels has its own first sample and count, (x, y) of its
// texel, instead of uFirstSample and uSamplesPerDraw. Looked up by the
// pixel's own cell, so a pixel drawn by a neighbour's tile (tiles at the
// edges overlap) still adds its own samples.
uniform highp usampler2D uCellSamples;
uniform uint uCellSize;

out vec4 outSum;

// NaN fails every comparison, so this rejects NaN and Inf even where a
// compiler treats isnan()/isinf() as always false. Finite negative samples
// are valid: an environment map may hold negative texels (lossy EXR codecs
// ring below zero), which Mitsuba's envmap, the format's definition, keeps.
bool isValidRadiance(vec3 c) {
  return all(lessThan(abs(c), vec3(MAX_RADIANCE)));
}

void accumulate(inout vec4 sum, vec3 radiance) {
  bool valid = isValidRadiance(radiance);
  sum.rgb += valid ? radiance : vec3(0.0);
  sum.a += valid ? 0.0 : 1.0;
}

// SwiftShader runs the lanes of a pixel quad in lock step and executes a
// loop body at least once (masked) per entry. So samples whose camera ray
// scatters nowhere (the sky, a light) are finished in a cheap inner loop,
// and the bounce loop of traceRadiance is entered only for a sample that
// scatters: a quad of sky costs one masked pass through it per draw, not
// one per sample. Each pixel still adds its samples in order, so the sums
// do not depend on how samples are split into draws.
void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 sum = texelFetch(uAccumulation, pixel, 0);
  rngBeginPixel(uvec2(pixel), uSeed);
  uvec2 whole = uvec2(uFirstSample, uSamplesPerDraw);
  uvec2 own = texelFetch(uCellSamples, pixel / int(max(uCellSize, 1u)), 0).xy;
  uvec2 samples = uCellSize > 0u ? own : whole;  // names only: one select
  uint firstSample = samples.x;
  uint sampleCount = samples.y;
  uint next = 0u;
  for (;;) {
    // Start samples until one scatters; finish those that do not.
    bool scattering = false;
    vec3 direction, radiance;
    Hit hit;
    Material material;
    for (;;) {
      if (scattering || next >= sampleCount) break;
      rngBeginSample(firstSample + next);
      next++;
      vec3 origin;
      generateCameraRay(vec2(pixel), origin, direction);
      hit = traceThrough(origin, direction, 0u, material);
      radiance = emitted(hit, material, direction, origin, true, 0.0);
      scattering = uMaxBounces > 0 && scatters(hit, material);
      if (!scattering) accumulate(sum, radiance);
    }
    if (!scattering) break;
    accumulate(sum, traceRadiance(direction, hit, material, radiance));
    if (next >= sampleCount) break;
  }
  outSum = sum;
}
