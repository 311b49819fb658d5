// The page: a 3D Gaussian Splatting scene from the user's disk, turned by drag or slider. Each turn
// rotates every splat's colour SH twice, with zhf's WGSL kernels on the GPU (zhf/webgpu.mjs) and
// with its WebAssembly module on the CPU (zhf/zhf.mjs), shows each path's time and how far apart
// they are, and draws each splat's colour as the camera sees it (point sprites; no Gaussian
// rasterizer). Serve it with examples/web/serve.mjs, which maps ./zhf/ to the package.
// window.zhfPage is the page's handle for tests: open(), setQuaternion(), results().
import { load } from "./zhf/zhf.mjs";
import { createSplatRotator, kernelSource } from "./zhf/webgpu.mjs";
import { readScene } from "./scene.mjs";

// npm's fzstd for .spz version 4 (its attributes are zstd frames), where serve.mjs finds it.
const zstd = (await import("./vendor/fzstd/index.mjs").catch(() => null))?.decompress;

const $ = (id) => document.getElementById(id);
const canvas = $("canvas");
const kPointPixels = 3;

function fail(message) {
  $("message").textContent = message;
  throw new Error(message);
}

const zhf = await load();
const adapter = await navigator.gpu?.requestAdapter();
if (!adapter) fail("This browser has no WebGPU adapter.");
const device = await adapter.requestDevice({ requiredLimits: {
  maxStorageBufferBindingSize: adapter.limits.maxStorageBufferBindingSize, maxBufferSize: adapter.limits.maxBufferSize } });
const emulated = /swiftshader/i.test(adapter.info?.architecture ?? "") || /swiftshader/i.test(adapter.info?.description ?? "");
const context = canvas.getContext("webgpu");
const format = navigator.gpu.getPreferredCanvasFormat();
context.configure({ device, format, alphaMode: "opaque" });

// The scene being shown, its GPU buffers and pipelines, the rotation and the last results.
let view = null;

// The colour of each splat as seen from the camera: 3DGS's SH evaluated at the direction from the
// camera to the splat (its basis is zhf's at (-x, -y, z): sh_eval of the generated kernels), plus
// one half; a square of kPointPixels pixels at the splat's projection (y down, as the .ply's axes).
function renderShader(degree, kernels) {
  const order = Math.max(2, degree + 1), n = (degree + 1) ** 2, rest = n - 1;
  return `${kernels}
struct Camera { look_at: vec3<f32>, distance: f32, focal: f32, aspect: f32, near: f32, far: f32, point: vec2<f32> }
@group(0) @binding(0) var<uniform> camera: Camera;
@group(0) @binding(1) var<storage, read> positions: array<f32>;
@group(0) @binding(2) var<storage, read> colours: array<f32>;
struct Varying { @builtin(position) clip: vec4<f32>, @location(0) colour: vec3<f32> }

@vertex
fn vs(@builtin(vertex_index) corner: u32, @builtin(instance_index) s: u32) -> Varying {
  var out: Varying;
  let p = vec3<f32>(positions[3u * s], positions[3u * s + 1u], positions[3u * s + 2u]);
  let d = p - (camera.look_at - vec3<f32>(0.0, 0.0, camera.distance));
  if (d.z <= camera.near) { out.clip = vec4<f32>(0.0, 0.0, 2.0, 1.0); return out; }
  let u = normalize(d);
  var y: array<f32, ${order * order}>;
  sh_eval_order${order}(array<f32, 3>(-u.x, -u.y, u.z), &y);
  let base = ${3 * n}u * s;
  var c = vec3<f32>(0.5) + y[0] * vec3<f32>(colours[base], colours[base + 1u], colours[base + 2u]);
  for (var k = 1u; k < ${n}u; k++) {
    c += y[k] * vec3<f32>(colours[base + 2u + k], colours[base + ${2 + rest}u + k], colours[base + ${2 + 2 * rest}u + k]);
  }
  out.colour = clamp(c, vec3<f32>(0.0), vec3<f32>(1.0));
  let offsets = array<vec2<f32>, 6>(vec2<f32>(-1.0, -1.0), vec2<f32>(1.0, -1.0), vec2<f32>(-1.0, 1.0),
                                    vec2<f32>(-1.0, 1.0), vec2<f32>(1.0, -1.0), vec2<f32>(1.0, 1.0));
  let w = d.z;
  let z = camera.far * (w - camera.near) / (camera.far - camera.near);
  out.clip = vec4<f32>(camera.focal / camera.aspect * d.x + offsets[corner].x * camera.point.x * w,
                       -camera.focal * d.y + offsets[corner].y * camera.point.y * w, z, w);
  return out;
}

@fragment
fn fs(in: Varying) -> @location(0) vec4<f32> { return vec4<f32>(in.colour, 1.0); }
`;
}

