// Folding along the unfold tree: flat at t = 0, a rigid copy of the mesh at t = 1.
import { test } from "node:test";
import assert from "node:assert/strict";
import { prepareFold, foldPositions } from "../src/fold.js";
import { sceneFrame, cornerUvs, cornerColors, faceGroups } from "../src/colour.js";

/** Every corner of vertex v lands on one point, and edge lengths are the mesh's. */
function assertFoldsIntoMesh(doc, positions, tolerance) {
  const { vertices, faces } = doc.mesh;
  const where = new Map();
  faces.forEach((f, i) =>
    f.forEach((v, k) => {
      const p = Array.from(positions.subarray(i * 9 + k * 3, i * 9 + k * 3 + 3));
      if (!where.has(v)) where.set(v, p);
      const q = where.get(v);
      assert.ok(Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) < tolerance, `vertex ${v} of face ${i} lands apart`);
    }),
  );
  for (const [a, b, c] of faces) {
    for (const [u, w] of [[a, b], [b, c], [c, a]]) {
      const d3 = Math.hypot(...[0, 1, 2].map((k) => vertices[u][k] - vertices[w][k]));
      const df = Math.hypot(...[0, 1, 2].map((k) => where.get(u)[k] - where.get(w)[k]));
      assert.ok(Math.abs(d3 - df) < tolerance, `edge ${u}-${w}: ${df} folded, ${d3} in the mesh`);
    }
  }
}

/** A tetrahedron and a hand-made net of it (root face 0, three faces around it). */
function tetrahedron(mirror) {
  const s = Math.sqrt(3);
  const vertices = [[0, 0, 0], [2, 0, 0], [1, s, 0], [1, s / 3, Math.sqrt(8 / 3) * 1]];
  const faces = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
  // Unfolded: the base triangle with the three side faces folded out around it.
  const m = (p) => (mirror ? [p[0], -p[1]] : p);
  const points = [
    [[0, 0], [1, -s], [2, 0]],
    [[0, 0], [2, 0], [1, s]],
    [[2, 0], [1, -s], [3, -s]],
    [[1, -s], [0, 0], [-1, -s]],
  ];
  // Face 0 is drawn mirrored to the others' order when read as (0,2,1): fix orientation per face.
  return {
    format: "papernet.net/2",
    mesh: { vertices, faces },
    net: { faces: points.map((p, i) => ({ parent: i === 0 ? -1 : 0, points: p.map(m) })) },
  };
}

test("a tetrahedron folds from flat to the mesh", () => {
  for (const mirror of [false, true]) {
    const doc = tetrahedron(mirror);
    const prepared = prepareFold(doc);
    const flat = foldPositions(prepared, 0);
    for (let i = 2; i < flat.length; i += 3) assert.equal(flat[i], 0);
    assertFoldsIntoMesh(doc, foldPositions(prepared, 1), 1e-5);
    // Half way, faces are still rigid: each face keeps its edge lengths.
    const half = foldPositions(prepared, 0.5);
    for (let i = 0; i < 4; ++i) {
      const c = [0, 1, 2].map((k) => Array.from(half.subarray(i * 9 + k * 3, i * 9 + k * 3 + 3)));
      const f = prepared.flat[i];
      for (const [u, w] of [[0, 1], [1, 2], [2, 0]]) {
        const a = Math.hypot(...[0, 1, 2].map((k) => c[u][k] - c[w][k]));
        const b = Math.hypot(...[0, 1, 2].map((k) => f[u][k] - f[w][k]));
        assert.ok(Math.abs(a - b) < 1e-5);
      }
    }
  }
});

