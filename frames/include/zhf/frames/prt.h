// Precomputed radiance transfer (Sloan, Kautz and Snyder 2002) with SH and with needlets, against
// the integral itself: the founding talk's case for needlets, measured.
//
// Receivers are vertices on the ground plane z = 0 (normal +z) under occluders; vertex p's
// transfer is T_p(w) = V_p(w) max(0, w_z) / pi (diffuse, albedo 1) or V_p(w) max(0, w_z)
// (e + 2) / (2 pi) max(0, w . r)^e (glossy Phong lobe about r, the mirror of the viewer
// (1, 0, 1) / sqrt2, e = kGlossyExponent), V_p(w) = 1 when the ray p + s w, s > 0, misses every
// occluder. Shading under sky L is  s_p = int L T_p.
//  - exact (prt_exact_shading): every occluder seen from p is a cap of directions (a sphere's
//    cone, a wall's half-space), so the visible sky is the upper hemisphere less a union of caps,
//    bounded by circles. It is integrated in (theta, phi) about the normal with the visible theta
//    intervals of each meridian found in closed form, and phi split wherever those intervals
//    change their form (a cap's edge tangent to a meridian, crossing the horizon, or crossing
//    another cap's edge); each phi piece is mapped by a cubic with zero slope at both ends, which
//    turns the square-root behaviour at a tangency into a smooth one, and both integrals are
//    composite Gauss-Legendre. Exact to 1e-10 of the shading for smooth skies (the convergence
//    table in docs/frames.md); an image sky's pixel edges are not split, so there it is a fine
//    quadrature, not an exact one;
//  - SH with K = n^2 coefficients: sum over bands < n of L_lm T_lm (the projections by the Gauss
//    product rule of degree 126), and a control that keeps each vertex's K largest |T_lm|;
//  - needlets with K coefficients: the frame's coefficients of T_p (analysed from those SH to the
//    band limit), the K largest |beta_T| kept per vertex, sum beta_T beta_L over them. With every
//    coefficient this is the SH sum exactly (Parseval: the frame is tight).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "zhf/frames/limits.h"
#include "zhf/frames/needlets.h"

namespace zhf::frames {

enum class PrtScene { kOpen, kSphere, kCorner, kSpheres };
enum class PrtTransfer { kDiffuse, kGlossy };
inline constexpr int kGlossyExponent = 20;
// Names as the CLI spells them ("open": the ground alone, "sphere", "corner", "spheres";
// "diffuse", "glossy"); false if unknown.
bool parse_prt_scene(const std::string& name, PrtScene& scene);
bool parse_prt_transfer(const std::string& name, PrtTransfer& transfer);

using Radiance = std::function<double(const Point&)>;

// The vertices: a side x side grid over [-1.5, 1.5]^2 on z = 0.
std::vector<Point> prt_vertices(int side);
// 1 when the ray from p towards w (unit) leaves the scene unoccluded, else 0.
double prt_visibility(PrtScene scene, const Point& p, const Point& w);
double prt_transfer(PrtScene scene, PrtTransfer transfer, const Point& p, const Point& w);

// The exact reference's panel width (radians) and Gauss-Legendre nodes per panel: step 0.1 agrees
// with 0.05 to 1e-11 of the shadings' RMS on every built-in scene and transfer under sun_and_sky
// (benchmarks/results/prt/reference.txt).
inline constexpr double kPrtExactStep = 0.1;
inline constexpr int kPrtExactNodes = 16;
// int L T_p for a vertex on the ground (z = 0; under the walls' tops and outside the spheres, as
// prt_vertices are), by the cap integration above; step is the panel width. Cost: about
// (2 pi / step) (pi / 2 / step) 1.5 kPrtExactNodes^2 sky and transfer evaluations (1.5e5 at 0.1).
// Throws std::invalid_argument for a vertex off the ground or inside an occluder.
double prt_exact_shading(PrtScene scene, PrtTransfer transfer, const Radiance& sky, const Point& p,
                         double step = kPrtExactStep);

// Bytes a vertex stores for K coefficients of kPrtValueBytes each (float): SH by whole bands
// implies its indices; the K largest of n coefficients (SH control, needlets) store an index each,
// of the fewest whole bytes that count n.
inline constexpr int kPrtValueBytes = 4;
int prt_bytes_whole_bands(int coefficients);
int prt_bytes_largest(int kept, int of);
// A clear sky with a sun: 0.25 + 0.75 w_z above the horizon, 0.15 below (ground), plus a sun of
// peak 40 and width ~1/sqrt(300) rad towards (0.5, 0.3, 0.8) normalised.
double sun_and_sky(const Point& w);
// An equirectangular image as a sky: row 0 at +z, phi from +x towards +y, the luminance (Rec. 709
// weights) of the pixel holding the direction. rgb: width x height pixels, row-major from the top
// row, 3 floats a pixel.
Radiance equirectangular_sky(int width, int height, std::shared_ptr<const std::vector<float>> rgb);

struct PrtRow {
  int kept = 0;                        // coefficients per vertex
  std::vector<double> sh, sh_best, needlet;  // each vertex's shading: SH bands, SH's K largest, needlets
  double sh_rms = 0, sh_worst = 0;     // shading error relative to the RMS / largest exact value
  double sh_best_rms = 0, sh_best_worst = 0;
  double needlet_rms = 0, needlet_worst = 0;
  int sh_bytes = 0, sh_best_bytes = 0, needlet_bytes = 0;  // storage per vertex
  double sh_sky_min = 0, needlet_sky_min = 0;  // least value of the sky rebuilt from K coefficients
};
struct PrtReport {
  int vertices = 0, sh_coefficients = 0, needlet_coefficients = 0;
  double exact_rms = 0, sky_min = 0;   // the true sky's least value
  std::vector<Point> vertex_positions;
  std::vector<double> exact;           // each vertex's exact shading
  double parseval_gap = 0;             // max |needlets, all kept - SH, all kept| / exact RMS
  std::vector<PrtRow> rows;            // one per K asked, then all coefficients
  // Rotation of the sky through a sweep of turns: per needlet level, the largest relative change
  // of its energy through the tabulated rotation (exact rotation changes none); and the energy
  // the K largest needlet coefficients of the turned sky hold, least and greatest over the sweep
  // (SH bands hold the same energy in every turn).
  std::vector<double> level_energy_change;
  std::vector<double> kept_energy_least, kept_energy_greatest;  // per K asked
};

// Throws std::invalid_argument for side outside 1..frames::kMaxPrtSide or a K outside 1..frame.size(). Calls
// checkpoint(vertices done, vertices) (which may throw) between vertices of the exact shading, the
// most of the cost, and between the later stages. threads: 0 for all cores; the report is the same
// for every count. Cost: vertices x (8128 samples + prt_exact_shading's + frame size x L^2).
PrtReport prt_experiment(const NeedletFrame& frame, PrtScene scene, PrtTransfer transfer, const Radiance& sky, int side,
                         const std::vector<int>& kept, int table_size,
                         const std::function<void(int, int)>& checkpoint = {}, int threads = 0);

}  // namespace zhf::frames
