// One triangle that covers the viewport; no vertex buffers needed. Or, when
// uTiles.x > 0, a run of tiles of a sample pass (src/render/tiles.ts): two
// triangles (6 vertices) per tile, tile number uTiles.w + gl_VertexID / 6.
// Tile u is grid cell (u * step) mod count, row-major; a cell is two pixel
// rows by one column segment, whose edges fall on even columns.
uniform uvec4 uTiles;      // count of tiles (0: full screen), step, column segments, first tile
uniform uvec2 uTileTarget; // width and height of the target in pixels

void main() {
  if (uTiles.x == 0u) {
    vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
    return;
  }
  uint vertex = uint(gl_VertexID);
  uint cell = ((uTiles.w + vertex / 6u) * uTiles.y) % uTiles.x;
  uint segments = uTiles.z;
  uint segment = cell % segments;
  uint y0 = (cell / segments) * 2u;
  uint y1 = min(y0 + 2u, uTileTarget.y);
  uint x0 = (segment * uTileTarget.x / segments) & ~1u;
  uint x1 = segment + 1u == segments ? uTileTarget.x : ((segment + 1u) * uTileTarget.x / segments) & ~1u;
  // Corners of the two triangles: (0,0) (1,0) (0,1), (0,1) (1,0) (1,1).
  uint corner = vertex % 6u;
  bool right = corner == 1u || corner == 4u || corner == 5u;
  bool top = corner == 2u || corner == 3u || corner == 5u;
  // Edges on whole pixels: pixel centres are half a pixel from every edge, so rounding cannot move one across.
  vec2 p = vec2(float(right ? x1 : x0), float(top ? y1 : y0));
  gl_Position = vec4(p / vec2(uTileTarget) * 2.0 - 1.0, 0.0, 1.0);
}
