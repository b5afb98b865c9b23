// Fixtures of JS_BEHAVIOUR.md (cube, patch, tetra, T, the T-junction strip, the pleated and
// incoherent prisms, the tetrahemihexahedron, the grids and cutters of the boolean
// sections, a UTM stand-in for the Kirra pair) and measuring helpers (area, signed volume,
// edge counts on exact vertex keys), written for the behaviour tests of this folder.
// A soup is an array of triangles {v0, v1, v2}, each corner {x, y, z}.

// ── building blocks ───────────────────────────────────────────────────────────────────

/** A vertex from an array [x, y, z] or an object {x, y, z} (a fresh object). */
export function P(p) {
	return Array.isArray(p) ? { x: p[0], y: p[1], z: p[2] === undefined ? 0 : p[2] } : { x: p.x, y: p.y, z: p.z };
}

/** A triangle of three corners given as arrays or objects. */
export function tri(a, b, c) {
	return { v0: P(a), v1: P(b), v2: P(c) };
}

/** The point `c` of a fixture: a number (all ordinates), an array or an object. */
function centre(c) {
	if (c === undefined || typeof c === "number") {
		const k = c || 0;
		return { x: k, y: k, z: k };
	}
	return P(c);
}

/** A deep copy of a soup (fresh triangle and vertex objects, extra fields kept). */
export function copySoup(soup) {
	return soup.map((t) => ({ ...t, v0: P(t.v0), v1: P(t.v1), v2: P(t.v2) }));
}

/** A triangle with its winding reversed (fresh objects). */
export function flipTri(t) {
	return { v0: P(t.v0), v1: P(t.v2), v2: P(t.v1) };
}

/** Every triangle of a soup reversed. */
export function flipSoup(soup) {
	return soup.map(flipTri);
}

/** A soup moved by (dx, dy, dz). */
export function translate(soup, dx, dy, dz) {
	const m = (v) => ({ x: v.x + dx, y: v.y + dy, z: v.z + dz });
	return soup.map((t) => ({ v0: m(t.v0), v1: m(t.v1), v2: m(t.v2) }));
}

/** A deterministic pseudo-random generator in [0, 1) (mulberry32). */
export function rng(seed) {
	let a = seed >>> 0;
	return () => {
		a = (a + 0x6d2b79f5) >>> 0;
		let t = a;
		t = Math.imul(t ^ (t >>> 15), t | 1);
		t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
		return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
	};
}

// ── the named fixtures ────────────────────────────────────────────────────────────────

/**
 * cube(c, s): the axis-aligned cube of edge `s` centred at `c`, 12 outward triangles.
 * Every face's diagonal runs through the cube's lowest or highest corner, so those two
 * corners are in 6 triangles and the others in 4 (30 pairs of triangles share exactly one
 * vertex).
 */
export function cube(c = 0, s = 1) {
	const o = centre(c), h = s / 2;
	const v = (i, j, k) => [o.x + (i ? h : -h), o.y + (j ? h : -h), o.z + (k ? h : -h)];
	const q = (a, b, cc, d) => [tri(a, b, cc), tri(a, cc, d)]; // quad a-b-c-d, diagonal a-c
	return [
		// z = -h (outward -z), diagonal (0,0,0)-(1,1,0)
		...q(v(0, 0, 0), v(0, 1, 0), v(1, 1, 0), v(1, 0, 0)),
		// z = +h, diagonal (0,0,1)-(1,1,1)
		...q(v(1, 1, 1), v(0, 1, 1), v(0, 0, 1), v(1, 0, 1)),
		// y = -h (outward -y), diagonal (0,0,0)-(1,0,1)
		...q(v(0, 0, 0), v(1, 0, 0), v(1, 0, 1), v(0, 0, 1)),
		// y = +h, diagonal (0,1,0)-(1,1,1)
		...q(v(1, 1, 1), v(1, 1, 0), v(0, 1, 0), v(0, 1, 1)),
		// x = -h (outward -x), diagonal (0,0,0)-(0,1,1)
		...q(v(0, 0, 0), v(0, 0, 1), v(0, 1, 1), v(0, 1, 0)),
		// x = +h, diagonal (1,0,0)-(1,1,1)
		...q(v(1, 1, 1), v(1, 0, 1), v(1, 0, 0), v(1, 1, 0)),
	];
}

