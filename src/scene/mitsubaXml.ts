/**
 * A tiny XML element tree for the Mitsuba 3 exporter (mitsuba.ts) and the
 * material plugins' `mitsuba` entries, serialized with two-space indentation.
 */
import type { Vec3 } from './types';

export interface XmlNode {
  tag: string;
  attrs: [string, string][];
  children: XmlNode[];
}

/** Escape a string for use inside an XML attribute value or text. */
export function escapeXml(value: string): string {
  return value
    .replace(/&/g, '&amp;')
    .replace(/</g, '&lt;')
    .replace(/>/g, '&gt;')
    .replace(/"/g, '&quot;')
    .replace(/'/g, '&apos;');
}

/** Shortest round-trip decimal form; non-finite numbers are a caller bug. */
export function num(x: number): string {
  if (!Number.isFinite(x)) throw new Error(`toMitsubaXml: non-finite number ${x}`);
  return String(x);
}

function int(x: number, name: string): string {
  if (!Number.isInteger(x) || x < 0) throw new Error(`toMitsubaXml: ${name} must be a non-negative integer, got ${x}`);
  return String(x);
}

export function triple(v: readonly number[]): string {
  return `${num(v[0])}, ${num(v[1])}, ${num(v[2])}`;
}

export function el(tag: string, attrs: Record<string, string>, children: XmlNode[] = []): XmlNode {
  return { tag, attrs: Object.entries(attrs), children };
}

export function serializeXml(node: XmlNode, depth: number, out: string[]): void {
  const pad = '  '.repeat(depth);
  const attrs = node.attrs.map(([k, v]) => ` ${k}="${escapeXml(v)}"`).join('');
  if (node.children.length === 0) {
    out.push(`${pad}<${node.tag}${attrs}/>`);
    return;
  }
  out.push(`${pad}<${node.tag}${attrs}>`);
  for (const child of node.children) serializeXml(child, depth + 1, out);
  out.push(`${pad}</${node.tag}>`);
}

export const float = (name: string, value: number) => el('float', { name, value: num(value) });
export const integer = (name: string, value: number) => el('integer', { name, value: int(value, name) });
export const str = (name: string, value: string) => el('string', { name, value });
export const rgb = (name: string, value: Vec3 | readonly number[]) => el('rgb', { name, value: triple(value) });
export const point = (name: string, value: Vec3) => el('point', { name, value: triple(value) });
export const bool = (name: string, value: boolean) => el('boolean', { name, value: String(value) });

/** A GGX microfacet lobe as Mitsuba's rough plugins take it: alpha = r^2, visible-normal sampling. */
export const ggxLobe = (roughness: number) => [str('distribution', 'ggx'), float('alpha', roughness * roughness), bool('sample_visible', true)];
