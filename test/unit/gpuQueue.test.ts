/**
 * The render loop's bound on its work in flight (src/app/gpuWork.ts:
 * GpuQueue, pathsWithRoom), against a simulated GPU with synthetic fences
 * and no clock: the page's commands reach the GPU late and in batches, the
 * GPU gives the loop only a part of its time, and a fence is seen passed
 * some milliseconds after its work, at the next frame. The work in flight
 * never passes the limit, whatever the GPU's speed or the batching, and a
 * GPU that runs behind is kept busy.
 */
import { describe, expect, it } from 'vitest';
import { type FenceSource, GpuQueue, pathsWithRoom } from '../../src/app/gpuWork';
import { random } from '../support/random';

/** Synthetic fences: numbers; `passedUpTo` says which have passed (as the page would see them). */
class Fences implements FenceSource<number> {
  next = 0;
  passedUpTo = -1;
  live = new Set<number>();
  insert(): number {
    this.live.add(this.next);
    return this.next++;
  }
  passed(fence: number): boolean {
    return fence <= this.passedUpTo;
  }
  remove(fence: number): void {
    this.live.delete(fence);
  }
}

interface GpuModel {
  /** Wall milliseconds per path of the loop's work on the GPU (the budget's estimate is `estimate` times it). */
  msPerPath: number;
  estimate: number;
  /** The fraction of the GPU's time the loop's work gets (the compositor, other pages take the rest). */
  share: number;
  /** Commands reach the GPU only every `batchFrames` frames (held, then released together). */
  batchFrames: number;
  /** A passed fence is seen this long after its work is done (and only at a frame's start). */
  seenMs: number;
}

const FRAME_MS = 1000 / 60;
const TARGET_MS = 35;
const LIMIT_MS = 2 * TARGET_MS;

/**
 * Runs the loop's submission rule for `frames` frames of 60 Hz against the
 * model. Returns the largest wall milliseconds of work ever queued on the
 * GPU or held before it (submitted and not done), and the fraction of the
 * GPU's time for the loop that it spent on the loop's work.
 */
function simulate(model: GpuModel, frames: number, seed = 1) {
  const rand = random(seed);
  const fences = new Fences();
  const queue = new GpuQueue(fences);
  const costPerPath = model.msPerPath * model.estimate;
  const budgetPaths = TARGET_MS / costPerPath;
  // Work submitted: its fence, wall ms, when it reached the GPU and when it is done (null until known).
  const work: { fence: number; ms: number; arrives: number; done: number | null }[] = [];
  let gpuFree = 0;
  let mostQueued = 0;
  for (let f = 0; f < frames; f++) {
    const now = f * FRAME_MS;
    // The GPU runs what has reached it, in order, at its share of the time.
    for (const w of work) {
      if (w.done !== null || w.arrives > now) continue;
      const start = Math.max(gpuFree, w.arrives);
      w.done = start + w.ms / model.share;
      gpuFree = w.done;
    }
    // Fences of work done at least seenMs ago are seen passed.
    for (const w of work) if (w.done !== null && w.done + model.seenMs <= now) fences.passedUpTo = Math.max(fences.passedUpTo, w.fence);
    const queued = work.filter((w) => w.done === null || w.done > now).reduce((sum, w) => sum + w.ms, 0);
    mostQueued = Math.max(mostQueued, queued);
    const paths = pathsWithRoom({ budgetPaths, costPerPath, pendingMs: queue.poll(), limitMs: LIMIT_MS, frameMs: TARGET_MS, leastPaths: 1024 });
    if (paths > 0) {
      queue.submitted(paths * costPerPath);
      // Held until the next batch is released.
      const arrives = (Math.floor(f / model.batchFrames) + 1) * model.batchFrames * FRAME_MS + rand();
      const ms = paths * model.msPerPath * (0.9 + 0.2 * rand());
      work.push({ fence: fences.next - 1, ms, arrives, done: null });
    }
  }
  const end = frames * FRAME_MS;
  const doneMs = work.filter((w) => w.done !== null && w.done <= end).reduce((sum, w) => sum + w.ms, 0);
  return { mostQueued, utilization: doneMs / (end * model.share), live: fences.live.size };
}

