// Kernels of the caustic-guide mixture and of the BSDF sample weights, for
// test/browser/guided-sampler.test.ts. Compiled with CAUSTIC_GUIDES = 1 and
// every material kind; the guide (mirror and light spheres) comes from the
// SceneBlock uniform block, as in the renderer, and buildGuides() makes the
// cone for the vertex at uPoint with normal uNormal.
uniform int uKernel;
uniform vec4 uMaterial[MATERIAL_TEXELS];  // the packed record of the request's material
uniform vec3 uWo;       // local frame
uniform vec2 uGrid;
uniform uint uSeed;
uniform vec3 uPoint;
uniform vec3 uNormal;
uniform vec4 uCap;      // pdfCap: axis (local frame), half angle in radians

out vec4 outValue;

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
  Bsdf m = bsdfFromRecord(materialOf(uMaterial));
  mat3 frame = basisAround(normalize(uNormal));
  buildGuides(uPoint, normalize(uNormal), m);
  if (uKernel == KERNEL_GUIDESETUP) {
    // The cone in the local frame, and the probability of drawing from it.
    outValue = pixel.x == 0 ? vec4(guideCone0.xyz * frame, guideCone0.w) : vec4(guideProbability);
  } else if (uKernel == KERNEL_SAMPLEGUIDED || uKernel == KERNEL_WEIGHTGUIDED) {
    BsdfSample s = sampleGuided(m, frame, uWo, rand4(), 0.0);
    float bsdfPdf;
    vec3 f = bsdfEval(m, uWo, s.wi, bsdfPdf);
    float mixturePdf = guidedPdf(bsdfPdf, frame * s.wi);
    outValue = uKernel == KERNEL_SAMPLEGUIDED
      ? (s.valid ? vec4(s.wi, s.isDelta ? -1.0 : s.pdf) : vec4(0.0))
      : vec4(s.valid ? s.weight.x : 0.0, s.valid ? 1.0 : 0.0, mixturePdf > 0.0 ? f.x / mixturePdf : 0.0, mixturePdf);
  } else if (uKernel == KERNEL_WEIGHTBSDF) {
    BsdfSample s = bsdfSample(m, uWo, rand4().xyz);
    float pdf;
    vec3 f = bsdfEval(m, uWo, s.wi, pdf);
    outValue = vec4(s.valid ? s.weight.x : 0.0, s.valid ? 1.0 : 0.0, pdf > 0.0 ? f.x / pdf : 0.0, s.isDelta ? -1.0 : s.pdf);
  } else if (uKernel == KERNEL_PDFCAP) {
    // A grid uniform in (theta, phi) over a cap around uCap.xyz, for narrow
    // lobes that a grid over the whole sphere cannot resolve: (wi, pdf).
    vec2 u = (vec2(pixel) + 0.5) / uGrid;
    float theta = u.y * uCap.w;
    float phi = 2.0 * PI * u.x;
    vec3 wi = basisAround(normalize(uCap.xyz)) * vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
    float pdf;
    bsdfEval(m, uWo, wi, pdf);
    outValue = vec4(wi, pdf);
  } else {
    // The grid over the sphere: f |cos|, the BSDF's pdf, the mixture's pdf.
    vec3 wi = gridDirection(vec2(pixel));
    float pdf;
    vec3 f = bsdfEval(m, uWo, wi, pdf);
    outValue = vec4(f.x, pdf, guidedPdf(pdf, frame * wi), 0.0);
  }
}
