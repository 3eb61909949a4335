// the [output.snapshots] observer: the configuration (and its contacts) at scheduled times and
// at every tap's measurement, into DIR/snapshots/ (docs/rendering.md, "Snapshots")
#pragma once
#include <memory>

#include "scene/spec.hpp"
#include "sim/observer.hpp"

namespace gs {

/// index of the snapshots taken: DIR/snapshots/index.csv
inline constexpr const char* kSnapshotIndexFile = "index.csv";
/// the ParaView collection: DIR/snapshots/snapshots.pvd
inline constexpr const char* kSnapshotCollectionFile = "snapshots.pvd";

/// the snapshot writer when the scene asks for snapshots; null otherwise
std::unique_ptr<Observer> make_snapshot_observer(const SceneSpec& scene);

}  // namespace gs
