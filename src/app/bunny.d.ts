/** The npm package `bunny` (public domain): the Stanford bunny as vertex positions and triangles. */
declare module 'bunny' {
  const bunny: { positions: [number, number, number][]; cells: [number, number, number][] };
  export default bunny;
}
