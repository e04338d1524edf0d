// Adds uSamplesPerDraw samples per pixel to the running sums.
// rgb = sum of radiance samples, a = count of rejected (non-finite) samples.
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
  vec4 added = vec4(0.0);
  rngBeginPixel(uvec2(pixel), uSeed);
  for (uint s = 0u; s < uSamplesPerDraw; s++) {
    rngBeginSample(uFirstSample + s);
    vec3 origin, direction;
    generateCameraRay(vec2(pixel), origin, direction);
    vec3 radiance = traceRadiance(origin, direction);
    if (isValidRadiance(radiance)) added.rgb += radiance;
    else added.a += 1.0;
  }
  outSum = texelFetch(uAccumulation, pixel, 0) + added;
}
