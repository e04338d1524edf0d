const float PI = 3.14159265358979;
const float INV_PI = 0.31830988618379;
const float INFINITY = 1e30;

float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }

// Orthonormal basis around a unit normal (Duff et al. 2017, branchless).
mat3 basisAround(vec3 n) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float b = n.x * n.y * a;
  vec3 t = vec3(1.0 + s * n.x * n.x * a, s * b, -s * n.x);
  vec3 bt = vec3(b, s + n.y * n.y * a, -n.y);
  return mat3(t, bt, n);
}

