/**
 * The three.js stage: renderer (WebGPU, or WebGL2 when WebGPU is absent or its device is lost), camera and orbit
 * controls, studio lighting with soft shadows, backdrop, floor and the collider shapes of the current scene.
 */
import {
  Color, DirectionalLight, DoubleSide, Fog, Group, HemisphereLight, Matrix4, Mesh, MeshStandardNodeMaterial,
  PCFShadowMap, PerspectiveCamera, PlaneGeometry, ACESFilmicToneMapping, Scene as ThreeScene, Vector3, WebGPURenderer,
} from 'three/webgpu';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import type { PosedCollider } from '../core/index.js';
import { isSoftwareAdapter, type AdapterInfoLike } from '../gpu/adapter.js';
import { colliderGeometry } from './collider-geometry.js';
import { backdropTexture, floorTexture, repaintTextures } from './textures.js';

export type BackendName = 'webgpu' | 'webgl2';
export type CameraPreset = 'front' | 'side' | 'top' | 'reset';

export interface StageOptions {
  /** skip WebGPU altogether */
  forceWebGL?: boolean;
  /** cheaper rendering (no MSAA, smaller shadow map, pixel ratio 1): for software rasterisers and tests */
  lite?: boolean;
  /** called when a WebGPU device is lost after start-up (the stage has already switched to WebGL2) */
  onFallback?: (reason: string) => void;
  /** called when the device was lost and WebGL2 failed too */
  onFallbackFailed?: (message: string) => void;
}

export class Stage {
  renderer!: WebGPURenderer;
  backend: BackendName = 'webgl2';
  /** the WebGPU adapter is a software fallback (e.g. SwiftShader): it can draw and compute, but slower than the CPU */
  softwareAdapter = false;
  readonly scene = new ThreeScene();
  readonly camera = new PerspectiveCamera(40, 1, 0.05, 200);
  readonly controls: OrbitControls;
  /** colliders and cloths live here */
  readonly content = new Group();
  private readonly colliderGroup = new Group();
  private readonly floor: Mesh;
  private readonly key: DirectionalLight;
  private readonly solidMaterial = new MeshStandardNodeMaterial({ color: 0xcfc8bd, roughness: 0.42, metalness: 0.0 });
  /** a tilted plane's large quad and a mesh collider's open shells are seen from both sides */
  private readonly twoSidedMaterial = new MeshStandardNodeMaterial({ color: 0xcfc8bd, roughness: 0.42, metalness: 0.0, side: DoubleSide });
  /** the scene collider each drawn mesh shows (an index into setColliders' list) */
  private drawn: { mesh: Mesh; index: number }[] = [];
  private readonly poseR = new Float64Array(9);
  private readonly poseO = new Float64Array(3);
  private readonly poseM = new Matrix4();
  private readonly poseBefore = new Matrix4();
  /** centre and size of what the camera frames */
  private focus = new Vector3(0, 0.6, 0);
  private extent = 1;
  private lost = false;
  private disposing = false;
  private switching: Promise<void> | null = null;

  private constructor(readonly container: HTMLElement, private readonly options: StageOptions) {
    const s = this.scene;
    s.background = backdropTexture();
    s.fog = new Fog(new Color('#e3e5e8'), 14, 40);

    // sky above, the light floor's bounce below: a cloth's underside is lit too, not near black
    const hemi = new HemisphereLight(0xf2f5ff, 0xb3a999, 1.25);
    const key = new DirectionalLight(0xfff3e2, 2.3);
    key.castShadow = true;
    key.shadow.mapSize.setScalar(options.lite ? 1024 : 2048);
    key.shadow.radius = 6;
    key.shadow.bias = -0.0004;
    key.shadow.normalBias = 0.02;
    this.key = key;
    const fill = new DirectionalLight(0xd8e6ff, 0.7);
    fill.position.set(-4, 3, -2);
    const rim = new DirectionalLight(0xffffff, 0.6);
    rim.position.set(0, 4, -6);
    // the floor's bounce, from below and in front (no shadow): what a sagging cloth's underside and the shaded
    // half of a collider are lit by in a room
    const bounce = new DirectionalLight(0xf0e4d2, 0.9);
    bounce.position.set(1.5, -4, 2.5);
    s.add(hemi, key, key.target, fill, rim, bounce);

    const fm = new MeshStandardNodeMaterial({ map: floorTexture(), roughness: 0.95, metalness: 0 });
    this.floor = new Mesh(new PlaneGeometry(40, 40), fm);
    this.floor.rotation.x = -Math.PI / 2;
    this.floor.receiveShadow = true;
    this.floor.name = 'floor';
    s.add(this.floor, this.colliderGroup, this.content);

    // Orbit controls listen on the container (not the canvas), so a renderer switch keeps them; the app's
    // pointer handlers are registered on the same element before this, so they can claim a press first.
    this.controls = new OrbitControls(this.camera, container);
    this.controls.enableDamping = true;
    this.controls.dampingFactor = 0.12;
    this.controls.maxPolarAngle = Math.PI * 0.495;
    this.controls.minDistance = 0.3;
    this.controls.maxDistance = 40;
    this.controls.screenSpacePanning = true;
    this.frame(1, new Vector3(0, 0.6, 0));
    this.setCamera('reset');
  }

