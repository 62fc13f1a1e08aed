/**
 * Dragging a cloth's particle with the pointer (mouse, pen, touch, through pointer events), for the addon's
 * `PointerGrab` and the app's pointer input alike: a press on a cloth grabs the particle under it where it is, and
 * dragging pulls it across the plane through it that faces the camera, keeping the offset from the point pressed (so
 * it does not jump to the pointer); letting go — or losing the pointer capture — releases it (it keeps its velocity).
 * The listeners run in the capture phase and swallow the events of a grab, and a second finger's meanwhile, so
 * orbit controls on the same element never turn during one; a press that misses the cloths is left to them.
 */
import { Plane, Raycaster, Vector2, Vector3, type Camera } from 'three';

/** A particle a ray met: `point` where the ray met its cloth, `position` where the particle is [m]. */
export interface DragHit {
  readonly point: Vector3;
  readonly position: Vector3;
}

/** What is dragged: how a ray picks a particle, and how it is grabbed, pulled and let go. */
export interface DragTarget<H extends DragHit> {
  pick(raycaster: Raycaster): H | null;
  grab(hit: H, target: Vector3): void;
  drag(hit: H, target: Vector3): void;
  release(hit: H): void;
}

export interface PointerDragOptions {
  /**
   * Sees a primary press first (none while a grab is on): returns true to take it itself (the app's pin tool),
   * which then grabs nothing and is not passed on. Default: none
   */
  press?: (e: PointerEvent, raycaster: Raycaster) => boolean;
  /** called when a grab starts (true) and ends (false). Default: none */
  onGrab?: (grabbing: boolean) => void;
}

export class PointerDrag<H extends DragHit> {
  private readonly raycaster = new Raycaster();
  private readonly ndc = new Vector2();
  private readonly plane = new Plane();
  private readonly at = new Vector3();
  private grabbed: { pointer: number; hit: H; offset: Vector3 } | null = null;

  /** Listens on `element` (the renderer's canvas), picking through `camera()`; `dispose()` stops. */
  constructor(private readonly element: HTMLElement, private readonly camera: () => Camera, private readonly target: DragTarget<H>,
    private readonly options: PointerDragOptions = {}) {
    element.addEventListener('pointerdown', this.down, { capture: true });
    element.addEventListener('pointermove', this.move, { capture: true });
    element.addEventListener('pointerup', this.up, { capture: true });
    element.addEventListener('pointercancel', this.up, { capture: true });
    element.addEventListener('lostpointercapture', this.up);
  }

  /** whether a particle is held */
  get grabbing(): boolean {
    return this.grabbed !== null;
  }

  /** The ray from the camera through a point of the element [CSS px, client coordinates]. */
  ray(clientX: number, clientY: number): Raycaster {
    const r = this.element.getBoundingClientRect();
    this.ndc.set(((clientX - r.left) / r.width) * 2 - 1, -((clientY - r.top) / r.height) * 2 + 1);
    this.raycaster.setFromCamera(this.ndc, this.camera());
    return this.raycaster;
  }

  private readonly down = (e: PointerEvent): void => {
    if (this.grabbed) {
      // a second finger while grabbing: neither orbit nor pinch
      swallow(e);
      return;
    }
    // the primary pointer's press only: a second finger that lands while the first orbits is the orbit's (a pinch)
    if (e.button !== 0 || e.isPrimary === false) return;
    const ray = this.ray(e.clientX, e.clientY);
    if (this.options.press?.(e, ray)) { swallow(e); return; }
    const hit = this.target.pick(ray);
    if (!hit) return;
    swallow(e);
    this.camera().getWorldDirection(this.at);
    this.plane.setFromNormalAndCoplanarPoint(this.at, hit.position);
    this.target.grab(hit, hit.position.clone());
    this.grabbed = { pointer: e.pointerId, hit, offset: hit.position.clone().sub(hit.point) };
    try { this.element.setPointerCapture(e.pointerId); } catch { /* a synthetic event's pointer */ }
    this.options.onGrab?.(true);
  };

  private readonly move = (e: PointerEvent): void => {
    const g = this.grabbed;
    if (!g) return;
    e.stopImmediatePropagation();
    if (e.pointerId !== g.pointer) return;
    if (!this.ray(e.clientX, e.clientY).ray.intersectPlane(this.plane, this.at)) return;
    this.target.drag(g.hit, this.at.add(g.offset));
  };

  private readonly up = (e: PointerEvent): void => {
    const g = this.grabbed;
    if (!g) return;
    e.stopImmediatePropagation();
    if (e.pointerId !== g.pointer) return;
    this.end();
  };

  /** Lets go of a grab without a pointer event (a scene change, a reset). */
  cancel(): void {
    if (this.grabbed) this.end();
  }

  /** Stops listening, and lets go of a grab in progress. */
  dispose(): void {
    this.element.removeEventListener('pointerdown', this.down, { capture: true });
    this.element.removeEventListener('pointermove', this.move, { capture: true });
    this.element.removeEventListener('pointerup', this.up, { capture: true });
    this.element.removeEventListener('pointercancel', this.up, { capture: true });
    this.element.removeEventListener('lostpointercapture', this.up);
    this.cancel();
  }

  private end(): void {
    const g = this.grabbed!;
    // (let go first: releasing the capture may send lostpointercapture at once)
    this.grabbed = null;
    try { this.element.releasePointerCapture(g.pointer); } catch { /* released already */ }
    this.target.release(g.hit);
    this.options.onGrab?.(false);
  }
}

/** The event is this handler's: no other listener sees it, and the browser does nothing with it. */
function swallow(e: Event): void {
  e.stopImmediatePropagation();
  e.preventDefault();
}
