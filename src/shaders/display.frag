// Mean radiance -> exposure -> tone mapping -> sRGB.
uniform sampler2D uAccumulation;
uniform float uInverseSampleCount;
uniform float uExposureScale;   // 2^exposure
uniform int uToneMap;
uniform vec2 uViewportSize;

out vec4 outColor;

// ACES filmic fit (Stephen Hill's RRT+ODT fit, as in three.js).
vec3 toneMapAces(vec3 color) {
  const mat3 inputMatrix = mat3(0.59719, 0.07600, 0.02840, 0.35458, 0.90834, 0.13383, 0.04823, 0.01566, 0.83777);
  const mat3 outputMatrix = mat3(1.60475, -0.10208, -0.00327, -0.53108, 1.10813, -0.07276, -0.07367, -0.00605, 1.07602);
  color = inputMatrix * color;
  vec3 a = color * (color + 0.0245786) - 0.000090537;
  vec3 b = color * (0.983729 * color + 0.4329510) + 0.238081;
  return outputMatrix * (a / b);
}

// Khronos PBR Neutral tone mapper (reference implementation).
vec3 toneMapNeutral(vec3 color) {
  const float startCompression = 0.8 - 0.04;
  const float desaturation = 0.15;
  float x = min(color.r, min(color.g, color.b));
  float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
  color -= offset;
  float peak = max(color.r, max(color.g, color.b));
  if (peak < startCompression) return color;
  const float d = 1.0 - startCompression;
  float newPeak = 1.0 - d * d / (peak + d - startCompression);
  color *= newPeak / peak;
  float g = 1.0 - 1.0 / (desaturation * (peak - newPeak) + 1.0);
  return mix(color, vec3(newPeak), g);
}

// AgX base (Troy Sobotka), the polynomial fit of Benjamin Wrensch.
vec3 agxContrast(vec3 x) {
  vec3 x2 = x * x;
  vec3 x4 = x2 * x2;
  return 15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x - 0.00232;
}
vec3 toneMapAgx(vec3 color) {
  const mat3 inset = mat3(0.842479062253094, 0.0423282422610123, 0.0423756549057051,
                          0.0784335999999992, 0.878468636469772, 0.0784336,
                          0.0792237451477643, 0.0791661274605434, 0.879142973793104);
  const mat3 outset = mat3(1.19687900512017, -0.0528968517574562, -0.0529716355144438,
                           -0.0980208811401368, 1.15190312990417, -0.0980434501171241,
                           -0.0990297440797205, -0.0989611768448433, 1.15107367264116);
  const float minEv = -12.47393;
  const float maxEv = 4.026069;
  color = inset * max(color, vec3(1e-10));
  color = clamp((log2(color) - minEv) / (maxEv - minEv), 0.0, 1.0);
  color = agxContrast(color);
  color = outset * color;
  // The curve's output is display-encoded; undo the encoding so the common
  // sRGB step below applies it exactly once.
  return pow(max(color, vec3(0.0)), vec3(2.2));
}

vec3 toneMap(vec3 color) {
  if (uToneMap == TONEMAP_ACES) return toneMapAces(color);
  if (uToneMap == TONEMAP_NEUTRAL) return toneMapNeutral(color);
  if (uToneMap == TONEMAP_AGX) return toneMapAgx(color);
  return color;
}

// The exact piecewise sRGB transfer function (IEC 61966-2-1).
vec3 linearToSrgb(vec3 c) {
  vec3 low = 12.92 * c;
  vec3 high = 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055;
  return mix(high, low, vec3(lessThanEqual(c, vec3(0.0031308))));
}

void main() {
  ivec2 size = textureSize(uAccumulation, 0);
  ivec2 texel = min(ivec2(gl_FragCoord.xy * vec2(size) / uViewportSize), size - 1);
  vec3 mean = texelFetch(uAccumulation, texel, 0).rgb * uInverseSampleCount;
  vec3 color = clamp(toneMap(mean * uExposureScale), 0.0, 1.0);
  outColor = vec4(linearToSrgb(color), 1.0);
}