/** An axis-aligned box [x0,x1]×[y0,y1]×[z0,z1], 12 outward triangles (cube's pattern). */
export function box(x0, y0, z0, x1, y1, z1) {
	const c = cube(0, 2);
	const m = (v) => ({ x: v.x < 0 ? x0 : x1, y: v.y < 0 ? y0 : y1, z: v.z < 0 ? z0 : z1 });
	return c.map((t) => ({ v0: m(t.v0), v1: m(t.v1), v2: m(t.v2) }));
}

/**
 * patch(w, n): a flat open w×w grid of n×n cells at height z, 2 triangles per cell, facing
 * +z, centred at the origin unless `origin` (its low corner) is given. Each cell's far
 * corner is its own start plus dx, while the next cell starts at origin + (i+1)·dx, so
 * shared corners may differ in their last bits.
 */
export function patch(w, n, { z = 0, origin } = {}) {
	const x00 = origin ? origin[0] : -w / 2, y00 = origin ? origin[1] : -w / 2;
	const d = w / n;
	const out = [];
	for (let i = 0; i < n; i++) {
		const x0 = x00 + i * d, x1 = x0 + d;
		for (let j = 0; j < n; j++) {
			const y0 = y00 + j * d, y1 = y0 + d;
			out.push(tri([x0, y0, z], [x1, y0, z], [x1, y1, z]), tri([x0, y0, z], [x1, y1, z], [x0, y1, z]));
		}
	}
	return out;
}

/** An open nx×ny grid of cells of size d with integer-exact corners computed once each, facing +z. */
export function grid(nx, ny, d = 1, { x0 = 0, y0 = 0, z = 0 } = {}) {
	const X = (i) => x0 + i * d, Y = (j) => y0 + j * d;
	const out = [];
	for (let i = 0; i < nx; i++) {
		for (let j = 0; j < ny; j++) {
			out.push(tri([X(i), Y(j), z], [X(i + 1), Y(j), z], [X(i + 1), Y(j + 1), z]), tri([X(i), Y(j), z], [X(i + 1), Y(j + 1), z], [X(i), Y(j + 1), z]));
		}
	}
	return out;
}

/** tetra: the outward unit tetrahedron on (0,0,0), (1,0,0), (0,1,0), (0,0,1). */
export function tetra() {
	const o = [0, 0, 0], a = [1, 0, 0], b = [0, 1, 0], c = [0, 0, 1];
	return [tri(o, b, a), tri(o, a, c), tri(o, c, b), tri(a, b, c)];
}

/** T: the triangle (0,0,0), (1,0,0), (0,1,0). */
export function T() {
	return [tri([0, 0, 0], [1, 0, 0], [0, 1, 0])];
}

/**
 * The T-junction strip: the triangle (0,0), (10,0), (5,8) over `cells` strip cells of
 * height 3 (y from -3 to 0) whose top corners lie on the triangle's base; all facing +z,
 * consistently wound. Area 40 + 30.
 */
export function tjunctionStrip(cells = 8) {
	const out = [tri([0, 0, 0], [10, 0, 0], [5, 8, 0])];
	const d = 10 / cells;
	for (let i = 0; i < cells; i++) {
		const x0 = i * d, x1 = i + 1 === cells ? 10 : (i + 1) * d;
		out.push(tri([x0, -3, 0], [x1, -3, 0], [x1, 0, 0]), tri([x0, -3, 0], [x1, 0, 0], [x0, 0, 0]));
	}
	return out;
}

/**
 * Three coplanar triangles (+z) with a vertex in the middle of another's edge:
 * "edge": the big triangle (0,0)-(2,0)-(1,1) over two triangles meeting at (1,0);
 * "diagonal": the triangle (0,0)-(100,100)-(0,100) over two meeting at (50,50).
 */
