#include "force/pair_loop.hpp"

#include <algorithm>
#include <stdexcept>

#include "force/laws/disk_pair.hpp"
#include "force/laws/polygon_pair.hpp"

namespace gs {
namespace {

// the contact's statistics: h_eff (or δ) and the same over the smaller grain's radius
// (one_radius: grains of one radius, whose max_overlap_rel finish_overlaps makes at the end)
void note_overlap(ForceStats& st, const World& w, PairKey key, double h, bool degenerate,
                  bool one_radius) {
  const std::uint32_t i = key_i(key), j = key_j(key);
  st.degenerate += degenerate;
  st.max_overlap = std::max(st.max_overlap, h);
  if (one_radius) return;
  const double ri = w.radius[i];
  st.max_overlap_rel =
      std::max(st.max_overlap_rel, h / (j >= w.size() ? ri : std::min(ri, w.radius[j])));
}

// grains of one radius rc: their largest overlap over the radius is the largest overlap divided
// by it once, the same bits (a correctly rounded division by a positive constant keeps the
// order), not a division and two loads per contact
void finish_overlaps(ForceStats& st, bool one_radius, double rc) {
  if (one_radius) st.max_overlap_rel = st.max_overlap / rc;
}

}  // namespace

// cheap pairs (disks) take a parallel region of their own from kParallelMinCheap
// pairs. But where the particle loops run in parallel anyway (n ≥ kParallelMinCheap: the
// accelerations come in the same region), the pairs join it from kParallelMin, so that the
// first thread does not evaluate them alone while the team waits, reading the others' positions
std::size_t PairLoop::parallel_pairs_from(bool cheap, std::size_t n) {
  return !cheap || n >= kParallelMinCheap ? kParallelMin : kParallelMinCheap;
}

// Below the thresholds a plain loop over the candidates sums each pair's force into its two
// particles as it goes. Above them: pairs in parallel into per-candidate slots → touching ones
// compacted into the contact set in fixed blocks → each particle's forces summed over its own
// pairs in candidate order, from zero. Each particle's terms are the same in the same order
// either way, so the forces are bitwise the same on any number of threads, serial or parallel.
template <class Ev>
ForceStats PairLoop::run(Ev& ev, const World& w, const std::vector<PairKey>& cand, ContactSet& cs,
                         ForceBuffer& f, double dt, ThreadTeam& team, std::uint64_t generation,
                         ParticlePhase* then) {
  static_assert(!Ev::kCheap || !Ev::kTorque, "the sums from the touching pairs add no torques");
  const std::size_t n = w.size();
  const std::size_t ncand = cand.size();
  if (ncand >= (std::size_t{1} << 31))
    throw std::length_error("ContactModel::evaluate: more than 2^31 candidate pairs");
  f.fx.resize(n);
  f.fy.resize(n);
  f.tq.resize(Ev::kTorque ? n : 0);
  ForceStats st;
  const std::size_t to_place = ev.begin(w, generation);
  if (run_parallel(ncand, parallel_pairs_from(Ev::kCheap, n))) {
    // cheap pairs of which few touched last step: each particle's sum from the few touching
    // pairs themselves, not from its candidates (sums_from_touching); else the per-particle index
    const bool from_touching = Ev::kCheap && few_touched(cs, ncand);
    const bool reindex = !from_touching && (generation == 0 || generation != indexed_generation_ ||
                                            n != indexed_n_ || ncand != indexed_count_);
    st = parallel(ev, w, cand, cs, f, dt, team, reindex, from_touching, to_place, then);
    if (reindex) {
      indexed_generation_ = generation;
      indexed_n_ = n;
      indexed_count_ = ncand;
    }
  } else {
    ev.place(w, 0, to_place);
    st = serial(ev, w, cand, cs, f, dt);
    if (then != nullptr)  // the serial loop summed each pair as it went
      parallel_ranges(team, n, kParallelMinCheap,
                      [then](std::size_t b, std::size_t e) { then->run(b, e); });
  }
  cs.replace(next_);
  cs.degenerate += st.degenerate;
  st.contacts = cs.keys.size();
  st.candidates = ncand;
  return st;
}

template <class Ev>
ForceStats PairLoop::serial(const Ev& ev, const World& w, const std::vector<PairKey>& cand,
                            const ContactSet& cs, ForceBuffer& f, double dt) {
  const std::uint32_t N = static_cast<std::uint32_t>(w.size());
  clear_forces(f, N);
  next_.clear();
  ForceStats st;
  PairForce pf;
  PairResult r;
  const double rc = ev.common_radius();
  const bool one_radius = rc > 0.0;
  HistoryCursor history(cs);
  // the sums' arrays by pointers taken once (the contact set's stores might alias the vectors)
  double* const fx = f.fx.data();
  double* const fy = f.fy.data();
  double* const tq = f.tq.data();
  // `at(q)`: the q-th candidate the loop visits (inlined: the pair's force stays in registers)
  auto run = [&](std::size_t count, auto&& at) __attribute__((always_inline)) {
    for (std::size_t q = 0; q < count; ++q) {
      const PairKey key = at(q);
      if (!ev.pair(w, key, history, dt, pf, r)) continue;
      const std::uint32_t i = key_i(key), j = key_j(key);
      fx[i] -= pf.fx;
      fy[i] -= pf.fy;
      if constexpr (Ev::kTorque) tq[i] -= pf.ti;
      if (j < N) {
        fx[j] += pf.fx;
        fy[j] += pf.fy;
        if constexpr (Ev::kTorque) tq[j] += pf.tj;
      }
      next_.keys.push_back(key);
      next_.records.push_back({key, r.s, r.n, r.fn, r.ft, r.overlap});
      if constexpr (Ev::kHistory) next_.state.push_back(r.state);
      note_overlap(st, w, key, r.h, r.degenerate, one_radius);
    }
  };
  auto all = [&](std::size_t q) { return cand[q]; };
  if constexpr (Ev::kCheap) {
    // where few candidates touched last step (a gas, the 1D ring), a branch-free pass
    // first keeps the pairs that may touch, so that the loop no longer mispredicts at each
    // contact; in a packing, where almost all touch, that pass would only add work. Either way
    // the same pairs are evaluated. Block by block: the selected pairs are evaluated while the
    // lines the selection read are still in the cache
    if (few_touched(cs, cand.size())) {
      constexpr std::size_t kSelectBlock = 1024;
      for (std::size_t k0 = 0; k0 < cand.size(); k0 += kSelectBlock) {
        const std::size_t k1 = std::min(cand.size(), k0 + kSelectBlock);
        const std::size_t m = ev.select(w, cand, k0, k1, sel_);
        Ev::prefetch(w, cand, sel_, m, f.fx.data(), f.fy.data());
        run(m, [&](std::size_t q) { return cand[sel_[q]]; });
      }
    } else {
      run(cand.size(), all);
    }
  } else {
    run(cand.size(), all);
  }
  finish_overlaps(st, one_radius, rc);
  note_touched(f, N);
  return st;
}

// zero the force buffer before the serial sum: only the entries the last serial evaluation
// wrote, where it recorded them (few touching pairs) and the buffer is still the same size
// and otherwise untouched; else every entry. Either way every entry is +0.0 afterwards.
void PairLoop::clear_forces(ForceBuffer& f, std::size_t n) {
  if (f.sparse && f.sparse_n == n && f.fx.size() == n && f.fy.size() == n) {
    const bool tq = f.tq.size() == n;
    for (std::uint32_t p : f.touched) {
      f.fx[p] = 0.0;
      f.fy[p] = 0.0;
      if (tq) f.tq[p] = 0.0;
    }
    if (tq || f.tq.empty()) return;
  }
  std::fill(f.fx.begin(), f.fx.end(), 0.0);
  std::fill(f.fy.begin(), f.fy.end(), 0.0);
  std::fill(f.tq.begin(), f.tq.end(), 0.0);
}

// after a serial sum: where at most 1/8 of the particles can hold a non-zero entry (a random
// write costs about a cache line, eight sequential zeros), remember them for clear_forces
void PairLoop::note_touched(ForceBuffer& f, std::size_t n) {
  f.touched.clear();
  f.sparse = 2 * next_.keys.size() <= n / 8;
  f.sparse_n = n;
  if (!f.sparse) return;
  for (PairKey key : next_.keys) {
    f.touched.push_back(key_i(key));
    if (key_j(key) < n) f.touched.push_back(key_j(key));
  }
}

template <class Ev>
ForceStats PairLoop::parallel(Ev& ev, const World& w, const std::vector<PairKey>& cand,
                              const ContactSet& cs, ForceBuffer& f, double dt, ThreadTeam& team,
                              bool reindex, bool from_touching, std::size_t to_place,
                              ParticlePhase* then) {
  const std::size_t n = w.size();
  const std::size_t ncand = cand.size();
  const double rc = ev.common_radius();
  const bool one_radius = rc > 0.0;
  if (reindex) index_candidates(cand, n);
  f.sparse = false;  // every entry is written below
  touch_.resize(ncand);
  pair_f_.resize(ncand);
  pair_r_.resize(ncand);
  // one parallel region: grains placed → every candidate pair, chunk by chunk (a chunk's
  // history search resumes where its last one ended), each chunk counting its touching pairs
  // → the chunks' first slots (a prefix sum) → each chunk's touching pairs compacted into the
  // contact set, in candidate order whatever the chunking → each particle's forces, its pairs
  // in candidate order, from zero
  constexpr std::size_t chunk = Ev::kChunk;
  const std::size_t nchunks = (ncand + chunk - 1) / chunk;
  chunk_first_.resize(nchunks);
  chunk_stats_.assign(nchunks, {});
  PassSchedule& schedule = team.pass();
  schedule.plan(nchunks, to_place);
#pragma omp parallel
  {
    const int tid = team_thread(), nt = team_size();
    const auto [p_begin, p_end] = team.particles(n, tid, nt);
    if (to_place > 0) {
      schedule.place(tid, nt, [&](std::size_t b, std::size_t e) { ev.place(w, b, e); });
#pragma omp barrier
    }
    // the time this thread spends on its own particles (summing, the particle phase): the next
    // step's particles are split by it
    double t_particles = 0.0;
    auto run_chunk = [&](std::size_t c) {
      const std::size_t k0 = c * chunk, k1 = std::min(ncand, k0 + chunk);
      HistoryCursor history(cs);
      std::size_t touching = 0;
      for (std::size_t k = k0; k < k1; ++k) {
        const bool t = ev.pair(w, cand[k], history, dt, pair_f_[k], pair_r_[k]);
        touch_[k] = t;
        touching += t;
      }
      chunk_first_[c] = touching;
    };
    schedule.run_chunks(tid, nt, run_chunk);
#pragma omp barrier
#pragma omp single
    {
      std::size_t total = 0;
      for (std::size_t& first : chunk_first_) {
        const std::size_t c = first;
        first = total;
        total += c;
      }
      next_.keys.resize(total);
      next_.records.resize(total);
      next_.state.resize(Ev::kHistory ? total : 0);
      touching_k_.resize(from_touching ? total : 0);
    }
    // the compaction over the same chunks as the pair loop's own ranges
    const ItemRange own_chunks = schedule.chunk_range(tid, nt);
    for (std::size_t c = own_chunks.begin; c < own_chunks.end; ++c) {
      std::size_t out = chunk_first_[c];
      const std::size_t k0 = c * chunk, k1 = std::min(ncand, k0 + chunk);
      for (std::size_t k = k0; k < k1; ++k) {
        if (!touch_[k]) continue;
        const PairKey key = cand[k];
        const PairResult& r = pair_r_[k];
        next_.keys[out] = key;
        if (from_touching) touching_k_[out] = static_cast<std::uint32_t>(k);
        next_.records[out] = {key, r.s, r.n, r.fn, r.ft, r.overlap};
        if constexpr (Ev::kHistory) next_.state[out] = r.state;
        ++out;
        note_overlap(chunk_stats_[c], w, key, r.h, r.degenerate, one_radius);
      }
    }
    if (from_touching) {  // the sums read every thread's compacted pairs
#pragma omp barrier
    }
    const double tp1 = wall_seconds();  // (the barrier's wait is no particle's work)
    if (from_touching) {
      sums_from_touching(w, f, p_begin, p_end);
    } else {
      for (std::size_t p = p_begin; p < p_end; ++p) {
        double fx = 0.0, fy = 0.0, tq = 0.0;
        for (std::uint32_t e = cand_start_[p]; e < cand_start_[p + 1]; ++e) {
          const std::uint32_t k = cand_entry_[e] >> 1;
          if (!touch_[k]) continue;
          const PairForce& r = pair_f_[k];
          if (cand_entry_[e] & 1u) {
            fx += r.fx;
            fy += r.fy;
            tq += r.tj;
          } else {
            fx -= r.fx;
            fy -= r.fy;
            tq -= r.ti;
          }
        }
        f.fx[p] = fx;
        f.fy[p] = fy;
        if constexpr (Ev::kTorque) f.tq[p] = tq;
      }
    }
    if (then != nullptr) then->run(p_begin, p_end);
    t_particles += wall_seconds() - tp1;
    schedule.record_particles(tid, nt, p_end - p_begin, t_particles);
  }  // omp parallel
  team.update();
  ForceStats st;  // maxima and counts: the same whatever the chunking
  for (const ForceStats& b : chunk_stats_) {
    st.degenerate += b.degenerate;
    st.max_overlap = std::max(st.max_overlap, b.max_overlap);
    st.max_overlap_rel = std::max(st.max_overlap_rel, b.max_overlap_rel);
  }
  finish_overlaps(st, one_radius, rc);
  return st;
}

// counting sort of the candidates' (k, side) entries by particle: ascending k per particle
void PairLoop::index_candidates(const std::vector<PairKey>& cand, std::size_t n) {
  const std::uint32_t N = static_cast<std::uint32_t>(n);
  cand_start_.assign(n + 1, 0);
  for (PairKey key : cand) {
    ++cand_start_[key_i(key) + 1];
    if (key_j(key) < N) ++cand_start_[key_j(key) + 1];
  }
  for (std::size_t p = 0; p < n; ++p) cand_start_[p + 1] += cand_start_[p];
  cand_entry_.resize(cand_start_[n]);
  fill_.assign(cand_start_.begin(), cand_start_.end() - 1);
  for (std::size_t k = 0; k < cand.size(); ++k) {
    const auto e = static_cast<std::uint32_t>(k << 1);
    cand_entry_[fill_[key_i(cand[k])]++] = e;
    if (key_j(cand[k]) < N) cand_entry_[fill_[key_j(cand[k])]++] = e | 1u;
  }
}

// the cheap pairs' forces of particles [b, e) from this step's touching pairs (compacted, in
// candidate order), from zero: for each particle the same terms in the same order as the
// per-particle index gives (its pairs in ascending candidate order), so bitwise the same. A
// walk over the few touching pairs instead of over every particle's candidates (a sparse gas:
// 0.44 candidates and 0.005 contacts per disk); it reads the compacted keys, a few lines, not
// the other threads' touch flags
void PairLoop::sums_from_touching(const World& w, ForceBuffer& f, std::size_t b,
                                  std::size_t e) const {
  const auto N = static_cast<std::uint32_t>(w.size());
  std::fill(f.fx.begin() + static_cast<std::ptrdiff_t>(b),
            f.fx.begin() + static_cast<std::ptrdiff_t>(e), 0.0);
  std::fill(f.fy.begin() + static_cast<std::ptrdiff_t>(b),
            f.fy.begin() + static_cast<std::ptrdiff_t>(e), 0.0);
  for (std::size_t q = 0; q < next_.keys.size(); ++q) {
    const std::uint32_t i = key_i(next_.keys[q]), j = key_j(next_.keys[q]);
    const bool own_i = i >= b && i < e, own_j = j < N && j >= b && j < e;
    if (!own_i && !own_j) continue;
    const PairForce& r = pair_f_[touching_k_[q]];
    if (own_i) {
      f.fx[i] -= r.fx;
      f.fy[i] -= r.fy;
    }
    if (own_j) {
      f.fx[j] += r.fx;
      f.fy[j] += r.fy;
    }
  }
}

// the loop for each model's evaluator
template ForceStats PairLoop::run(PolygonPairEvaluator&, const World&, const std::vector<PairKey>&,
                                  ContactSet&, ForceBuffer&, double, ThreadTeam&, std::uint64_t,
                                  ParticlePhase*);
template ForceStats PairLoop::run(DiskPairEvaluator&, const World&, const std::vector<PairKey>&,
                                  ContactSet&, ForceBuffer&, double, ThreadTeam&, std::uint64_t,
                                  ParticlePhase*);

}  // namespace gs
