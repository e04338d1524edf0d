/**
 * The page's denoise scheduling (src/app/liveDenoise.ts) against a fake
 * tracer and a denoiser whose answers the test releases: milestones, only
 * still views, results shown only for the accumulation they were read
 * from, a worker replaced when its work went stale, the final state when
 * rendering stops, and a failing denoiser turning the toggle off.
 */
import { describe, expect, it } from 'vitest';
import type { Denoiser, DenoiseInput } from '../../src/denoise/denoiser';
import { GUIDE_SAMPLES, LiveDenoiser, milestoneAtOrBelow, type DenoiseState } from '../../src/app/liveDenoise';
import type { PathTracer } from '../../src/render/PathTracer';

class FakeTracer {
  readonly width = 4;
  readonly height = 2;
  generation = 0;
  samples = 0;
  shown: Float32Array | null = null;
  aovs: [boolean, number?] = [false];
  reads = 0;
  lost = false;

  accumulation() {
    return this.lost ? null : { generation: this.generation, samples: this.samples };
  }
  readLinear() {
    this.reads++;
    return new Float32Array(this.width * this.height * 4).fill(this.samples);
  }
  readAovs() {
    const guide = new Float32Array(this.width * this.height * 4);
    return { albedo: guide, normal: guide, samples: Math.min(this.samples, GUIDE_SAMPLES) };
  }
  showImage(linear: Float32Array | null) {
    this.shown = linear;
  }
  get showsImage() {
    return this.shown !== null;
  }
  setAovs(enabled: boolean, maxSamples?: number) {
    this.aovs = [enabled, maxSamples];
  }
  on() {
    return () => {};
  }
  /** A camera move: accumulation starts again and the shown image is dropped (as PathTracer.reset does). */
  restart() {
    this.generation++;
    this.samples = 0;
    this.shown = null;
  }
}

/** A denoiser whose calls wait until the test answers them; its output is the colour + 1000. */
class FakeDenoiser implements Denoiser {
  readonly backend = 'fake';
  disposed = false;
  calls: { input: DenoiseInput; answer: () => void; fail: (error: Error) => void }[] = [];
  denoise(input: DenoiseInput): Promise<Float32Array> {
    return new Promise((resolve, reject) => {
      this.calls.push({ input, answer: () => resolve(input.color.map((v) => v + 1000)), fail: reject });
    });
  }
  dispose() {
    this.disposed = true;
  }
}

const settle = () => new Promise((resolve) => setTimeout(resolve, 0));

function setUp(options: { failToStart?: boolean } = {}) {
  const tracer = new FakeTracer();
  const view = { denoise: false };
  const page = { moving: false, stopped: false, redisplays: 0 };
  const workers: FakeDenoiser[] = [];
  const denoiser = new LiveDenoiser(
    tracer as unknown as PathTracer,
    view,
    { moving: () => page.moving, stopped: () => page.stopped, redisplay: () => page.redisplays++ },
    async () => {
      if (options.failToStart) throw new Error('denoiser: no backend available: WebAssembly could not start');
      workers.push(new FakeDenoiser());
      return workers[workers.length - 1];
    },
  );
  const states: DenoiseState[] = [];
  const failures: string[] = [];
  denoiser.onState = (state) => states.push(state);
  denoiser.onFailure = (message) => failures.push(message);
  /** Renders up to `spp` (one frame per sample) and lets promises run. */
  const renderTo = async (spp: number) => {
    while (tracer.samples < spp) {
      denoiser.tick();
      tracer.samples++;
      await settle();
    }
    denoiser.tick();
    await settle();
  };
  const lastState = () => states[states.length - 1];
  return { tracer, view, page, workers, denoiser, states, failures, renderTo, lastState };
}

