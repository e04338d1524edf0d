/** Reads the emitter-choice tables a packed scene carries (render/lightChoice.ts) in tests. */
import type { PackedScene } from '../../src/render/packScene';

/** Entry i of table `table` (default: the global one, the last): alias threshold, alias, its emitter's probability, its alias's. */
export function choiceEntry(packed: PackedScene, i: number, table = packed.lightChoice.tables - 1) {
  const { tables, texels } = packed.lightChoice;
  const count = texels.length / 4 / tables;
  const at = (table * count + i) * 4;
  return { threshold: texels[at], alias: texels[at + 1], pdf: texels[at + 2], aliasPdf: texels[at + 3] };
}
