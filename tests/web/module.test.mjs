// The WebAssembly module through its JavaScript API, both builds (SIMD128 and scalar), against what
// the native build writes (web_reference.cc: the long-double reference and the native tests'
// tolerance for each order and type): every order 1..16 (the generated kernels and the run-time
// orders), one rotation for many vectors and one per vector, float and double, three conventions;
// 3DGS splats of degree 0..4; in place and in the module's own memory. Then bad input at the
// boundary: a wrong type or length, NaN, a matrix that is not a rotation, an order or degree out
// of range, each refused with the argument named and no output changed; and the package as npm
// packs it.
// Run: ZHF_WEB_PACKAGE=<build>/web/package ZHF_WEB_REFERENCE=<file> node --test tests/web/
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { pathToFileURL } from "node:url";

const packageDir = process.env.ZHF_WEB_PACKAGE;
const reference = JSON.parse(readFileSync(process.env.ZHF_WEB_REFERENCE, "utf8"));
const { load, simdSupported } = await import(pathToFileURL(`${packageDir}/zhf.mjs`).href);

const kIsas = ["simd128", "generic"];
const modules = Object.fromEntries(await Promise.all(kIsas.map(async (isa) => [isa, await load({ isa })])));

// Where value k of count vectors of order^2 values lies: which vector, band and index.
const inVectors = (order) => (k) => {
  const n = order * order, i = k % n;
  return `vector ${Math.floor(k / n)}, band ${Math.floor(Math.sqrt(i))}, index ${i}`;
};
// The same for splats in the .ply's layout: band 0's R, G, B, then bands 1.. of each channel.
const inSplats = (order) => (k) => {
  const per = 3 * order * order, rest = order * order - 1, j = k % per;
  const [channel, i] = j < 3 ? [j, 0] : [Math.floor((j - 3) / rest), 1 + ((j - 3) % rest)];
  return `splat ${Math.floor(k / per)}, channel ${"RGB"[channel]}, band ${Math.floor(Math.sqrt(i))}, index ${i}`;
};

// Fails naming where the worst value lies when it is past the tolerance.
function expectClose(got, expected, tolerance, where, place) {
  assert.equal(got.length, expected.length, `${where}: length`);
  let worst = 0, at = 0;
  for (let k = 0; k < got.length; ++k) {
    const error = Math.abs(got[k] - expected[k]);
    if (!(error <= worst)) worst = error, at = k;
  }
  assert.ok(worst <= tolerance, `${where}: ${place(at)}: error ${worst} > tolerance ${tolerance}`);
}

test("load() takes SIMD128 where the engine runs it, and each module names its path", () => {
  assert.equal(simdSupported(), true);  // Node 20 and every current browser
  for (const isa of kIsas) assert.equal(modules[isa].isa, isa);
});

for (const isa of kIsas) {
  const zhf = modules[isa];
  test(`${isa}: every order 1..16, shared and per-vector rotations, float and double, against the native reference`, () => {
    for (const c of reference.cases) {
      for (const [type, Type] of [["float", Float32Array], ["double", Float64Array]]) {
        const where = `${isa}, order ${c.order}, ${c.convention}, ${type}`;
        const input = Type.from(c.coefficients);
        const shared = zhf.rotate(c.rotation, input, { order: c.order, convention: c.convention });
        assert.ok(shared instanceof Type);
        expectClose(shared, c.rotated, c.tolerance[type], `${where}, one rotation`, inVectors(c.order));
        const each = zhf.rotateEach(Type.from(c.rotations), input, { order: c.order, convention: c.convention });
        expectClose(each, c.rotated_each, c.tolerance[type], `${where}, a rotation per vector`, inVectors(c.order));
        // In place: the output is the input's own array.
        const inPlace = Type.from(c.coefficients);
        assert.equal(zhf.rotate(c.rotation, inPlace, { order: c.order, convention: c.convention, out: inPlace }), inPlace);
        assert.deepEqual(inPlace, shared);
      }
    }
  });

  test(`${isa}: 3DGS splats of degree 0..4 against the native reference, in JS arrays and in module memory`, () => {
    for (const s of reference.splats) {
      const where = `${isa}, splats of degree ${s.degree} (order ${s.degree + 1})`;
      const input = Float32Array.from(s.splats);
      const out = zhf.rotateSplats(s.rotation, input, { degree: s.degree });
      expectClose(out, s.rotated, s.tolerance.float, where, inSplats(s.degree + 1));
      const inModule = zhf.allocate("f32", input.length);
      inModule.array.set(input);
      assert.equal(zhf.rotateSplats(s.rotation, inModule, { degree: s.degree, out: inModule }), inModule);
      assert.deepEqual(inModule.array, out);
      inModule.free();
    }
  });
}

