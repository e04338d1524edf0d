// One triangle that covers the viewport; no vertex buffers needed. Or, when
// uTiles.x > 0, a run of tiles of a sample pass (src/render/tiles.ts), drawn
// as points: tile number uTiles.w + gl_VertexID is grid cell
// (number * step) mod count, row-major, a square of uTileGrid.x pixels
// (moved inward at the right and top edges to end there).
// Or, when uTileList, the cells listed in the vertex attribute aCell (grid
// cell numbers, row-major: adaptive sampling's cells, src/render/adaptive.ts).
uniform uvec4 uTiles;    // count of tiles (0: full screen), step, tiles per row, first tile
uniform uvec3 uTileGrid; // tile side, target width and height, in pixels
uniform bool uTileList;
// A float, so that programs that never enable it read the default generic
// attribute (a float) without a type mismatch; cell numbers stay below 2^16.
layout(location = 0) in float aCell;

void main() {
  gl_PointSize = 1.0;
  if (uTiles.x == 0u) {
    vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
    return;
  }
  uint listed = uint(aCell);
  uint ordered = ((uTiles.w + uint(gl_VertexID)) * uTiles.y) % uTiles.x;
  uint cell = uTileList ? listed : ordered;
  uint size = uTileGrid.x;
  uint x0 = min((cell % uTiles.z) * size, uTileGrid.y - size);
  uint y0 = min((cell / uTiles.z) * size, uTileGrid.z - size);
  // The square's edges fall on whole pixels, half a pixel from every pixel centre.
  vec2 centre = vec2(float(x0), float(y0)) + 0.5 * float(size);
  gl_Position = vec4(centre / vec2(float(uTileGrid.y), float(uTileGrid.z)) * 2.0 - 1.0, 0.0, 1.0);
  gl_PointSize = float(size);
}
