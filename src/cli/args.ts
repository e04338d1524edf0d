/**
 * Parsing and validation of the render flags. Commander hands over raw
 * strings; everything is checked here so each problem gets one clear line
 * (`--spp: must be a positive integer (got "abc")`) and exit code 2.
 */
import { MAX_IMAGE_SIZE } from '../scene/limits';
import { usageError } from './errors';

export const DEFAULT_SPP = 256;
export const DEFAULT_SEED = 0;
export const DEFAULT_EXPOSURE = 0;
export const DEFAULT_TONEMAP = 'none';
/** Largest sample count per pixel accepted from --spp (the shader counts samples in 32-bit ints). */
export const MAX_SPP = 1_000_000_000;
export const MAX_SEED = 0xffff_ffff;
/** 2^±100 stays well inside float32 range. */
export const MAX_ABS_EXPOSURE = 100;
/** One week: longer is almost certainly a typo. */
export const MAX_TIME_SECONDS = 7 * 24 * 3600;

/** Raw option values as commander collects them (all strings, all optional). */
export interface RawRenderOptions {
  output?: string;
  hdr?: string;
  spp?: string;
  time?: string;
  seed?: string;
  width?: string;
  height?: string;
  exposure?: string;
  tonemap?: string;
  /** --denoise (commander gives true when present). */
  denoise?: boolean;
  /** --adaptive (commander gives true when present). */
  adaptive?: boolean;
  /** --aov ALBEDO.pfm,NORMAL.pfm */
  aov?: string;
  /** A model file's glTF camera: --camera (true, the first) or --camera N (src/cli/model.ts). */
  camera?: string | boolean;
  /** A model file's environment: --env FILE or --env none (src/cli/model.ts). */
  env?: string;
}

/** Where --aov writes the denoiser's guide buffers. */
export interface AovPaths {
  albedo: string;
  normal: string;
}

/** How long to render: a fixed sample count, or a time budget. */
export type Budget = { kind: 'spp'; spp: number } | { kind: 'time'; seconds: number };

export interface RenderArgs {
  budget: Budget;
  seed: number;
  /** Explicit size overrides; missing ones come from the scene (see resolveSize). */
  width?: number;
  height?: number;
  exposure: number;
  toneMap: string;
  /** Denoise the final image (PNG and --hdr); default false: the unbiased estimate. */
  denoise: boolean;
  /** Adaptive sampling (PathTracerOptions.adaptive); default false. */
  adaptive: boolean;
  /** Also write the albedo and normal guides as PFM. */
  aov?: AovPaths;
}

const INTEGER = /^\+?\d+$/;
const DECIMAL = /^[+-]?(\d+\.?\d*|\.\d+)(e[+-]?\d+)?$/i;

function got(raw: string): string {
  return `(got ${JSON.stringify(raw)})`;
}

/** An integer in [min, max]; rejects "1.5", "1e3", "0x10", "12abc" and "". */
export function parseInteger(flag: string, raw: string, min: number, max: number, what: string): number {
  const value = Number(raw.trim());
  if (!INTEGER.test(raw.trim()) || !Number.isSafeInteger(value) || value < min) {
    throw usageError(`${flag}: must be ${what} ${got(raw)}`);
  }
  if (value > max) throw usageError(`${flag}: must be at most ${max} ${got(raw)}`);
  return value;
}

/** A finite decimal number (exponents allowed) in [min, max]. */
export function parseNumber(flag: string, raw: string, min: number, max: number, what: string): number {
  const value = Number(raw.trim());
  if (!DECIMAL.test(raw.trim()) || !Number.isFinite(value)) throw usageError(`${flag}: must be ${what} ${got(raw)}`);
  if (value < min || value > max) throw usageError(`${flag}: must be ${what} between ${min} and ${max} ${got(raw)}`);
  return value;
}

export function parsePositiveInteger(flag: string, raw: string, max: number): number {
  return parseInteger(flag, raw, 1, max, 'a positive integer');
}

/**
 * Checks every render flag and collects all problems at once, so a user with
 * three typos sees three lines rather than fixing them one run at a time.
 */
