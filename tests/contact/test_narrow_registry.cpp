// the narrow-phase registry: the run-time table holds the very functions the evaluators call
// by their kinds, unsupported pairings have none, and each function gives the contact frame
// of its pairing (disks by hand; a polygon's periodic image as the general routine gives it for
// the polygon moved to the image)
#include <gtest/gtest.h>

#include "contact/narrow.hpp"
#include "core/rng.hpp"
#include "geometry/prepared.hpp"

namespace gs {
namespace {

using K = BodyKind;

// a disk, or the wall w, as the narrow phase reads it
PlacedBody disk(Vec2 c, double r) { return PlacedBody{c, r, nullptr, {}, nullptr}; }
PlacedBody wall(const Wall& w) { return PlacedBody{{}, 0.0, nullptr, {}, &w}; }

static_assert(narrow_fn(K::Disk, K::Disk) == &narrow<K::Disk, K::Disk>);
static_assert(narrow_fn(K::Disk, K::Wall) == &narrow<K::Disk, K::Wall>);
static_assert(narrow_fn(K::Polygon, K::Polygon) == &narrow<K::Polygon, K::Polygon>);
static_assert(narrow_fn(K::Polygon, K::Wall) == &narrow<K::Polygon, K::Wall>);
static_assert(narrow_fn(K::Disk, K::Polygon) == nullptr &&
              narrow_fn(K::Polygon, K::Disk) == nullptr);
static_assert(narrow_fn(K::Wall, K::Disk) == nullptr && narrow_fn(K::Wall, K::Polygon) == nullptr &&
              narrow_fn(K::Wall, K::Wall) == nullptr);
static_assert(body_kind(ShapeKind::Disk) == K::Disk && body_kind(ShapeKind::Polygon) == K::Polygon);

TEST(NarrowRegistry, DiskPairsByHand) {
  const NarrowFn fn = narrow_fn(K::Disk, K::Disk);
  const ContactGeom g = fn(disk({0.0, 0.0}, 1.0), disk({1.5, 0.0}, 1.0));
  ASSERT_TRUE(g.touching);
  EXPECT_EQ(g.overlap, 0.5);
  EXPECT_EQ(g.n, (Vec2{1.0, 0.0}));
  EXPECT_EQ(g.s, (Vec2{0.75, 0.0}));
  EXPECT_FALSE(fn(disk({0.0, 0.0}, 1.0), disk({2.0, 0.0}, 1.0)).touching);
  EXPECT_FALSE(fn(disk({0.0, 0.0}, 1.0), disk({0.0, 0.0}, 1.0)).touching);  // no normal
}

TEST(NarrowRegistry, DiskWallByHand) {
  Wall floor{};  // the floor y = 0, the wall below it
  floor.normal = {0.0, -1.0};
  floor.offset = 0.0;
  const NarrowFn fn = narrow_fn(K::Disk, K::Wall);
  const ContactGeom g = fn(disk({0.3, 0.75}, 1.0), wall(floor));
  ASSERT_TRUE(g.touching);
  EXPECT_EQ(g.overlap, 0.25);
  EXPECT_EQ(g.n, floor.normal);
  EXPECT_EQ(g.s, (Vec2{0.3, -0.125}));
  EXPECT_FALSE(fn(disk({0.3, 1.0}, 1.0), wall(floor)).touching);
}

// a periodic image: the prepared polygon stays at the grain's own place, the registry shifts a
// copy; the same frame as the general routine on the polygon placed at the image
TEST(NarrowRegistry, PolygonImageMatchesGeneral) {
  RngStream rng(23, 0);
  const Poly body = regular_polygon(10, 9e-3);
  const double L = 0.1;
  PolyStore st;
  st.resize(2, 10);
  int touching = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec2 ca{rng.uniform(0.0, 0.01), rng.uniform(0.0, L)};
    const Vec2 cb{ca.x + L - rng.uniform(0.012, 0.02), ca.y + rng.uniform(-0.01, 0.01)};
    const Vec2 image = cb - Vec2{L, 0.0};  // b's image left of a
    const double ta = rng.uniform(0.0, 6.3), tb = rng.uniform(0.0, 6.3);
    st.set_placed(0, body, ca, ta);
    st.set_placed(1, body, cb, tb);
    const PolyRef ra = st.ref(0), rb = st.ref(1);
    const ContactGeom g = narrow_fn(K::Polygon, K::Polygon)(
        PlacedBody{ca, 0.0, &ra, {}, nullptr}, PlacedBody{image, 0.0, &rb, image - cb, nullptr});
    const Poly pa = place(body, ca, ta);
    Poly pb = place(body, cb, tb);  // b's polygon moved to the image, as the shift moves it
    for (int v = 0; v < pb.n; ++v) pb.v[v] += image - cb;
    const ContactGeom ref = polygon_polygon(BodyView{ca, 9e-3, &pa}, BodyView{image, 9e-3, &pb});
    ASSERT_EQ(g.touching, ref.touching);
    touching += g.touching;
    if (!g.touching) continue;
    ASSERT_EQ(g.overlap, ref.overlap);
    ASSERT_EQ(g.s, ref.s);
    ASSERT_EQ(g.n, ref.n);
    ASSERT_EQ(g.chord, ref.chord);
  }
  EXPECT_GT(touching, 1000);
}

}  // namespace
}  // namespace gs
