// zhf's WebAssembly module turning 3D Gaussian Splatting colours, in Node, against
// @playcanvas/splat-transform 3.7's own SH rotation and against native zhf on one thread, in one run
// (benchmarks/web_splats.sh records it). The same rotation and 10^6 splats of each SH degree 1..4, in
// place, in memory, no file I/O:
//   splat-transform: its bakeTransform over a source that hands back the arrays (its `color`
//                    layer: DC then f_rest channel by channel, zhf's layout), i.e. RotateSH per
//                    splat and channel as its transform bake runs it; it rotates degrees 1..3 only
//                    (at degree 4 the line says whether it refuses or leaves the colours unrotated);
//   zhf wasm:        rotateSplats on a Float32Array (copied into the module and back) and on a
//                    WasmArray (in the module's memory, no copies), simd128 and generic modules;
//                    every call checks every value first (non-finite input is refused);
//   native zhf:      zhf::dispatch's apply_splats on one thread (benchmarks/web_splats_native.cc),
//                    alone and after the same check (dispatch::all_finite), as the CLI and the
//                    Python module run it; the ratio to the WebAssembly module is of the checked.
// Best of RUNS each; ns per splat, and the largest difference between zhf's and splat-transform's
// results (the two must agree).
//   node benchmarks/web_splats.mjs PACKAGE_DIR SPLAT_TRANSFORM_DIR NATIVE_PROGRAM [splats=1000000] [runs=7]
import { spawnSync } from "node:child_process";
import { join } from "node:path";
import { pathToFileURL } from "node:url";

const [packageDir, stDir, native, splatsArg, runsArg] = process.argv.slice(2);
const splats = Number(splatsArg ?? 1000000), runs = Number(runsArg ?? 7);
const zhfModule = await import(pathToFileURL(join(packageDir, "zhf.mjs")).href);
const st = await import(pathToFileURL(join(stDir, "dist/index.mjs")).href);
const kQuaternion = [0.8775825619, 0.1369787253, 0.2054680880, 0.4109361759];  // (w, x, y, z): 1 rad about (2, 3, 6) / 7, as the native program's

function best(work) {
  let fastest = Infinity;
  for (let run = 0; run < runs; ++run) {
    const start = process.hrtime.bigint();
    work();
    fastest = Math.min(fastest, Number(process.hrtime.bigint() - start));
  }
  return fastest / splats;  // ns per splat
}

async function bestAsync(work) {
  let fastest = Infinity;
  for (let run = 0; run < runs; ++run) {
    const start = process.hrtime.bigint();
    await work();
    fastest = Math.min(fastest, Number(process.hrtime.bigint() - start));
  }
  return fastest / splats;
}

const values = (per) => Float32Array.from({ length: per * splats }, (_, i) => Math.sin(i % 65536));

// splat-transform's bake of one rotation over the arrays, in place.
function splatTransformBake(degree) {
  const { Transform } = st;
  const transform = new Transform();
  transform.rotation.set(kQuaternion[1], kQuaternion[2], kQuaternion[3], kQuaternion[0]);
  const source = { meta: { transform, shBands: degree, numGaussians: splats }, read: async () => {}, close: () => {} };
  return st.bakeTransform(source, new Transform());
}

const zhf = { simd128: await zhfModule.load({ isa: "simd128" }), generic: await zhfModule.load({ isa: "generic" }) };
const rotation = zhf.simd128.rotationFromQuaternion(kQuaternion);
const nativeLines = spawnSync(native, [String(splats), String(runs)], { encoding: "utf8" });
if (nativeLines.status !== 0) throw new Error(`${native}: ${nativeLines.stderr}`);
const nativeNs = {}, nativeChecked = {}, nativeIsa = {};
for (const line of nativeLines.stdout.trim().split("\n")) {
  const [, degree, , ns, , checked, , isa] = line.split(" ");
  nativeNs[degree] = Number(ns);
  nativeChecked[degree] = Number(checked);
  nativeIsa[degree] = isa;
}

console.log(`ns per splat, best of ${runs} runs of ${splats} splats; node ${process.version}, splat-transform ${st.version}`);
console.log("");
console.log("| SH degree | splat-transform | zhf simd128, JS arrays | zhf simd128, in module | zhf generic, in module | " +
  "native zhf, one thread: kernel | checked | splat-transform / zhf simd128 | zhf simd128 / native checked | max abs(zhf - splat-transform) |");
console.log("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
for (const degree of [1, 2, 3, 4]) {
  const per = 3 * (degree + 1) ** 2;
  const input = values(per);
  // zhf: the reference result, then the timings.
  const turned = zhf.simd128.rotateSplats(rotation, input, { degree });
  const arrays = input.slice();
  const zhfArrays = best(() => zhf.simd128.rotateSplats(rotation, arrays, { degree, out: arrays }));
  const inModule = {};
  for (const isa of ["simd128", "generic"]) {
    const w = zhf[isa].allocate("f32", input.length);
    w.array.set(input);
    inModule[isa] = best(() => zhf[isa].rotateSplats(rotation, w, { degree, out: w }));
    w.free();
  }
  let stNs = "refused", difference = "-";
  if (degree <= 3) {
    const bake = splatTransformBake(degree);
    const data = input.slice();
    await bake.read({ color: { data: data.buffer, count: splats } });
    difference = data.reduce((worst, v, k) => Math.max(worst, Math.abs(v - turned[k])), 0).toExponential(1);
    const timed = input.slice();
    stNs = await bestAsync(() => bake.read({ color: { data: timed.buffer, count: splats } }));
  } else {
    // Its rotation stops at band 3: past it the bake leaves the colours as they were, or fails.
    const data = input.slice();
    try {
      await splatTransformBake(degree).read({ color: { data: data.buffer, count: splats } });
      stNs = data.every((v, k) => v === input[k]) ? "unrotated" : "rotated?";
    } catch (e) {
      stNs = "refused";
    }
  }
  const f = (x) => (typeof x === "number" ? x.toFixed(1) : x);
  const ratio = (a, b) => (typeof a === "number" ? (a / b).toFixed(2) : "-");
  console.log(`| ${[degree, f(stNs), f(zhfArrays), f(inModule.simd128), f(inModule.generic), `${f(nativeNs[degree])} (${nativeIsa[degree]})`,
    f(nativeChecked[degree]), ratio(stNs, inModule.simd128), ratio(inModule.simd128, nativeChecked[degree]), difference].join(" | ")} |`);
}
