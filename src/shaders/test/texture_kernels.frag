// One texture lookup per pixel through textures/texture.glsl, for
// test/browser/texture-lookup.test.ts (src/headless/textureKernels.ts).
// uLookups: RGBA32F, the lookup of each pixel at its texel: (texture index
// in the scene data's texture table, input: 0 colour or 1 scalar, u, v).
uniform highp sampler2D uLookups;

out vec4 outValue;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 lookup = texelFetch(uLookups, p, 0);
  int t = int(lookup.x);
  vec2 uv = lookup.zw;
  outValue = lookup.y == 0.0 ? vec4(textureColor(t, uv), 1.0) : vec4(textureScalar(t, uv), 0.0, 0.0, 1.0);
}