describe('live denoising on the page', () => {
  it('has milestones at 4, 16, 64, 256... spp', () => {
    expect([0, 1, 3, 4, 15, 16, 63, 64, 255, 256, 1023, 1024].map(milestoneAtOrBelow)).toEqual([0, 0, 0, 4, 4, 16, 16, 64, 64, 256, 256, 1024]);
  });

  it('denoises the still view at each milestone, one read-back each, and shows the result', async () => {
    const { tracer, view, workers, renderTo, lastState } = setUp();
    view.denoise = true;
    await renderTo(3);
    expect(tracer.aovs).toEqual([true, GUIDE_SAMPLES]);
    expect(workers).toHaveLength(1);
    expect(workers[0].calls).toHaveLength(0);
    expect(lastState()).toMatchObject({ shown: 'raw' });
    await renderTo(4);
    expect(workers[0].calls).toHaveLength(1);
    expect(tracer.reads).toBe(1);
    expect(lastState().text).toBe('raw; denoising 4 spp…');
    await renderTo(10); // the worker is still busy: nothing new is read back
    expect(tracer.reads).toBe(1);
    workers[0].calls[0].answer();
    await settle();
    expect(tracer.shown?.[0]).toBe(1004);
    expect(lastState()).toMatchObject({ shown: 'denoised', spp: 4 });
    expect(lastState().text).toMatch(/^denoised at 4 spp \(\d+\.\d s\)$/);
    await renderTo(15);
    expect(workers[0].calls).toHaveLength(1);
    await renderTo(16);
    expect(workers[0].calls).toHaveLength(2);
    expect(lastState().text).toMatch(/^denoised at 4 spp \(.*\); denoising 16 spp…$/);
  });

  it('starts from the current state when a milestone passed while the worker was busy', async () => {
    const { tracer, view, workers, renderTo } = setUp();
    view.denoise = true;
    await renderTo(4);
    await renderTo(20);
    workers[0].calls[0].answer();
    await settle();
    await renderTo(21);
    expect(workers[0].calls).toHaveLength(2);
    expect(workers[0].calls[1].input.color[0]).toBe(20);
    expect(tracer.reads).toBe(2);
  });

  it('never shows a result read before a restart, and replaces a worker busy with stale work', async () => {
    const { tracer, view, workers, renderTo, lastState } = setUp();
    view.denoise = true;
    await renderTo(4);
    // The result comes back after a restart the page has not yet ticked through.
    tracer.restart();
    workers[0].calls[0].answer();
    await settle();
    expect(tracer.shown).toBeNull();
    await renderTo(4);
    expect(workers[0].calls).toHaveLength(2);
    // A restart seen while the worker is busy: a fresh worker takes the next milestone.
    tracer.restart();
    await renderTo(1);
    expect(lastState()).toMatchObject({ shown: 'raw' });
    expect(workers).toHaveLength(2);
    expect(workers[0].disposed).toBe(true);
    workers[0].calls[1].answer(); // the old worker answers anyway (it was terminated): ignored
    await settle();
    expect(tracer.shown).toBeNull();
    await renderTo(4);
    expect(workers[1].calls).toHaveLength(1);
    workers[1].calls[0].answer();
    await settle();
    expect(tracer.shown?.[0]).toBe(1004);
  });

  it('waits while the view moves, and denoises the final state when rendering stops', async () => {
    const { tracer, view, page, workers, denoiser, renderTo } = setUp();
    view.denoise = true;
    page.moving = true;
    await renderTo(5);
    expect(workers[0].calls).toHaveLength(0);
    page.moving = false;
    denoiser.tick();
    await settle();
    expect(workers[0].calls.map((c) => c.input.color[0])).toEqual([5]);
    workers[0].calls[0].answer();
    await renderTo(7);
    expect(workers[0].calls).toHaveLength(1); // no milestone between 5 and 7
    page.stopped = true; // paused, or the target spp reached: the last state is final
    denoiser.tick();
    await settle();
    expect(workers[0].calls.map((c) => c.input.color[0])).toEqual([5, 7]);
    workers[0].calls[1].answer();
    await settle();
    denoiser.tick();
    expect(workers[0].calls).toHaveLength(2);
    expect(tracer.shown?.[0]).toBe(1007);
  });

  it('turning the toggle off shows the raw image and stops keeping guides', async () => {
    const { tracer, view, page, workers, renderTo, lastState } = setUp();
    view.denoise = true;
    await renderTo(4);
    workers[0].calls[0].answer();
    await settle();
    expect(tracer.showsImage).toBe(true);
    view.denoise = false;
    const redisplays = page.redisplays;
    await renderTo(5);
    expect(tracer.shown).toBeNull();
    expect(tracer.aovs[0]).toBe(false);
    expect(page.redisplays).toBeGreaterThan(redisplays);
    expect(workers[0].disposed).toBe(true);
    expect(lastState()).toEqual({ shown: 'raw', text: '', spp: 0 });
  });

  it('turns the toggle off with a message when no denoiser can start, or when one fails', async () => {
    const broken = setUp({ failToStart: true });
    broken.view.denoise = true;
    await broken.renderTo(2);
    expect(broken.view.denoise).toBe(false);
    expect(broken.failures).toEqual(['denoiser: no backend available: WebAssembly could not start']);
    expect(broken.tracer.aovs[0]).toBe(false);
    expect(broken.tracer.samples).toBe(2); // the samples are untouched

    const failing = setUp();
    failing.view.denoise = true;
    await failing.renderTo(4);
    failing.workers[0].calls[0].fail(new Error('denoiser worker failed: out of memory'));
    await settle();
    expect(failing.view.denoise).toBe(false);
    expect(failing.failures).toEqual(['denoiser worker failed: out of memory']);
  });
});
