// One environment-map function per pixel, for the browser tests
// (test/browser/envmap-*.test.ts through src/headless/environmentKernels.ts).
uniform int uKernel;
uniform vec4 uParams;
uniform vec2 uGrid;
uniform uint uSeed;

out vec4 outValue;

// Pixel centre -> direction, uniform in (cos theta = y, phi).
vec3 gridDirection(vec2 pixel) {
  vec2 u = (pixel + 0.5) / uGrid;
  float cosTheta = 2.0 * u.y - 1.0;
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  float phi = 2.0 * PI * u.x;
  return vec3(sinTheta * cos(phi), cosTheta, sinTheta * sin(phi));
}

// Map coordinates of pixel centres (u shifted by uParams.x) -> world direction.
vec3 uvGridDirection(vec2 pixel) {
  vec2 uv = (pixel + 0.5) / uGrid + vec2(uParams.x, 0.0);
  float theta = PI * uv.y;
  float phi = 2.0 * PI * (uv.x - 0.5);
  return environmentToWorld(vec3(-sin(theta) * sin(phi), cos(theta), sin(theta) * cos(phi)));
}

// A uniformly random unit direction of this pixel's random stream.
vec3 randomDirection() {
  vec2 u = rand4().xy;
  float cosTheta = 2.0 * u.y - 1.0;
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  return vec3(sinTheta * cos(2.0 * PI * u.x), cosTheta, sinTheta * sin(2.0 * PI * u.x));
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  uint index = uint(pixel.y) * uint(uGrid.x) + uint(pixel.x);
  rngBeginSample(uvec2(index, 0u), 0u, uSeed);
  if (uKernel == KERNEL_SAMPLE) {
    float pdf;
    vec3 d = sampleEnvironment(rand4().xy, pdf);
    outValue = vec4(d, pdf);
  } else if (uKernel == KERNEL_SAMPLEPDFS) {
    float pdf;
    vec3 d = sampleEnvironment(rand4().xy, pdf);
    outValue = vec4(pdf, environmentPdf(d), 0.0, 0.0);
  } else if (uKernel == KERNEL_PDFSPHEREGRID) {
    vec3 d = gridDirection(vec2(pixel));
    outValue = vec4(d, environmentPdf(d));
  } else if (uKernel == KERNEL_PDFUVGRID) {
    vec3 d = uvGridDirection(vec2(pixel));
    outValue = vec4(d, environmentPdf(d));
  } else if (uKernel == KERNEL_RANDOMDIRECTION) {
    outValue = vec4(randomDirection(), 0.0);
  } else if (uKernel == KERNEL_RANDOMRADIANCE) {
    outValue = vec4(environmentRadiance(randomDirection()), 0.0);
  } else {
    outValue = vec4(environmentRadiance(normalize(uParams.xyz)), 0.0);
  }
}