export function midEdgePatch(kind = "edge") {
	if (kind === "diagonal") {
		return [tri([0, 0, 0], [100, 100, 0], [0, 100, 0]), tri([100, 100, 0], [50, 50, 0], [100, 0, 0]), tri([50, 50, 0], [0, 0, 0], [100, 0, 0])];
	}
	return [tri([0, 0, 0], [2, 0, 0], [1, 1, 0]), tri([1, 0, 0], [0, 0, 0], [1, -1, 0]), tri([2, 0, 0], [1, 0, 0], [1, -1, 0])];
}

/**
 * A 30×30 grid of 30 m cells with its low corner at (478000, 478000) plus one triangle
 * below the first bottom edge whose apex is that edge's midpoint (one T-junction).
 */
export function utmGridWithTJunction(n = 30, d = 30, x0 = 478000, y0 = 478000) {
	const out = grid(n, n, d, { x0, y0, z: 0 });
	out.push(tri([x0, y0 - d, 0], [x0 + d / 2, y0, 0], [x0, y0, 0]));
	return out;
}

// ── section 11: immersed prisms and RP² ──────────────────────────────────────────────

/**
 * The pleated prism: the extrusion along y (0 → 2) of the profile in the xz-plane
 * (0,0) → (1,0) → (1,1) → (0.4,1) → (0.6,1) → (0,1), whose top doubles back so that three
 * coincident layers (up, down, up) lie over 0.4 ≤ x ≤ 0.6. Sides are quads split on a
 * diagonal; the end caps are fans from (0,0), one triangle of which, (0,0)-(0.4,1)-(0.6,1),
 * is reversed. Closed and manifold on vertex indices (and on exact keys); winding 1 inside
 * [0,1]×[0,2]×[0,1], 0 outside; signed volume 2. `offset` moves every point.
 */
export function pleatedPrism(offset = [0, 0, 0]) {
	const prof = [[0, 0], [1, 0], [1, 1], [0.4, 1], [0.6, 1], [0, 1]];
	const [ox, oy, oz] = offset;
	const at = (k, y) => [prof[k][0] + ox, y + oy, prof[k][1] + oz];
	const out = [];
	const n = prof.length;
	for (let k = 0; k < n; k++) {
		const l = (k + 1) % n;
		out.push(tri(at(k, 0), at(k, 2), at(l, 2)), tri(at(k, 0), at(l, 2), at(l, 0)));
	}
	for (let k = 1; k + 1 < n; k++) {
		out.push(tri(at(0, 0), at(k, 0), at(k + 1, 0))); // y = 0 cap, outward -y
		out.push(tri(at(0, 2), at(k + 1, 2), at(k, 2))); // y = 2 cap, outward +y
	}
	return out;
}

/** The pleated prism with its two bottom (z = 0 face) triangles reversed. */
export function pleatedPrismBottomReversed(offset = [0, 0, 0]) {
	return pleatedPrism(offset).map((t, i) => (i < 2 ? flipTri(t) : t));
}

/** The incoherent prism: the pleated prism with every triangle whose centroid z > 0.5 reversed. */
export function incoherentPrism(offset = [0, 0, 0]) {
	const oz = offset[2];
	return pleatedPrism(offset).map((t) => ((t.v0.z + t.v1.z + t.v2.z) / 3 - oz > 0.5 ? flipTri(t) : t));
}

/**
 * The tetrahemihexahedron (an immersion of RP²) on (±1,0,0), (0,±1,0), (0,0,±1): the 4
 * octahedron faces with sign product +1, plus the three axis squares, the xy square split
 * on the x axis, the yz square on the y axis and the zx square on the z axis. Every edge
 * is in two triangles; the squares cross one another along the axes.
 */
export function tetrahemihexahedron() {
	const X = [1, 0, 0], x = [-1, 0, 0], Y = [0, 1, 0], y = [0, -1, 0], Z = [0, 0, 1], z = [0, 0, -1];
	return [
		tri(X, Y, Z), tri(X, z, y), tri(x, z, Y), tri(x, y, Z),
		// xy square X-Y-x-y split on X-x
		tri(X, Y, x), tri(X, x, y),
		// yz square Y-Z-y-z split on Y-y
		tri(Y, Z, y), tri(Y, y, z),
		// zx square Z-X-z-x split on Z-z
		tri(Z, X, z), tri(Z, z, x),
	];
}