  static async create(container: HTMLElement, options: StageOptions = {}): Promise<Stage> {
    // calls three.js still has in flight when a WebGPU device dies reject with "Instance dropped…": they are the
    // symptom of the loss handled by deviceLost(), not errors of their own
    window.addEventListener('unhandledrejection', (e) => {
      const r = e.reason as { name?: string; message?: string } | undefined;
      if (r && r.name === 'OperationError' && /Instance dropped|device (was )?(lost|destroyed)/i.test(r.message ?? '')) e.preventDefault();
    });
    const stage = new Stage(container, options);
    await stage.makeRenderer(options.forceWebGL === true);
    return stage;
  }

  private async makeRenderer(forceWebGL: boolean): Promise<void> {
    const canvas = document.createElement('canvas');
    canvas.className = 'drape-canvas';
    this.container.prepend(canvas);
    // the GPU simulation shares this device: ask for the adapter's largest buffers (a 1025² cloth needs ~400 MB)
    let requiredLimits: Record<string, number> | undefined;
    if (!forceWebGL && typeof navigator !== 'undefined' && navigator.gpu) {
      try {
        const adapter = await navigator.gpu.requestAdapter();
        if (adapter) {
          // isFallbackAdapter moved from the adapter to its info
          const a = adapter as unknown as { isFallbackAdapter?: boolean; info?: AdapterInfoLike };
          this.softwareAdapter = isSoftwareAdapter(a.info, a.isFallbackAdapter);
          requiredLimits = {
            maxStorageBufferBindingSize: adapter.limits.maxStorageBufferBindingSize,
            maxBufferSize: adapter.limits.maxBufferSize,
          };
        }
      } catch { /* three.js decides */ }
    }
    const r = new WebGPURenderer({ canvas, antialias: !this.options.lite, forceWebGL, requiredLimits });
    r.onDeviceLost = (info: { message: string; reason: string | null }) => {
      if (this.renderer === r) this.deviceLost(info.reason ? `reason: ${info.reason}` : info.message);
    };
    r.setPixelRatio(this.options.lite ? 1 : Math.min(window.devicePixelRatio, 2));
    r.shadowMap.enabled = true;
    r.shadowMap.type = PCFShadowMap;
    r.toneMapping = ACESFilmicToneMapping;
    r.toneMappingExposure = 1.0;
    try {
      await r.init();
    } catch (e) {
      canvas.remove();
      throw e;
    }
    performance.mark(forceWebGL ? 'drape:renderer-webgl' : 'drape:renderer');
    const old = this.renderer as WebGPURenderer | undefined;
    this.renderer = r;
    this.backend = (r.backend as { isWebGPUBackend?: boolean }).isWebGPUBackend ? 'webgpu' : 'webgl2';
    const device = (r.backend as { device?: GPUDevice }).device;
    if (this.backend === 'webgpu' && device) {
      // three.js ignores a loss with reason 'destroyed', but Chromium reports exactly that when it cannot present
      // to the canvas (no WebGPU context provider): any loss we did not cause ourselves means "switch".
      void device.lost.then((info) => {
        if (this.renderer === r && !this.disposing) this.deviceLost(info.reason ? `reason: ${info.reason}` : info.message || 'no reason given');
      });
    }
    this.resize();
    if (old) {
      this.disposing = true;
      try { old.dispose(); } catch { /* a lost device may refuse */ }
      this.disposing = false;
      old.domElement.remove();
    }
  }

  /** WebGPU device lost: recreate the renderer on WebGL2 (a canvas that had a WebGPU context needs replacing). */
  private deviceLost(reason: string): void {
    if (this.lost) return;
    this.lost = true;

    this.switching = this.switchToWebGL().then(
      () => {
        this.switching = null;
        this.needsRender = true;
        repaintTextures();
        this.options.onFallback?.(reason);
      },
      (e: unknown) => {
        this.options.onFallbackFailed?.(`${reason}; WebGL2 could not start either (${e instanceof Error ? e.message : String(e)})`);
      },
    );
  }

