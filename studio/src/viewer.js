// The WebGL viewer: a "before" and an "after" scene sharing one camera, drawn
// side by side (split) or one at a time (toggled with a key), flat or
// wireframe, each with its defect layer. Renders on demand.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { buildDefectLayer, disposeGroup } from './defects.js';

const SIDES = ['before', 'after'];

function makeSide(name) {
  const scene = new THREE.Scene();
  scene.background = new THREE.Color('#20242b');
  scene.add(new THREE.HemisphereLight('#ffffff', '#555a66', 1.6));
  const light = new THREE.DirectionalLight('#ffffff', 1.4);
  light.position.set(1, 2, 3);
  scene.add(light);
  return { name, scene, light, mesh: null, meshData: null, defects: null, hidden: new Set() };
}

function finiteBox(p) {
  const box = new THREE.Box3();
  const v = new THREE.Vector3();
  for (let i = 0; i + 2 < p.length; i += 3) {
    if (Number.isFinite(p[i]) && Number.isFinite(p[i + 1]) && Number.isFinite(p[i + 2])) box.expandByPoint(v.set(p[i], p[i + 1], p[i + 2]));
  }
  return box;
}

export class Viewer {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setScissorTest(true);
    container.appendChild(this.renderer.domElement);
    this.canvas = this.renderer.domElement;
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    this.camera.position.set(0, 0, 5);
    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.addEventListener('change', () => this.requestRender());
    this.sides = { before: makeSide('before'), after: makeSide('after') };
    this.layout = 'split';   // 'split' | 'single'
    this.shown = 'after';    // the side drawn in 'single' layout
    this.wireframe = false;
    this.listeners = [];
    this.pending = false;
    this.flight = null;
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  onChange(f) { this.listeners.push(f); }
  emit() { for (const f of this.listeners) f(this); }

  resize() {
    const w = Math.max(1, this.container.clientWidth), h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
    this.canvas.style.width = w + 'px';
    this.canvas.style.height = h + 'px';
    this.requestRender();
  }

  // The sides on screen, in left-to-right order.
  visibleSides() {
    if (this.layout === 'split' && this.sides.after.mesh) return ['before', 'after'];
    if (!this.sides.after.mesh) return ['before'];
    return [this.shown];
  }