// ── section 1 and 2: booleans with open sheets ───────────────────────────────────────

/** Section 1: the 6×6 grid of unit cells at z = 0 (integer corners) and the box of half-size 1.5 centred (3,3,0). */
export function gridAndBox() {
	return { grid: grid(6, 6, 1), box: cube([3, 3, 0], 3) };
}

/**
 * Section 2's diagonal sheet: 10 squares of side 2.4 (2 triangles each) at z = 0 centred
 * at (12t, 12t), t = -1, -0.8, ..., 0.8 (t accumulated in floating point, so corners touch
 * only up to ~1e-15), each square's diagonal along the sheet's direction.
 */
export function diagonalSheet() {
	const out = [];
	for (let k = 0, t = -1; k < 10; k++, t += 0.2) {
		const c = 12 * t, a = c - 1.2, b = c + 1.2;
		out.push(tri([a, a, 0], [b, a, 0], [b, b, 0]), tri([a, a, 0], [b, b, 0], [a, b, 0]));
	}
	return out;
}

/** The closed box of half-size 5 at the origin. */
export function box5() {
	return cube(0, 10);
}

/** The leaky cutter: box5 with its +X and +Y walls (4 triangles) removed. */
export function leakyBox() {
	return box5().filter((t) => !([t.v0, t.v1, t.v2].every((v) => v.x === 5) || [t.v0, t.v1, t.v2].every((v) => v.y === 5)));
}

/** The 24×24 sheet of 2×2 cells centred at the origin and offset by (0.37, 0.61), at z = 0. */
export function leakySheet() {
	return grid(24, 24, 2, { x0: -24 + 0.37, y0: -24 + 0.61, z: 0 });
}

/** The census case: cube(0,2) plus one fin triangle on a bottom edge (an edge of 3 triangles). */
export function finnedCube() {
	return [...cube(0, 2), tri([-1, -1, -1], [1, -1, -1], [0, -2, -1])];
}

/**
 * Giant face vs dense seam: the floor (2 triangles over [0,100]² at z = 0, facing +z) and a
 * vertical fence at x = 50, y 10…90, z ±1 in 0.5-wide strips (2 triangles each).
 */
export function fenceAndFloor() {
	const floor = [tri([0, 0, 0], [100, 0, 0], [100, 100, 0]), tri([0, 0, 0], [100, 100, 0], [0, 100, 0])];
	const fence = [];
	for (let i = 0; i < 160; i++) {
		const y0 = 10 + 0.5 * i, y1 = 10 + 0.5 * (i + 1);
		fence.push(tri([50, y0, -1], [50, y1, -1], [50, y1, 1]), tri([50, y0, -1], [50, y1, 1], [50, y0, 1]));
	}
	return { floor, fence };
}

/** The shared-edge case: the square of two triangles and the vertical triangle whose seam ends on their shared edge. */
export function sharedEdgeCase() {
	const square = [tri([0, 0, 0], [4, 0, 0], [0, 4, 0]), tri([4, 0, 0], [4, 4, 0], [0, 4, 0])];
	const blade = [tri([1, 1, -1], [1, 1, 1], [2, 2, 0])];
	return { square, blade };
}

/** Coplanar opposite triangles (0,0),(4,0),(0,4) (+z) and (1,-1),(3,3),(3,-1) (-z); overlap area 19/12. */
export function coplanarOpposite() {
	return { a: [tri([0, 0, 0], [4, 0, 0], [0, 4, 0])], b: [tri([1, -1, 0], [3, 3, 0], [3, -1, 0])] };
}

// ── the UTM stand-in for the Kirra pair ──────────────────────────────────────────────

const KX0 = 53340, KX1 = 53560, KY0 = 217140, KY1 = 217410;
const KNX = 16, KNY = 18;
const CONE = { cx: 53450.3, cy: 217275.7, rings: 18, segs: 24 };