export function parseRenderArgs(raw: RawRenderOptions, tonemaps: readonly string[]): RenderArgs {
  const problems: string[] = [];
  const attempt = <T>(fn: () => T): T | undefined => {
    try {
      return fn();
    } catch (error) {
      const lines = (error as { lines?: string[] }).lines;
      problems.push(...(lines ?? [String(error)]));
      return undefined;
    }
  };

  let budget: Budget | undefined = { kind: 'spp', spp: DEFAULT_SPP };
  if (raw.spp !== undefined && raw.time !== undefined) {
    problems.push('--spp, --time: give one of them, not both');
  } else if (raw.spp !== undefined) {
    const spp = attempt(() => parsePositiveInteger('--spp', raw.spp!, MAX_SPP));
    budget = spp === undefined ? undefined : { kind: 'spp', spp };
  } else if (raw.time !== undefined) {
    const seconds = attempt(() => parseTime(raw.time!));
    budget = seconds === undefined ? undefined : { kind: 'time', seconds };
  }
  const seed = raw.seed === undefined ? DEFAULT_SEED : attempt(() => parseInteger('--seed', raw.seed!, 0, MAX_SEED, 'a non-negative integer'));
  const width = raw.width === undefined ? undefined : attempt(() => parsePositiveInteger('--width', raw.width!, MAX_IMAGE_SIZE));
  const height = raw.height === undefined ? undefined : attempt(() => parsePositiveInteger('--height', raw.height!, MAX_IMAGE_SIZE));
  const exposure =
    raw.exposure === undefined
      ? DEFAULT_EXPOSURE
      : attempt(() => parseNumber('--exposure', raw.exposure!, -MAX_ABS_EXPOSURE, MAX_ABS_EXPOSURE, 'a number of EV stops'));
  const tonemap = raw.tonemap ?? DEFAULT_TONEMAP;
  if (!tonemaps.includes(tonemap)) {
    problems.push(`--tonemap: must be one of ${tonemaps.join(', ')} ${got(tonemap)}`);
  }
  const aov = raw.aov === undefined ? undefined : attempt(() => parseAovPaths(raw.aov!));
  if (problems.length > 0) throw usageError(problems);
  return { budget: budget!, seed: seed!, width, height, exposure: exposure!, toneMap: tonemap, denoise: raw.denoise === true, adaptive: raw.adaptive === true, aov };
}

/** `albedo.pfm,normal.pfm`: exactly two different, non-empty paths, albedo first. */
export function parseAovPaths(raw: string): AovPaths {
  const parts = raw.split(',').map((part) => part.trim());
  if (parts.length !== 2 || parts.some((part) => part === '')) {
    throw usageError(`--aov: must be two PFM paths separated by a comma, albedo first: ALBEDO.pfm,NORMAL.pfm ${got(raw)}`);
  }
  if (parts[0] === parts[1]) throw usageError(`--aov: the albedo and normal files must differ ${got(raw)}`);
  return { albedo: parts[0], normal: parts[1] };
}

function parseTime(raw: string): number {
  const seconds = parseNumber('--time', raw, 0, MAX_TIME_SECONDS, 'a positive number of seconds');
  if (seconds <= 0) throw usageError(`--time: must be a positive number of seconds ${got(raw)}`);
  return seconds;
}

/**
 * The image size to render: the scene's, with --width/--height overriding it.
 * Given only one of them, the other follows the scene's aspect ratio.
 */
export function resolveSize(
  scene: { width: number; height: number },
  args: { width?: number; height?: number },
): { width: number; height: number } {
  const { width, height } = args;
  if (width !== undefined && height !== undefined) return { width, height };
  const clamp = (n: number) => Math.min(MAX_IMAGE_SIZE, Math.max(1, Math.round(n)));
  if (width !== undefined) return { width, height: clamp((width * scene.height) / scene.width) };
  if (height !== undefined) return { width: clamp((height * scene.width) / scene.height), height };
  return { width: scene.width, height: scene.height };
}
