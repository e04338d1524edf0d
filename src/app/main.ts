// Placeholder page: renders the default scene progressively.
import { PathTracer } from '../render/PathTracer';
import { defaultScene } from '../scene/presets';

const canvas = document.querySelector<HTMLCanvasElement>('[data-testid="viewport"]')!;
const spp = document.querySelector<HTMLElement>('[data-testid="spp"]')!;
const tracer = new PathTracer(canvas, defaultScene());
function frame() {
  tracer.render(1);
  tracer.display({ toneMap: 'aces' });
  spp.textContent = String(tracer.sampleCount);
  requestAnimationFrame(frame);
}
requestAnimationFrame(frame);
