// Folding a papernet.net/2 net into its mesh along the unfold trees, without three.js (so it is
// tested in Node). Every face hangs from its parent by the mesh edge they share; folding by t
// rotates each face's subtree about that edge by t × its fold angle, composed from the root down.
// At t = 0 every piece lies flat in z = 0 as drawn (x, y = its 2D points, y mirrored when the
// piece is drawn clockwise), the pieces side by side in rows; at t = 1 every piece is where its
// part is in the model (a model in parts is seen whole), in the frame prepareFold is given (the
// model's coordinates turned so that the model stands up: colour.js sceneFrame), each piece
// turning and moving there steadily as t grows.

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const unit = (a) => {
  const n = Math.hypot(a[0], a[1], a[2]);
  return n > 0 ? [a[0] / n, a[1] / n, a[2] / n] : [0, 0, 0];
};

/** Affine 3×4 matrices as 12 numbers, row-major: [r00 r01 r02 tx, r10 ... ty, r20 ... tz]. */

function multiply(a, b) {
  const out = new Array(12);
  for (let r = 0; r < 3; ++r) {
    for (let c = 0; c < 4; ++c) {
      let s = c === 3 ? a[r * 4 + 3] : 0;
      for (let k = 0; k < 3; ++k) s += a[r * 4 + k] * b[k * 4 + c];
      out[r * 4 + c] = s;
    }
  }
  return out;
}

/** Rotation by `angle` about the line through `p` with unit direction `d`. */
function rotationAbout(p, d, angle) {
  const c = Math.cos(angle);
  const s = Math.sin(angle);
  const [x, y, z] = d;
  const C = 1 - c;
  const r = [
    c + x * x * C, x * y * C - z * s, x * z * C + y * s,
    y * x * C + z * s, c + y * y * C, y * z * C - x * s,
    z * x * C - y * s, z * y * C + x * s, c + z * z * C,
  ];
  // Translate p to the origin, rotate, translate back: t = p - R p.
  const t = [0, 1, 2].map((i) => p[i] - (r[i * 3] * p[0] + r[i * 3 + 1] * p[1] + r[i * 3 + 2] * p[2]));
  return [r[0], r[1], r[2], t[0], r[3], r[4], r[5], t[1], r[6], r[7], r[8], t[2]];
}

/** The rigid motion taking the triangle a (3 points) onto the congruent triangle b. */
function rigidOnto(a, b) {
  const frame = ([p0, p1, p2]) => {
    const e1 = unit(sub(p1, p0));
    const n = unit(cross(sub(p1, p0), sub(p2, p0)));
    return [e1, cross(n, e1), n];
  };
  const fa = frame(a);
  const fb = frame(b);
  // R = Fb Fa^T (frames as columns), then t = b0 - R a0.
  const r = [];
  for (let i = 0; i < 3; ++i)
    for (let j = 0; j < 3; ++j) r.push(fb[0][i] * fa[0][j] + fb[1][i] * fa[1][j] + fb[2][i] * fa[2][j]);
  const t = [0, 1, 2].map((i) => b[0][i] - (r[i * 3] * a[0][0] + r[i * 3 + 1] * a[0][1] + r[i * 3 + 2] * a[0][2]));
  return [r[0], r[1], r[2], t[0], r[3], r[4], r[5], t[1], r[6], r[7], r[8], t[2]];
}

/** The rotation of a rigid motion as a unit axis and an angle in [0, π]. */
function axisAngle(m) {
  const angle = Math.acos(Math.min(1, Math.max(-1, (m[0] + m[5] + m[10] - 1) / 2)));
  const axis = [m[9] - m[6], m[2] - m[8], m[4] - m[1]];
  if (Math.hypot(...axis) > 1e-6) return { axis: unit(axis), angle };
  if (angle < 1) return { axis: [0, 0, 1], angle: 0 };
  // A half turn: R = 2 a a^T - I, so a is along the column of R + I with the largest diagonal.
  const d = [m[0], m[5], m[10]];
  const k = d.indexOf(Math.max(...d));
  return { axis: unit([0, 1, 2].map((i) => m[i * 4 + k] + (i === k ? 1 : 0))), angle };
}

function transform(m, p) {
  return [
    m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3],
    m[4] * p[0] + m[5] * p[1] + m[6] * p[2] + m[7],
    m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11],
  ];
}

const IDENTITY = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0];

/**
 * Prepares a net document (papernet.net/2) for folding: the tree order from each piece's root,
 * and per face its hinge (a point and direction in the flat net) and fold angle (radians,
 * signed). `frame` (a rigid 3×4 matrix, default none) turns the model's coordinates into those
 * the folded model is shown in. Throws an Error naming the face when the document breaks the
 * format's promises.
 */
