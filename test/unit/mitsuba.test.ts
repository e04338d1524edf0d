import { describe, expect, it } from 'vitest';
import { escapeXml, toMitsubaXml } from '../../src/scene/mitsuba';
import type { Scene } from '../../src/scene/types';

/** A minimal strict XML parser: throws on anything not well-formed. */
interface XmlNode {
  tag: string;
  attrs: Record<string, string>;
  children: XmlNode[];
}

function unescape(s: string): string {
  if (/&(?!(amp|lt|gt|quot|apos);)/.test(s)) throw new Error(`bad entity in ${s}`);
  return s
    .replace(/&lt;/g, '<')
    .replace(/&gt;/g, '>')
    .replace(/&quot;/g, '"')
    .replace(/&apos;/g, "'")
    .replace(/&amp;/g, '&');
}

function parseXml(xml: string): XmlNode {
  const body = xml.replace(/^<\?xml[^?]*\?>/, '').replace(/<!--[\s\S]*?-->/g, '');
  const root: XmlNode = { tag: '#document', attrs: {}, children: [] };
  const stack = [root];
  const token = /<(\/?)([A-Za-z_][\w.-]*)((?:\s+[\w.-]+="[^"<]*")*)\s*(\/?)>|([^<]+)|(<)/g;
  let m: RegExpExecArray | null;
  while ((m = token.exec(body))) {
    const [, close, tag, attrText, selfClose, text, stray] = m;
    if (stray) throw new Error(`stray '<' at ${m.index}`);
    if (text !== undefined) {
      if (text.trim()) throw new Error(`unexpected text ${text.trim()}`);
      continue;
    }
    if (close) {
      const open = stack.pop();
      if (!open || open.tag !== tag) throw new Error(`</${tag}> closes <${open?.tag}>`);
      continue;
    }
    const attrs: Record<string, string> = {};
    for (const a of attrText.matchAll(/([\w.-]+)="([^"]*)"/g)) {
      if (a[1] in attrs) throw new Error(`duplicate attribute ${a[1]}`);
      attrs[a[1]] = unescape(a[2]);
    }
    const node: XmlNode = { tag, attrs, children: [] };
    stack[stack.length - 1].children.push(node);
    if (!selfClose) stack.push(node);
  }
  if (stack.length !== 1) throw new Error(`unclosed <${stack[stack.length - 1].tag}>`);
  if (root.children.length !== 1) throw new Error('expected one root element');
  return root.children[0];
}

const kids = (n: XmlNode, tag: string, type?: string) =>
  n.children.filter((c) => c.tag === tag && (type === undefined || c.attrs.type === type));
const one = (n: XmlNode, tag: string, type?: string) => {
  const found = kids(n, tag, type);
  expect(found, `<${tag} type=${type}> under <${n.tag} type=${n.attrs.type}>`).toHaveLength(1);
  return found[0];
};
const prop = (n: XmlNode, tag: string, name: string) => {
  const found = n.children.filter((c) => c.tag === tag && c.attrs.name === name);
  expect(found, `${tag} ${name}`).toHaveLength(1);
  return found[0].attrs.value;
};
const nums = (s: string) => s.split(',').map(Number);

function scene(overrides: Partial<Scene> = {}): Scene {
  return {
    version: 1,
    camera: { position: [0, 1, 5], target: [0, 1, 0], up: [0, 1, 0], fov: 40, aperture: 0 },
    image: { width: 64, height: 32 },
    render: { maxBounces: 6 },
    environment: { color: [0.5, 0.25, 1], intensity: 2 },
    ground: { height: -0.5, material: { type: 'standard', color: [0.6, 0.6, 0.6], roughness: 1 } },
    lights: [{ type: 'sphere', position: [1, 4, 2], radius: 0.5, color: [1, 0.5, 0.25], intensity: 8 }],
    meshes: [],
    spheres: [
      { center: [-1, 0, 0], radius: 0.5, material: { type: 'standard', color: [0.9, 0.6, 0.3], roughness: 0 } },
      { center: [0, 0, 0], radius: 0.5, material: { type: 'standard', color: [0.2, 0.4, 0.8], roughness: 0.5 } },
      { center: [1, 0, 0], radius: 0.5, material: { type: 'standard', color: [0.7, 0.7, 0.7], roughness: 1 } },
    ],
    ...overrides,
  };
}

