/* The C API of zhf's WebAssembly module: what web/js/zhf.mjs calls, and what any other host of the
 * module may call. It is zhf::dispatch (dispatch/include/zhf/dispatch/rotator.h) compiled for one
 * WebAssembly path, "simd128" or the scalar "generic", with the conventions of runtime/conventions.h
 * applied at the edge. Conventions as the runtime's: real SH, index l(l+1)+m, R row-major mapping
 * v to R v, the result the coefficients of f(R^T w) (docs/conventions.md).
 *
 * Every call that can fail returns 0 on success, else 1 with zhf_web_error() naming the argument and
 * what is wrong in one line; a call that fails writes nothing to its output. Inputs and outputs may
 * be the same array (the call then reads everything before it writes). Work runs on the calling
 * thread. Accuracy: float within tolerance::kFloatRotation at orders 2..8 and kRuntimeOrdersFloat
 * above; double within kDouble (runtime/tolerances.h). */
#ifndef ZHF_WEB_ZHF_WEB_H
#define ZHF_WEB_ZHF_WEB_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* "simd128" or "generic": the instruction-set path this module was built for. */
const char* zhf_web_isa(void);
/* The last failed call's message (empty after a success). */
const char* zhf_web_error(void);
/* The largest order rotate and rotate_each take, and the largest SH degree rotate_splats takes. */
int zhf_web_max_order(void);
int zhf_web_max_splat_degree(void);
/* The conventions (runtime/conventions.h) by index: their count and names. */
int zhf_web_convention_count(void);
const char* zhf_web_convention_name(int index);

/* The rotation of the quaternion q = (w, x, y, z), of any nonzero length, into out[9]. */
int zhf_web_rotation_from_quaternion(const double* q, double* out);
/* A rotation given in the convention's axes, for the convention's coefficients, as zhf's kernels
 * take it (out[9]): what every call below does first, for callers of the WGSL kernels. */
int zhf_web_rotation_in_zhf_terms(int convention, const double* rotation, double* out);

/* count vectors of order N (N^2 values each) under one rotation, given in the convention's own axes
 * and applied to coefficients in that convention (conventions.h: K R K in zhf's terms). */
int zhf_web_rotate_f32(int order, int convention, const double* rotation, size_t count, const float* in, float* out);
int zhf_web_rotate_f64(int order, int convention, const double* rotation, size_t count, const double* in, double* out);
/* count vectors, each under its own rotation: rotations[9 v + k], row-major. */
int zhf_web_rotate_each_f32(int order, int convention, size_t count, const float* rotations, const float* in, float* out);
int zhf_web_rotate_each_f64(int order, int convention, size_t count, const double* rotations, const double* in, double* out);
/* count 3D Gaussian Splatting splats of SH degree 0..zhf_web_max_splat_degree() in the .ply's layout:
 * per splat 3 band-0 values (R, G, B), then bands 1.. of R, of G and of B ((degree + 1)^2 - 1
 * each), under one rotation in the convention's axes (3D Gaussian Splatting's is "3dgs"). */
int zhf_web_rotate_splats_f32(int degree, int convention, const double* rotation, size_t count, const float* in, float* out);

/* Memory inside the module for the arrays above (JavaScript fills it in place): bytes aligned to
 * 16, or null when the module cannot grow that far. */
void* zhf_web_alloc(size_t bytes);
void zhf_web_free(void* pointer);

#ifdef __cplusplus
}
#endif

#endif /* ZHF_WEB_ZHF_WEB_H */
