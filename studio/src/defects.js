// The defect layer: one three.js group per defect kind of an overlay (points,
// segments, triangles in the kind's colour), drawn over the mesh.
import * as THREE from 'three';

// The kinds in the contract's order (doc/studio.md): key, label, colour.
export const KINDS = [
  ['boundary_loops', 'boundary loops', '#1f77b4'],
  ['small_holes', 'small holes', '#17becf'],
  ['non_manifold_edges', 'non-manifold edges', '#d62728'],
  ['non_manifold_vertices', 'non-manifold vertices', '#ff7f0e'],
  ['spikes', 'spiked vertices', '#e377c2'],
  ['near_degenerate_faces', 'near-degenerate faces', '#bcbd22'],
  ['small_components', 'small components', '#9467bd'],
  ['crossing_pairs', 'crossing triangle pairs', '#ff0000'],
  ['t_junctions', 'T-junctions', '#2ca02c'],
];

function geometry(array) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(array, 3));
  return g;
}

// overlay: decoded (Float32Array per primitive). Returns {group, kinds}, where
// kinds[key] = {object, count, label, color, first, firstRadius, drawn, truncated}.
export function buildDefectLayer(overlay) {
  const group = new THREE.Group();
  group.name = 'defects';
  const kinds = {};
  const order = KINDS.map(([k]) => k);
  const keys = Object.keys(overlay.kinds || {}).sort((a, b) => order.indexOf(a) - order.indexOf(b));
  keys.forEach((key, rank) => {
    const k = overlay.kinds[key];
    const color = new THREE.Color(k.color || '#ffffff');
    const object = new THREE.Group();
    object.name = key;
    // later kinds draw over earlier ones (crossing pairs over components)
    object.renderOrder = 10 + rank;
    if (k.triangles && k.triangles.length) {
      const m = new THREE.Mesh(geometry(k.triangles), new THREE.MeshBasicMaterial({
        color, side: THREE.DoubleSide, polygonOffset: true,
        polygonOffsetFactor: -1, polygonOffsetUnits: -2 - rank }));
      m.renderOrder = object.renderOrder;
      object.add(m);
    }
    if (k.segments && k.segments.length) {
      const l = new THREE.LineSegments(geometry(k.segments), new THREE.LineBasicMaterial({ color }));
      l.renderOrder = object.renderOrder;
      object.add(l);
    }
    if (k.points && k.points.length) {
      const p = new THREE.Points(geometry(k.points), new THREE.PointsMaterial({
        color, size: 9, sizeAttenuation: false }));
      p.renderOrder = object.renderOrder;
      object.add(p);
    }
    group.add(object);
    kinds[key] = {
      object, key, count: k.count, label: k.label || key, color: k.color,
      first: k.first || null, firstRadius: k.first_radius || null,
      drawn: k.drawn, truncated: !!k.truncated,
    };
  });
  return { group, kinds };
}

export function disposeGroup(group) {
  group.traverse((o) => {
    if (o.geometry) o.geometry.dispose();
    if (o.material) o.material.dispose();
  });
}
