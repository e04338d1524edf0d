// Counter-based random numbers: every value is a pure function of
// (pixel, sample index, seed, dimension), so renders are reproducible
// bit for bit and samples never repeat or band after long runs.
// Hash: pcg4d (Jarzynski & Olano, "Hash Functions for GPU Rendering", 2020).
uvec4 pcg4d(uvec4 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
  v ^= v >> 16u;
  v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
  return v;
}

uvec4 rngKey;
uint rngDimension;

void rngBeginSample(uvec2 pixel, uint sampleIndex, uint seed) {
  rngKey = pcg4d(uvec4(pixel, sampleIndex, seed));
  rngDimension = 0u;
}

// Four independent uniform numbers in [0, 1) for the next dimension.
vec4 rand4() {
  uvec4 h = pcg4d(rngKey + uvec4(0u, 0u, 0u, rngDimension));
  rngDimension += 1u;
  return vec4(h >> 8u) * (1.0 / 16777216.0);
}
