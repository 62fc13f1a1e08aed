/**
 * Pointer input on the 3D view (mouse, pen and touch alike, through pointer events), on the addon's pointer
 * handling (src/three/pointer-drag.ts, as `PointerGrab` uses it):
 * - press on the cloth: grab the particle under the cursor and pull it in the plane facing the camera; release
 *   lets it go with the velocity it was moved with (the core keeps it);
 * - with the pin tool on, a click on the cloth pins or unpins that particle instead;
 * - press elsewhere: left to OrbitControls (orbit, pan, zoom, pinch).
 * The handlers listen in the capture phase on the element OrbitControls listens on, and swallow the presses they
 * take, so orbiting never starts while grabbing (not even with a second finger).
 */
import { Vector3, type PerspectiveCamera } from 'three/webgpu';
import { pickParticle, type PickHit } from '../core/index.js';
import { PointerDrag, type DragHit } from '../three/pointer-drag.js';
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

/** A grab's particle: its slot and number, where it was pressed and where it is [m]. */
interface GrabHit extends DragHit {
  readonly slot: number;
  readonly particle: number;
}

export class Interaction {
  private readonly tmp = new Vector3();
  private readonly drag: PointerDrag<GrabHit>;

  constructor(private readonly el: HTMLElement, private readonly host: InteractionHost) {
    this.drag = new PointerDrag(el, () => host.camera, {
      pick: (raycaster) => {
        const hit = this.pickRay(raycaster.ray.origin, raycaster.ray.direction);
        if (!hit) return null;
        const x = host.sim.mirrors[hit.slot].sim.state.positions, i = 3 * hit.particle;
        return { slot: hit.slot, particle: hit.particle, point: new Vector3(...hit.point), position: new Vector3(x[i], x[i + 1], x[i + 2]) };
      },
      grab: (hit, p) => host.sim.grab(hit.slot, hit.particle, [p.x, p.y, p.z]),
      drag: (hit, p) => host.sim.grab(hit.slot, hit.particle, [p.x, p.y, p.z]),
      // (a scene change may have taken the slot away)
      release: (hit) => { if (hit.slot < host.sim.mirrors.length) host.sim.release(hit.slot); },
    }, {
      press: (e) => {
        if (!host.pinTool) return false;
        // a click on (or next to) a pin marker unpins it, even where the cloth hangs in front of it
        const target = this.pinnedNear(e.clientX, e.clientY, PIN_MARKER_PX) ?? this.pick(e.clientX, e.clientY);
        if (!target) return false;
        host.togglePin(target.slot, target.particle);
        return true;
      },
      onGrab: (active) => host.grabChanged(active),
    });
  }

  get grabbing(): boolean {
    return this.drag.grabbing;
  }

  /** The nearest cloth particle under a point of the view, over all cloths. */
  pick(clientX: number, clientY: number): SlotHit | null {
    const { origin, direction } = this.drag.ray(clientX, clientY).ray;
    return this.pickRay(origin, direction);
  }

  private pickRay(origin: Vector3, direction: Vector3): SlotHit | null {
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

  /** Ends a grab without a pointer event (scene change, reset). */
  cancel(): void {
    this.drag.cancel();
  }
}