  /** The GPU process may be restarting right after a loss: WebGL2 can fail for a moment, so try a few times. */
  private async switchToWebGL(): Promise<void> {
    for (let attempt = 0; ; attempt++) {
      await new Promise((r) => setTimeout(r, attempt === 0 ? 50 : 400));
      try {
        await this.makeRenderer(true);
        return;
      } catch (e) {
        if (attempt >= 5) throw e;
      }
    }
  }

  /** the renderer's WebGPU device (shared with the GPU simulation), or null on WebGL2 or once lost */
  get device(): GPUDevice | null {
    if (this.backend !== 'webgpu' || this.lost) return null;
    return (this.renderer.backend as { device?: GPUDevice }).device ?? null;
  }

  /** true while a renderer switch is under way (nothing to draw on) */
  get busy(): boolean {
    return this.switching !== null;
  }

  /** width covered by the control panel on the right [CSS px]: the view is centred in what is left */
  insetRight = 0;

  /** the width on the right the view leaves to the panel [CSS px]: insetRight, unless the window is too narrow for it */
  get viewInset(): number {
    const w = Math.max(1, this.container.clientWidth);
    return this.insetRight > 0 && w > 2.5 * this.insetRight ? this.insetRight : 0;
  }

  resize(): void {
    const w = Math.max(1, this.container.clientWidth), h = Math.max(1, this.container.clientHeight);
    this.renderer?.setSize(w, h, true);
    const inset = this.viewInset;
    // render the right part of a wider virtual image, so the principal point sits in the middle of the free area
    this.camera.aspect = (w + inset) / h;
    if (inset) this.camera.setViewOffset(w + inset, h, inset, 0, w, h);
    else this.camera.clearViewOffset();
    this.camera.updateProjectionMatrix();
    this.needsRender = true;
  }

  /**
   * Shows a mesh per sphere, plane (a 20 m square), box, capsule, cylinder and mesh collider, named by its type, its
   * geometry in the shape's own frame (collider-geometry.ts), where the collider is at time 0; the first floor is
   * the stage's ground. `colliders`: the scene's colliders as the simulation built them (its params), in the order
   * poseColliders is given them.
   */
  setColliders(colliders: readonly PosedCollider[]): void {
    for (const c of [...this.colliderGroup.children]) {
      this.colliderGroup.remove(c);
      (c as Mesh).geometry.dispose();
    }
    this.drawn = [];
    this.floorIndex = -1;
    colliders.forEach((c, index) => {
      if (c.type === 'floor') {
        if (this.floorIndex < 0) this.floorIndex = index;
        return;
      }
      const shape = colliderGeometry(c);
      if (!shape) return;
      const m = new Mesh(shape.geometry, shape.twoSided ? this.twoSidedMaterial : this.solidMaterial);
      m.castShadow = true;
      m.receiveShadow = true;
      m.name = c.type;
      this.colliderGroup.add(m);
      this.drawn.push({ mesh: m, index });
    });
    // a scene without a floor still gets a visual ground far below, so the studio does not look empty
    this.floor.quaternion.setFromAxisAngle(new Vector3(1, 0, 0), -Math.PI / 2);
    this.floor.position.set(0, -0.001, 0);
    this.floor.updateMatrix();
    this.floor.visible = true;
    this.poseColliders(colliders, colliders.map(() => 0));
    this.needsRender = true;
  }

  /**
   * Draws the colliders where they are at each one's time [s]: `colliders[k]` is setColliders' k-th spec as the
   * simulation built it (keyframes evaluated here as the physics does: PosedCollider.poseAt; a still one at its
   * placement, which may have changed with the scene), `times[k]` the simulated time of its cloth. Returns whether
   * anything moved.
   */
  poseColliders(colliders: readonly PosedCollider[], times: readonly number[]): boolean {
    let moved = false;
    const R = this.poseR, o = this.poseO, M = this.poseM;
    for (const d of this.drawn) {
      const c = colliders[d.index];
      if (!c) continue;
      c.poseAt(times[d.index] ?? 0, R, o);
      // the shape's own frame (its mesh's geometry is built in it: centred, axis or normal along y)
      M.set(R[0], R[1], R[2], o[0], R[3], R[4], R[5], o[1], R[6], R[7], R[8], o[2], 0, 0, 0, 1);
      const m = d.mesh;
      this.poseBefore.copy(m.matrix);
      M.decompose(m.position, m.quaternion, m.scale);
      m.updateMatrix();
      if (!m.matrix.equals(this.poseBefore)) moved = true;
    }
    // the first floor is the stage's own ground: it moves (rises, tilts) with its collider as the others do; its
    // frame is the half-space y < 0 at (0, height, 0), the ground quad lies in its xy plane
    const floor = this.floorIndex >= 0 ? colliders[this.floorIndex] : undefined;
    if (floor) {
      floor.poseAt(times[this.floorIndex] ?? 0, R, o);
      M.set(R[0], R[1], R[2], o[0], R[3], R[4], R[5], o[1], R[6], R[7], R[8], o[2], 0, 0, 0, 1).multiply(this.groundFix);
      const m = this.floor;
      this.poseBefore.copy(m.matrix);
      M.decompose(m.position, m.quaternion, m.scale);
      m.updateMatrix();
      if (!m.matrix.equals(this.poseBefore)) moved = true;
    }
    if (moved) this.needsRender = true;
    return moved;
  }