  // mesh: {positions: Float32Array, indices: Uint32Array, faces, decimated}
  setMesh(side, mesh) {
    const s = this.sides[side];
    const columns = this.visibleSides().length;
    if (s.mesh) {
      s.scene.remove(s.mesh);
      s.mesh.geometry.dispose();
      s.mesh.material.dispose();
      s.mesh = null;
    }
    s.meshData = mesh;
    if (mesh) {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(mesh.positions, 3));
      g.setIndex(new THREE.BufferAttribute(mesh.indices, 1));
      // the bounds of the finite positions (a NaN vertex must not lose the camera)
      g.boundingBox = finiteBox(mesh.positions);
      g.boundingSphere = g.boundingBox.isEmpty() ? new THREE.Sphere() : g.boundingBox.getBoundingSphere(new THREE.Sphere());
      const material = new THREE.MeshStandardMaterial({
        color: side === 'before' ? '#b9bec8' : '#c8c2b4', flatShading: true, roughness: 0.8,
        metalness: 0.0, side: THREE.DoubleSide, wireframe: this.wireframe,
        polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
      s.mesh = new THREE.Mesh(g, material);
      s.scene.add(s.mesh);
    }
    // the viewports changed width (a first result beside the input): frame again
    if (this.visibleSides().length !== columns) this.frameAll();
    this.requestRender();
    this.emit();
  }

  clearSide(side) {
    this.setMesh(side, null);
    this.setDefects(side, null);
  }

  // overlay: decoded (see payload.js); null removes the layer
  setDefects(side, overlay) {
    const s = this.sides[side];
    if (s.defects) {
      s.scene.remove(s.defects.group);
      disposeGroup(s.defects.group);
      s.defects = null;
    }
    if (overlay) {
      s.defects = buildDefectLayer(overlay);
      s.scene.add(s.defects.group);
      this.applyVisibility(side);
    }
    this.requestRender();
    this.emit();
  }

  // a defect kind on or off on both sides
  setKindVisible(key, visible) {
    for (const side of SIDES) {
      if (visible) this.sides[side].hidden.delete(key); else this.sides[side].hidden.add(key);
      this.applyVisibility(side);
    }
    this.requestRender();
  }

  applyVisibility(side) {
    const s = this.sides[side];
    if (!s.defects) return;
    for (const [key, k] of Object.entries(s.defects.kinds)) k.object.visible = !s.hidden.has(key);
  }

  setWireframe(on) {
    this.wireframe = on;
    for (const side of SIDES) if (this.sides[side].mesh) this.sides[side].mesh.material.wireframe = on;
    this.requestRender();
    this.emit();
  }

  setLayout(layout) {
    const columns = this.visibleSides().length;
    this.layout = layout;
    if (this.visibleSides().length !== columns) this.frameAll();
    this.requestRender();
    this.emit();
  }
  toggleShown() {
    if (this.layout === 'split') this.layout = 'single';
    else this.shown = this.shown === 'after' ? 'before' : 'after';
    this.requestRender();
    this.emit();
  }

  // the camera frames both meshes
  frameAll() {
    const box = new THREE.Box3();
    for (const side of SIDES) if (this.sides[side].mesh) box.union(this.sides[side].mesh.geometry.boundingBox);
    if (box.isEmpty()) return;
    const sphere = box.getBoundingSphere(new THREE.Sphere());
    this.place(sphere.center, sphere.radius, new THREE.Vector3(0.6, 0.45, 1).normalize());
  }

  // the distance at which a sphere of radius r fills the narrower field of view of a viewport
  fitDistance(r) {
    const aspect = this.canvas.width / this.visibleSides().length / Math.max(1, this.canvas.height);
    const v = THREE.MathUtils.degToRad(this.camera.fov) / 2;
    const h = Math.atan(Math.tan(v) * aspect);
    return r / Math.sin(Math.min(v, h));
  }

  place(center, radius, direction) {
    const r = Math.max(radius, 1e-6);
    const distance = this.fitDistance(r) * 1.05;
    this.camera.near = distance / 1000;
    this.camera.far = distance * 100;
    this.camera.position.copy(center).addScaledVector(direction, distance);
    this.controls.target.copy(center);
    this.camera.updateProjectionMatrix();
    this.controls.update();
    this.requestRender();
  }

  // flies the camera to a point, framing a sphere of the given radius, keeping the view direction
  flyTo(point, radius, duration = 600) {
    const center = new THREE.Vector3(...point);
    const size = this.sceneRadius();
    const r = Math.max(radius || 0, size * 0.03);
    const dir = this.camera.position.clone().sub(this.controls.target).normalize();
    const distance = this.fitDistance(r) * 1.6;
    const fromPos = this.camera.position.clone(), fromTarget = this.controls.target.clone();
    const toPos = center.clone().addScaledVector(dir, distance);
    const start = performance.now();
    this.flight = { center, toPos };
    const step = (now) => {
      const t = Math.min(1, (now - start) / duration);
      const e = t * t * (3 - 2 * t);
      this.camera.position.lerpVectors(fromPos, toPos, e);
      this.controls.target.lerpVectors(fromTarget, center, e);
      this.camera.near = Math.min(this.camera.near, distance / 100);
      this.camera.updateProjectionMatrix();
      this.controls.update();
      this.render();
      if (t < 1) requestAnimationFrame(step); else this.flight = null;
    };
    requestAnimationFrame(step);
  }

  sceneRadius() {
    let r = 0;
    for (const side of SIDES) {
      const m = this.sides[side].mesh;
      if (m && m.geometry.boundingSphere) r = Math.max(r, m.geometry.boundingSphere.radius);
    }
    return r || 1;
  }

  requestRender() {
    if (this.pending) return;
    this.pending = true;
    requestAnimationFrame(() => { this.pending = false; this.render(); });
  }

  render() {
    const w = this.canvas.width, h = this.canvas.height;
    const sides = this.visibleSides();
    const vw = Math.floor(w / sides.length);
    this.camera.aspect = vw / h;
    this.camera.updateProjectionMatrix();
    sides.forEach((side, i) => {
      const s = this.sides[side];
      s.light.position.copy(this.camera.position).sub(this.controls.target).normalize()
        .add(new THREE.Vector3(0.3, 0.5, 0)).multiplyScalar(10).add(this.controls.target);
      // the renderer's viewport is in CSS pixels
      const ratio = this.renderer.getPixelRatio();
      this.renderer.setViewport(i * vw / ratio, 0, vw / ratio, h / ratio);
      this.renderer.setScissor(i * vw / ratio, 0, vw / ratio, h / ratio);
      this.renderer.render(s.scene, this.camera);
    });
  }

  // renders now and waits for the GPU (for timings)
  renderNow() {
    this.render();
    this.renderer.getContext().finish();
  }

  png() {
    this.render();
    return this.canvas.toDataURL('image/png');
  }
}