function coneRing(k) {
	const s = k / CONE.rings;
	return { r: 110 - 85 * s, z: 534 + 26 * (1 - s) ** 2 };
}

/**
 * The open cutter: a faceted bowl (pit shell) over the solid, its rim of 24 edges at
 * z = 560 (radius 110), 18 bands of 48 triangles down to a flat fan of 24 at z = 534
 * inside the solid: 888 triangles, 24 open edges; it crosses the solid's top in one
 * closed loop. Facing up (its inside is below it).
 */
export function kirraCutter() {
	const { cx, cy, rings, segs } = CONE;
	const pt = (k, j) => {
		const { r, z } = coneRing(k);
		const a = (2 * Math.PI * (j % segs)) / segs + 0.013;
		return [cx + r * Math.cos(a), cy + r * Math.sin(a), z];
	};
	const out = [];
	for (let k = 0; k < rings; k++) {
		for (let j = 0; j < segs; j++) {
			// ring k (outer, higher) to ring k+1 (inner, lower); facing up-and-in
			out.push(tri(pt(k, j), pt(k + 1, j), pt(k + 1, j + 1)), tri(pt(k, j), pt(k + 1, j + 1), pt(k, j + 1)));
		}
	}
	const bottom = [cx, cy, coneRing(rings).z];
	for (let j = 0; j < segs; j++) out.push(tri(pt(rings, j), bottom, pt(rings, j + 1)));
	return out;
}

/** The cutter's height above (x, y), from its triangles (null outside its footprint). */
function heightOn(soup, x, y) {
	for (const t of soup) {
		const { v0: a, v1: b, v2: c } = t;
		const d = (b.y - c.y) * (a.x - c.x) + (c.x - b.x) * (a.y - c.y);
		const l1 = ((b.y - c.y) * (x - c.x) + (c.x - b.x) * (y - c.y)) / d;
		const l2 = ((c.y - a.y) * (x - c.x) + (a.x - c.x) * (y - c.y)) / d;
		const l3 = 1 - l1 - l2;
		if (l1 >= -1e-12 && l2 >= -1e-12 && l3 >= -1e-12) return l1 * a.z + l2 * b.z + l3 * c.z;
	}
	return null;
}

/**
 * The closed solid: a slab over [53340, 53560] × [217140, 217410] (16 × 18 cells, 1288
 * triangles, mean edge ≈ 16 m), bottom flat at z = 530, top between 538 and 540 with
 * jittered interior vertices. Top vertices within 1 m (vertically) of the cutter are
 * moved to 0.3–1.2 mm off it (vertically), so that the crossing passes 1–5 mm from those solid
 * vertices, as in the field data. Outward.
 */
export function kirraSolid() {
	const cutter = kirraCutter();
	const r = rng(20240605);
	const dx = (KX1 - KX0) / KNX, dy = (KY1 - KY0) / KNY;
	const top = [], bot = [];
	for (let i = 0; i <= KNX; i++) {
		top.push([]);
		bot.push([]);
		for (let j = 0; j <= KNY; j++) {
			const edge = i === 0 || j === 0 || i === KNX || j === KNY;
			let x = KX0 + i * dx, y = KY0 + j * dy;
			if (!edge) {
				x += (r() - 0.5) * 0.3 * dx;
				y += (r() - 0.5) * 0.3 * dy;
			}
			let z = 538 + 2 * r();
			const h = heightOn(cutter, x, y);
			if (h !== null && Math.abs(z - h) < 1) {
				const mm = 0.001 * (0.3 + 0.9 * r());
				z = h + (r() < 0.5 ? -mm : mm);
			}
			top[i].push([x, y, z]);
			bot[i].push([x, y, 530]);
		}
	}
	const out = [];
	for (let i = 0; i < KNX; i++) {
		for (let j = 0; j < KNY; j++) {
			const a = top[i][j], b = top[i + 1][j], c = top[i + 1][j + 1], d = top[i][j + 1];
			const flipDiag = (i + j) % 2 === 1;
			if (flipDiag) out.push(tri(a, b, d), tri(b, c, d));
			else out.push(tri(a, b, c), tri(a, c, d));
			const A = bot[i][j], B = bot[i + 1][j], C = bot[i + 1][j + 1], D = bot[i][j + 1];
			if (flipDiag) out.push(tri(A, D, B), tri(B, D, C));
			else out.push(tri(A, C, B), tri(A, D, C));
		}
	}
	// walls: walk the boundary counter-clockwise (seen from above)
	const ring = [];
	for (let i = 0; i < KNX; i++) ring.push([i, 0]);
	for (let j = 0; j < KNY; j++) ring.push([KNX, j]);
	for (let i = KNX; i > 0; i--) ring.push([i, KNY]);
	for (let j = KNY; j > 0; j--) ring.push([0, j]);
	for (let k = 0; k < ring.length; k++) {
		const [i0, j0] = ring[k], [i1, j1] = ring[(k + 1) % ring.length];
		const a = bot[i0][j0], b = bot[i1][j1], c = top[i1][j1], d = top[i0][j0];
		out.push(tri(a, b, c), tri(a, c, d));
	}
	return out;
}

