/**
 * Grabbing a world's cloths with the pointer (mouse, pen, touch): a press on a cloth grabs the particle under it,
 * dragging pulls it across the plane through it that faces the camera (keeping the offset from the point pressed),
 * and letting go releases it (it keeps its velocity). A press that misses the cloths is left to the page's other
 * listeners (orbit controls); the events of a grab are not passed on (the listeners run in the capture phase, before
 * theirs). The pointer handling is the app's own (pointer-drag.ts).
 */
import { Vector3, type Camera } from 'three';
import { PointerDrag, type DragHit } from './pointer-drag.js';
import type { DrapeHit, DrapeWorld } from './world.js';

export interface PointerGrabOptions {
  /** called when a grab starts (true) and ends (false): e.g. to turn orbit controls off meanwhile. Default: none */
  onGrab?: (grabbing: boolean) => void;
}

export class PointerGrab {
  private readonly drag: PointerDrag<DrapeHit & DragHit>;

  /** Listens on `element` (the renderer's canvas) for the pointer, picking through `camera`; `dispose()` stops. */
  constructor(world: DrapeWorld, camera: Camera, element: HTMLElement, options: PointerGrabOptions = {}) {
    if (!element || typeof element.addEventListener !== 'function') throw new TypeError('PointerGrab: element must be an HTMLElement (the renderer\'s canvas)');
    this.drag = new PointerDrag(element, () => camera, {
      pick(raycaster) {
        const hit = world.pick(raycaster);
        return hit && { ...hit, position: new Vector3().fromArray(hit.cloth.positions, 3 * hit.particle) };
      },
      grab: (hit, target) => world.grab(hit, target),
      drag: (_hit, target) => world.drag(target),
      release: () => world.release(),
    }, { onGrab: options.onGrab });
  }

  /** Stops listening (and lets go of a grab in progress). */
  dispose(): void {
    this.drag.dispose();
  }
}
