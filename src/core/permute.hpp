// moving per-particle arrays between slots (the spatial sort, Simulation::sort_particles):
// perm[k] is the old slot whose value slot k receives
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace gs {

/// v[k] ← v[perm[k]] for every slot k, through tmp, which keeps v's old buffer for the next
/// call (an empty v stays empty)
template <class T>
void gather_permuted(std::vector<T>& v, std::span<const std::uint32_t> perm, std::vector<T>& tmp) {
  if (v.empty()) return;
  tmp.resize(perm.size());
  for (std::size_t k = 0; k < perm.size(); ++k) tmp[k] = v[perm[k]];
  v.swap(tmp);
}

/// v[k] ← v[perm[k]] for every slot k, through tmp, and copied back: v keeps its buffer, so that
/// a view onto it (the Python module's NumPy arrays) stays on the same quantity
template <class T>
void gather_in_place(std::vector<T>& v, std::span<const std::uint32_t> perm, std::vector<T>& tmp) {
  if (v.empty()) return;
  tmp.resize(perm.size());
  for (std::size_t k = 0; k < perm.size(); ++k) tmp[k] = v[perm[k]];
  std::copy(tmp.begin(), tmp.end(), v.begin());
}

/// the inverse permutation: out[perm[k]] = k
inline std::vector<std::uint32_t> inverse_permutation(std::span<const std::uint32_t> perm) {
  std::vector<std::uint32_t> out(perm.size());
  for (std::size_t k = 0; k < perm.size(); ++k) out[perm[k]] = static_cast<std::uint32_t>(k);
  return out;
}

}  // namespace gs