  /** the scene's first floor, drawn as the stage's ground (−1: none) */
  private floorIndex = -1;
  private readonly groundFix = new Matrix4().makeRotationX(-Math.PI / 2);

  /** The ground's height at the origin [m] (the first floor's, where it is now). */
  groundHeight(): number {
    return this.floor.position.y;
  }

  /** Where a drawn collider mesh is: its position and quaternion (x, y, z, w), in the scene's order of drawn meshes. */
  colliderPoses(): { position: number[]; quaternion: number[] }[] {
    return this.drawn.map((d) => ({ position: d.mesh.position.toArray(), quaternion: d.mesh.quaternion.toArray() }));
  }

  /** The collider meshes drawn, by type, in the scene's order (the floor is not one: it is the stage's own). */
  colliderNames(): string[] {
    return this.colliderGroup.children.map((c) => c.name);
  }

  /** Fits lights, shadow camera and camera presets around a region [centre, size in m]. */
  frame(extent: number, center: Vector3): void {
    this.extent = Math.max(0.5, extent);
    this.focus.copy(center);
    const e = this.extent;
    const key = this.key;
    key.position.set(center.x + 2.2 * e + 1.5, center.y + 4 * e + 2, center.z + 1.6 * e + 1.5);
    key.target.position.copy(center);
    const cam = key.shadow.camera;
    const half = 0.9 * e + 1;
    cam.left = -half; cam.right = half; cam.top = half; cam.bottom = -half;
    cam.near = 0.5; cam.far = 12 * e + 12;
    cam.updateProjectionMatrix();
  }

  /** what the 'reset' camera preset goes back to */
  defaultView: Exclude<CameraPreset, 'reset'> | 'reset' = 'reset';

  /**
   * Puts the camera at a preset around the focus. Its distance frames the region in a landscape view; a portrait
   * view (a phone) is narrower than high, so the camera backs off by height / width to keep the region's width in it.
   */
  setCamera(preset: CameraPreset): void {
    const w = Math.max(1, this.container.clientWidth - this.viewInset), h = Math.max(1, this.container.clientHeight);
    const c = this.focus, d = (1.6 * this.extent + 1.0) * Math.max(1, h / w);
    const p = this.camera.position;
    if (preset === 'reset' && this.defaultView !== 'reset') preset = this.defaultView;
    switch (preset) {
      case 'front': p.set(c.x, c.y + 0.3 * d, c.z + d); break;
      case 'side': p.set(c.x + d, c.y + 0.25 * d, c.z); break;
      case 'top': p.set(c.x, c.y + 1.25 * d, c.z + 0.001); break;
      case 'reset': p.set(c.x + 0.5 * d, c.y + 0.38 * d, c.z + 0.8 * d); break;
    }
    this.controls.target.copy(c);
    this.camera.lookAt(c);
    this.controls.update();
    this.needsRender = true;
  }

  /** true when something asked for a new frame (camera preset, colliders, renderer switch, resize) */
  needsRender = true;

  /** Moves the camera by the controls' input and damping; true when it moved. */
  updateControls(): boolean {
    return this.controls.update();
  }

  /**
   * The view drawn at `width` × `height` pixels without the panel's part: the camera centred as on screen, without
   * the view offset, the canvas drawn at that size for the copy and put back at once (the copy is taken when toBlob
   * is called). Null when the canvas cannot be read or a renderer switch is under way.
   */
  snapshot(width: number, height: number): Promise<Blob | null> {
    if (this.switching) return Promise.resolve(null);
    const r = this.renderer;
    const ratio = r.getPixelRatio();
    r.setPixelRatio(1);
    r.setSize(width, height, false);
    this.camera.aspect = width / height;
    this.camera.clearViewOffset();
    this.camera.updateProjectionMatrix();
    r.render(this.scene, this.camera);
    const blob = new Promise<Blob | null>((resolve) => r.domElement.toBlob(resolve, 'image/png'));
    r.setPixelRatio(ratio);
    this.resize();
    this.render();
    return blob;
  }

  render(): void {
    if (this.switching) return;
    this.renderer.render(this.scene, this.camera);
    this.needsRender = false;
  }
}
