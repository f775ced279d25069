// Stage 6: finding the photons near a point. A photon map needs "every photon within r of x" for
// every visible point of every pass, so the photons go into a uniform grid of cells of side
// `cell` >= 2r: the ball of radius r about x then touches at most 2 x 2 x 2 cells. Only cells that
// hold photons take memory: a cell's integer coordinates are hashed into a table about twice the
// photon count (Teschner et al., "Optimized Spatial Hashing for Collision Detection of Deformable
// Objects", VMV 2003, whose three primes are used here), the photons are sorted by bucket (a
// counting sort, stable, so a bucket lists its photons in the order they were traced), and a
// lookup checks each photon's own cell, so two cells that share a bucket are never mixed up.
// The order a lookup visits photons depends only on the photons, never on threads: sums over
// them are the same bit for bit in every run.
#pragma once

#include "common/math.h"

#include <cstdint>
#include <span>
#include <vector>

namespace rt {

struct Photon {
  Vec3 position;
  Vec3 wi;      // unit, world: back towards where the photon came from
  Color power;  // the flux it carries, times the number of photons emitted (the vertex's beta)
  std::uint32_t source = 0;  // the light vertex it was made from, for a caller that keeps them (stage 7)
};

class PhotonGrid {
 public:
  // `cell` > 0: the side of a cell, at least twice the largest radius a lookup will ask for. The
  // photons come in chunks, as the threads traced them, taken in order: joining them into one array
  // first cost more than sorting them (1.3 s a pass of 3 * 10^6 photons, a page fault per 4 KiB).
  PhotonGrid(std::span<const std::vector<Photon>> chunks, float cell) { assign(chunks, cell); }
  PhotonGrid(const std::vector<Photon>& photons, float cell) : PhotonGrid(std::span(&photons, 1), cell) {}
  PhotonGrid() : PhotonGrid(std::vector<Photon>{}, 1.0f) {}  // no photons

  // The grid of new photons, in the memory of the old ones: a renderer that builds one grid per
  // pass keeps it, and pays for fresh pages only when a pass has more photons than any before. A
  // grid built anew each iteration cost stage 7's VCM some 340 page faults an iteration on the
  // 64 x 64 Cornell box, and about a sixth of its time (docs/stage7.md, section 6).
  void assign(std::span<const std::vector<Photon>> chunks, float cell);

  // Calls visit(photon) for each photon within `radius` of x (|p - x| <= radius), cells in a
  // fixed order and each cell's photons in the order they were traced.
  template <class Visit>
  void for_each_within(Vec3 x, float radius, Visit&& visit) const {
    const glm::ivec3 lo = cell_of(x - Vec3(radius)), hi = cell_of(x + Vec3(radius));
    const float radius2 = radius * radius;
    for (int cz = lo.z; cz <= hi.z; ++cz)
      for (int cy = lo.y; cy <= hi.y; ++cy)
        for (int cx = lo.x; cx <= hi.x; ++cx) {
          const glm::ivec3 c(cx, cy, cz);
          const std::size_t b = bucket(c);
          for (std::uint32_t i = start_[b]; i < start_[b + 1]; ++i) {
            const Photon& p = photons_[i];
            const Vec3 d = p.position - x;
            if (glm::dot(d, d) <= radius2 && cell_of(p.position) == c) visit(p);
          }
        }
  }

  std::size_t size() const { return photons_.size(); }

 private:
  // Clamped, so a far point never converts an out-of-range float to int (undefined behaviour); far
  // points then share the border cells, which costs time, never a wrong photon (the distance test).
  glm::ivec3 cell_of(Vec3 p) const {
    constexpr float kLimit = 0x1p30f;
    return glm::ivec3(glm::clamp(glm::floor(p * inverse_cell_), Vec3(-kLimit), Vec3(kLimit)));
  }
  std::size_t bucket(glm::ivec3 c) const {
    const std::uint32_t h = (std::uint32_t(c.x) * 73856093u) ^ (std::uint32_t(c.y) * 19349663u) ^
                            (std::uint32_t(c.z) * 83492791u);
    return std::size_t(h & mask_);
  }

  std::vector<Photon> photons_;       // sorted by bucket
  std::vector<std::uint32_t> start_;  // bucket b holds photons_[start_[b], start_[b + 1])
  std::vector<std::uint32_t> next_;   // while sorting: where each bucket's next photon goes
  float inverse_cell_ = 1.0f;
  std::uint32_t mask_ = 0;
};

}  // namespace rt
