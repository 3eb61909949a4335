#include "app/run/observers.hpp"

#include "app/render/render_recorder.hpp"
#include "app/render/snapshot_observer.hpp"
#include "measure/rfm_observer.hpp"
#include "measure/tap_observer.hpp"
#include "output/csv.hpp"

namespace gs {

Observers make_observers(const SceneSpec& scene) {
  Observers obs;
  // each feature appends its observers here
  // tapping (negative g, rotating g): taps.csv and segregation.csv, one row per tap
  if (auto tap = make_tap_observer(scene, csv_records())) obs.push_back(std::move(tap));
  // Random Force Model ([rfm], on for the random force): measure/rfm_observer.hpp
  if (auto rfm = make_rfm_observer(scene, csv_records())) obs.push_back(std::move(rfm));
  // [render]: frames and movie, trajectory.xyz (app/render/render_recorder.cpp)
  add_render_observers(scene, obs);
  // [output.snapshots]: configurations and contact forces (app/render/snapshot_observer.cpp)
  if (auto snap = make_snapshot_observer(scene)) obs.push_back(std::move(snap));
  return obs;
}

}  // namespace gs