test("quaternions: (w, x, y, z) and (x, y, z, w) give the same matrix, of any nonzero length", () => {
  const zhf = modules.simd128;
  const half = 0.35, axis = [2 / 7, 3 / 7, 6 / 7];
  const q = [Math.cos(half), ...axis.map((a) => a * Math.sin(half))];
  const r = zhf.rotationFromQuaternion(q);
  assert.deepEqual(zhf.rotationFromQuaternion([q[1], q[2], q[3], q[0]].map((x) => 3 * x), { order: "xyzw" })
    .map((x, k) => Math.round((x - r[k]) * 1e12)), new Float64Array(9));
  // The axis is fixed by the rotation.
  for (let i = 0; i < 3; ++i) assert.ok(Math.abs(r[3 * i] * axis[0] + r[3 * i + 1] * axis[1] + r[3 * i + 2] * axis[2] - axis[i]) < 1e-15);
});

test("bad input at the boundary: one error naming the argument, no output changed", () => {
  const zhf = modules.simd128;
  const I = [1, 0, 0, 0, 1, 0, 0, 0, 1];
  const good = new Float32Array(32).fill(0.25);
  const splats = new Float32Array(48).fill(0.25);
  const calls = [
    [() => zhf.rotate(I, good, { order: 4, out: new Float32Array(31) }), TypeError, /zhf\.rotate: out: /],
    [() => zhf.rotate(I, new Float32Array(17), { order: 4 }), TypeError, /zhf\.rotate: coefficients: length 17 is not a multiple of 16/],
    [() => zhf.rotate(I, [1, 2, 3, 4], { order: 2 }), TypeError, /zhf\.rotate: coefficients: a Float32Array/],
    [() => zhf.rotate(I.slice(0, 8), good, { order: 4 }), TypeError, /zhf\.rotate: rotation: 8 numbers, not 9/],
    [() => zhf.rotate(I, good, { order: 0 }), RangeError, /zhf\.rotate: order: 0 is not an integer 1\.\.128/],
    [() => zhf.rotate(I, good, { order: 4, convention: "ue5" }), RangeError, /zhf\.rotate: convention: 'ue5' is not one of zhf, /],
    [() => zhf.rotate([1, 0, 0, 0, 1, 0, 0, 0, NaN], good, { order: 4 }), RangeError, /zhf\.rotate: rotation: .*non-finite/],
    [() => zhf.rotate([1, 0, 0, 0, 1, 0, 0, 0, -1], good, { order: 4 }), RangeError, /zhf\.rotate: rotation: .*reflection/],
    [() => zhf.rotate([1, 0.1, 0, 0, 1, 0, 0, 0, 1], good, { order: 4 }), RangeError, /zhf\.rotate: rotation: .*not orthonormal/],
    [() => zhf.rotateEach(new Float32Array(18).fill(0), good, { order: 4 }), RangeError, /zhf\.rotateEach: rotations\[0\]: /],
    [() => zhf.rotateEach(new Float32Array(9), good, { order: 4 }), TypeError, /zhf\.rotateEach: rotations: 9 numbers, not 18/],
    [() => zhf.rotateSplats(I, splats, { degree: 5 }), RangeError, /zhf\.rotateSplats: degree: 5 is not an integer 0\.\.4/],
    [() => zhf.rotateSplats(I, new Float64Array(48), { degree: 3 }), TypeError, /zhf\.rotateSplats: splats: a Float32Array/],
    [() => zhf.rotateSplats(I, new Float32Array(47), { degree: 3 }), TypeError, /zhf\.rotateSplats: splats: length 47/],
    [() => zhf.rotationFromQuaternion([0, 0, 0, 0]), RangeError, /zhf\.rotationFromQuaternion: quaternion: zero or not finite/],
  ];
  for (const [call, type, pattern] of calls) assert.throws(call, (e) => e instanceof type && pattern.test(e.message), String(call));
  // A NaN among the inputs, in JS arrays and in module memory: refused, the output untouched.
  const poisoned = good.slice();
  poisoned[21] = NaN;
  const out = new Float32Array(32).fill(7);
  assert.throws(() => zhf.rotate(I, poisoned, { order: 4, out }), /zhf\.rotate: coefficients\[21\]: not a finite number/);
  assert.deepEqual(out, new Float32Array(32).fill(7));
  const inModule = zhf.allocate("f32", 48);
  inModule.array.set(splats);
  inModule.array[40] = Infinity;
  const before = inModule.array.slice();
  assert.throws(() => zhf.rotateSplats([0, -1, 0, 1, 0, 0, 0, 0, 1], inModule, { degree: 3, out: inModule }), /splats\[40\]: not a finite/);
  assert.deepEqual(inModule.array, before);
  inModule.free();
  const sameOut = new Float32Array(32).fill(7);
  assert.throws(() => zhf.rotate([0, 0, 1, 0, 1, 0, 1, 0, 0], good, { order: 4, out: sameOut }), /reflection/);
  assert.deepEqual(sameOut, new Float32Array(32).fill(7));
});
