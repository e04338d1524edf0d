/**
 * The planar lights' two-level culling (scene/intersect.glsl,
 * planarCandidates): the lights are ordered so that each run of
 * PLANAR_GROUP_SIZE consecutive ones lies close together (a median split of
 * their centres along the widest axis, as a BVH build), and each run gets a
 * sphere around its members' bounding spheres. A query tests the groups'
 * spheres, then the members' spheres of the groups it passes, then the
 * shapes of the members it passes: about count / size + size + 1 tests
 * instead of count.
 */
export type Sphere = readonly [number, number, number, number];

/** The order of the lights (indices into `bounds`) that puts neighbours into the same group. */
export function planarGroupOrder(bounds: readonly Sphere[], groupSize: number): number[] {
  const order = bounds.map((_, i) => i);
  const split = (from: number, to: number): void => {
    if (to - from <= groupSize) return;
    const axis = widestAxis(order.slice(from, to).map((i) => bounds[i]));
    const part = order.slice(from, to).sort((a, b) => bounds[a][axis] - bounds[b][axis] || a - b);
    order.splice(from, to - from, ...part);
    // The split falls on a group boundary, so groups never straddle two halves.
    const half = from + Math.ceil((to - from) / 2 / groupSize) * groupSize;
    split(from, half);
    split(half, to);
  };
  split(0, order.length);
  return order;
}

function widestAxis(spheres: readonly Sphere[]): number {
  const extent = [0, 1, 2].map((a) => Math.max(...spheres.map((s) => s[a])) - Math.min(...spheres.map((s) => s[a])));
  return extent.indexOf(Math.max(...extent));
}

/** A sphere holding every sphere of `members` (centred on their boxes' middle: not the smallest, but tight enough). */
export function enclosingSphere(members: readonly Sphere[]): Sphere {
  const lo = [0, 1, 2].map((a) => Math.min(...members.map((s) => s[a] - s[3])));
  const hi = [0, 1, 2].map((a) => Math.max(...members.map((s) => s[a] + s[3])));
  const c = [0, 1, 2].map((a) => (lo[a] + hi[a]) / 2);
  const r = Math.max(...members.map((s) => Math.hypot(s[0] - c[0], s[1] - c[1], s[2] - c[2]) + s[3]));
  return [c[0], c[1], c[2], r * (1 + 1e-3) + 1e-7]; // padded as planarBound's
}

/** Each group's sphere, for lights already in planarGroupOrder's order. */
export function planarGroupBounds(ordered: readonly Sphere[], groupSize: number): Sphere[] {
  const groups: Sphere[] = [];
  for (let first = 0; first < ordered.length; first += groupSize) groups.push(enclosingSphere(ordered.slice(first, first + groupSize)));
  return groups;
}
