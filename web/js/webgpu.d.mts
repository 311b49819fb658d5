// Type declarations of webgpu.mjs (GPU types: @webgpu/types): 3D Gaussian Splatting colours rotated by zhf's WGSL kernels.
import type { Convention, Matrix, Zhf } from "./zhf.mjs";

/** The WGSL kernels of order N, fetched from beside the module (wgsl/zhf_orderN.wgsl). */
export function kernelSource(order: number): Promise<string>;
/** The compute shader rotating splats of SH degree 1.. (entry point main). */
export function splatShader(degree: number, kernels: string): string;

export interface SplatRotator {
  readonly degree: number;
  readonly bytesPerSplat: number;
  /** Records the rotation of `count` splats from `input` to `output` on `encoder`. */
  rotate(encoder: GPUCommandEncoder, args: { rotation: Matrix; convention?: Convention; input: GPUBuffer; output: GPUBuffer; count: number }): void;
}

/** A rotator of splats of SH degree 1..4 on `device`. */
export function createSplatRotator(device: GPUDevice, options: { degree: number; zhf: Zhf; kernels?: string }): Promise<SplatRotator>;