async function openScene(name, bytes) {
  $("message").textContent = "";
  const scene = await readScene(name, bytes, { zstd });
  if (view) for (const b of view.buffers) b.destroy();
  const order = Math.max(2, scene.degree + 1);
  const kernels = await kernelSource(order);
  const storage = (size, extra = 0) => device.createBuffer({ size: Math.max(16, size), usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST | extra });
  const coloursIn = storage(scene.colours.byteLength), coloursOut = storage(scene.colours.byteLength, GPUBufferUsage.COPY_SRC);
  const positions = storage(scene.positions.byteLength);
  const camera = device.createBuffer({ size: 48, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
  device.queue.writeBuffer(coloursIn, 0, scene.colours);
  device.queue.writeBuffer(coloursOut, 0, scene.colours);
  const module = device.createShaderModule({ code: renderShader(scene.degree, kernels) });
  const pipeline = await device.createRenderPipelineAsync({
    layout: "auto",
    vertex: { module, entryPoint: "vs" },
    fragment: { module, entryPoint: "fs", targets: [{ format }] },
    primitive: { topology: "triangle-list" },
    depthStencil: { format: "depth24plus", depthWriteEnabled: true, depthCompare: "less" },
  });
  const group = device.createBindGroup({ layout: pipeline.getBindGroupLayout(0), entries: [
    { binding: 0, resource: { buffer: camera } }, { binding: 1, resource: { buffer: positions } },
    { binding: 2, resource: { buffer: coloursOut } }] });
  // The camera looks along +z at the scene's centre, from 2.5 times its RMS radius.
  let centre = [0, 0, 0], spread = 0;
  for (let s = 0; s < scene.count; ++s) for (let k = 0; k < 3; ++k) centre[k] += scene.positions[3 * s + k] / scene.count;
  for (let s = 0; s < scene.count; ++s) for (let k = 0; k < 3; ++k) spread += (scene.positions[3 * s + k] - centre[k]) ** 2 / scene.count;
  view = {
    name, scene, pipeline, group, camera, positions, coloursIn, coloursOut,
    buffers: [coloursIn, coloursOut, positions, camera],
    rotator: scene.degree > 0 ? await createSplatRotator(device, { degree: scene.degree, zhf, kernels }) : null,
    centre, distance: 2.5 * Math.sqrt(Math.max(spread, 1e-12)),
    cpu: new Float32Array(scene.colours.length), turned: new Float32Array(scene.positions.length),
    quaternion: [1, 0, 0, 0], times: {},
  };
  await turn(view.quaternion);
}

// The rotation of the sliders: yaw about y, then pitch about x, then roll about z, as a quaternion
// (w, x, y, z).
function slidersQuaternion() {
  const half = (id) => (Number($(id).value) * Math.PI) / 360;
  const about = (axis, a) => [Math.cos(a), ...[0, 1, 2].map((k) => (k === axis ? Math.sin(a) : 0))];
  const times = (a, b) => [a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
    a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]];
  return times(times(about(1, half("yaw")), about(0, half("pitch"))), about(2, half("roll")));
}

// Turns the scene by q: positions in JavaScript, colours on the CPU (WebAssembly) and on the GPU
// (WGSL), each timed; then draws it.
async function turn(q) {
  if (!view) return;
  const { scene } = view;
  view.quaternion = q;
  const r = zhf.rotationFromQuaternion(q);
  for (let s = 0; s < scene.count; ++s) {
    const [x, y, z] = scene.positions.subarray(3 * s, 3 * s + 3);
    for (let i = 0; i < 3; ++i) view.turned[3 * s + i] = r[3 * i] * x + r[3 * i + 1] * y + r[3 * i + 2] * z;
  }
  device.queue.writeBuffer(view.positions, 0, view.turned);
  let start = performance.now();
  zhf.rotateSplats(r, scene.colours, { degree: scene.degree, out: view.cpu });
  view.times.cpu = performance.now() - start;
  await device.queue.onSubmittedWorkDone();
  start = performance.now();
  const encoder = device.createCommandEncoder();
  if (view.rotator) view.rotator.rotate(encoder, { rotation: r, input: view.coloursIn, output: view.coloursOut, count: scene.count });
  device.queue.submit([encoder.finish()]);
  await device.queue.onSubmittedWorkDone();
  view.times.gpu = performance.now() - start;
  view.target = [0, 1, 2].map((i) => r[3 * i] * view.centre[0] + r[3 * i + 1] * view.centre[1] + r[3 * i + 2] * view.centre[2]);
  draw();
  showStats();
}

function draw() {
  const width = Math.max(1, Math.round(canvas.clientWidth * devicePixelRatio));
  const height = Math.max(1, Math.round(canvas.clientHeight * devicePixelRatio));
  if (canvas.width !== width || canvas.height !== height) {
    canvas.width = width;
    canvas.height = height;
  }
  if (!view) return;
  const focal = 1.8, aspect = width / height, near = 0.01 * view.distance, far = 10 * view.distance;
  device.queue.writeBuffer(view.camera, 0, new Float32Array([...view.target, view.distance, focal, aspect, near, far,
    kPointPixels / width, kPointPixels / height, 0, 0]));
  if (!view.depth || view.depth.width !== width || view.depth.height !== height) {
    view.depth?.destroy();
    view.depth = device.createTexture({ size: [width, height], format: "depth24plus", usage: GPUTextureUsage.RENDER_ATTACHMENT });
  }
  const encoder = device.createCommandEncoder();
  const pass = encoder.beginRenderPass({
    colorAttachments: [{ view: context.getCurrentTexture().createView(), clearValue: { r: 0.08, g: 0.09, b: 0.11, a: 1 },
      loadOp: "clear", storeOp: "store" }],
    depthStencilAttachment: { view: view.depth.createView(), depthClearValue: 1, depthLoadOp: "clear", depthStoreOp: "store" },
  });
  pass.setPipeline(view.pipeline);
  pass.setBindGroup(0, view.group);
  pass.draw(6, view.scene.count);
  pass.end();
  device.queue.submit([encoder.finish()]);
}

function showStats() {
  const { scene, times } = view;
  $("stats").textContent = [`${view.name}`, `${scene.count.toLocaleString()} splats, SH degree ${scene.degree}`,
    `CPU (WebAssembly, ${zhf.isa}): ${times.cpu.toFixed(2)} ms`, `GPU (WGSL): ${times.gpu.toFixed(2)} ms`,
    ...(emulated ? ["  on SwiftShader, a CPU emulation"] : []),
    view.difference === undefined ? "" : `max |GPU - CPU|: ${view.difference.toExponential(2)}`].join("\n");
}

// The GPU's rotated colours, read back.
async function gpuColours() {
  const bytes = view.scene.colours.byteLength;
  const readback = device.createBuffer({ size: Math.max(16, bytes), usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
  const encoder = device.createCommandEncoder();
  encoder.copyBufferToBuffer(view.coloursOut, 0, readback, 0, Math.max(16, bytes));
  device.queue.submit([encoder.finish()]);
  await readback.mapAsync(GPUMapMode.READ);
  const out = new Float32Array(readback.getMappedRange(0, bytes).slice(0));
  readback.destroy();
  return out;
}

async function compare() {
  const gpu = await gpuColours();
  view.difference = gpu.reduce((worst, g, k) => Math.max(worst, Math.abs(g - view.cpu[k])), 0);
  showStats();
  return gpu;
}

// One turn at a time; a newer request replaces one that waits.
let busy = null, waiting = null;
function request(q) {
  waiting = q;
  if (busy) return busy;
  busy = (async () => {
    while (waiting) {
      const next = waiting;
      waiting = null;
      try {
        await turn(next);
      } catch (e) {
        $("message").textContent = e.message;
      }
    }
    busy = null;
  })();
  return busy;
}

for (const id of ["yaw", "pitch", "roll"]) {
  $(id).addEventListener("input", () => {
    $(`${id}-value`).textContent = `${$(id).value}°`;
    request(slidersQuaternion());
  });
  $(id).addEventListener("change", () => view && busy?.then(compare));
}
let dragFrom = null;
canvas.addEventListener("pointerdown", (e) => {
  dragFrom = [e.clientX, e.clientY, Number($("yaw").value), Number($("pitch").value)];
  canvas.setPointerCapture(e.pointerId);
});
canvas.addEventListener("pointermove", (e) => {
  if (!dragFrom) return;
  const wrap = (a) => ((((a + 180) % 360) + 360) % 360) - 180;
  $("yaw").value = wrap(dragFrom[2] + (e.clientX - dragFrom[0]) / 2);
  $("pitch").value = Math.max(-90, Math.min(90, dragFrom[3] - (e.clientY - dragFrom[1]) / 2));
  $("yaw").dispatchEvent(new Event("input"));
});
canvas.addEventListener("pointerup", () => {
  dragFrom = null;
  if (view) busy ? busy.then(compare) : compare();
});
$("file").addEventListener("change", async () => {
  const file = $("file").files[0];
  if (!file) return;
  try {
    await openScene(file.name, await file.arrayBuffer());
    await compare();
  } catch (e) {
    $("message").textContent = e.message;
  }
});
new ResizeObserver(() => view && draw()).observe(canvas);
draw();

const toBase64 = (floats) => {
  const bytes = new Uint8Array(floats.buffer, floats.byteOffset, floats.byteLength);
  let binary = "";
  for (let k = 0; k < bytes.length; k += 0x8000) binary += String.fromCharCode(...bytes.subarray(k, k + 0x8000));
  return btoa(binary);
};

window.zhfPage = {
  isa: zhf.isa,
  /** The scene open, or null. */
  scene: () => view && { name: view.name, count: view.scene.count, degree: view.scene.degree },
  /** Turns the scene by the quaternion (w, x, y, z), as a drag or the sliders do. */
  setQuaternion: async (q) => {
    await request(q);
    await compare();
  },
  /** The turned positions, the CPU's and the GPU's colours (float32, base64), the times and their distance. */
  results: async () => ({ positions: toBase64(view.turned), cpu: toBase64(view.cpu), gpu: toBase64(await gpuColours()),
    times: view.times, difference: view.difference, emulated }),
};
document.body.dataset.ready = "true";
