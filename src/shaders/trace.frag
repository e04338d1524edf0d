// Adds uSamplesPerDraw samples per pixel to the running sums.
// rgb = sum of radiance samples, a = count of rejected (non-finite) samples.
// Samples are added one by one onto the stored sum, so the result is the
// same sequence of float additions however the samples are split into draws:
// a seed gives the same bits whatever the caller's chunking.
uniform sampler2D uAccumulation;
uniform uint uFirstSample;
uniform uint uSamplesPerDraw;
uniform uint uSeed;

out vec4 outSum;

// NaN fails every comparison, so this rejects NaN, Inf and negative values
// even where a compiler treats isnan()/isinf() as always false.
bool isValidRadiance(vec3 c) {
  return all(greaterThanEqual(c, vec3(0.0))) && all(lessThan(c, vec3(MAX_RADIANCE)));
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 sum = texelFetch(uAccumulation, pixel, 0);
  rngBeginPixel(uvec2(pixel), uSeed);
  for (uint s = 0u; s < uSamplesPerDraw; s++) {
    rngBeginSample(uFirstSample + s);
    vec3 origin, direction;
    generateCameraRay(vec2(pixel), origin, direction);
    vec3 radiance = traceRadiance(origin, direction);
    if (isValidRadiance(radiance)) sum.rgb += radiance;
    else sum.a += 1.0;
  }
  outSum = sum;
}
