/**
 * The frame loop (requestAnimationFrame): steps the simulation by the time that passed, moves the sweep on, draws
 * only when something changed, and measures the frame rate; the energy plot and the HUD text are refreshed a few
 * times a second.
 */
import { FRAME_DT, type PosedCollider } from '../core/index.js';
import { captionFor } from '../ui/captions.js';
import type { App } from './app.js';
import { GpuSim } from '../three/sim/gpu-sim.js';
import { webGpuBackend } from '../three/sim/solver-buffers.js';
import { ContactBudget } from './contact-budget.js';
import { hudInfo } from './hud-feed.js';

/** The requestAnimationFrame loop, and what it measures (fps, first frame). */
export class FrameLoop {
  private lastTime = 0;
  private fpsFrames = 0;
  private fpsTime = 0;
  /** frames drawn per second, over the last half second */
  fps = 0;
  /** nothing was drawn in the last half second (paused and untouched) */
  idle = false;
  private hudTime = 0;
  private plotTime = 0;
  /** every cloth's colliders and each one's cloth's time [s], refilled when the view is redrawn (no allocation) */
  private readonly posed: PosedCollider[] = [];
  private readonly posedTimes: number[] = [];
  /** performance.now() when the first frame was drawn */
  firstFrameAt = 0;

  constructor(private readonly app: App) {}

  /** One display frame; it asks for the next one itself (start it with requestAnimationFrame). */
  readonly frame = (now: number): void => {
    const app = this.app;
    requestAnimationFrame(this.frame);
    const dt = this.lastTime ? now - this.lastTime : 0;
    this.lastTime = now;
    app.sim.tick(dt, now);
    app.sweep.advance();
    app.slots.syncViews();
    if (app.sim instanceof GpuSim && !app.sim.lost) {
      const backend = webGpuBackend(app.stage.renderer);
      app.views.forEach((v, k) => {
        const solver = (app.sim as GpuSim).solverOf(k);
        if (backend && solver && !v.attached && v.model === app.sim.mirrors[k].sim.model) {
          v.attachGpu(backend, solver.positionBuffer, solver.normalBuffer);
          app.dirty = true;
        }
      });
      // a recording takes every frame's positions (paused, a step reads its frames back itself)
      app.sim.eagerReadback = (app.recorder.active && !app.sim.paused) || app.views.some((v) => v.needsCpuPositions);
    }
    const redraw = app.dirty;
    if (app.dirty) {
      app.sim.mirrors.forEach((m, k) => app.views[k]?.update(m.sim.state, m.grabbed));
      // colliders that move are drawn where they are at their cloth's time (the mirrors hold the same keyframes)
      const posed = this.posed, times = this.posedTimes;
      posed.length = 0;
      times.length = 0;
      for (const m of app.sim.mirrors) {
        for (const c of m.sim.params.colliders) {
          posed.push(c);
          times.push(m.frame * FRAME_DT);
        }
      }
      app.stage.poseColliders(posed, times);
      app.dirty = false;
    }
    const moved = app.stage.updateControls();
    // draw only when something changed: a paused, untouched view costs nothing
    const draw = !app.stage.busy && (redraw || moved || app.stage.needsRender || !this.firstFrameAt);
    if (draw) {
      app.labels.place();
      app.stage.render();
      this.fpsFrames++;
      if (!this.firstFrameAt) {
        this.firstFrameAt = performance.now();
        performance.mark('drape:first-frame');
      }
    }
    if (now - this.fpsTime >= 500) {
      this.fps = (1000 * this.fpsFrames) / (now - this.fpsTime);
      this.idle = this.fpsFrames === 0;
      this.fpsFrames = 0;
      this.fpsTime = now;
    }
    if (now - this.plotTime >= 100 && !app.sim.paused) {
      this.plotTime = now;
      app.hud.sample(app.sim.stats.energy);
    }
    if (now - this.hudTime >= 250) {
      this.hudTime = now;
      if (app.contactBudget.watch(now, app.scene.solver.selfContact, app.sim.paused, app.sim.stats.stepMs)) {
        const ms = app.sim.stats.stepMs;
        if (app.commands.setPath('solver.selfContact', false)) {
          app.panel.sync(); // the panel's switch shows it (setPath leaves the panel to the control that asked)
          app.overlay.message(ContactBudget.message(ms), 'notice');
        }
      }
      app.hud.update(hudInfo(app, this.fps, this.idle));
      app.layout.caption.set(captionFor(app.sceneKey, app.scene.description));
    }
  };
}