test("folded, the net is the model where it is, turned by the frame: glTF stands up", () => {
  const doc = tetrahedron(false);
  const { vertices, faces } = doc.mesh;
  for (const format of ["obj", "glb", "gltf"]) {
    const m = sceneFrame(format);
    const folded = foldPositions(prepareFold(doc, { frame: m }), 1);
    faces.forEach((f, i) =>
      f.forEach((v, k) => {
        const [x, y, z] = vertices[v];
        const want = [0, 1, 2].map((r) => m[r * 4] * x + m[r * 4 + 1] * y + m[r * 4 + 2] * z + m[r * 4 + 3]);
        for (let c = 0; c < 3; ++c) assert.ok(Math.abs(folded[i * 9 + k * 3 + c] - want[c]) < 1e-6, `${format} face ${i} corner ${k}`);
        // glTF's up (y) is the scene's z.
        if (format !== "obj") assert.ok(Math.abs(folded[i * 9 + k * 3 + 2] - y) < 1e-6);
      }),
    );
  }
});

test("colour: corner coordinates and colours, faces grouped by material and mapping", () => {
  const doc = tetrahedron(false);
  doc.mesh.uvs = [[[0, 0], [1, 0], [0, 1]], null, [[0.5, 0.5], [1, 1], [0, 1]], null];
  doc.mesh.face_materials = [0, 0, 1, -1];
  doc.materials = [
    { name: "a", base_color: [1, 1, 1, 1], texture: 0 },
    { name: "b", base_color: [1, 0, 0, 1], texture: null },
  ];
  const uvs = cornerUvs(doc);
  assert.deepEqual(Array.from(uvs.subarray(0, 6)), [0, 0, 1, 0, 0, 1]);
  assert.deepEqual(Array.from(uvs.subarray(6, 12)), [0, 0, 0, 0, 0, 0]);
  assert.equal(cornerColors(doc), null);
  // Face 3 has no material: it takes the most common one (0); faces 1 and 3 have no coordinates.
  assert.deepEqual(faceGroups(doc), [
    { material: 0, textured: true, faces: [0] },
    { material: 0, textured: false, faces: [1, 3] },
    { material: 1, textured: false, faces: [2] },
  ]);
  doc.mesh.colors = [null, [[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 0.5]], null, null];
  const colors = cornerColors(doc);
  assert.deepEqual(Array.from(colors.subarray(0, 18)), [1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 0, 0, 0, 1, 0, 0, 0, 1]);
  // Without materials every face is one untextured group of no material.
  assert.deepEqual(faceGroups(tetrahedron(false)), [{ material: -1, textured: false, faces: [0, 1, 2, 3] }]);
});

test("broken trees are refused with the face named", () => {
  const doc = tetrahedron(false);
  doc.net.faces[2].parent = -1;
  assert.throws(() => prepareFold(doc), /two root faces/);
  const cyc = tetrahedron(false);
  cyc.net.faces[1].parent = 3;
  cyc.net.faces[3].parent = 1;
  assert.throws(() => prepareFold(cyc), /not connected|cycle/);
});

