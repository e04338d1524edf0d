/**
 * The progress display on stderr: a cli-progress bar (samples, rate, time
 * left) when stderr is a terminal, and nothing at all otherwise, so logs and
 * pipes stay clean.
 */
import cliProgress from 'cli-progress';
import type { Budget } from './args';

export interface ProgressUpdate {
  /** Samples per pixel finished so far. */
  spp: number;
  /** Seconds spent rendering so far. */
  elapsed: number;
  /** Samples per pixel per second, as last measured. */
  sppPerSecond: number;
}

export interface Progress {
  /** A one-line status before the bar starts (e.g. "starting Chromium"). */
  status(text: string): void;
  start(): void;
  update(update: ProgressUpdate): void;
  /** Removes the bar (or status line) from the terminal. */
  stop(): void;
}

export interface ProgressStream {
  isTTY?: boolean;
  columns?: number;
  write(chunk: string): boolean;
}

const SILENT: Progress = { status() {}, start() {}, update() {}, stop() {} };

/** A bar for `budget` at `pixels` paths per sample, or a silent stand-in when `stream` is not a TTY. */
export function createProgress(stream: ProgressStream, budget: Budget, pixels: number): Progress {
  if (!stream.isTTY) return SILENT;
  return new TerminalProgress(stream, budget, pixels);
}

class TerminalProgress implements Progress {
  private bar: cliProgress.SingleBar | undefined;
  private statusShown = false;

  constructor(
    private readonly stream: ProgressStream,
    private readonly budget: Budget,
    private readonly pixels: number,
  ) {}

  status(text: string): void {
    this.stream.write(`\r\x1b[K${text}`);
    this.statusShown = true;
  }

  start(): void {
    this.clearStatus();
    const counter = this.budget.kind === 'spp' ? '{value}/{total} spp' : '{spp} spp, {elapsed}/{budget}';
    this.bar = new cliProgress.SingleBar(
      {
        format: `rendering {bar} ${counter} | {rate} | {left} left`,
        stream: this.stream as unknown as NodeJS.WritableStream,
        barsize: 24,
        hideCursor: true,
        clearOnComplete: true,
        fps: 5,
      },
      cliProgress.Presets.shades_classic,
    );
    const total = this.budget.kind === 'spp' ? this.budget.spp : Math.round(this.budget.seconds * 1000);
    this.bar.start(total, 0, this.payload({ spp: 0, elapsed: 0, sppPerSecond: 0 }));
  }

  update(update: ProgressUpdate): void {
    if (!this.bar) return;
    const value = this.budget.kind === 'spp' ? update.spp : Math.round(update.elapsed * 1000);
    this.bar.update(value, this.payload(update));
  }

  stop(): void {
    if (this.bar) {
      this.bar.stop();
      this.bar = undefined;
    }
    this.clearStatus();
  }

  private clearStatus(): void {
    if (this.statusShown) this.stream.write('\r\x1b[K');
    this.statusShown = false;
  }

  private payload(u: ProgressUpdate): Record<string, string | number> {
    const remaining =
      this.budget.kind === 'spp'
        ? u.sppPerSecond > 0
          ? (this.budget.spp - u.spp) / u.sppPerSecond
          : NaN
        : Math.max(0, this.budget.seconds - u.elapsed);
    return {
      spp: u.spp,
      rate: u.sppPerSecond > 0 ? `${formatRate(u.sppPerSecond * this.pixels)} paths/s` : '- paths/s',
      left: formatDuration(remaining),
      elapsed: formatDuration(u.elapsed),
      budget: this.budget.kind === 'time' ? formatDuration(this.budget.seconds) : '',
    };
  }
}

/** 1234567 -> "1.23 M". */
export function formatRate(perSecond: number): string {
  if (!Number.isFinite(perSecond)) return '-';
  const units: [number, string][] = [
    [1e9, ' G'],
    [1e6, ' M'],
    [1e3, ' k'],
  ];
  for (const [scale, suffix] of units) {
    if (perSecond >= scale) return `${(perSecond / scale).toPrecision(3)}${suffix}`;
  }
  return perSecond.toPrecision(3);
}

/** Seconds -> "4.2 s", "3m 05s", "1h 02m"; "-" when unknown. */
export function formatDuration(seconds: number): string {
  if (!Number.isFinite(seconds) || seconds < 0) return '-';
  if (seconds < 60) return `${seconds.toFixed(1)} s`;
  const s = Math.round(seconds);
  if (s < 3600) return `${Math.floor(s / 60)}m ${String(s % 60).padStart(2, '0')}s`;
  return `${Math.floor(s / 3600)}h ${String(Math.floor((s % 3600) / 60)).padStart(2, '0')}m`;
}
