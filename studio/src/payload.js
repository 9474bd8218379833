// Decoding of the arrays the studio server and the HTML report send:
// base64 float32/uint32 (little-endian) in JSON, and the binary mesh format
// of the studio API.

// base64 -> ArrayBuffer (null and '' give an empty buffer)
export function base64ToBuffer(b64) {
  if (!b64) return new ArrayBuffer(0);
  const bin = atob(b64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return bytes.buffer;
}

export const f32 = (b64) => new Float32Array(base64ToBuffer(b64));
export const u32 = (b64) => new Uint32Array(base64ToBuffer(b64));

// A mesh of the report payload: {positions: b64 f32, indices: b64 u32, faces, decimated}
export function decodePayloadMesh(m) {
  return { positions: f32(m.positions), indices: u32(m.indices), faces: m.faces,
           decimated: !!m.decimated };
}

// The studio's binary mesh (GET /api/mesh/...): a 16-byte header of four
// little-endian uint32 (vertices n, triangles m, faces of the full mesh,
// flags: bit 0 = decimated preview), then 3n float32 positions, then 3m
// uint32 indices.
export function decodeBinaryMesh(buffer) {
  const h = new DataView(buffer, 0, 16);
  const n = h.getUint32(0, true), m = h.getUint32(4, true);
  const faces = h.getUint32(8, true), flags = h.getUint32(12, true);
  const positions = new Float32Array(buffer, 16, 3 * n);
  const indices = new Uint32Array(buffer, 16 + 12 * n, 3 * m);
  return { positions, indices, faces, decimated: (flags & 1) !== 0 };
}

// An overlay as sent in JSON: the arrays of each kind decoded in place (a copy).
export function decodeOverlay(overlay) {
  if (!overlay || !overlay.kinds) return { kinds: {} };
  const kinds = {};
  for (const [key, k] of Object.entries(overlay.kinds)) {
    kinds[key] = { ...k, points: f32(k.points), segments: f32(k.segments), triangles: f32(k.triangles) };
  }
  return { kinds };
}

// SHA-256 (hex) of a mesh's arrays as the page holds them: the float32
// positions' bytes followed by the uint32 indices' bytes. The browser tests
// compare it with the same hash computed by Python from the library's mesh.
export async function meshHash(mesh) {
  const a = new Uint8Array(mesh.positions.buffer, mesh.positions.byteOffset, mesh.positions.byteLength);
  const b = new Uint8Array(mesh.indices.buffer, mesh.indices.byteOffset, mesh.indices.byteLength);
  const all = new Uint8Array(a.length + b.length);
  all.set(a, 0);
  all.set(b, a.length);
  const digest = await crypto.subtle.digest('SHA-256', all);
  return Array.from(new Uint8Array(digest), (x) => x.toString(16).padStart(2, '0')).join('');
}