export function prepareFold(doc, { frame = IDENTITY } = {}) {
  const vertices = doc.mesh.vertices;
  const faces = doc.mesh.faces;
  const netFaces = doc.net.faces;
  const n = faces.length;
  if (netFaces.length !== n) throw new Error(`net has ${netFaces.length} faces, mesh ${n}`);
  const pieceOf = netFaces.map((f) => f.piece ?? 0);
  const pieces = n === 0 ? 0 : Math.max(...pieceOf) + 1;
  const roots = new Array(pieces).fill(-1);
  const children = Array.from({ length: n }, () => []);
  netFaces.forEach((f, i) => {
    if (f.parent === -1) {
      if (roots[pieceOf[i]] !== -1) throw new Error(`piece ${pieceOf[i]} has two root faces`);
      roots[pieceOf[i]] = i;
    } else if (f.parent >= 0 && f.parent < n && f.parent !== i && pieceOf[f.parent] === pieceOf[i]) {
      children[f.parent].push(i);
    } else throw new Error(`face ${i} has parent ${f.parent}`);
  });
  if (roots.length === 0 || roots.includes(-1)) throw new Error("a piece has no root face");
  // Each piece mirrored when it is drawn clockwise (so the flat +z side is the outside), then
  // moved beside the one before it.
  const flip = roots.map((root) => {
    const [r0, r1, r2] = netFaces[root].points;
    return (r1[0] - r0[0]) * (r2[1] - r0[1]) - (r1[1] - r0[1]) * (r2[0] - r0[0]) < 0 ? -1 : 1;
  });
  const lo = roots.map(() => [Infinity, Infinity]);
  const hi = roots.map(() => [-Infinity, -Infinity]);
  netFaces.forEach((f, i) => {
    const p = pieceOf[i];
    for (const [u, v] of f.points) {
      const y = flip[p] * v;
      lo[p] = [Math.min(lo[p][0], u), Math.min(lo[p][1], y)];
      hi[p] = [Math.max(hi[p][0], u), Math.max(hi[p][1], y)];
    }
  });
  const width = (p) => hi[p][0] - lo[p][0];
  const height = (p) => hi[p][1] - lo[p][1];
  const gap = 0.1 * Math.max(...roots.map((_, p) => Math.max(width(p), height(p))));
  // Rows about twice as wide as the pieces' area is deep, so that a kit of many pieces stays in
  // view; the first piece stays where it is drawn, the rows go on below it.
  let area = 0;
  for (let p = 0; p < pieces; ++p) area += (width(p) + gap) * (height(p) + gap);
  const rowWidth = Math.max(...roots.map((_, p) => width(p)), 2 * Math.sqrt(area));
  const shift = [];
  let x = lo.length > 0 ? lo[0][0] : 0;
  let top = lo.length > 0 ? hi[0][1] : 0;
  let rowHeight = 0;
  for (let p = 0; p < pieces; ++p) {
    if (p > 0 && x + width(p) > (lo[0][0] + rowWidth)) {
      x = lo[0][0];
      top -= rowHeight + gap;
      rowHeight = 0;
    }
    shift.push(p === 0 ? [0, 0] : [x - lo[p][0], top - hi[p][1]]);
    x += width(p) + gap;
    rowHeight = Math.max(rowHeight, height(p));
  }
  const flat = netFaces.map((f, i) => {
    const p = pieceOf[i];
    return f.points.map(([u, v]) => [u + shift[p][0], flip[p] * v + shift[p][1], 0]);
  });
  const normal = faces.map(([a, b, c]) => unit(cross(sub(vertices[b], vertices[a]), sub(vertices[c], vertices[a]))));

  const order = [];
  const hinge = new Array(n);
  const seen = new Uint8Array(n);
  for (const root of roots) {
    const queue = [root];
    seen[root] = 1;
    while (queue.length > 0) {
      const i = queue.shift();
      order.push(i);
      for (const c of children[i]) {
        if (seen[c]) throw new Error(`the unfold tree has a cycle at face ${c}`);
        seen[c] = 1;
        queue.push(c);
        const p = i;
        const shared = faces[c].filter((v) => faces[p].includes(v));
        if (shared.length !== 2) throw new Error(`face ${c} shares no edge with its parent ${p}`);
        const [a, b] = shared;
        const pa = flat[c][faces[c].indexOf(a)];
        const pb = flat[c][faces[c].indexOf(b)];
        const e = unit(sub(vertices[b], vertices[a]));
        const angle = Math.atan2(dot(cross(normal[p], normal[c]), e), dot(normal[p], normal[c]));
        hinge[c] = { parent: p, point: pa, direction: unit(sub(pb, pa)), angle };
      }
    }
  }
  if (order.length !== n) throw new Error(`${n - order.length} faces are not connected to a root`);
  // Folded, a piece's root face would stay where it lies flat; `place[p]` takes piece p from
  // there to where its part is in the model (in `frame`), as a turn about an axis through the
  // root face's centre and a move of that centre.
  const onto = roots.map((root) => rigidOnto(flat[root], faces[root].map((v) => vertices[v])));
  const place = roots.map((root, p) => {
    const motion = multiply(frame, onto[p]);
    const centre = [0, 1, 2].map((k) => (flat[root][0][k] + flat[root][1][k] + flat[root][2][k]) / 3);
    return { centre, target: transform(motion, centre), ...axisAngle(motion) };
  });
  return { faces, flat, order, hinge, roots, pieces, pieceOf, place };
}

/**
 * Corner positions of every face folded by t ∈ [0, 1] (0 flat, 1 the mesh): a Float32Array of
 * 9 numbers per face (face i's corners k = 0..2 at 9i + 3k), written into `out` if given.
 */
export function foldPositions(prepared, t, out = new Float32Array(prepared.faces.length * 9)) {
  const { flat, order, hinge, pieceOf, place } = prepared;
  const matrix = new Array(flat.length);
  const placed = place.map(({ centre, target, axis, angle }) => {
    const m = rotationAbout(centre, axis, t * angle);
    for (let k = 0; k < 3; ++k) m[k * 4 + 3] += t * (target[k] - centre[k]);
    return m;
  });
  for (const i of order) {
    const h = hinge[i];
    matrix[i] = h ? multiply(matrix[h.parent], rotationAbout(h.point, h.direction, t * h.angle)) : placed[pieceOf[i]];
    for (let k = 0; k < 3; ++k) out.set(transform(matrix[i], flat[i][k]), i * 9 + k * 3);
  }
  return out;
}
