// A cloth from `drape/three` dropped on your own scene: your renderer, camera, lights and meshes; Drape adds
// colliders made from two of the meshes and a cloth mesh to draw. Drag the cloth to pull it; drag elsewhere to orbit.
import { BoxGeometry, Color, DirectionalLight, HemisphereLight, Mesh, MeshStandardMaterial, PerspectiveCamera, Scene, SphereGeometry } from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { WebGPURenderer } from 'three/webgpu';
import { DrapeWorld, PointerGrab } from 'drape/three';

const renderer = new WebGPURenderer({ antialias: true }); // WebGPU where there is an adapter, else WebGL2
renderer.setPixelRatio(Math.min(devicePixelRatio, 2));
renderer.setSize(innerWidth, innerHeight);
document.body.append(renderer.domElement);
await renderer.init();

const scene = new Scene();
scene.background = new Color(0xe8ecf1);
const camera = new PerspectiveCamera(45, innerWidth / innerHeight, 0.05, 50);
camera.position.set(1.4, 1.3, 2);
const controls = new OrbitControls(camera, renderer.domElement);
controls.target.set(0, 0.45, 0);
controls.update();
const sun = new DirectionalLight(0xffffff, 2);
sun.position.set(2, 4, 3);
scene.add(new HemisphereLight(0xffffff, 0x8a7f74, 1.5), sun);

// your meshes: a ball on a table
const ball = new Mesh(new SphereGeometry(0.3, 48, 32), new MeshStandardMaterial({ color: 0xb5473a, roughness: 0.5 }));
ball.position.set(0, 0.5, 0);
const table = new Mesh(new BoxGeometry(1.6, 0.2, 1.6), new MeshStandardMaterial({ color: 0x8d6e63 }));
table.position.set(0, 0.1, 0);
scene.add(ball, table);

// the cloth: a world on your renderer (its WebGPU device, else a worker), colliders from your meshes
// 'auto' simulates on the GPU unless it is a software one (then in a worker); ?backend=gpu insists on the GPU
const backend = new URLSearchParams(location.search).get('backend') === 'gpu' ? 'gpu' : 'auto';
const world = new DrapeWorld({ renderer, backend });
world.addCollider(ball); // a sphere, inferred from its geometry
world.addCollider(table); // a box
const cloth = world.addCloth({ fabric: 'silk', width: 1.1, height: 1.1, resolution: 24, position: [0, 1.05, 0] });
scene.add(cloth);
new PointerGrab(world, camera, renderer.domElement, { onGrab: (grabbing) => { controls.enabled = !grabbing; } });

addEventListener('resize', () => {
  camera.aspect = innerWidth / innerHeight;
  camera.updateProjectionMatrix();
  renderer.setSize(innerWidth, innerHeight);
});
renderer.setAnimationLoop(() => {
  world.update(); // steps by the time since the last frame, in fixed 1/60 s steps
  renderer.render(scene, camera);
});

// for the browser tests (e2e/three.e2e.ts): ?testhook puts the world on the window
if (new URLSearchParams(location.search).has('testhook')) Object.assign(window, { drapeExample: { world, cloth, ball, camera } });