describe('GpuQueue and pathsWithRoom', () => {
  it('never has more than the limit of work in flight, however late and batched the commands', () => {
    for (const batchFrames of [1, 3, 6]) {
      for (const share of [1, 0.6, 0.25]) {
        const model = { msPerPath: 3e-3, estimate: 1, share, batchFrames, seenMs: 10 };
        const { mostQueued, live } = simulate(model, 600);
        // The predicted ms of a frame is within the noise of its work (+-10%).
        expect(mostQueued, JSON.stringify(model)).toBeLessThanOrEqual(1.1 * LIMIT_MS);
        // The passed fences were freed: at most those of the work in flight (frames of 1024 paths or more).
        expect(live).toBeLessThanOrEqual(Math.ceil(LIMIT_MS / (1024 * model.msPerPath)));
      }
    }
  });

  it('keeps a GPU that runs behind busy when fences are seen soon after their work', () => {
    for (const share of [1, 0.6, 0.25]) {
      const model = { msPerPath: 3e-3, estimate: 1, share, batchFrames: 1, seenMs: 15 };
      const { utilization } = simulate(model, 600);
      expect(utilization, JSON.stringify(model)).toBeGreaterThan(0.85);
    }
  });

  it('bounds the queue by what was predicted: an estimate too low lets through only its error', () => {
    // The budget thinks a path costs half what it does: the queue holds at most twice the limit, not more and more.
    const { mostQueued } = simulate({ msPerPath: 3e-3, estimate: 0.5, share: 0.6, batchFrames: 3, seenMs: 10 }, 600);
    expect(mostQueued).toBeLessThanOrEqual(2.2 * LIMIT_MS);
  });

  it('pathsWithRoom: the budget, cut to the room; a whole frame or nothing before the cost is known', () => {
    const base = { budgetPaths: 10_000, costPerPath: 3e-3, pendingMs: 0, limitMs: 70, frameMs: 35, leastPaths: 1024 };
    expect(pathsWithRoom(base)).toBe(10_000);
    expect(pathsWithRoom({ ...base, pendingMs: 50 })).toBe(Math.floor(20 / 3e-3));
    expect(pathsWithRoom({ ...base, pendingMs: 68 })).toBe(0); // room for 666 paths: left unused
    expect(pathsWithRoom({ ...base, pendingMs: 80 })).toBe(0);
    expect(pathsWithRoom({ ...base, budgetPaths: 500, pendingMs: 68 })).toBe(500); // a budget smaller than leastPaths still goes
    expect(pathsWithRoom({ ...base, costPerPath: null, pendingMs: 35 })).toBe(10_000);
    expect(pathsWithRoom({ ...base, costPerPath: null, pendingMs: 36 })).toBe(0);
  });

  it('GpuQueue: fences pass in order, a newer one passed frees the older ones; reset frees the rest unless the context was lost', () => {
    const fences = new Fences();
    const queue = new GpuQueue(fences);
    queue.submitted(10);
    queue.submitted(20);
    queue.submitted(30);
    expect(queue.poll()).toBe(60);
    fences.passedUpTo = 1; // the second passed: the first did too
    expect(queue.poll()).toBe(30);
    expect([...fences.live]).toEqual([2]);
    queue.submitted(5);
    queue.reset();
    expect(queue.pendingMs).toBe(0);
    expect(fences.live.size).toBe(0);
    queue.submitted(5);
    queue.reset(true); // a lost context took its fences with it
    expect(fences.live.size).toBe(1);
    // A fence that never signals is given up after maxPolls polls (with all before it).
    const stuck = new GpuQueue(fences, 3);
    stuck.submitted(7);
    stuck.submitted(8);
    for (let i = 0; i < 3; i++) expect(stuck.poll()).toBe(15);
    expect(stuck.poll()).toBe(0);
    // Work without a fence is not counted: nothing would say when it is done.
    const none = new GpuQueue<number>({ insert: () => null, passed: () => true, remove: () => undefined });
    none.submitted(50);
    expect(none.poll()).toBe(0);
  });
});
