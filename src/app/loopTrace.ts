/**
 * EXPERIMENT (not for main): a per-frame trace of the render loop, on when
 * the page's globalThis.__loopTrace is an array. Each frame's work is
 * bracketed by GPU timestamps, and a fence is polled every frame.
 */
interface Ext {
  TIMESTAMP_EXT: number;
  QUERY_COUNTER_BITS_EXT: number;
  GPU_DISJOINT_EXT: number;
  queryCounterEXT(q: WebGLQuery, target: number): void;
}

interface Pending {
  frame: number;
  begin: WebGLQuery | null;
  end: WebGLQuery | null;
  fence: WebGLSync | null;
}

export class LoopTrace {
  readonly rows: Record<string, number>[] | null;
  private ext: Ext | null;
  private pending: Pending[] = [];
  private frame = 0;
  private clock: { cpu: number; gpu: number }[] = [];

  constructor(private readonly gl: WebGL2RenderingContext) {
    const t = (globalThis as unknown as { __loopTrace?: Record<string, number>[] }).__loopTrace;
    this.rows = Array.isArray(t) ? t : null;
    this.ext = this.rows ? (gl.getExtension('EXT_disjoint_timer_query_webgl2') as unknown as Ext | null) : null;
    if (this.rows) {
      const g = globalThis as unknown as { __loopClock: unknown; __loopSync: () => void };
      g.__loopClock = this.clock;
      g.__loopSync = () => this.syncClock();
    }
  }

  get on(): boolean {
    return this.rows !== null;
  }

  /** Syncs the GPU clock with performance.now (stalls: only now and then). */
  syncClock(): void {
    if (!this.ext) return;
    const a = performance.now();
    const gpu = Number(this.gl.getParameter(this.ext.TIMESTAMP_EXT));
    const b = performance.now();
    this.clock.push({ cpu: (a + b) / 2, gpu: gpu / 1e6, err: (b - a) / 2 } as { cpu: number; gpu: number });
  }

  stamp(): WebGLQuery | null {
    if (!this.ext) return null;
    const q = this.gl.createQuery();
    if (q) this.ext.queryCounterEXT(q, this.ext.TIMESTAMP_EXT);
    return q;
  }

  /** Begins a frame: returns its row. */
  begin(now: number, fields: Record<string, number>): Record<string, number> {
    const row = { frame: this.frame++, now, start: performance.now(), ...fields };
    this.rows!.push(row);
    this.poll(row);
    return row;
  }

  /** After the frame's submissions. */
  end(row: Record<string, number>, begin: WebGLQuery | null, end: WebGLQuery | null): void {
    row.submitted = performance.now();
    const fence = this.gl.fenceSync(this.gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
    this.pending.push({ frame: row.frame, begin, end, fence });
  }

  private poll(row: Record<string, number>): void {
    const gl = this.gl;
    const rows = this.rows!;
    const base = rows.length ? rows[0].frame : 0;
    for (const p of this.pending) {
      const r = rows[p.frame - base];
      if (p.fence && r.fenceSeen === undefined) {
        const s = gl.getSyncParameter(p.fence, gl.SYNC_STATUS);
        if (s === gl.SIGNALED) {
          r.fenceSeen = row.now;
          r.fenceSeenFrame = row.frame;
          gl.deleteSync(p.fence);
          p.fence = null;
        }
      }
      for (const k of ['begin', 'end'] as const) {
        const q = p[k];
        if (q && gl.getQueryParameter(q, gl.QUERY_RESULT_AVAILABLE)) {
          r[`gpu_${k}`] = Number(gl.getQueryParameter(q, gl.QUERY_RESULT)) / 1e6;
          r[`gpu_${k}_seen`] = row.now;
          gl.deleteQuery(q);
          p[k] = null;
        }
      }
    }
    this.pending = this.pending.filter((p) => p.fence || p.begin || p.end);
    if (this.pending.length > 200) this.pending.splice(0, this.pending.length - 200);
  }
}
