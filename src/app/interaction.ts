/**
 * Pointer input on the 3D view (mouse, pen and touch alike, through pointer events):
 * - press on the cloth: grab the particle under the cursor and pull it in the plane facing the camera; release
 *   lets it go with the velocity it was moved with (the core keeps it);
 * - with the pin tool on, a click on the cloth pins or unpins that particle instead;
 * - press elsewhere: left to OrbitControls (orbit, pan, zoom, pinch).
 * The handlers listen in the capture phase on the element OrbitControls listens on, and swallow the presses they
 * take, so orbiting never starts while grabbing (not even with a second finger).
 */
import { Plane, Raycaster, Vector2, Vector3, type PerspectiveCamera } from 'three/webgpu';
import { pickParticle, type PickHit } from '../core/index.js';
import type { Mirror, SimDriver } from '../three/sim/sim-client.js';

/** how close to a pin marker a pin-tool click must be to unpin it [CSS px] */
const PIN_MARKER_PX = 10;

export interface InteractionHost {
  readonly sim: SimDriver;
  readonly camera: PerspectiveCamera;
  readonly pinTool: boolean;
  togglePin(slot: number, particle: number): void;
  /** called when a grab starts or ends (for the cursor and the HUD) */
  grabChanged(active: boolean): void;
}

export interface SlotHit extends PickHit {
  slot: number;
}

export class Interaction {
  private readonly raycaster = new Raycaster();
  private readonly plane = new Plane();
  private readonly ndc = new Vector2();
  private readonly tmp = new Vector3();
  private grab: { pointer: number; slot: number; particle: number; offset: Vector3 } | null = null;

  constructor(private readonly el: HTMLElement, private readonly host: InteractionHost) {
    el.addEventListener('pointerdown', this.down, { capture: true });
    el.addEventListener('pointermove', this.move, { capture: true });
    el.addEventListener('pointerup', this.up, { capture: true });
    el.addEventListener('pointercancel', this.up, { capture: true });
    el.addEventListener('lostpointercapture', this.up);
  }

  get grabbing(): boolean {
    return this.grab !== null;
  }

  private ray(e: { clientX: number; clientY: number }): Raycaster {
    const r = this.el.getBoundingClientRect();
    this.ndc.set(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
    this.raycaster.setFromCamera(this.ndc, this.host.camera);
    return this.raycaster;
  }

  /** The nearest cloth particle under a point of the view, over all cloths. */
  pick(clientX: number, clientY: number): SlotHit | null {
    const { origin, direction } = this.ray({ clientX, clientY }).ray;
    const o: [number, number, number] = [origin.x, origin.y, origin.z];
    const d: [number, number, number] = [direction.x, direction.y, direction.z];
    let best: SlotHit | null = null;
    this.host.sim.mirrors.forEach((m: Mirror, slot) => {
      const hit = pickParticle(m.sim.model, m.sim.state, o, d);
      if (hit && (!best || hit.t < best.t)) best = { ...hit, slot };
    });
    return best;
  }

  /** The pinned particle drawn nearest to a point of the view, within `px` CSS pixels. */
  pinnedNear(clientX: number, clientY: number, px: number): { slot: number; particle: number } | null {
    const r = this.el.getBoundingClientRect();
    let best: { slot: number; particle: number } | null = null, bestD = px;
    this.host.sim.mirrors.forEach((m, slot) => {
      const { pinned, positions: x } = m.sim.state;
      for (let i = 0; i < pinned.length; i++) {
        if (!pinned[i]) continue;
        this.tmp.set(x[3 * i], x[3 * i + 1], x[3 * i + 2]).project(this.host.camera);
        if (this.tmp.z > 1) continue;
        const d = Math.hypot(r.left + ((this.tmp.x + 1) / 2) * r.width - clientX, r.top + ((1 - this.tmp.y) / 2) * r.height - clientY);
        if (d < bestD) { bestD = d; best = { slot, particle: i }; }
      }
    });
    return best;
  }

  private readonly down = (e: PointerEvent): void => {
    if (this.grab) {
      // a second finger while grabbing: neither orbit nor pinch
      e.stopImmediatePropagation();
      e.preventDefault();
      return;
    }
    if (e.button !== 0) return;
    if (this.host.pinTool) {
      // a click on (or next to) a pin marker unpins it, even where the cloth hangs in front of it
      const marker = this.pinnedNear(e.clientX, e.clientY, PIN_MARKER_PX);
      const target = marker ?? this.pick(e.clientX, e.clientY);
      if (!target) return;
      e.stopImmediatePropagation();
      e.preventDefault();
      this.host.togglePin(target.slot, target.particle);
      return;
    }
    const hit = this.pick(e.clientX, e.clientY);
    if (!hit) return;
    e.stopImmediatePropagation();
    e.preventDefault();
    const m = this.host.sim.mirrors[hit.slot];
    const x = m.sim.state.positions, i = 3 * hit.particle;
    const p = new Vector3(x[i], x[i + 1], x[i + 2]);
    // drag in the plane through the particle facing the camera; keep the offset from the hit point
    this.host.camera.getWorldDirection(this.tmp);
    this.plane.setFromNormalAndCoplanarPoint(this.tmp, p);
    const offset = p.clone().sub(new Vector3(...hit.point));
    this.grab = { pointer: e.pointerId, slot: hit.slot, particle: hit.particle, offset };
    try { this.el.setPointerCapture(e.pointerId); } catch { /* synthetic events */ }
    this.host.sim.grab(hit.slot, hit.particle, [p.x, p.y, p.z]);
    this.host.grabChanged(true);
  };

  private readonly move = (e: PointerEvent): void => {
    const g = this.grab;
    if (!g) return;
    if (e.pointerId !== g.pointer) { e.stopImmediatePropagation(); return; }
    e.stopImmediatePropagation();
    const hit = this.ray(e).ray.intersectPlane(this.plane, this.tmp);
    if (!hit) return;
    hit.add(g.offset);
    this.host.sim.grab(g.slot, g.particle, [hit.x, hit.y, hit.z]);
  };

  private readonly up = (e: PointerEvent): void => {
    const g = this.grab;
    if (!g || e.pointerId !== g.pointer) return;
    e.stopImmediatePropagation();
    this.grab = null;
    try { this.el.releasePointerCapture(e.pointerId); } catch { /* already released */ }
    this.host.sim.release(g.slot);
    this.host.grabChanged(false);
  };

  /** Ends a grab without a pointer event (scene change, reset). */
  cancel(): void {
    if (!this.grab) return;
    const g = this.grab;
    this.grab = null;
    if (g.slot < this.host.sim.mirrors.length) this.host.sim.release(g.slot);
    this.host.grabChanged(false);
  }
}
