// The 3-D view: bodies drawn as their parts in their body frames, body axes, trails, contact
// points and force arrows, with an orbit camera (three.js).
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';

const COLORS = [0x4e79a7, 0xf28e2b, 0x59a14f, 0xe15759, 0x76b7b2, 0xedc948, 0xb07aa1, 0xff9da7];
export const FORCE_COLORS = {
  reaction: 0x1f5fbf,
  normal: 0x2e9d3a,
  friction: 0xe07b00,
  applied: 0xb02a9a,
};

/** A three.js quaternion from [w, x, y, z]. */
export function quat(q) {
  return new THREE.Quaternion(q[1], q[2], q[3], q[0]);
}

function dim(p, key, i = 0) {
  const v = p.dimensions[key];
  return Array.isArray(v) ? v[i] : v;
}

/** A rough size of a part [m], for the scene's scale and for thin shapes' thickness. */
export function partSize(p) {
  const d = p.dimensions || {};
  let s = 0;
  for (const v of Object.values(d)) for (const x of [].concat(v)) s = Math.max(s, Math.abs(x));
  if (p.mesh) {
    const a = p.mesh.positions;
    for (let i = 0; i < a.length; i++) s = Math.max(s, Math.abs(a[i]));
  }
  if (p.ellipsoid) s = Math.max(s, ...p.ellipsoid.semi_axes);
  return s;
}

/**
 * The geometry of a part in its own frame P (docs/scene-format.md, shapes: axes of symmetry
 * along z; three.js builds cylinders and cones along y, so they are turned by +90° about x).
 */
function partGeometry(p, thin) {
  const zUp = (g) => g.rotateX(Math.PI / 2);
  if (p.ellipsoid) {
    // A part of mass and inertia only: the uniform ellipsoid with the same inertia.
    const [a, b, c] = p.ellipsoid.semi_axes.map((x) => Math.max(x, thin / 2));
    return new THREE.SphereGeometry(1, 32, 16).scale(a, b, c);
  }
  switch (p.shape) {
    case 'box':
      return new THREE.BoxGeometry(dim(p, 'size', 0), dim(p, 'size', 1), dim(p, 'size', 2));
    case 'plate':
      return new THREE.BoxGeometry(dim(p, 'size', 0), dim(p, 'size', 1), thin);
    case 'sphere':
    case 'spherical_shell':
      return new THREE.SphereGeometry(dim(p, 'radius'), 32, 16);
    case 'thick_spherical_shell':
      return new THREE.SphereGeometry(dim(p, 'outer_radius'), 32, 16);
    case 'hemisphere':
    case 'hemispherical_shell':
      return zUp(new THREE.SphereGeometry(dim(p, 'radius'), 32, 8, 0, 2 * Math.PI, 0, Math.PI / 2));
    case 'ellipsoid': {
      const g = new THREE.SphereGeometry(1, 32, 16);
      return g.scale(dim(p, 'semi_axes', 0), dim(p, 'semi_axes', 1), dim(p, 'semi_axes', 2));
    }
    case 'cylinder':
    case 'cylindrical_shell':
      return zUp(new THREE.CylinderGeometry(dim(p, 'radius'), dim(p, 'radius'), dim(p, 'length'), 32));
    case 'tube':
      return zUp(
        new THREE.CylinderGeometry(dim(p, 'outer_radius'), dim(p, 'outer_radius'), dim(p, 'length'), 32),
      );
    case 'disk':
      return zUp(new THREE.CylinderGeometry(dim(p, 'radius'), dim(p, 'radius'), thin, 48));
    case 'ring':
      return new THREE.TorusGeometry(dim(p, 'radius'), thin / 2, 8, 64);
    case 'torus':
    case 'toroidal_shell':
      return new THREE.TorusGeometry(dim(p, 'major_radius'), dim(p, 'minor_radius'), 16, 64);
    case 'rod': {
      const r = Math.max(thin / 2, 0.015 * dim(p, 'length'));
      return zUp(new THREE.CylinderGeometry(r, r, dim(p, 'length'), 12));
    }
    case 'cone':
    case 'conical_shell': {
      // Origin at the centre of the base, apex at +z; a conical shell is open unless closed.
      const h = dim(p, 'height');
      const open = p.shape === 'conical_shell' && !p.dimensions.closed;
      const g = new THREE.ConeGeometry(dim(p, 'radius'), h, 32, 1, open);
      g.translate(0, h / 2, 0);
      return zUp(g);
    }
    case 'triangular_prism': {
      const v = p.dimensions.vertices;
      const s = new THREE.Shape();
      s.moveTo(v[0], v[1]);
      s.lineTo(v[2], v[3]);
      s.lineTo(v[4], v[5]);
      s.closePath();
      const L = dim(p, 'length');
      const g = new THREE.ExtrudeGeometry(s, { depth: L, bevelEnabled: false });
      return g.translate(0, 0, -L / 2);
    }
    case 'mesh': {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(p.mesh.positions, 3));
      g.setIndex(new THREE.BufferAttribute(p.mesh.indices, 1));
      g.computeVertexNormals();
      return g;
    }
    default:
      // point, custom, planar: a marker.
      return new THREE.SphereGeometry(thin, 12, 8);
  }
}