test("pieces lie side by side flat and each folds into its part", () => {
  // Two tetrahedra as two pieces: the second drawn over the first in its own frame.
  const one = tetrahedron(false);
  const two = tetrahedron(true);
  const offset = one.mesh.vertices.length;
  const doc = {
    format: "papernet.net/2",
    mesh: {
      vertices: [...one.mesh.vertices, ...two.mesh.vertices.map(([x, y, z]) => [x + 5, y, z])],
      faces: [...one.mesh.faces, ...two.mesh.faces.map((f) => f.map((v) => v + offset))],
    },
    net: {
      faces: [
        ...one.net.faces.map((f) => ({ ...f, piece: 0 })),
        ...two.net.faces.map((f) => ({ ...f, piece: 1, parent: f.parent < 0 ? -1 : f.parent + 4 })),
      ],
    },
  };
  const prepared = prepareFold(doc);
  assert.equal(prepared.pieces, 2);
  assert.deepEqual(prepared.roots, [0, 4]);
  // Flat: every corner of the second piece right of every corner of the first.
  const flat = foldPositions(prepared, 0);
  const xs = (from, to) => Array.from({ length: (to - from) * 3 }, (_, k) => flat[from * 9 + 3 * k]);
  assert.ok(Math.min(...xs(4, 8)) > Math.max(...xs(0, 4)));
  // Folded: each piece a rigid copy of its part (its corners meet, its edges keep their length).
  const folded = foldPositions(prepared, 1);
  for (const [piece, from] of [[one, 0], [two, 4]]) {
    const part = { mesh: { vertices: piece.mesh.vertices, faces: piece.mesh.faces } };
    assertFoldsIntoMesh(part, folded.subarray(from * 9, (from + 4) * 9), 1e-5);
  }
  // And together as in the model: every two corners as far apart as their vertices in the mesh.
  const corners = doc.mesh.faces.flatMap((f, i) => f.map((v, k) => [v, Array.from(folded.subarray(i * 9 + k * 3, i * 9 + k * 3 + 3))]));
  for (const [u, p] of corners)
    for (const [w, q] of corners) {
      const d3 = Math.hypot(...[0, 1, 2].map((k) => doc.mesh.vertices[u][k] - doc.mesh.vertices[w][k]));
      assert.ok(Math.abs(Math.hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]) - d3) < 1e-5, `vertices ${u} and ${w}`);
    }
  // Half way, the second piece is still rigid.
  const half = foldPositions(prepared, 0.5);
  for (let i = 4; i < 8; ++i)
    for (const [u, w] of [[0, 1], [1, 2], [2, 0]]) {
      const a = Math.hypot(...[0, 1, 2].map((k) => half[i * 9 + u * 3 + k] - half[i * 9 + w * 3 + k]));
      const b = Math.hypot(...[0, 1, 2].map((k) => prepared.flat[i][u][k] - prepared.flat[i][w][k]));
      assert.ok(Math.abs(a - b) < 1e-5);
    }
  doc.net.faces[5].parent = 1;  // a parent in the other piece
  assert.throws(() => prepareFold(doc), /face 5 has parent 1/);
});

test("a net from the server folds into its mesh", async () => {
  const { startServer, sample } = await import("../../js/test/server.js");
  const { PapernetClient } = await import("../../js/papernet.js");
  const server = await startServer();
  try {
    const client = new PapernetClient(server.url);
    for (const [name, file] of [["sample.obj", "sample.obj"], ["Duck.glb", "Duck.glb"]]) {
      const job = await client.submit(sample(file), { filename: name, options: { strategy: "TU" } });
      const done = await client.wait(job.id);
      assert.ok(["succeeded", "approximated"].includes(done.status), JSON.stringify(done.error));
      const doc = await client.netJson(job.id);
      const prepared = prepareFold(doc);
      const flat = foldPositions(prepared, 0);
      const diagonal = Math.hypot(...[0, 1, 2].map((k) => {
        const xs = doc.mesh.vertices.map((p) => p[k]);
        return Math.max(...xs) - Math.min(...xs);
      }));
      // Flat: each piece (as printed: cut to fit a sheet) its net's own 2D points, up to the mirror
      // and a shift of the piece beside the others, z = 0.
      const offsets = new Map(); // piece -> [x - u], [y - v], [y + v]
      doc.net.faces.forEach((f, i) =>
        f.points.forEach(([u, v], k) => {
          if (!offsets.has(f.piece)) offsets.set(f.piece, [[], [], []]);
          const [dx, dy, dyMirrored] = offsets.get(f.piece);
          dx.push(flat[i * 9 + k * 3] - u);
          dy.push(flat[i * 9 + k * 3 + 1] - v);
          dyMirrored.push(flat[i * 9 + k * 3 + 1] + v);
          assert.ok(Math.abs(flat[i * 9 + k * 3 + 2]) < 1e-9 * diagonal);
        }),
      );
      const spread = (xs) => Math.max(...xs) - Math.min(...xs);
      for (const [piece, [dx, dy, dyMirrored]] of offsets) {
        assert.ok(spread(dx) < 1e-6 * diagonal, `piece ${piece} moved rigidly in x`);
        assert.ok(Math.min(spread(dy), spread(dyMirrored)) < 1e-6 * diagonal, `piece ${piece} in y`);
      }
      assert.ok(doc.pieces.length > 1, "the sheets' pieces: cut to fit");
      assertFoldsIntoMesh(doc, foldPositions(prepared, 1), 1e-3 * diagonal);
    }
  } finally {
    await server.stop();
  }
});
