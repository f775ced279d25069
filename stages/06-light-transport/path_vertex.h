// Stage 6: paths as lists of vertices. Written over paths instead of directions, the rendering
// equation becomes one integral over all paths x_0 x_1 ... x_k (camera at x_0, light at x_k):
//     I = sum_k integral f(x_0 ... x_k) dA(x_1) ... dA(x_k),
//     f = We(x_0 <- x_1) G(x_0, x_1) [prod_i f_s(x_i) G(x_i, x_i+1)] Le(x_k -> x_k-1),
//     G(a, b) = |cos(theta_a)| |cos(theta_b)| / |a - b|^2   (visibility included)
// (Veach's thesis, chapter 8, the path integral formulation). A path tracer samples it from the
// camera end, a light tracer from the light end, and BDPT from both at once; all of them are
// estimators f(x) / p(x) of the same integral, and differ only in the density p(x) of the path.
//
// That density is a product of one factor per vertex, each per unit AREA: p_A(x_i) = p_w(x_i) |cos
// theta_i| / |x_i - x_i-1|^2 for a direction sampled at the vertex before (a solid-angle density
// converted to area at the vertex it reaches). BDPT needs each vertex's density in both directions
// (pdf_fwd: as its own subpath sampled it; pdf_rev: as the other end would have), because the
// same path made by another strategy has its vertices sampled the other way round
// (docs/stage6.md, section 4). The random walk fills both in as it goes.
#pragma once

#include "04-radiometry/direct_lighting.h"
#include "common/camera.h"
#include "common/emission.h"

#include <optional>
#include <vector>

namespace rt {

enum class VertexKind { camera, light, surface };

struct PathVertex {
  VertexKind kind = VertexKind::surface;
  // Point, geometric normal (turned to the side the subpath arrived from; a light's front; the
  // camera's view direction) and rounding error, so that stage 2's offsets apply to rays leaving it.
  Hit hit;
  std::optional<ShadingPoint> at;  // surfaces only: the BSDF and the shading frame
  // The subpath's throughput up to this vertex: for a camera subpath the product of the sampling
  // weights f cos / p before it; for a light subpath Le / (P_choice p_A) at the light and the
  // product of weights after it (the flux a photon arriving here carries).
  Color beta{1.0f};
  float pdf_fwd = 0.0f;  // per unit area: the density its own subpath sampled it with
  float pdf_rev = 0.0f;  // per unit area: the density the next vertex of its subpath would give it
  bool delta = false;    // a mirror or glass: no connection can end here
  int emitter = -1;      // the area emitter it lies on (LightingScene::emitter_index), or -1

  Vec3 point() const { return hit.point; }
  Vec3 normal() const { return hit.normal; }
  // The unit direction from this vertex towards another.
  Vec3 direction_to(const PathVertex& other) const { return glm::normalize(other.point() - point()); }
};

// Le of a light vertex towards w, over the Le its beta already holds: 1 on the emitter's front
// side, 0 behind (common/emission.h's one-sided rule).
inline Color emission_towards(const PathVertex& light, Vec3 w) {
  return front_side_emission(Color(1.0f), glm::dot(light.normal(), w) > 0.0f);
}

// The pinhole as a path's first vertex: its point, and the view direction as its normal.
PathVertex camera_vertex(const Camera& camera);

// The longest subpath a walk makes. Russian roulette ends paths long before (each bounce survives
// with probability at most 0.95; 0.95^256 < 2e-6); the cap sizes the arrays the MIS weight uses.
inline constexpr int kMaxSubpathVertices = 256;

// Task stage6.bdpt.area_density. A solid-angle density p_w of the direction from `from` to `to`,
// per unit area at `to`: p_w |cos(theta_to)| / |to - from|^2, theta_to against to's geometric
// normal. The pinhole has no area: towards the camera, p_w / |to - from|^2 alone.
float to_area_density(float pdf_w, const PathVertex& from, const PathVertex& to);

// What stands for a delta lobe's density in MIS weights (a mirror or glass "samples" its one
// direction with a Dirac delta): 1 per unit PROJECTED solid angle, so |cos theta| per unit solid
// angle along the lobe's direction w, against v's geometric normal. Every strategy that exists
// samples each delta vertex's scattering once, from one side or the other, so the Dirac factors
// cancel in the ratios of path densities, and what is left must be the same for every strategy:
// in area measure, a delta-sampled edge then carries its G(x, y) like any other sampled edge,
// which is what the true densities' ratios have. (Taking the delta's area density as 1 instead
// keeps the weights summing to 1 but drops G from one side of the ratio: wrong weights,
// unbiased, noisier; docs/stage6.md, section 4.)
float delta_lobe_density(const PathVertex& v, Vec3 w);

// The area density at `next` with which vertex v, reached from `prev` (nullptr at a subpath's
// start), would sample `next`: the camera by its film (camera_direction_pdf), a light by its
// emission lobe (cos / pi), a surface by its BSDF's pdf, a delta lobe by delta_lobe_density (for
// `next` along the lobe).
float vertex_pdf(const Camera& camera, const PathVertex& v, const PathVertex* prev, const PathVertex& next);
// The density with which light sampling (the emission sampler, light_emission.h) would have
// started a light subpath at v: P_choice / area of its emitter, 0 if v lies on none.
float light_origin_pdf(const LightingScene& scene, const PathVertex& v);
// The area density at `next` of v's emitter emitting towards it: (cos / pi) converted.
float light_emission_pdf(const LightingScene& scene, const PathVertex& v, const PathVertex& next);

// The BSDF of a surface vertex as the path-integral form uses it, with the light arriving from
// `towards_light` and leaving towards `towards_camera` (world directions):
//     f_s(wo, wi) |cos_shading(wi)| / |cos_geometric(wi)|,
// so that, with G's geometric cosines, f G gives the same radiance the path tracer's f cos / p
// does, and shading normals stay consistent whichever end sampled the vertex (Veach's thesis,
// section 5.3). Equal to f_s where the two normals agree.
Color scattering(const PathVertex& v, Vec3 towards_camera, Vec3 towards_light);

struct WalkSettings {
  TransportMode mode = TransportMode::radiance;  // camera subpaths carry radiance, light subpaths importance
  int max_vertices = kMaxSubpathVertices;  // the subpath, its start included
  int roulette_start = 4;                  // bounces before Russian roulette (stage 5's rule)
  OffsetPolicy offset;
};

// Task stage6.bdpt.random_walk. Extends the subpath `path` (its last vertex the camera or a light)
// along `ray`, which left that vertex with solid-angle density pdf_w carrying throughput `beta`:
// at each surface hit, a vertex with pdf_fwd (pdf_w converted to area), then a BSDF sample for
// the next direction (ShadingPoint::sample, for the quantity settings.mode carries), whose reverse
// density sets the previous vertex's pdf_rev; delta lobes give both directions delta_lobe_density.
// Russian roulette as in stage 5 (survival_probability on the throughput relative to the walk's
// start), at most settings.max_vertices vertices. Ends where a ray leaves the scene.
template <SamplerType S>
void random_walk(const LightingScene& scene, Ray ray, Color beta, float pdf_w, const WalkSettings& settings, S& sampler,
                 std::vector<PathVertex>& path);

}  // namespace rt
