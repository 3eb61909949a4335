// the enum spelling tables (see names.hpp); canonical spelling first, aliases after
#include "scene/names.hpp"

namespace gs {

namespace {
constexpr EnumName<ShapeKind> kShape[] = {{"polygon", ShapeKind::Polygon},
                                          {"disk", ShapeKind::Disk}};
constexpr EnumName<ModelKind> kModel[] = {{"P", ModelKind::Polygon},
                                          {"S", ModelKind::Disk},
                                          {"polygon_dem", ModelKind::Polygon},
                                          {"soft_disk", ModelKind::Disk}};
constexpr EnumName<BoxKind> kBox[] = {
    {"walls", BoxKind::Walls}, {"periodic", BoxKind::Periodic}, {"ring", BoxKind::Ring1D}};
constexpr EnumName<PlacementKind> kPlacement[] = {{"loose_column", PlacementKind::LooseColumn},
                                                  {"hexagonal", PlacementKind::Hexagonal},
                                                  {"square", PlacementKind::Square},
                                                  {"uniform", PlacementKind::Uniform},
                                                  {"random", PlacementKind::Random}};
constexpr EnumName<DriveKind> kDrive[] = {{"none", DriveKind::None},
                                          {"gravity", DriveKind::Gravity},
                                          {"negative_g", DriveKind::NegativeG},
                                          {"rotating_g", DriveKind::RotatingG},
                                          {"random_force", DriveKind::RandomForce}};
constexpr EnumName<BroadPhaseKind> kBroad[] = {{"auto", BroadPhaseKind::Auto},
                                               {"box2d_tree", BroadPhaseKind::Box2DTree},
                                               {"cell_grid", BroadPhaseKind::CellGrid}};
constexpr EnumName<IntegratorKind> kIntegrator[] = {
    {"gear6", IntegratorKind::Gear6},
    {"velocity_verlet", IntegratorKind::VelocityVerlet},
    {"position_verlet", IntegratorKind::PositionVerlet},
    {"semi_implicit_euler", IntegratorKind::SemiImplicitEuler}};
}  // namespace

std::span<const EnumName<ShapeKind>> enum_names(ShapeKind) { return kShape; }
std::span<const EnumName<ModelKind>> enum_names(ModelKind) { return kModel; }
std::span<const EnumName<BoxKind>> enum_names(BoxKind) { return kBox; }
std::span<const EnumName<PlacementKind>> enum_names(PlacementKind) { return kPlacement; }
std::span<const EnumName<DriveKind>> enum_names(DriveKind) { return kDrive; }
std::span<const EnumName<BroadPhaseKind>> enum_names(BroadPhaseKind) { return kBroad; }
std::span<const EnumName<IntegratorKind>> enum_names(IntegratorKind) { return kIntegrator; }

}  // namespace gs
