const float PI = 3.14159265358979;
const float INV_PI = 0.31830988618379;
const float INFINITY = 1e30;

// c ? a : b, both evaluated: a branch-free choice between computed values.
// ANGLE emits a ternary as if/else unless both operands are plain names,
// constants or swizzles, and SwiftShader's compile time doubles with every
// if/else in sequence inside a loop (its SpirvShader::ExistsPath queues a
// block once per path to it: bench/results/compile-time-2026-12-06.md).
// Through a function the operands are parameters (names): one OpSelect.
// So shader code writes `c ? a : b` only with names and constants, and
// pick(c, x, y) otherwise; an if/else only where one side is heavy and the
// other empty (then write it as an if without else).
float pick(bool c, float a, float b) { return c ? a : b; }
vec2 pick(bool c, vec2 a, vec2 b) { return c ? a : b; }
vec3 pick(bool c, vec3 a, vec3 b) { return c ? a : b; }
vec4 pick(bool c, vec4 a, vec4 b) { return c ? a : b; }
int pick(bool c, int a, int b) { return c ? a : b; }
uint pick(bool c, uint a, uint b) { return c ? a : b; }
bool pick(bool c, bool a, bool b) { return c ? a : b; }
ivec2 pick(bool c, ivec2 a, ivec2 b) { return c ? a : b; }

float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }

// Orthonormal basis around a unit normal (Duff et al. 2017, branchless).
mat3 basisAround(vec3 n) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;  // constants: a select
  float a = -1.0 / (s + n.z);
  float b = n.x * n.y * a;
  vec3 t = vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
  vec3 bt = vec3(b, s + n.y * n.y * a, -n.y);
  return mat3(t, bt, n);
}