// ── measures ─────────────────────────────────────────────────────────────────────────

/** The exact key of a vertex (its three numbers). */
export function key(v) {
	return `${v.x},${v.y},${v.z}`;
}

/** A key rounded to a grid of `step` (e.g. 0.001 for millimetres). */
export function roundedKey(v, step) {
	return `${Math.round(v.x / step)},${Math.round(v.y / step)},${Math.round(v.z / step)}`;
}

export function sub(a, b) {
	return [a.x - b.x, a.y - b.y, a.z - b.z];
}

export function crossArr(u, v) {
	return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
}

/** The (unnormalised, twice-area) normal of a triangle. */
export function normalOf(t) {
	return crossArr(sub(t.v1, t.v0), sub(t.v2, t.v0));
}

export function triArea(t) {
	const n = normalOf(t);
	return 0.5 * Math.hypot(n[0], n[1], n[2]);
}

/** The total area of a soup. */
export function area(soup) {
	return soup.reduce((s, t) => s + triArea(t), 0);
}

/** The signed volume of a soup (divergence theorem, about its first vertex for precision). */
export function signedVolume(soup) {
	if (soup.length === 0) return 0;
	const o = soup[0].v0;
	let v = 0;
	for (const t of soup) {
		const a = sub(t.v0, o), b = sub(t.v1, o), c = sub(t.v2, o);
		v += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
	}
	return v / 6;
}

export function centroid(t) {
	return { x: (t.v0.x + t.v1.x + t.v2.x) / 3, y: (t.v0.y + t.v1.y + t.v2.y) / 3, z: (t.v0.z + t.v1.z + t.v2.z) / 3 };
}

/** The longest edge of a triangle. */
export function longestEdge(t) {
	const d = (a, b) => Math.hypot(a.x - b.x, a.y - b.y, a.z - b.z);
	return Math.max(d(t.v0, t.v1), d(t.v1, t.v2), d(t.v2, t.v0));
}

/** A triangle's smallest altitude: 2·area / longest edge. */
export function altitude(t) {
	const l = longestEdge(t);
	return l === 0 ? 0 : (2 * triArea(t)) / l;
}

/** The mean edge length of a soup. */
export function meanEdge(soup) {
	let s = 0;
	for (const t of soup) {
		s += Math.hypot(...sub(t.v0, t.v1)) + Math.hypot(...sub(t.v1, t.v2)) + Math.hypot(...sub(t.v2, t.v0));
	}
	return s / (3 * Math.max(1, soup.length));
}

/**
 * Edge census on vertex keys (`keyOf`, exact by default): `{vertices, edges, open,
 * nonManifold, inconsistent, euler}` — open edges are in one triangle, non-manifold ones
 * in more than two, inconsistent ones in two that run them the same way; triangles with
 * two equal corners are skipped.
 */
