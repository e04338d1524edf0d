/**
 * The problems a scene can have and the one error the scene parsers throw,
 * apart from the parser itself (schema.ts re-exports them): modules that
 * report or catch them need not import the schema.
 */
import type { Scene } from './types';

/** One problem in a scene. `path` is like "spheres[2].material.roughness"; "" is the document root. */
export interface SceneIssue {
  path: string;
  message: string;
}

/** The only error the parse functions throw. `message` lists the issues, one "path: message" per line. */
export class SceneError extends Error {
  readonly issues: SceneIssue[];

  constructor(issues: SceneIssue[]) {
    super(issues.map(formatIssue).join('\n'));
    this.name = 'SceneError';
    this.issues = issues;
  }
}

/** "path: message", with "scene" standing for the root. */
export function formatIssue(issue: SceneIssue): string {
  return `${issue.path === '' ? 'scene' : issue.path}: ${issue.message}`;
}

export type SafeParseResult = { ok: true; scene: Scene } | { ok: false; issues: SceneIssue[] };
