// The rectangle light (src/lights/rectangle/kind.ts): corners c +- u +- v,
// emitting towards cross(u, v). Seen from where it covers a fair solid
// angle it is sampled uniformly in that solid angle (Urena, Fajardo and
// King 2013, "An area-preserving parametrization for spherical
// rectangles", as pbrt-v4's SampleSphericalRectangle), which removes the
// 1 / d^2 and cosine variance of area sampling near the light; where it
// covers almost nothing (float cancellation in the spherical excess) or
// nearly a hemisphere, uniformly by area, as pbrt-v4 does. Both the sample
// and the density of a BSDF hit (rectanglePdf) choose the same way, from
// the same solid angle.

const float RECTANGLE_MIN_SOLID_ANGLE = 1e-2;
const float RECTANGLE_MAX_SOLID_ANGLE = 6.22;

float rectangleArea(vec3 u, vec3 v) { return 4.0 * length(cross(u, v)); }

// Solid angle of the triangle a, b, c (vectors from the viewpoint; Van Oosterom and Strackee 1983: accurate when small).
float triangleSolidAngle(vec3 a, vec3 b, vec3 c) {
  float la = length(a), lb = length(b), lc = length(c);
  float numerator = abs(dot(a, cross(b, c)));
  float denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
  return 2.0 * atan(numerator, denominator);
}

float rectangleSolidAngle(vec3 x, vec3 c, vec3 u, vec3 v) {
  vec3 p00 = c - u - v - x, p10 = c + u - v - x, p11 = c + u + v - x, p01 = c - u + v - x;
  return triangleSolidAngle(p00, p10, p11) + triangleSolidAngle(p00, p11, p01);
}

bool rectangleBySolidAngle(float omega) { return omega > RECTANGLE_MIN_SOLID_ANGLE && omega < RECTANGLE_MAX_SOLID_ANGLE; }

// The angle between unit vectors, accurate near 0 and pi (pbrt-v4's AngleBetween).
float angleBetween(vec3 a, vec3 b) {
  return pick(dot(a, b) < 0.0, PI - 2.0 * asin(min(1.0, length(a + b) * 0.5)), 2.0 * asin(min(1.0, length(b - a) * 0.5)));
}

// A point of the rectangle (corner s, edges ex and ey) uniformly distributed
// in the solid angle it subtends at x (Urena et al. 2013, section 3).
vec3 sampleSphericalRectangle(vec3 x, vec3 s, vec3 ex, vec3 ey, vec2 rnd) {
  float exl = length(ex), eyl = length(ey);
  vec3 rx = ex / exl, ry = ey / eyl, rz = cross(rx, ry);
  vec3 d = s - x;
  float x0 = dot(d, rx), y0 = dot(d, ry), z0 = dot(d, rz);
  rz = pick(z0 > 0.0, -rz, rz);    // z towards the rectangle's far side from x
  z0 = -abs(z0);
  float x1 = x0 + exl, y1 = y0 + eyl;
  vec3 v00 = vec3(x0, y0, z0), v01 = vec3(x0, y1, z0), v10 = vec3(x1, y0, z0), v11 = vec3(x1, y1, z0);
  vec3 n0 = normalize(cross(v00, v10)), n1 = normalize(cross(v10, v11));
  vec3 n2 = normalize(cross(v11, v01)), n3 = normalize(cross(v01, v00));
  float g0 = angleBetween(-n0, n1), g1 = angleBetween(-n1, n2), g2 = angleBetween(-n2, n3), g3 = angleBetween(-n3, n0);
  // The sub-rectangle [x0, xu] of solid angle u.x * omega, then a point of height yv uniform in its column.
  float au = rnd.x * (g0 + g1 - 2.0 * PI) + (rnd.x - 1.0) * (g2 + g3);
  float fu = (cos(au) * n0.z - n2.z) / sin(au);
  float cu = clamp((fu >= 0.0 ? 1.0 : -1.0) / sqrt(fu * fu + n0.z * n0.z), -0.99999994, 0.99999994);
  float xu = clamp(-(cu * z0) / sqrt(max(0.0, 1.0 - cu * cu)), x0, x1);
  float dd = sqrt(xu * xu + z0 * z0);
  float h0 = y0 / sqrt(dd * dd + y0 * y0), h1 = y1 / sqrt(dd * dd + y1 * y1);
  float hv = h0 + rnd.y * (h1 - h0);
  float yv = pick(hv * hv < 1.0 - 1e-4, hv * dd / sqrt(1.0 - hv * hv), y1);
  return x + rx * xu + ry * yv + rz * z0;
}

// Density, in solid angle at x, of sampleRectangle drawing the direction
// towards p (a point of the rectangle), given the solid angle omega it
// subtends at x.
float rectanglePdfGiven(float omega, vec3 x, vec3 p, vec3 u, vec3 v) {
  vec3 toP = p - x;
  float d2 = dot(toP, toP);
  float cosLight = abs(dot(toP, normalize(cross(u, v)))) * inversesqrt(d2);
  float byArea = pick(cosLight > 0.0, d2 / (cosLight * rectangleArea(u, v)), 0.0);
  return pick(rectangleBySolidAngle(omega), 1.0 / omega, byArea);
}

float rectanglePdf(vec3 x, vec3 p, vec3 c, vec3 u, vec3 v) { return rectanglePdfGiven(rectangleSolidAngle(x, c, u, v), x, p, u, v); }

// A point on the rectangle seen from x and the density, in solid angle at x,
// of the direction towards it (before the one-sided check).
vec3 sampleRectangle(vec3 x, vec3 c, vec3 u, vec3 v, vec2 rnd, out float pdf) {
  float omega = rectangleSolidAngle(x, c, u, v);
  vec3 byArea = c + (2.0 * rnd.x - 1.0) * u + (2.0 * rnd.y - 1.0) * v;
  vec3 p = byArea;
  if (rectangleBySolidAngle(omega)) p = sampleSphericalRectangle(x, c - u - v, 2.0 * u, 2.0 * v, rnd);
  pdf = rectanglePdfGiven(omega, x, p, u, v);
  return p;
}

// The light interface (src/lights/kind.ts).
LightSample rectangleLightSample(Emitter e, vec3 x, vec2 u) {
  PlanarLight l = loadPlanarLight(e.primitive);
  float pdf;
  vec3 p = sampleRectangle(x, l.center, l.u, l.v, u, pdf);
  LightSample s = planarAreaSample(l, x, p, rectangleArea(l.u, l.v), e.radiance);
  s.pdf = s.pdf > 0.0 ? pdf : 0.0;  // planarAreaSample's is 0 behind the light (no emission)
  return s;
}

float rectangleLightPdf(vec3 x, vec3 direction, Hit hit) {
  PlanarLight l = loadPlanarLight(int(hit.geometry.x));
  return rectanglePdf(x, hit.position, l.center, l.u, l.v);
}