export function edgeCounts(soup, keyOf = key) {
	const verts = new Set();
	const edges = new Map();
	let faces = 0;
	for (const t of soup) {
		const k = [keyOf(t.v0), keyOf(t.v1), keyOf(t.v2)];
		if (k[0] === k[1] || k[1] === k[2] || k[2] === k[0]) continue;
		faces++;
		for (const x of k) verts.add(x);
		for (let i = 0; i < 3; i++) {
			const a = k[i], b = k[(i + 1) % 3];
			const e = a < b ? `${a}|${b}` : `${b}|${a}`;
			if (!edges.has(e)) edges.set(e, []);
			edges.get(e).push(a < b);
		}
	}
	let open = 0, nonManifold = 0, inconsistent = 0;
	for (const uses of edges.values()) {
		if (uses.length === 1) open++;
		else if (uses.length > 2) nonManifold++;
		else if (uses[0] === uses[1]) inconsistent++;
	}
	return { vertices: verts.size, edges: edges.size, faces, open, nonManifold, inconsistent, euler: verts.size - edges.size + faces };
}

/** Edge-connected components on vertex keys: an array of arrays of triangle indices, largest first. */
export function edgeComponents(soup, keyOf = key) {
	const parent = soup.map((_, i) => i);
	const find = (i) => {
		while (parent[i] !== i) i = parent[i] = parent[parent[i]];
		return i;
	};
	const byEdge = new Map();
	soup.forEach((t, i) => {
		const k = [keyOf(t.v0), keyOf(t.v1), keyOf(t.v2)];
		for (let c = 0; c < 3; c++) {
			const a = k[c], b = k[(c + 1) % 3];
			if (a === b) continue;
			const e = a < b ? `${a}|${b}` : `${b}|${a}`;
			if (byEdge.has(e)) parent[find(i)] = find(byEdge.get(e));
			else byEdge.set(e, i);
		}
	});
	const parts = new Map();
	soup.forEach((_, i) => {
		const r = find(i);
		if (!parts.has(r)) parts.set(r, []);
		parts.get(r).push(i);
	});
	return [...parts.values()].sort((p, q) => q.length - p.length);
}

/** A triangle's corner keys sorted (the same triangle whatever its winding or start). */
export function triSetKey(t) {
	return [key(t.v0), key(t.v1), key(t.v2)].sort().join(" ");
}

/** A triangle's key up to rotation (keeps the winding). */
export function triOrientedKey(t) {
	const k = [key(t.v0), key(t.v1), key(t.v2)];
	let m = 0;
	for (let i = 1; i < 3; i++) if (k[i] < k[m]) m = i;
	return `${k[m]} ${k[(m + 1) % 3]} ${k[(m + 2) % 3]}`;
}

/** The sorted multiset of keys of a soup (for comparing soups as sets of triangles). */
export function soupKeys(soup, keyFn = triSetKey) {
	return soup.map(keyFn).sort();
}

/** Strictly inside the axis-aligned box centred at `c` of half-size h. */
export function insideBox(p, h, c = { x: 0, y: 0, z: 0 }) {
	return Math.abs(p.x - c.x) < h && Math.abs(p.y - c.y) < h && Math.abs(p.z - c.z) < h;
}

/** Flat arrays {positions: Float64Array, index: Uint32Array} of a soup, exactly equal corners shared. */
export function toIndexed(soup) {
	const ids = new Map();
	const pos = [];
	const index = new Uint32Array(3 * soup.length);
	soup.forEach((t, i) => {
		[t.v0, t.v1, t.v2].forEach((v, c) => {
			const k = key(v);
			if (!ids.has(k)) {
				ids.set(k, pos.length / 3);
				pos.push(v.x, v.y, v.z);
			}
			index[3 * i + c] = ids.get(k);
		});
	});
	return { positions: Float64Array.from(pos), index };
}

/** A soup from {positions, index}. */
export function fromIndexed(m) {
	const v = (i) => ({ x: m.positions[3 * i], y: m.positions[3 * i + 1], z: m.positions[3 * i + 2] });
	const out = [];
	for (let t = 0; t < m.index.length; t += 3) out.push({ v0: v(m.index[t]), v1: v(m.index[t + 1]), v2: v(m.index[t + 2]) });
	return out;
}
