// The npm package folder: `npm pack` makes a tarball holding the modules, the API, its declarations,
// the WebGPU helper and the WGSL kernels; and the declarations type-check a consumer under tsc
// --strict (TypeScript and @webgpu/types from tools/node, which scripts/setup_web.sh installs).
import { test } from "node:test";
import assert from "node:assert/strict";
import { spawnSync } from "node:child_process";
import { mkdtempSync, mkdirSync, rmSync, symlinkSync, writeFileSync, existsSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";

const packageDir = process.env.ZHF_WEB_PACKAGE;
const tools = process.env.ZHF_NODE_TOOLS;

function temporary() {
  return mkdtempSync(join(tmpdir(), "zhf-web-"));
}

test("npm pack makes the package's tarball", () => {
  const dir = temporary();
  try {
    const r = spawnSync("npm", ["pack", "--json", "--ignore-scripts", "--pack-destination", dir], { cwd: packageDir, encoding: "utf8" });
    assert.equal(r.status, 0, r.stderr);
    const [info] = JSON.parse(r.stdout);
    assert.ok(existsSync(join(dir, info.filename)), info.filename);
    const files = info.files.map((f) => f.path);
    for (const file of ["package.json", "README.md", "zhf.mjs", "zhf.d.mts", "webgpu.mjs", "webgpu.d.mts", "zhf_simd128.wasm",
      "zhf_generic.wasm", ...[2, 3, 4, 5, 6, 7, 8].map((n) => `wgsl/zhf_order${n}.wgsl`)])
      assert.ok(files.includes(file), `${file} is not in the tarball (${files.join(", ")})`);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});

test("the declarations type-check a consumer (tsc --strict)", () => {
  const tsc = join(tools, "node_modules/typescript/bin/tsc");
  assert.ok(existsSync(tsc), `${tsc} missing (scripts/setup_web.sh installs it)`);
  const dir = temporary();
  try {
    mkdirSync(join(dir, "node_modules/@webgpu"), { recursive: true });
    symlinkSync(packageDir, join(dir, "node_modules/zhf"));
    symlinkSync(join(tools, "node_modules/@webgpu/types"), join(dir, "node_modules/@webgpu/types"));
    writeFileSync(join(dir, "tsconfig.json"), JSON.stringify({
      compilerOptions: { strict: true, noEmit: true, target: "es2022", module: "nodenext", moduleResolution: "nodenext",
        lib: ["es2022", "dom"], types: ["@webgpu/types"] },
      files: ["consumer.mts"],
    }));
    writeFileSync(join(dir, "consumer.mts"), `
import { load, type Zhf } from "zhf";
import { createSplatRotator } from "zhf/webgpu";
const zhf: Zhf = await load({ isa: "simd128" });
const r: Float64Array = zhf.rotationFromQuaternion([1, 0, 0, 0]);
const a: Float32Array = zhf.rotate(r, new Float32Array(16), { order: 4 });
const b: Float64Array = zhf.rotateEach(new Float64Array(9), new Float64Array(4), { order: 2, convention: "3dgs" });
const inModule = zhf.allocate("f32", 48);
const c = zhf.rotateSplats(r, inModule, { degree: 3, out: inModule });
c.free();
export async function gpu(device: GPUDevice, input: GPUBuffer, output: GPUBuffer) {
  const rotator = await createSplatRotator(device, { degree: 3, zhf });
  const encoder = device.createCommandEncoder();
  rotator.rotate(encoder, { rotation: r, input, output, count: 10 });
  device.queue.submit([encoder.finish()]);
}
export const used = [a, b];
`);
    const r = spawnSync(process.execPath, [tsc, "-p", dir], { encoding: "utf8" });
    assert.equal(r.status, 0, r.stdout + r.stderr);
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
});
