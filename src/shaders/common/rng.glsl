// Counter-based random numbers: every value is a pure function of
// (pixel, sample index, seed, dimension), so renders are reproducible
// bit for bit and samples never repeat or band after long runs.
// Hash: pcg4d (Jarzynski & Olano, "Hash Functions for GPU Rendering", 2020).
//
// Low discrepancy (LOW_DISCREPANCY): the camera jitter and the first
// bounce's light and BSDF directions (three 2D dimensions) together follow
// a Kronecker sequence: coordinate j of sample i is frac(shift_j + i alpha_j)
// with alpha_j = 1 / phi^j, phi the generalized golden ratio for six
// coordinates (M. Roberts' R_d sequence; generators from src/render/sampling.ts).
// The shifts are a random Cranley-Patterson rotation hashed from (pixel,
// seed): every sample is exactly uniform, so the estimate stays unbiased, and
// renders with different seeds are statistically independent. Arithmetic is
// 32-bit fixed point, exact for any sample index. All else is white noise.
uvec4 pcg4d(uvec4 v) {
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
  v ^= v >> 16u;
  v.x += v.y * v.w; v.y += v.z * v.x; v.z += v.x * v.y; v.w += v.y * v.z;
  return v;
}

uvec2 rngPixelKey;
uint rngSampleIndex;
uint rngDimension;
#if LOW_DISCREPANCY
uvec4 rngShift01;  // rotations of the camera (xy) and first light (zw) dimensions
uvec2 rngShift2;   // rotation of the first BSDF dimension
#endif

// Once per pixel: the keys of its random streams.
void rngBeginPixel(uvec2 pixel, uint seed) {
  uvec4 k = pcg4d(uvec4(pixel, seed, 0x9e3779b9u));
  rngPixelKey = k.xy;
#if LOW_DISCREPANCY
  rngShift01 = pcg4d(uvec4(k.xy, 0xffffffffu, 0u));
  rngShift2 = pcg4d(uvec4(k.xy, 0xffffffffu, 1u)).xy;
#endif
}

void rngBeginSample(uint sampleIndex) {
  rngSampleIndex = sampleIndex;
  rngDimension = 0u;
}

void rngBeginSample(uvec2 pixel, uint sampleIndex, uint seed) {
  rngBeginPixel(pixel, seed);
  rngBeginSample(sampleIndex);
}

// Dimensions are numbered by the caller so that a dimension means the same
// thing in every sample (the sequence stratifies each dimension).
void rngSetDimension(uint dimension) { rngDimension = dimension; }

vec2 toUnit(uvec2 bits) { return vec2(bits >> 8u) * (1.0 / 16777216.0); }

// Four independent uniform numbers in [0, 1) for the next dimension.
vec4 rand4() {
  uvec4 h = pcg4d(uvec4(rngPixelKey, rngSampleIndex, rngDimension));
  rngDimension += 1u;
  return vec4(toUnit(h.xy), toUnit(h.zw));
}

// A uniform number in [0, 1) keyed by `event` instead of a sequence
// dimension (the pass-through decisions at cut-outs, whose count varies
// along a path): independent of every dimension's values.
float randEvent(uint event) { return toUnit(pcg4d(uvec4(rngPixelKey, rngSampleIndex, 0x80000000u | event)).xy).x; }

#if LOW_DISCREPANCY
// The low-discrepancy points of the current sample (see the top).
vec2 ldCamera() { return toUnit(rngShift01.xy + rngSampleIndex * LD_GENERATOR_CAMERA); }
vec2 ldLight() { return toUnit(rngShift01.zw + rngSampleIndex * LD_GENERATOR_LIGHT); }
vec2 ldBsdf() { return toUnit(rngShift2 + rngSampleIndex * LD_GENERATOR_BSDF); }
#endif