/** The BSDF of a shape (one-sided, as the format says for spheres and the ground). */
function innerBsdf(shape: XmlNode): XmlNode {
  return one(shape, 'bsdf');
}

describe('toMitsubaXml', () => {
  const root = parseXml(toMitsubaXml(scene()));
  const shapes = kids(root, 'shape', 'sphere');

  it('writes a well-formed Mitsuba 3 scene', () => {
    expect(root.tag).toBe('scene');
    expect(root.attrs.version).toBe('3.0.0');
  });

  it('uses the path integrator with max_depth = maxBounces + 1 and no Russian roulette', () => {
    const integrator = one(root, 'integrator', 'path');
    const maxDepth = Number(prop(integrator, 'integer', 'max_depth'));
    expect(maxDepth).toBe(7);
    expect(Number(prop(integrator, 'integer', 'rr_depth'))).toBeGreaterThan(maxDepth);
    const zero = parseXml(toMitsubaXml(scene({ render: { maxBounces: 0 } })));
    expect(prop(one(zero, 'integrator', 'path'), 'integer', 'max_depth')).toBe('1');
  });

  it('writes a pinhole camera with a vertical fov, box filter and rgb film', () => {
    const sensor = one(root, 'sensor', 'perspective');
    expect(prop(sensor, 'string', 'fov_axis')).toBe('y');
    expect(prop(sensor, 'float', 'fov')).toBe('40');
    const lookat = one(one(sensor, 'transform'), 'lookat');
    expect(nums(lookat.attrs.origin)).toEqual([0, 1, 5]);
    expect(nums(lookat.attrs.target)).toEqual([0, 1, 0]);
    expect(nums(lookat.attrs.up)).toEqual([0, 1, 0]);
    const film = one(sensor, 'film', 'hdrfilm');
    expect(prop(film, 'integer', 'width')).toBe('64');
    expect(prop(film, 'integer', 'height')).toBe('32');
    expect(prop(film, 'string', 'pixel_format')).toBe('rgb');
    one(film, 'rfilter', 'box');
    const sampler = one(sensor, 'sampler', 'independent');
    expect(prop(sampler, 'integer', 'sample_count')).toBe('256');
    expect(prop(sampler, 'integer', 'seed')).toBe('0');
  });

  it('applies spp, seed and size options', () => {
    const sensor = one(parseXml(toMitsubaXml(scene(), { spp: 7, seed: 3, width: 10, height: 20 })), 'sensor');
    expect(prop(one(sensor, 'sampler'), 'integer', 'sample_count')).toBe('7');
    expect(prop(one(sensor, 'sampler'), 'integer', 'seed')).toBe('3');
    expect(prop(one(sensor, 'film'), 'integer', 'width')).toBe('10');
    expect(prop(one(sensor, 'film'), 'integer', 'height')).toBe('20');
  });

  it('writes a thin lens focused at the target distance by default', () => {
    const camera = { ...scene().camera, aperture: 0.1 };
    const sensor = one(parseXml(toMitsubaXml(scene({ camera }))), 'sensor', 'thinlens');
    expect(prop(sensor, 'float', 'aperture_radius')).toBe('0.1');
    expect(Number(prop(sensor, 'float', 'focus_distance'))).toBeCloseTo(5, 12);
    const focused = one(parseXml(toMitsubaXml(scene({ camera: { ...camera, focusDistance: 2.5 } }))), 'sensor');
    expect(prop(focused, 'float', 'focus_distance')).toBe('2.5');
  });

  it('replaces an up vector parallel to the view with an orthogonal one', () => {
    const camera = { ...scene().camera, position: [0, 5, 0], target: [0, 0, 0] } as Scene['camera'];
    const lookat = one(one(one(parseXml(toMitsubaXml(scene({ camera }))), 'sensor'), 'transform'), 'lookat');
    const up = nums(lookat.attrs.up);
    expect(up.every(Number.isFinite)).toBe(true);
    expect(Math.abs(up[1])).toBeLessThan(1e-9);
  });

  it('writes a mirror as a conductor without Fresnel and no blend', () => {
    const bsdf = innerBsdf(shapes[1]);
    expect(bsdf.attrs.type).toBe('conductor');
    expect(prop(bsdf, 'string', 'material')).toBe('none');
    expect(nums(prop(bsdf, 'rgb', 'specular_reflectance'))).toEqual([0.9, 0.6, 0.3]);
  });

  it('blends GGX (alpha = r^2) first and Lambert second with weight = roughness', () => {
    const blend = innerBsdf(shapes[2]);
    expect(blend.attrs.type).toBe('blendbsdf');
    expect(prop(blend, 'float', 'weight')).toBe('0.5');
    const [first, second] = kids(blend, 'bsdf');
    expect(first.attrs.type).toBe('roughconductor');
    expect(prop(first, 'string', 'distribution')).toBe('ggx');
    expect(prop(first, 'string', 'material')).toBe('none');
    expect(Number(prop(first, 'float', 'alpha'))).toBe(0.25);
    expect(prop(first, 'boolean', 'sample_visible')).toBe('true');
    expect(nums(prop(first, 'rgb', 'specular_reflectance'))).toEqual([0.2, 0.4, 0.8]);
    expect(second.attrs.type).toBe('diffuse');
    expect(nums(prop(second, 'rgb', 'reflectance'))).toEqual([0.2, 0.4, 0.8]);
    const r = 0.3;
    const rough = parseXml(toMitsubaXml(scene({ lights: [], spheres: [{ center: [0, 0, 0], radius: 1, material: { type: 'standard', color: [1, 1, 1], roughness: r } }] })));
    const alpha = Number(prop(kids(innerBsdf(one(rough, 'shape', 'sphere')), 'bsdf')[0], 'float', 'alpha'));
    expect(alpha).toBe(r * r);
  });

  it('writes roughness 1 as a pure diffuse BSDF', () => {
    const bsdf = innerBsdf(shapes[3]);
    expect(bsdf.attrs.type).toBe('diffuse');
    expect(nums(prop(bsdf, 'rgb', 'reflectance'))).toEqual([0.7, 0.7, 0.7]);
  });

  it('writes lights as black spheres with an area emitter of radiance color * intensity', () => {
    const light = shapes[0];
    expect(nums(prop(light, 'point', 'center'))).toEqual([1, 4, 2]);
    expect(prop(light, 'float', 'radius')).toBe('0.5');
    expect(nums(prop(one(light, 'bsdf', 'diffuse'), 'rgb', 'reflectance'))).toEqual([0, 0, 0]);
    expect(nums(prop(one(light, 'emitter', 'area'), 'rgb', 'radiance'))).toEqual([8, 4, 2]);
  });

  it('writes the ground as a 40000-wide rectangle at its height facing +y', () => {
    const ground = one(root, 'shape', 'rectangle');
    const steps = one(ground, 'transform').children;
    expect(steps.map((s) => s.tag)).toEqual(['scale', 'rotate', 'translate']);
    expect(Number(steps[0].attrs.value)).toBe(20000);
    expect(steps[1].attrs).toEqual({ x: '1', angle: '-90' });
    expect(nums(steps[2].attrs.value)[1]).toBe(-0.5);
    expect(innerBsdf(ground).attrs.type).toBe('diffuse');
    expect(kids(parseXml(toMitsubaXml(scene({ ground: null }))), 'shape', 'rectangle')).toHaveLength(0);
  });

  it('writes the environment as a constant emitter, and none when null', () => {
    expect(nums(prop(one(root, 'emitter', 'constant'), 'rgb', 'radiance'))).toEqual([1, 0.5, 2]);
    expect(kids(parseXml(toMitsubaXml(scene({ environment: null }))), 'emitter')).toHaveLength(0);
  });

  it('rejects non-finite numbers and a camera looking at itself', () => {
    expect(() => toMitsubaXml(scene({ render: { maxBounces: 1.5 } }))).toThrow(/max_depth/);
    const bad = scene();
    bad.spheres[0].radius = Number.NaN;
    expect(() => toMitsubaXml(bad)).toThrow(/non-finite/);
    const camera = { ...scene().camera, target: [0, 1, 5] } as Scene['camera'];
    expect(() => toMitsubaXml(scene({ camera }))).toThrow(/camera/);
  });
});

describe('escapeXml', () => {
  it('escapes the five XML special characters', () => {
    expect(escapeXml(`a<b>&"c'`)).toBe('a&lt;b&gt;&amp;&quot;c&apos;');
    expect(parseXml(`<x v="${escapeXml('<&>"\'')}"/>`).attrs.v).toBe('<&>"\'');
  });
});
