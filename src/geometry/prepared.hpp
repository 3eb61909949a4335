// prepared convex polygons for the contact hot loop: each grain's world-frame vertices, vertex
// mean, bounding circle and longest edge, computed once per step into flat arrays, so that the
// overlap of a pair needs no per-pair set-up (docs/physics.md §2.1)
#pragma once
#include <cstddef>
#include <vector>

#include "core/vec.hpp"
#include "geometry/polygon.hpp"

namespace gs {

/// a read-only view of one prepared convex polygon (counter-clockwise vertices)
struct PolyRef {
  int n = 0;
  /// vertex abscissae and ordinates, m, n + 1 of each: x[n], y[n] repeat vertex 0, so that
  /// edge k = vertex k+1 − vertex k is x[k+1] − x[k], y[k+1] − y[k] for every k < n
  const double* x = nullptr;
  const double* y = nullptr;
  double ex(int k) const { return x[k + 1] - x[k]; }  ///< edge k, x component, m
  double ey(int k) const { return y[k + 1] - y[k]; }  ///< edge k, y component, m
  Vec2 mean;            ///< vertex mean (the interior point overlap() uses), m
  double radius = 0.0;  ///< a circle about `mean` holding every vertex (rounded up), m
  double len = 0.0;     ///< the longest edge (rounded up), m
  /// regular polygons from 5 sides (equal edges and exterior angles, to 1e-9): every point
  /// within this L1 distance of an edge's midpoint lies strictly inside every edge line but
  /// those of that edge and its two neighbours (0: no such bound), m
  double near = 0.0;
};

/// is the closed polygon (x, y) of n vertices regular (equal edges and exterior angles)?
bool is_regular(int n, const double* x, const double* y);
/// PolyRef::near of the regular polygon (x, y) of n vertices
double near_bound(int n, const double* x, const double* y);

/// what placing a body needs beyond its vertices: sizes that no placement changes
struct BodyExtent {
  double reach = 0.0;  ///< the largest distance of a vertex from the body origin, m
  double len = 0.0;    ///< the longest edge, m
  double near = 0.0;   ///< PolyRef::near of the body, m
};
BodyExtent body_extent(const Poly& body);

/// prepared polygons in one flat array (structure of arrays per polygon, fixed stride)
class PolyStore {
 public:
  /// room for `count` polygons of at most `max_n` vertices (contents undefined until set)
  void resize(std::size_t count, int max_n);
  /// polygon i := body placed at c with orientation θ (the same arithmetic as place());
  /// `ext` = body_extent(body), computed once per body by callers that place it often
  void set_placed(std::size_t i, const Poly& body, const BodyExtent& ext, Vec2 c, double theta);
  void set_placed(std::size_t i, const Poly& body, Vec2 c, double theta) {
    set_placed(i, body, body_extent(body), c, theta);
  }
  /// polygon i := p (world coordinates)
  void set(std::size_t i, const Poly& p);
  /// a view of polygon i (valid until the next resize)
  PolyRef ref(std::size_t i) const {
    PolyRef r;
    r.n = n_[i];
    r.x = data_.data() + i * 2 * stride_;
    r.y = r.x + stride_;
    r.mean = meta_[i].mean;
    r.radius = meta_[i].radius;
    r.len = meta_[i].len;
    r.near = meta_[i].near;
    return r;
  }
  /// polygon i as a Poly (for the general routines)
  Poly poly(std::size_t i) const;
  std::size_t size() const { return n_.size(); }

 private:
  void finish(std::size_t i);             // edges, mean, radius, longest edge from the vertices
  Vec2 edges(std::size_t i, double& l2);  // vertex 0 repeated; returns the vertex mean
  struct Meta {
    Vec2 mean;
    double radius = 0.0, len = 0.0;
    double near = 0.0;
  };
  std::size_t stride_ = 0;    ///< the most vertices, plus one (the repeated vertex 0)
  std::vector<double> data_;  ///< per polygon: x, y, each `stride_` long
  std::vector<int> n_;
  std::vector<Meta> meta_;
};

/// exact overlap of prepared convex polygons a and b: the same result, bit for bit, as
/// overlap(Poly, Poly), except that `centroid` is only computed when a caller needs it
/// (fewer than two distinct crossings, or c1 == c2) and is left zero otherwise. Faster:
/// bounding circles reject separated pairs, and after the facing edge has cut a down to the
/// cap inside b, the edge lines of b that provably cut nothing of the cap are skipped.
Overlap overlap(const PolyRef& a, const PolyRef& b);

}  // namespace gs
