#include "06-light-transport/photon_grid.h"

#include <bit>
#include <stdexcept>

namespace rt {

void PhotonGrid::assign(std::span<const std::vector<Photon>> chunks, float cell) {
  if (!(cell > 0.0f) || !std::isfinite(1.0f / cell)) throw std::invalid_argument("photon grid: cell size must be > 0");
  inverse_cell_ = 1.0f / cell;
  std::size_t count = 0;
  for (const std::vector<Photon>& chunk : chunks) count += chunk.size();
  const std::uint32_t table = std::bit_ceil(std::uint32_t(std::max<std::size_t>(2 * count, 1)));
  mask_ = table - 1;
  // A counting sort by bucket: sizes, then where each bucket starts, then each photon in its place.
  start_.assign(std::size_t(table) + 1, 0);
  for (const std::vector<Photon>& chunk : chunks)
    for (const Photon& p : chunk) ++start_[bucket(cell_of(p.position)) + 1];
  for (std::size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
  next_.assign(start_.begin(), start_.end() - 1);
  photons_.resize(count);
  for (const std::vector<Photon>& chunk : chunks)
    for (const Photon& p : chunk) photons_[next_[bucket(cell_of(p.position))]++] = p;
}

}  // namespace rt
