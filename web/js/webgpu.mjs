// zhf's WGSL kernels on WebGPU: 3D Gaussian Splatting colours rotated on the GPU, the same rotation
// zhf.rotateSplats does on the CPU (zhf.mjs). Core WebGPU only.
//
// The kernels are zhf's generated WGSL (wgsl/zhf_orderN.wgsl beside this file, in zhf's
// convention); the rotation is brought into zhf's terms by the WebAssembly module
// (Zhf.rotationInZhfTerms), so one implementation of the conventions serves both paths. Layout as
// rotateSplats: per splat band 0's R, G, B, then bands 1.. of R, of G and of B, float32.

const kWorkgroup = 64;
const kMaxGroupsPerDimension = 65535;

/** The WGSL kernels of order N (degree N - 1), fetched from beside this module. */
export async function kernelSource(order) {
  const url = new URL(`wgsl/zhf_order${order}.wgsl`, import.meta.url);
  if (url.protocol === "file:") {
    const { readFile } = await import("node:fs/promises");
    return readFile(url, "utf8");
  }
  const response = await fetch(url);
  if (!response.ok) throw new Error(`zhf: ${url}: ${response.status} ${response.statusText}`);
  return response.text();
}

/** The compute shader that rotates every splat of SH degree 1.. with rotate_rgb_orderN: the
 * kernels' source followed by an entry point `main` (bind group 0: the rotation, 9 floats in zhf's
 * terms; the splats in; the splats out). */
export function splatShader(degree, kernels) {
  const order = degree + 1, rest = order * order - 1, per = 3 * order * order;
  return `${kernels}
@group(0) @binding(0) var<storage, read> rotation: array<f32, 9>;
@group(0) @binding(1) var<storage, read> splats_in: array<f32>;
@group(0) @binding(2) var<storage, read_write> splats_out: array<f32>;

const kFloatsPerSplat: u32 = ${per}u;

@compute @workgroup_size(${kWorkgroup})
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
  let splat = id.x + id.y * ${kWorkgroup * kMaxGroupsPerDimension}u;
  if (splat >= arrayLength(&splats_in) / kFloatsPerSplat) { return; }
  let base = splat * kFloatsPerSplat;
  var coeffs: array<vec3<f32>, ${order * order}>;
  coeffs[0] = vec3<f32>(splats_in[base], splats_in[base + 1u], splats_in[base + 2u]);
  for (var i = 1u; i < ${order * order}u; i++) {
    let k = base + 2u + i;
    coeffs[i] = vec3<f32>(splats_in[k], splats_in[k + ${rest}u], splats_in[k + ${2 * rest}u]);
  }
  var rotated: array<vec3<f32>, ${order * order}>;
  rotate_rgb_order${order}(rotation, coeffs, &rotated);
  splats_out[base] = rotated[0].x;
  splats_out[base + 1u] = rotated[0].y;
  splats_out[base + 2u] = rotated[0].z;
  for (var i = 1u; i < ${order * order}u; i++) {
    let k = base + 2u + i;
    splats_out[k] = rotated[i].x;
    splats_out[k + ${rest}u] = rotated[i].y;
    splats_out[k + ${2 * rest}u] = rotated[i].z;
  }
}
`;
}

/**
 * A rotator of splats of SH degree 1..4 on `device`. options.zhf: the loaded WebAssembly module
 * (for the conventions); options.kernels: the WGSL of order degree + 1 (default: kernelSource).
 * rotate() records the work on `encoder` in parts of at most the device's storage-binding size
 * (whole splats, offsets at its alignment) and returns; submit the encoder to run it.
 */
export async function createSplatRotator(device, { degree, zhf, kernels }) {
  if (!Number.isInteger(degree) || degree < 1 || degree > zhf.maxSplatDegree)
    throw new RangeError(`zhf.createSplatRotator: degree: ${String(degree)} is not an integer 1..${zhf.maxSplatDegree}`);
  const code = splatShader(degree, kernels ?? await kernelSource(degree + 1));
  const module = device.createShaderModule({ code });
  const info = await module.getCompilationInfo();
  const errors = info.messages.filter((m) => m.type === "error");
  if (errors.length) throw new Error(`zhf: the WGSL kernels of order ${degree + 1} did not compile: ${errors[0].message}`);
  const pipeline = await device.createComputePipelineAsync({ layout: "auto", compute: { module, entryPoint: "main" } });
  const bytesPerSplat = 12 * (degree + 1) ** 2;
  // Splats per part: whole splats that keep every part's offset a multiple of the alignment.
  const alignment = device.limits.minStorageBufferOffsetAlignment;
  const step = alignment / gcd(alignment, bytesPerSplat);
  const perPart = Math.floor(device.limits.maxStorageBufferBindingSize / bytesPerSplat / step) * step;
  return {
    degree,
    bytesPerSplat,
    /** Records the rotation of `count` splats from `input` to `output` (GPU buffers with STORAGE
     * usage; distinct) by `rotation` (9 numbers, row-major, in the convention's axes). */
    rotate(encoder, { rotation, convention = "3dgs", input, output, count }) {
      // A buffer of its own per call: the encoder may hold several rotations before it is submitted.
      const rotationBuffer = device.createBuffer({ size: 9 * 4, usage: GPUBufferUsage.STORAGE, mappedAtCreation: true });
      new Float32Array(rotationBuffer.getMappedRange()).set(zhf.rotationInZhfTerms(rotation, { convention }));
      rotationBuffer.unmap();
      for (let first = 0; first < count; first += perPart) {
        const splats = Math.min(perPart, count - first);
        const window = { offset: first * bytesPerSplat, size: splats * bytesPerSplat };
        const group = device.createBindGroup({
          layout: pipeline.getBindGroupLayout(0),
          entries: [
            { binding: 0, resource: { buffer: rotationBuffer } },
            { binding: 1, resource: { buffer: input, ...window } },
            { binding: 2, resource: { buffer: output, ...window } },
          ],
        });
        const pass = encoder.beginComputePass();
        pass.setPipeline(pipeline);
        pass.setBindGroup(0, group);
        const groups = Math.ceil(splats / kWorkgroup);
        pass.dispatchWorkgroups(Math.min(groups, kMaxGroupsPerDimension), Math.ceil(groups / kMaxGroupsPerDimension));
        pass.end();
      }
    },
  };
}

function gcd(a, b) {
  return b ? gcd(b, a % b) : a;
}
