// Rotates the colour SH of every splat of a 3D Gaussian Splatting scene (degree 3: order 4) by one
// rotation, with zhf's generated WGSL kernel. Prepend the kernels to this source:
//   zhf emit --table generated/lobes/order_4.json --lang wgsl --convention 3dgs --out kernels/
//   device.createShaderModule({code: kernelsText + thisText})
// (--convention 3dgs folds 3DGS's sign convention and axes into the kernel; generated/wgsl/ holds
// zhf's own convention.) Layout per splat, as 3DGS's .ply stores it: f_dc_0..2, then f_rest_0..44
// channel by channel (15 red, 15 green, 15 blue coefficients of bands 1..3): 48 floats.
// Core WebGPU: the splat count is the input's length. The test suite runs this file on Vulkan
// through naga against the C++ kernel (tests/verify/webgpu_example_test.cc); the npm package's
// webgpu.mjs (web/js) makes the same shader for any degree and runs it in a browser.

@group(0) @binding(0) var<storage, read> rotation: array<f32, 9>;  // R, row-major, v -> R v
@group(0) @binding(1) var<storage, read> splats_in: array<f32>;
@group(0) @binding(2) var<storage, read_write> splats_out: array<f32>;

const kFloatsPerSplat: u32 = 48u;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
  let splat = id.x;
  if (splat >= arrayLength(&splats_in) / kFloatsPerSplat) { return; }
  let base = splat * kFloatsPerSplat;
  var coeffs: array<vec3<f32>, 16>;
  coeffs[0] = vec3<f32>(splats_in[base], splats_in[base + 1u], splats_in[base + 2u]);
  for (var i = 1u; i < 16u; i++) {
    let rest = base + 3u + (i - 1u);
    coeffs[i] = vec3<f32>(splats_in[rest], splats_in[rest + 15u], splats_in[rest + 30u]);
  }
  var rotated: array<vec3<f32>, 16>;
  rotate_rgb_order4(rotation, coeffs, &rotated);
  splats_out[base] = rotated[0].x;
  splats_out[base + 1u] = rotated[0].y;
  splats_out[base + 2u] = rotated[0].z;
  for (var i = 1u; i < 16u; i++) {
    let rest = base + 3u + (i - 1u);
    splats_out[rest] = rotated[i].x;
    splats_out[rest + 15u] = rotated[i].y;
    splats_out[rest + 30u] = rotated[i].z;
  }
}
