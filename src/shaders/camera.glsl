// Camera rays from the inverse view-projection (rotation only; the position
// is added separately), a box filter (uniform jitter inside the pixel) and a
// thin lens.
uniform mat4 uInverseViewProjection;
uniform vec3 uCameraPosition;
uniform vec3 uCameraRight;
uniform vec3 uCameraUp;
uniform vec3 uCameraForward;
uniform float uAperture;       // lens radius, world units
uniform float uFocusDistance;  // along the view direction
uniform vec2 uResolution;      // render target size in pixels

void generateCameraRay(vec2 pixel, out vec3 origin, out vec3 direction) {
  vec4 u = rand4();
#if LOW_DISCREPANCY
  u.xy = ldCamera();
#endif
  vec2 ndc = 2.0 * (pixel + u.xy) / uResolution - 1.0;
  vec4 p = uInverseViewProjection * vec4(ndc, -1.0, 1.0);
  direction = normalize(p.xyz / p.w);
  origin = uCameraPosition;
  if (uAperture > 0.0) {
    vec3 focus = origin + direction * (uFocusDistance / dot(direction, uCameraForward));
    vec2 lens = uAperture * sampleUniformDisk(u.zw);
    origin += lens.x * uCameraRight + lens.y * uCameraUp;
    direction = normalize(focus - origin);
  }
}
