// Concentric square-to-disk map (Shirley & Chiu): uniform on the unit disk.
// Returns the point and its radius (the radius exactly, not re-derived from
// the point: approximate sin/cos would make |point| drift past 1).
vec2 sampleUniformDisk(vec2 u, out float radius) {
  vec2 o = 2.0 * u - 1.0;
  bool xMajor = abs(o.x) > abs(o.y);
  float r = xMajor ? o.x : o.y;
  float theta = pick(xMajor, (PI / 4.0) * (o.y / o.x), (PI / 2.0) - (PI / 4.0) * (o.x / o.y));
  bool center = o.x == 0.0 && o.y == 0.0;  // theta is NaN there: not picked
  radius = center ? 0.0 : r;
  return pick(center, vec2(0.0), r * vec2(cos(theta), sin(theta)));
}

vec2 sampleUniformDisk(vec2 u) {
  float radius;
  return sampleUniformDisk(u, radius);
}

// The point at angle 2 pi u on the unit circle: (cos, sin).
vec2 unitCircle(float u) {
  float phi = 2.0 * PI * u;
  return vec2(cos(phi), sin(phi));
}

// Uniform direction in the cone around +z with 1 - cos(theta_max) given;
// u picks the polar angle, `circle` (unitCircle) the azimuth.
// Working with 1 - cos keeps precision for tiny cones (small, far lights).
vec3 sampleUniformCone(float u, vec2 circle, float oneMinusCosMax) {
  float oneMinusCos = u * oneMinusCosMax;
  float cosTheta = 1.0 - oneMinusCos;
  float sinTheta = sqrt(max(0.0, oneMinusCos * (2.0 - oneMinusCos)));
  return vec3(sinTheta * circle, cosTheta);
}

vec3 sampleUniformCone(vec2 u, float oneMinusCosMax) {
  return sampleUniformCone(u.x, unitCircle(u.y), oneMinusCosMax);
}

float uniformConePdf(float oneMinusCosMax) {
  return 1.0 / (2.0 * PI * oneMinusCosMax);
}

// Power heuristic (beta = 2) in a form that cannot overflow.
float powerHeuristic(float pdfA, float pdfB) {
  float ratio = pdfB / pdfA;
  return pick(pdfA <= 0.0, 0.0, 1.0 / (1.0 + ratio * ratio));
}
