/**
 * Assembles GLSL ES 3.00 sources from named chunks and maps compile errors
 * back to `chunk:line`.
 */
export interface ShaderChunk {
  name: string;
  source: string;
  /** Lines put before the file's own (a guard): its line 1 is source line 1 + lineOffset. */
  lineOffset?: number;
}

export interface ShaderSource {
  text: string;
  /** For each line of `text` (0-based), where it came from. */
  origins: { chunk: string; line: number }[];
}

const PRELUDE = ['#version 300 es', 'precision highp float;', 'precision highp int;', 'precision highp sampler2D;'];

export function buildShader(chunks: ShaderChunk[], defines: Record<string, string | number> = {}): ShaderSource {
  const lines: string[] = [];
  const origins: ShaderSource['origins'] = [];
  const push = (line: string, chunk: string, n: number) => {
    lines.push(line);
    origins.push({ chunk, line: n });
  };
  PRELUDE.forEach((line, i) => push(line, 'prelude', i + 1));
  Object.entries(defines).forEach(([key, value], i) => push(`#define ${key} ${value}`, 'defines', i + 1));
  for (const chunk of chunks) {
    chunk.source.split('\n').forEach((line, i) => push(line, chunk.name, i + 1 - (chunk.lineOffset ?? 0)));
  }
  return { text: lines.join('\n'), origins };
}

/**
 * Rewrites "ERROR: 0:123: ..." lines of a compile log to name the chunk and
 * its line, and appends the offending source lines.
 */
export function describeCompileLog(log: string, source: ShaderSource): string {
  const out: string[] = [];
  for (const entry of log.split('\n')) {
    const match = /^(ERROR|WARNING): \d+:(\d+): (.*)$/.exec(entry.trim());
    if (!match) {
      if (entry.trim()) out.push(entry.trim());
      continue;
    }
    const index = Number(match[2]) - 1;
    const origin = source.origins[index];
    const where = origin ? `${origin.chunk}:${origin.line}` : `line ${index + 1}`;
    out.push(`${match[1]}: ${where}: ${match[3]}`);
    if (source.text.split('\n')[index] !== undefined) out.push(`    ${source.text.split('\n')[index].trim()}`);
  }
  return out.join('\n');
}
