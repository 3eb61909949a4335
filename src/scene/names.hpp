// the lower-case names scene files use for each enum, in one table per enum, so the
// parser, the writer and the docs cannot drift apart. The first entry for a value is its
// canonical spelling (what scene_to_toml writes); later entries are accepted aliases.
#pragma once
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "scene/spec.hpp"

namespace gs {

/// one spelling of an enum value in a scene file
template <class E>
struct EnumName {
  std::string_view name;
  E value;
};

std::span<const EnumName<ShapeKind>> enum_names(ShapeKind);
std::span<const EnumName<ModelKind>> enum_names(ModelKind);
std::span<const EnumName<BoxKind>> enum_names(BoxKind);
std::span<const EnumName<PlacementKind>> enum_names(PlacementKind);
std::span<const EnumName<DriveKind>> enum_names(DriveKind);
std::span<const EnumName<BroadPhaseKind>> enum_names(BroadPhaseKind);
/// integrator names live here too, so gs_scene needs no link to gs_integrate
std::span<const EnumName<IntegratorKind>> enum_names(IntegratorKind);

/// canonical scene-file spelling of an enum value
template <class E>
std::string_view scene_name(E value) {
  for (const auto& n : enum_names(E{}))
    if (n.value == value) return n.name;
  return "?";
}

/// look a spelling up (exact, case-sensitive); nullopt if unknown
template <class E>
std::optional<E> scene_enum(std::string_view name) {
  for (const auto& n : enum_names(E{}))
    if (n.name == name) return n.value;
  return std::nullopt;
}

/// every accepted spelling, quoted and comma-separated: "\"disk\", \"polygon\""
template <class E>
std::string scene_enum_list() {
  std::string s;
  for (const auto& n : enum_names(E{})) {
    if (!s.empty()) s += ", ";
    s += '"';
    s += n.name;
    s += '"';
  }
  return s;
}

}  // namespace gs