/** A body as a group in its body frame B: its parts, axes, centre of mass and named points. */
export function makeBody(body, index, scale) {
  const group = new THREE.Group();
  group.name = body.name;
  const color = COLORS[index % COLORS.length];
  const thin = Math.max(0.01 * scale, 1e-6);
  for (const p of body.parts) {
    const g = partGeometry(p, p.shape === 'point' || p.shape === 'custom' ? 2 * thin : thin);
    const material = p.subtract
      ? new THREE.MeshStandardMaterial({ color: 0xcc3333, transparent: true, opacity: 0.35, wireframe: true })
      : new THREE.MeshStandardMaterial({
          color,
          roughness: 0.6,
          metalness: 0.1,
          side: THREE.DoubleSide,
          transparent: true,
          opacity: 0.85,
        });
    const mesh = new THREE.Mesh(g, material);
    mesh.position.fromArray(p.ellipsoid ? p.ellipsoid.center : p.position);
    mesh.quaternion.copy(quat(p.ellipsoid ? p.ellipsoid.quaternion : p.quaternion));
    mesh.name = p.name;
    group.add(mesh);
    const edges = new THREE.LineSegments(
      new THREE.EdgesGeometry(g, 30),
      new THREE.LineBasicMaterial({ color: 0x222222, transparent: true, opacity: 0.35 }),
    );
    edges.position.copy(mesh.position);
    edges.quaternion.copy(mesh.quaternion);
    group.add(edges);
  }
  const axes = new THREE.AxesHelper(0.35 * scale);
  axes.material.depthTest = false;
  axes.material.transparent = true;
  axes.renderOrder = 2;
  group.add(axes);
  const cm = new THREE.Mesh(
    new THREE.SphereGeometry(1.5 * thin, 12, 8),
    new THREE.MeshBasicMaterial({ color: 0x000000 }),
  );
  cm.position.fromArray(body.center_of_mass);
  group.add(cm);
  for (const pt of body.points || []) {
    const m = new THREE.Mesh(
      new THREE.SphereGeometry(thin, 8, 6),
      new THREE.MeshBasicMaterial({ color: 0x555555 }),
    );
    m.position.fromArray(pt.position);
    group.add(m);
  }
  return group;
}

