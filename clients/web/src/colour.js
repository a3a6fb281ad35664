// The model's colour as the demo draws it, from a papernet.net/2 document (README "The net",
// docs/colour.md), without three.js (so it is tested in Node): per face corner texture
// coordinates and vertex colours laid out like foldPositions' corners (face i's corner k at
// 3i + k), the faces grouped by what they are drawn with, and the turn that stands a model up.

/**
 * The turn from the model's frame into the demo's scene (z up), as a rigid 3×4 row-major matrix
 * (fold.js's): glTF is y up (its +z, the model's front, faces the viewer at -y), so y becomes z;
 * every other format is drawn as its coordinates say (STL, PLY and OFF are mostly z up).
 * `format` is the job's `input.format` (glb, gltf, obj, ...).
 */
export function sceneFrame(format) {
  if (format === "glb" || format === "gltf") return [1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0];
  return [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0];
}

/** Corner texture coordinates (glTF's: v down from the image's top): 6 numbers per face, 0 where null. */
export function cornerUvs(doc) {
  const faces = doc.mesh.faces;
  const uvs = doc.mesh.uvs;
  const out = new Float32Array(faces.length * 6);
  if (!uvs) return out;
  faces.forEach((_, i) => {
    const f = uvs[i];
    if (!f) return;
    for (let k = 0; k < 3; ++k) {
      out[i * 6 + k * 2] = f[k][0];
      out[i * 6 + k * 2 + 1] = f[k][1];
    }
  });
  return out;
}

/** Corner vertex colours, linear RGB, 9 numbers per face (white where null), or null when the net has none. */
export function cornerColors(doc) {
  const colors = doc.mesh.colors;
  if (!colors || !colors.some((c) => c)) return null;
  const n = doc.mesh.faces.length;
  const out = new Float32Array(n * 9).fill(1);
  for (let i = 0; i < n; ++i) {
    const f = colors[i];
    if (!f) continue;
    for (let k = 0; k < 3; ++k) for (let c = 0; c < 3; ++c) out[i * 9 + k * 3 + c] = f[k][c];
  }
  return out;
}

/**
 * What each face is drawn with: its material (an index into `materials`, -1 for none) and
 * whether its texture is mapped by the face's own coordinates (`textured`) or stood in for by
 * its colour (faces of an approximate piece carry no coordinates: null). A face with no material
 * in a model that has materials takes the one most faces have (an approximate piece's faces have
 * none of their own). Returns the groups, each {material, textured, faces}, in a fixed order.
 */
export function faceGroups(doc) {
  const n = doc.mesh.faces.length;
  const materials = doc.materials ?? [];
  const uvs = doc.mesh.uvs;
  const own = doc.mesh.face_materials ?? [];
  const valid = (m) => Number.isInteger(m) && m >= 0 && m < materials.length;
  const count = new Map();
  for (const m of own) if (valid(m)) count.set(m, (count.get(m) ?? 0) + 1);
  let common = materials.length > 0 ? 0 : -1;
  for (const [m, c] of count) if (c > (count.get(common) ?? 0)) common = m;
  const groups = new Map();
  for (let i = 0; i < n; ++i) {
    const material = valid(own[i]) ? own[i] : common;
    const texture = material >= 0 ? materials[material].texture : null;
    const textured = Number.isInteger(texture) && texture >= 0 && !!uvs?.[i];
    const key = `${material}/${textured}`;
    if (!groups.has(key)) groups.set(key, { material, textured, faces: [] });
    groups.get(key).faces.push(i);
  }
  return [...groups.values()].sort((a, b) => a.material - b.material || Number(b.textured) - Number(a.textured));
}
