/**
 * The files of the `textured` example (examples.ts): copies of
 * test/fixtures/textures/{checker,grid,rough,bumps}.png and
 * test/fixtures/meshes/uvbox.obj (CC0, made for the project; a unit test
 * keeps them equal), 8 kB in all. Inlined in this module's own chunk, loaded
 * the first time the example is opened.
 */
import checker from './checker.png?inline';
import grid from './grid.png?inline';
import rough from './rough.png?inline';
import bumps from './bumps.png?inline';
import uvbox from './uvbox.obj?raw';
import { dataUrlBytes } from '../bundledMaps';

const png = (url: string) => new Blob([dataUrlBytes(url) as BlobPart], { type: 'image/png' });

/** The example's files by the names its scene gives them. */
export function texturedExampleFiles(): Map<string, Blob> {
  return new Map([
    ['checker.png', png(checker)],
    ['grid.png', png(grid)],
    ['rough.png', png(rough)],
    ['bumps.png', png(bumps)],
    ['uvbox.obj', new Blob([uvbox], { type: 'text/plain' })],
  ]);
}