/** An arrow for a force: from `origin`, along `force` scaled by `scale` [m/N]. */
export class ForceArrow {
  constructor(color, parent, head) {
    this.head = head;
    this.arrow = new THREE.ArrowHelper(new THREE.Vector3(1, 0, 0), new THREE.Vector3(), 1, color);
    // Drawn over the (translucent) bodies: transparent objects are drawn after opaque ones,
    // in renderOrder.
    for (const m of [this.arrow.line.material, this.arrow.cone.material]) {
      m.depthTest = false;
      m.transparent = true;
    }
    this.arrow.renderOrder = 3;
    parent.add(this.arrow);
  }

  set(origin, force, scale) {
    this.shown = { origin: Array.from(origin), force: Array.from(force) };
    const f = new THREE.Vector3(force[0], force[1], force[2]);
    const L = f.length() * scale;
    if (!(L > 1e-12)) {
      this.arrow.visible = false;
      return;
    }
    this.arrow.visible = true;
    this.arrow.position.set(origin[0], origin[1], origin[2]);
    this.arrow.setDirection(f.normalize());
    this.arrow.setLength(L, Math.min(0.3 * L, 0.08 * this.head), Math.min(0.2 * L, 0.05 * this.head));
  }
}

/** The renderer, camera, lights and controls of a view in `container`. */
export class View {
  constructor(container, { planar, center, size, floor }) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setClearColor(0xf7f7f4);
    container.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(40, 1, size * 1e-3, size * 1e3);
    // z up (the chapter's world frame); a planar scene is seen from +z onto its x-y plane.
    if (planar) {
      this.camera.up.set(0, 1, 0);
      this.camera.position.set(center[0], center[1], center[2] + 2.9 * size);
    } else {
      this.camera.up.set(0, 0, 1);
      this.camera.position.set(center[0] + 1.5 * size, center[1] - 2.2 * size, center[2] + 1.0 * size);
    }
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.target.set(center[0], center[1], center[2]);
    this.controls.update();
    this.controls.addEventListener('change', () => this.render());
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x888877, 1.6));
    const sun = new THREE.DirectionalLight(0xffffff, 1.4);
    sun.position.set(size, -size, 2 * size).add(new THREE.Vector3(...center));
    this.scene.add(sun);
    const axes = new THREE.AxesHelper(0.5 * size);
    axes.position.set(0, 0, 0);
    this.scene.add(axes);
    // A grid in W's x-y plane under everything (a planar scene: behind it), 20 squares across.
    const step = 10 ** Math.floor(Math.log10(size / 4));
    const n = Math.max(2, Math.round((6 * size) / step / 2) * 2);
    const grid = new THREE.GridHelper(n * step, n, 0xb0b0a8, 0xd8d8d0);
    grid.rotateX(Math.PI / 2);
    grid.position.set(
      Math.round(center[0] / step) * step,
      Math.round(center[1] / step) * step,
      planar ? Math.min(floor, 0) - 1e-3 * size : floor,
    );
    this.scene.add(grid);
    this.resize();
    window.addEventListener('resize', () => {
      this.resize();
      this.render();
    });
  }

  resize() {
    const w = Math.max(this.container.clientWidth, 100);
    const h = Math.max(this.container.clientHeight, 100);
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
  }

  /** A square of the plane through `point` with unit `normal`, `size` across. */
  addPlane(point, normal, size) {
    const g = new THREE.PlaneGeometry(size, size, 10, 10);
    const m = new THREE.Mesh(
      g,
      new THREE.MeshStandardMaterial({ color: 0xc9c4b5, side: THREE.DoubleSide, transparent: true, opacity: 0.5 }),
    );
    m.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), new THREE.Vector3(...normal).normalize());
    m.position.set(...point);
    this.scene.add(m);
    const grid = new THREE.LineSegments(
      new THREE.WireframeGeometry(g),
      new THREE.LineBasicMaterial({ color: 0x999988, transparent: true, opacity: 0.4 }),
    );
    grid.quaternion.copy(m.quaternion);
    grid.position.copy(m.position);
    this.scene.add(grid);
  }

  render() {
    this.renderer.render(this.scene, this.camera);
  }
}

export { THREE };
