/**
 * glTF KHR_lights_punctual lights as the format's point, spot and
 * directional lights (scene-format.md, "Lights in version 3"), placed by
 * their nodes in the file's object space: a light shines down its node's
 * -z. Intensities as given (candela, lux); a spot's outer and inner cone
 * angles (radians) become cutoffAngle and beamWidth (degrees: Mitsuba's
 * linear falloff, not glTF's); `range` is ignored, with a warning.
 */
import type { Document, Node } from '@gltf-transform/core';
import type { Light as GltfLight } from '@gltf-transform/extensions';
import { lightSchema, normalizeLight, type Light } from '../../lights/registry';
import { AssetError } from '../assetError';
import type { Vec3 } from '../types';

const DEGREES = 180 / Math.PI;

export function gltfLights(document: Document, warnings: string[]): Light[] {
  const root = document.getRoot();
  const scene = root.getDefaultScene() ?? root.listScenes()[0];
  if (!scene) return [];
  const lights: Light[] = [];
  let ranged = 0;
  scene.traverse((node: Node) => {
    const light = node.getExtension<GltfLight>('KHR_lights_punctual');
    if (!light) return;
    if (light.getRange() !== null) ranged++;
    lights.push(placeLight(light, node.getWorldMatrix() as unknown as number[], `the light on node ${JSON.stringify(node.getName() || '(unnamed)')}`));
  });
  if (ranged > 0) warnings.push(`ignores the \`range\` of ${ranged} KHR_lights_punctual light${ranged > 1 ? 's' : ''} (lights here fall off as 1/d^2 without a cut-off)`);
  return lights;
}

function placeLight(light: GltfLight, m: number[], where: string): Light {
  const position: Vec3 = [m[12], m[13], m[14]];
  const down = [-m[8], -m[9], -m[10]];
  const length = Math.hypot(down[0], down[1], down[2]) || 1;
  const direction = down.map((c) => c / length) as Vec3;
  const color = light.getColor().map((c) => Math.max(0, c)) as Vec3;
  const intensity = Math.max(0, light.getIntensity());
  const type = light.getType();
  if (type === 'directional') return parseLight({ type, direction, color, irradiance: intensity }, where);
  if (type === 'point') return parseLight({ type, position, color, intensity }, where);
  const cutoff = Math.min(90, Math.max(1e-3, light.getOuterConeAngle() * DEGREES));
  const beam = Math.min(cutoff, Math.max(0, light.getInnerConeAngle() * DEGREES));
  const target: Vec3 = [position[0] + direction[0], position[1] + direction[1], position[2] + direction[2]];
  return parseLight({ type: 'spot', position, target, color, intensity, cutoffAngle: cutoff, beamWidth: beam }, where);
}

/** Through the light schema, so every default is the format's. */
function parseLight(json: Record<string, unknown>, where: string): Light {
  const result = lightSchema(json.type)!.safeParse(json);
  if (!result.success) {
    const issue = result.error.issues[0];
    throw new AssetError(`${where}: ${issue.path.join('.')}: ${issue.message}`);
  }
  return normalizeLight(result.data as Record<string, unknown>);
}
