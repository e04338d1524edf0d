// One renderer function per pixel, for the sampler tests.
uniform int uKernel;
uniform vec4 uParams;
uniform vec4 uMaterial[MATERIAL_TEXELS];  // the packed record of the request's material
uniform vec3 uWo;
uniform vec2 uGrid;
uniform uint uSeed;
uniform vec4 uRect[3];  // sampleRectangle: the rectangle's centre and half-axes u, v (.xyz)

out vec4 outValue;

// Pixel centre -> direction on the sphere, uniform in (cos theta, phi).
vec3 gridDirection(vec2 pixel) {
  vec2 u = (pixel + 0.5) / uGrid;
  float cosTheta = 2.0 * u.y - 1.0;
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  float phi = 2.0 * PI * u.x;
  return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  uint index = uint(pixel.y) * uint(uGrid.x) + uint(pixel.x);
  rngBeginSample(uvec2(index, 0u), 0u, uSeed);
  Bsdf material = bsdfFromRecord(materialOf(uMaterial));
  if (uKernel == KERNEL_SAMPLECONE) {
    outValue = vec4(sampleUniformCone(rand4().xy, uParams.x), uniformConePdf(uParams.x));
  } else if (uKernel == KERNEL_SAMPLERECTANGLE) {
    // From uWo: the sampled point's plane coordinates (a, b) in [-1, 1]^2, the sampler's density and rectanglePdf's for that point.
    vec3 c = uRect[0].xyz, u = uRect[1].xyz, v = uRect[2].xyz;
    float pdf;
    vec3 p = sampleRectangle(uWo, c, u, v, rand4().xy, pdf);
    outValue = vec4(dot(p - c, u) / dot(u, u), dot(p - c, v) / dot(v, v), pdf, rectanglePdf(uWo, p, c, u, v));
  } else if (uKernel == KERNEL_SAMPLEMATERIAL) {
    BsdfSample s = bsdfSample(material, uWo, rand4().xyz);
    outValue = s.valid ? vec4(s.wi, s.isDelta ? -1.0 : s.pdf) : vec4(0.0);
  } else {
    vec3 wi = gridDirection(vec2(pixel));
    float pdf;
    bsdfEval(material, uWo, wi, pdf);
    outValue = vec4(wi, pdf);
  }
}
