// Type declarations of zhf.mjs: rotation of real spherical-harmonic vectors in WebAssembly.

/** The instruction-set path of a module: SIMD128, or scalar WebAssembly. */
export type Isa = "simd128" | "generic";
/** The SH conventions zhf converts at the edge (docs/conventions.md). */
export type Convention = "zhf" | "condon-shortley" | "3dgs" | "y-up-rh" | "y-up-lh";
/** A 3x3 matrix, row-major, mapping v to R v: 9 numbers. */
export type Matrix = ArrayLike<number>;
export type FloatArray = Float32Array | Float64Array;

export interface LoadOptions {
  /** Which module (default: "simd128" where the engine runs SIMD128). */
  isa?: Isa;
  /** The module's bytes or a compiled module (default: the .wasm file beside zhf.mjs). */
  module?: BufferSource | WebAssembly.Module;
}

/** Whether this engine runs WebAssembly SIMD128. */
export function simdSupported(): boolean;
/** Loads zhf's WebAssembly module. */
export function load(options?: LoadOptions): Promise<Zhf>;

/** An array inside the module's memory: calls read and write it in place, without copies. */
export class WasmArray<K extends "f32" | "f64" = "f32" | "f64"> {
  readonly kind: K;
  readonly length: number;
  /** A view of the values, made anew on each read (the module's memory may have grown). */
  readonly array: K extends "f32" ? Float32Array : Float64Array;
  free(): void;
}

type F32 = Float32Array | WasmArray<"f32">;
type F64 = Float64Array | WasmArray<"f64">;

export interface RotateOptions {
  /** Order N: N bands, N^2 coefficients a vector; 1..maxOrder. */
  order: number;
  /** The convention of the rotation's axes and of the coefficients (default "zhf"). */
  convention?: Convention;
}

export interface SplatOptions {
  /** SH degree 0..maxSplatDegree (order degree + 1). */
  degree: number;
  /** The scene's convention (default "3dgs"). */
  convention?: Convention;
}

/** Each call returns `out` when given (of the input's type and length; it may be the input itself,
 * for a rotation in place), else a new typed array of the input's element type. */
export class Zhf {
  readonly isa: Isa;
  readonly maxOrder: number;
  readonly maxSplatDegree: number;
  readonly conventions: Convention[];
  /** An array of `length` values inside the module; free() it when done. */
  allocate<K extends "f32" | "f64">(kind: K, length: number): WasmArray<K>;
  /** The rotation matrix of a quaternion of any nonzero length. */
  rotationFromQuaternion(quaternion: ArrayLike<number>, options?: { order?: "wxyz" | "xyzw" }): Float64Array;
  /** A rotation in a convention's axes, for its coefficients, as zhf's kernels (C++, WGSL) take it. */
  rotationInZhfTerms(rotation: Matrix, options?: { convention?: Convention }): Float64Array;
  /** Every vector (N^2 values each) under one rotation. */
  rotate<O extends F32 | F64>(rotation: Matrix, coefficients: O, options: RotateOptions & { out: O }): O;
  rotate(rotation: Matrix, coefficients: F32, options: RotateOptions): Float32Array;
  rotate(rotation: Matrix, coefficients: F64, options: RotateOptions): Float64Array;
  /** Vector v under rotation v (9 numbers each in `rotations`). */
  rotateEach<O extends F32 | F64>(rotations: ArrayLike<number>, coefficients: O, options: RotateOptions & { out: O }): O;
  rotateEach(rotations: ArrayLike<number>, coefficients: F32, options: RotateOptions): Float32Array;
  rotateEach(rotations: ArrayLike<number>, coefficients: F64, options: RotateOptions): Float64Array;
  /** 3D Gaussian Splatting colours in the .ply's layout (band 0 RGB, then f_rest channel by channel). */
  rotateSplats<O extends F32>(rotation: Matrix, splats: F32, options: SplatOptions & { out: O }): O;
  rotateSplats(rotation: Matrix, splats: F32, options: SplatOptions): Float32Array;
}
